"""The spawn pose a launch file or a package gets for a world: given and checked, the robot pose of the spec
the world was built from, or the deepest free point of its room (see :mod:`worldgen.geometry.placement`)."""

from __future__ import annotations

from pathlib import Path
from typing import Sequence

from ..core.spawnpose import Pose
from ..geometry.placement import checked_spawn, robot_radius, spawn_in_scene, world_rooms


def spawn_for_world(world_path: str | Path, model: str = "optenv", spawn: Sequence[float] | None = None
                    ) -> tuple[Pose, str]:
    """The spawn pose for a launch file of ``world_path`` and where it came from: ``given`` (``spawn``, checked
    against the world), ``spec`` (the robot pose of ``NAME.yaml``/``.yml``/``.json`` beside ``NAME.world``, the
    spec it was built from), ``world`` (the deepest point of the room) or ``open`` (the world has no closed
    room: the deepest free point inside its walls' bounds).

    Raises InputError when the pose is no place for the robot (see :func:`spawn_problem`) and WorldFileError
    when the world cannot be read.
    """
    from ..sdf.reader import read_world

    world_path = Path(world_path)
    rooms = world_rooms(read_world(world_path), robot_radius(model))
    if spawn is not None:
        return checked_spawn(rooms, spawn, source=world_path), "given"
    pose = _spec_pose(world_path)
    if pose is not None:
        return checked_spawn(rooms, pose, source=world_path, what="the spec's robot pose"), "spec"
    return checked_spawn(rooms, None, source=world_path), ("world" if rooms.rooms() else "open")


def launch_model(spec, model: str = "optenv") -> str:
    """The robot model the launch file of ``spec``'s world starts: ``model`` as asked, except that the default
    (``optenv``: TURTLEBOT3_MODEL, else the Burger) gives way to a robot the spec names other than the Burger —
    a line track's Waffle Pi, the one with the camera, as the class's lab B starts it."""
    named = spec.robot.model if spec.robot is not None else None
    return named if model == "optenv" and named not in (None, "burger") else model


def spec_spawn(spec, world_text: str, model: str = "optenv") -> Pose:
    """The spawn pose for the world built from ``spec``: the spec's robot pose, checked against ``world_text``
    (the built world) as ``worldgen launch`` checks it, or without one the deepest point of its room."""
    from ..sdf.reader import read_world_text

    pose = (spec.robot.at[0], spec.robot.at[1], 0.0, spec.robot.yaw) if spec.robot is not None else None
    return spawn_in_scene(read_world_text(world_text, source=spec.source), model, pose, source=spec.source,
                          what="the spec's robot pose", hint="move the robot's at: onto free floor inside the room")


def _spec_pose(world_path: Path) -> Pose | None:
    from ..spec.load import spec_beside

    found = spec_beside(world_path)
    if found is None or found[1].robot is None:
        return None
    robot = found[1].robot
    return (robot.at[0], robot.at[1], 0.0, robot.yaw)
