"""``worldgen drive`` as a library job: read a world (or build one from a spec), then run the spin or the
stop-at-wall exercise once per gain set, each in a fresh session from the same spawn pose.

:func:`drive_exercise` takes and returns plain JSON-able values so that it can run in a child process
(``run_isolated("worldgen.sim.exercise:drive_exercise", kwargs)``).
"""

from __future__ import annotations

import math
import time

from ..scene import Scene

BEHAVIOURS = ("spin", "stop-at-wall")
SETTLE_SECONDS = 0.5   # the robot comes to rest on its wheels and caster before each run
STOP_DURATION = 20.0   # s of stop-at-wall when no duration is given (a spin's default is one full turn)


def load_world(path: str, kind: str = "world", model_paths=()) -> tuple[Scene, dict | None]:
    """The scene of a world file, or of the world a spec builds (``kind`` "spec"), and the spec's robot entry
    ({"model", "spawn"}) when it has one."""
    from ..sdf.reader import read_world, read_world_text

    if kind != "spec":
        return read_world(path, model_paths=tuple(model_paths)), None
    from ..sdf.writer import spec_world_sdf
    from ..spec import load_spec

    spec = load_spec(path)
    scene = read_world_text(spec_world_sdf(spec), source=spec.source or path,
                            model_paths=tuple(model_paths))
    robot = None
    if spec.robot is not None:
        robot = {"model": spec.robot.model, "spawn": [spec.robot.at[0], spec.robot.at[1], spec.robot.yaw]}
    return scene, robot


def drive_exercise(world: str, kind: str = "world", behaviour: str = "stop-at-wall", robot: str | None = None,
                   spawn: list[float] | None = None, gains: list[dict] | None = None, target: float = 0.5,
                   duration: float | None = None, max_speed: float = 0.22, omega: float = 1.0, rate: float = 5.0,
                   front_angle: float = 10.0, no_hit: str = "inf", tolerance: float = 0.05, band: float = 0.02,
                   model_paths=(), seed: int = 0) -> dict:
    """Run ``behaviour`` in ``world`` and return what happened: the robot and spawn pose used (and where they
    came from), one result per gain set (spin: one run), simulated and wall-clock seconds.

    Robot and spawn pose: the arguments when given, else the spec's ``robot`` entry, else burger at the origin; a
    spawn inside a wall or an obstacle, closer to one than the robot's radius or outside the room is an
    InputError.
    ``front_angle`` (degrees) is the half-width of the cone whose nearest beam is the front distance.
    """
    from .behaviours import settle, spin, stop_at_wall
    from .session import Session

    if behaviour not in BEHAVIOURS:
        raise ValueError(f"behaviour must be one of {BEHAVIOURS}, not {behaviour!r}")
    started = time.perf_counter()
    scene, spec_robot = load_world(world, kind, model_paths)
    robot_used = robot or (spec_robot or {}).get("model") or "burger"
    if spawn is not None:
        spawn_used, spawn_source = [float(v) for v in spawn], "--spawn"
    elif spec_robot is not None:
        spawn_used, spawn_source = [float(v) for v in spec_robot["spawn"]], "the spec's robot entry"
    else:
        spawn_used, spawn_source = [0.0, 0.0, 0.0], "the world's origin"
    _check_spawn(scene, robot_used, spawn_used, spawn_source, world)
    runs, sim_seconds = [], 0.0
    for gain in (gains or [{"kp": 0.5, "ki": 0.0, "kd": 0.0}]) if behaviour == "stop-at-wall" else [{}]:
        with Session(scene, robot_used, spawn_used, no_hit=no_hit, seed=seed) as session:
            rest = settle(session, SETTLE_SECONDS)
            if behaviour == "spin":
                result = spin(session, seconds=duration or 2 * math.pi / abs(omega or 1.0), omega=omega)
            else:
                result = stop_at_wall(session, target=target, kp=gain.get("kp", 0.0), ki=gain.get("ki", 0.0),
                                      kd=gain.get("kd", 0.0), duration=duration or STOP_DURATION,
                                      max_speed=max_speed, rate=rate, half_angle=math.radians(front_angle),
                                      band=band, tolerance=tolerance)
            runs.append({**result.to_dict(), "settle": rest.to_dict()})
            sim_seconds += session.t
    return {"world": world, "behaviour": behaviour, "robot": robot_used, "spawn": spawn_used,
            "spawn_source": spawn_source, "scene_findings": [f.to_dict() for f in scene.findings],
            "runs": runs, "sim_seconds": sim_seconds, "wall_seconds": time.perf_counter() - started}


def _check_spawn(scene: Scene, robot: str, spawn: list[float], source: str, world: str) -> None:
    """InputError when ``spawn`` is inside a wall or an obstacle, closer to one than the robot's radius, or
    outside the world's room (as ``worldgen launch`` refuses it), with the room's deepest point as a hint."""
    from ..launch import format_number
    from ..spawn import checked_spawn, deepest_point, robot_radius, spawn_problem, world_rooms

    rooms = world_rooms(scene, robot_radius(robot))
    if spawn_problem(rooms, spawn[0], spawn[1]) is None:
        return
    point = deepest_point(rooms)
    hint = "pass --spawn X,Y: a free point inside the room"
    if point is not None:
        hint += f", e.g. --spawn {format_number(point[0])},{format_number(point[1])} (the deepest one)"
    checked_spawn(rooms, spawn[:2], source=world, what=source, hint=hint)
