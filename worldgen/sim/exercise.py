"""``worldgen drive`` as a simulator job: the spin or the stop-at-wall exercise in a scene, once per gain set,
each in a fresh session from the same spawn pose.

:func:`drive_exercise` takes a pickled scene (:func:`worldgen.check.sources.run_on_scene` hands it over) and
plain JSON-able values, and returns plain values, so that it runs in a child process.
"""

from __future__ import annotations

import math
import time

from ..core import stoplaw
from ..core.scene import Scene

BEHAVIOURS = ("spin", "stop-at-wall")
SETTLE_SECONDS = 0.5   # the robot comes to rest on its wheels and caster before each run
STOP_DURATION = 30.0   # s of stop-at-wall when no duration is given (a spin's default is one full turn)


def drive_exercise(scene_file: str, world: str, spec_robot: dict | None = None, behaviour: str = "stop-at-wall", robot: str | None = None,
                   spawn: list[float] | None = None, gains: list[dict] | None = None, target: float = 0.5,
                   duration: float | None = None, max_speed: float = 0.22, omega: float = 1.0, rate: float = 5.0,
                   front_angle: float = 10.0, no_hit: str = "inf", tolerance: float = 0.05, band: float = 0.02,
                   seed: int = 0, stop_band: float | None = None, record_scans: bool = False) -> dict:
    """Run ``behaviour`` in the scene pickled in ``scene_file`` (read from ``world``, with the robot entry
    ``spec_robot`` of the spec it came from, if any) and return what happened: the robot and spawn pose used (and where they
    came from), one result per gain set (spin: one run), simulated and wall-clock seconds.

    Robot and spawn pose: the arguments when given, else the spec's ``robot`` entry, else burger at the origin; a
    spawn inside a wall or an obstacle, closer to one than the robot's radius or outside the room is an
    InputError.
    ``front_angle`` (degrees) is the half-width of the cone whose nearest beam is the front distance;
    ``stop_band`` (m) how near the target the law stops and holds (:mod:`worldgen.core.stoplaw`).
    ``record_scans``: each run's series also has ``scan`` (see :func:`~worldgen.sim.behaviours.stop_at_wall`)
    and the result ``lidar``, the beam layout (:func:`~worldgen.sim.lidar.lidar_info`; None without a LiDAR).
    """
    from .behaviours import settle, spin, stop_at_wall
    from .lidar import lidar_info
    from .session import Session

    if behaviour not in BEHAVIOURS:
        raise ValueError(f"behaviour must be one of {BEHAVIOURS}, not {behaviour!r}")
    started = time.perf_counter()
    scene = Scene.load(scene_file)
    robot_used = robot or (spec_robot or {}).get("model") or "burger"
    if spawn is not None:
        spawn_used, spawn_source = [float(v) for v in spawn], "--spawn"
    elif spec_robot is not None:
        spawn_used, spawn_source = [float(v) for v in spec_robot["spawn"]], "the spec's robot entry"
    else:
        spawn_used, spawn_source = [0.0, 0.0, 0.0], "the world's origin"
    _check_spawn(scene, robot_used, spawn_used, spawn_source, world)
    runs, sim_seconds, lidar = [], 0.0, None
    for gain in (gains or [{"kp": 0.5, "ki": 0.0, "kd": 0.0}]) if behaviour == "stop-at-wall" else [{}]:
        with Session(scene, robot_used, spawn_used, no_hit=no_hit, seed=seed) as session:
            rest = settle(session, SETTLE_SECONDS)
            if behaviour == "spin":
                result = spin(session, seconds=duration or 2 * math.pi / abs(omega or 1.0), omega=omega,
                              record_scans=record_scans)
            else:
                result = stop_at_wall(session, target=target, kp=gain.get("kp", 0.0), ki=gain.get("ki", 0.0),
                                      kd=gain.get("kd", 0.0), duration=duration or STOP_DURATION,
                                      max_speed=max_speed, rate=rate, half_angle=math.radians(front_angle),
                                      band=band, tolerance=tolerance,
                                      stop_band=stoplaw.STOP_BAND if stop_band is None else stop_band,
                                      record_scans=record_scans)
            runs.append({**result.to_dict(), "settle": rest.to_dict()})
            sim_seconds += session.t
            lidar = lidar_info(session.lidar) if session.lidar is not None else None
    done = {"world": world, "behaviour": behaviour, "robot": robot_used, "spawn": spawn_used,
            "spawn_source": spawn_source, "scene_findings": [f.to_dict() for f in scene.findings],
            "runs": runs, "sim_seconds": sim_seconds, "wall_seconds": time.perf_counter() - started}
    if record_scans:
        done["lidar"] = lidar
    return done


def _check_spawn(scene: Scene, robot: str, spawn: list[float], source: str, world: str) -> None:
    """InputError when ``spawn`` is inside a wall or an obstacle, closer to one than the robot's radius, or
    outside the world's room (as ``worldgen launch`` refuses it), with the room's deepest point as a hint."""
    from ..core.numbers import format_number
    from ..geometry.placement import checked_spawn, deepest_point, robot_radius, spawn_problem, world_rooms

    rooms = world_rooms(scene, robot_radius(robot))
    if spawn_problem(rooms, spawn[0], spawn[1]) is None:
        return
    point = deepest_point(rooms)
    hint = "pass --spawn X,Y: a free point inside the room"
    if point is not None:
        hint += f", e.g. --spawn {format_number(point[0])},{format_number(point[1])} (the deepest one)"
    checked_spawn(rooms, spawn[:2], source=world, what=source, hint=hint)
