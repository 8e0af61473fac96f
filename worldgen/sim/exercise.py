"""``worldgen drive`` as a simulator job: the spin or the stop-at-wall exercise in a scene, once per gain set,
each in a fresh session from the same spawn pose.

What the command asks for is one value, :class:`Exercise`, built once by the command and passed down; it
crosses into the child process as a dict (:meth:`Exercise.to_dict`, :meth:`Exercise.from_dict`).
:func:`drive_exercise` takes a pickled scene (:func:`worldgen.check.sources.run_on_scene` hands it over) and
that dict, and returns plain values, so that it runs in a child process.
"""

from __future__ import annotations

import math
import time
from dataclasses import asdict, dataclass
from typing import Optional, Tuple

from ..core import stoplaw
from ..core.numbers import format_number
from ..core.scene import Scene
from ..geometry.placement import checked_spawn, deepest_point, robot_radius, spawn_problem, world_rooms

BEHAVIOURS = ("spin", "stop-at-wall")
SETTLE_SECONDS = 0.5   # the robot comes to rest on its wheels and caster before each run
STOP_DURATION = 30.0   # s of stop-at-wall when no duration is given (a spin's default is one full turn)


@dataclass(frozen=True)
class Gains:
    """One gain set of the stop-at-wall law (one run)."""

    kp: float = stoplaw.KP
    ki: float = 0.0
    kd: float = 0.0


@dataclass(frozen=True)
class Exercise:
    """What ``worldgen drive`` asks of the simulator, as a value.

    Robot and spawn pose (x, y, yaw): None takes the spec's ``robot`` entry, else burger at the origin.
    ``gains``: one stop-at-wall run each (a spin runs once). ``duration`` None: 30 s for stop-at-wall, one full
    turn for spin. ``front_angle`` (degrees) is the half-width of the cone whose nearest beam is the front
    distance; ``stop_band`` (m) how near the target the law stops and holds (:mod:`worldgen.core.stoplaw`);
    ``band`` the settling band, ``tolerance`` how near the target a run must end. ``record_scans``: each run's
    series also has ``scan`` and the result ``lidar``, the beam layout, for a replay page.
    """

    behaviour: str = "stop-at-wall"
    robot: Optional[str] = None
    spawn: Optional[Tuple[float, float, float]] = None
    gains: Tuple[Gains, ...] = (Gains(),)
    target: float = stoplaw.TARGET
    duration: Optional[float] = None
    max_speed: float = stoplaw.MAX_SPEED
    omega: float = 1.0
    rate: float = 5.0
    front_angle: float = stoplaw.FRONT_ANGLE
    no_hit: str = "inf"
    tolerance: float = 0.05
    band: float = 0.02
    seed: int = 0
    stop_band: float = stoplaw.STOP_BAND
    record_scans: bool = False

    def __post_init__(self):
        if self.behaviour not in BEHAVIOURS:
            raise ValueError(f"behaviour must be one of {BEHAVIOURS}, not {self.behaviour!r}")

    def to_dict(self) -> dict:
        """The exercise as JSON-able values (what the child process gets)."""
        return asdict(self)

    @classmethod
    def from_dict(cls, data: dict) -> "Exercise":
        """The exercise :meth:`to_dict` gave (lists where it had tuples)."""
        spawn = data.get("spawn")
        return cls(**{**data, "spawn": None if spawn is None else tuple(float(v) for v in spawn),
                      "gains": tuple(Gains(**g) for g in data.get("gains", [asdict(Gains())]))})

    def law(self, gains: Gains) -> stoplaw.StopLaw:
        """The stop-at-wall law of one gain set."""
        return stoplaw.StopLaw(target=self.target, kp=gains.kp, ki=gains.ki, kd=gains.kd, max_speed=self.max_speed,
                               stop_band=self.stop_band)


def drive_exercise(scene_file: str, world: str, exercise: dict, spec_robot: dict | None = None) -> dict:
    """Run the :class:`Exercise` ``exercise`` (as :meth:`Exercise.to_dict` gives it) in the scene pickled in
    ``scene_file`` (read from ``world``, with the robot entry ``spec_robot`` of the spec it came from, if any)
    and return what happened: the robot and spawn pose used (and where they came from), one result per gain
    set (spin: one run), simulated and wall-clock seconds (and ``lidar``, the beam layout
    (:func:`~worldgen.sim.lidar.lidar_info`; None without a LiDAR), when it records scans).

    A spawn inside a wall or an obstacle, closer to one than the robot's radius or outside the room is an
    InputError.
    """
    from .behaviours import settle, spin, stop_at_wall   # pybullet: only the child process needs it
    from .lidar import lidar_info
    from .session import Session

    ask = Exercise.from_dict(exercise)
    started = time.perf_counter()
    scene = Scene.load(scene_file)
    robot_used = ask.robot or (spec_robot or {}).get("model") or "burger"
    if ask.spawn is not None:
        spawn_used, spawn_source = list(ask.spawn), "--spawn"
    elif spec_robot is not None:
        spawn_used, spawn_source = [float(v) for v in spec_robot["spawn"]], "the spec's robot entry"
    else:
        spawn_used, spawn_source = [0.0, 0.0, 0.0], "the world's origin"
    _check_spawn(scene, robot_used, spawn_used, spawn_source, world)
    runs, sim_seconds, lidar = [], 0.0, None
    for gains in ask.gains if ask.behaviour == "stop-at-wall" else [None]:
        with Session(scene, robot_used, spawn_used, no_hit=ask.no_hit, seed=ask.seed) as session:
            rest = settle(session, SETTLE_SECONDS)
            if gains is None:
                result = spin(session, seconds=ask.duration or 2 * math.pi / abs(ask.omega or 1.0),
                              omega=ask.omega, record_scans=ask.record_scans)
            else:
                result = stop_at_wall(session, ask.law(gains), duration=ask.duration or STOP_DURATION,
                                      rate=ask.rate, half_angle=math.radians(ask.front_angle), band=ask.band,
                                      tolerance=ask.tolerance, record_scans=ask.record_scans)
            runs.append({**result.to_dict(), "settle": rest.to_dict()})
            sim_seconds += session.t
            lidar = lidar_info(session.lidar) if session.lidar is not None else None
    done = {"world": world, "behaviour": ask.behaviour, "robot": robot_used, "spawn": spawn_used,
            "spawn_source": spawn_source, "scene_findings": [f.to_dict() for f in scene.findings],
            "runs": runs, "sim_seconds": sim_seconds, "wall_seconds": time.perf_counter() - started}
    if ask.record_scans:
        done["lidar"] = lidar
    return done


def _check_spawn(scene: Scene, robot: str, spawn: list[float], source: str, world: str) -> None:
    """InputError when ``spawn`` is inside a wall or an obstacle, closer to one than the robot's radius, or
    outside the world's room (as ``worldgen launch`` refuses it), with the room's deepest point as a hint."""
    rooms = world_rooms(scene, robot_radius(robot))
    if spawn_problem(rooms, spawn[0], spawn[1]) is None:
        return
    point = deepest_point(rooms)
    hint = "pass --spawn X,Y: a free point inside the room"
    if point is not None:
        hint += f", e.g. --spawn {format_number(point[0])},{format_number(point[1])} (the deepest one)"
    checked_spawn(rooms, spawn[:2], source=world, what=source, hint=hint)
