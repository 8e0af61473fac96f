"""The class's exercises, run on a :class:`~worldgen.sim.session.Session`: stand still, spin in place, and the
sensory-motor loop "stop at a wall" with P/PI/PID gains. Each returns a plain result object (``to_dict`` for
JSON) with the numbers a check or a student looks at.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

from ..core import stoplaw
from .lidar import front_distance, scan_row
from .session import Session

UPRIGHT_TILT = math.radians(10)   # roll or pitch beyond this: the robot fell over or is stuck on something
STOPPED_SPEED = 0.02              # m/s: slower than this through the last second counts as stopped
STILL_SPEED = 0.001               # m/s and rad/s: a holding robot slower than this, turning slower than this,
STILL_DRIFT = 0.001               # m: and within this of where it came to rest is still (see stop_at_wall)
SCAN_RECORD_RATE = 5.0            # Hz: at most this many scans a simulated second recorded for a replay


@dataclass
class SettleResult:
    upright: bool
    roll: float
    pitch: float
    z: float             # base frame height above the ground plane z = 0
    drift: float         # how far the base frame slid while standing
    contacts: list[dict]

    def to_dict(self) -> dict:
        return dict(self.__dict__)


def settle(session: Session, seconds: float = 1.0) -> SettleResult:
    """Stand still for ``seconds`` (zero command) and say whether the robot rests upright on the ground."""
    start = session.odometry()
    session.cmd_vel(0.0, 0.0)
    session.start_exercise()
    session.run(seconds)
    end = session.odometry()
    return SettleResult(upright=abs(end.roll) < UPRIGHT_TILT and abs(end.pitch) < UPRIGHT_TILT,
                        roll=end.roll, pitch=end.pitch, z=end.z,
                        drift=math.hypot(end.x - start.x, end.y - start.y), contacts=session.touches.to_list())


@dataclass
class SpinResult:
    omega: float
    seconds: float
    turned: float        # yaw turned in total (rad, unwrapped)
    drift: float         # final distance of the base frame from where it started
    max_drift: float
    drift_limit: float   # the most max_drift may be for the run to count as spinning in place
    contacts: list[dict]
    series: dict[str, list] = field(default_factory=dict)   # t, x, y, yaw, drift, w_cmd (and scan: see spin)
    start_t: float = 0.0   # the session's time when the series' t is 0 (contacts' times are the session's)

    @property
    def ok(self) -> bool:
        return self.max_drift <= self.drift_limit and not self.contacts

    def to_dict(self) -> dict:
        return {**self.__dict__, "ok": self.ok}


def spin(session: Session, seconds: float = 2 * math.pi, omega: float = 1.0, sample_rate: float = 30.0,
         drift_limit: float = 0.05, record_scans: bool = False) -> SpinResult:
    """Turn in place at ``omega`` rad/s for ``seconds``, then command a stop and let it come to rest
    (0.5 s). A diff-drive robot turns about the midpoint of its wheels, so the base frame should stay put.
    ``record_scans`` (and a LiDAR): the series also has ``scan``, as :func:`stop_at_wall`'s."""
    start = session.odometry()
    session.start_exercise()
    series: dict[str, list] = {"t": [], "x": [], "y": [], "yaw": [], "drift": [], "w_cmd": []}
    every = _scan_every(sample_rate) if record_scans and session.lidar is not None else 0
    if every:
        series["scan"] = []
    turned, last_yaw, max_drift = 0.0, start.yaw, 0.0
    session.cmd_vel(0.0, omega)
    period = 1.0 / sample_rate
    steps = max(1, round(seconds / period))
    for i in range(steps + round(0.5 / period)):
        if i == steps:
            session.cmd_vel(0.0, 0.0)
        session.run(period)
        o = session.odometry()
        turned += math.remainder(o.yaw - last_yaw, math.tau)
        last_yaw = o.yaw
        drift = math.hypot(o.x - start.x, o.y - start.y)
        max_drift = max(max_drift, drift)
        for key, value in (("t", o.t - start.t), ("x", o.x), ("y", o.y), ("yaw", o.yaw), ("drift", drift),
                           ("w_cmd", omega if i < steps else 0.0)):
            series[key].append(value)
        if every:
            series["scan"].append(scan_row(session.scan()) if i % every == 0 else None)
    return SpinResult(omega=omega, seconds=seconds, turned=turned, drift=series["drift"][-1], max_drift=max_drift,
                      drift_limit=drift_limit, contacts=session.touches.to_list(), series=series, start_t=start.t)


@dataclass
class StopAtWallResult:
    """One run of the stop-at-wall loop. Distances are the LiDAR's front distance from ``base_scan``; the
    ``true`` series is the exact one (no noise), ``measured`` what the controller saw."""

    target: float
    kp: float
    ki: float
    kd: float
    final_distance: float | None      # true front distance at the end
    min_distance: float | None        # closest true approach
    overshoot: float                  # how far the closest approach went below the target (≥ 0)
    steady_state_error: float | None  # final − target
    settling_time: float | None       # from the start until the distance stays within ±band of its final value
    band: float
    stop_band: float                  # the law stops (and holds) once within this of the target
    stop_time: float | None           # when the law last stopped and began to hold (None: it never did)
    stopped: bool                     # holding at the end, and |v| < STOPPED_SPEED over the last second
    within_tolerance: bool            # |final − target| ≤ tolerance
    tolerance: float
    contacts: list[dict]
    series: dict[str, list] = field(default_factory=dict)   # t, measured, true, v_cmd, v, x, y, yaw (, scan)
    start_t: float = 0.0   # the session's time when the series' t is 0 (contacts' times are the session's)

    @property
    def ok(self) -> bool:
        return self.stopped and self.within_tolerance and not self.contacts

    def to_dict(self) -> dict:
        return {**self.__dict__, "ok": self.ok}


@dataclass(frozen=True)
class Ending:
    """When a :func:`stop_at_wall` run ends: after ``seconds``, or sooner once the law has held, with the robot
    still (slower than :data:`STILL_SPEED`, within :data:`STILL_DRIFT` of where it came to rest), for ``still``
    seconds (None: never sooner). In a world where nothing else moves, the rest of the run would only let it
    creep (a resting robot's wheels slip by a few tenths of a millimetre a second), far less than any
    tolerance."""

    seconds: float
    still: float | None = None


def stop_at_wall(session: Session, law: stoplaw.StopLaw | None = None, duration: float | Ending = 15.0,
                 rate: float = 5.0, half_angle: float = math.radians(stoplaw.FRONT_ANGLE), band: float = 0.02,
                 tolerance: float = 0.05, record_scans: bool = False) -> StopAtWallResult:
    """Drive toward whatever is ahead and stop ``law.target`` m from it, exactly as the generated
    ``stop_at_wall.py`` node does: ``law`` (:class:`worldgen.core.stoplaw.StopLaw`, its parameters; a fresh copy
    keeps the memory, default the class's law) at ``rate`` Hz (the LiDAR's 5 Hz, or 30) reads the front distance
    (nearest beam within ±``half_angle``; None when nothing is seen there) and commands
    ``v = clamp(kp·e + ki·∫e dt + kd·de/dt, 0, max_speed)`` with ``e = front − target``; nothing seen: full
    speed; once within ``stop_band`` of the target: stop and hold, so LiDAR noise cannot start it again. It never
    reverses. ``band`` is the settling-time band around the final distance, ``tolerance`` how close to the
    target the run must end.

    The series has one sample per control step and one for the state at the end: ``t`` (s from the start),
    ``measured`` and ``true`` front distances, ``v_cmd``, ``v``, and the base frame's world ``x``, ``y``, ``yaw``.
    ``record_scans`` adds ``scan``: the scan the controller saw, as :func:`~worldgen.sim.lidar.scan_row`, at
    most :data:`SCAN_RECORD_RATE` a second (None at the samples between) and always at the end. ``duration``
    (s) may be an :class:`Ending`, which may end the run sooner."""
    if session.lidar is None:
        session.scan()   # raises the "no LiDAR" error
    period = 1.0 / rate
    start_t = session.t
    session.start_exercise()
    series: dict[str, list] = {"t": [], "measured": [], "true": [], "v_cmd": [], "v": [], "x": [], "y": [],
                               "yaw": []}
    every = _scan_every(rate) if record_scans else 0
    if every:
        series["scan"] = []
    law = replace(law or stoplaw.StopLaw(), holding=False, integral=0.0, last_error=None)
    stop_time = None
    ending = duration if isinstance(duration, Ending) else Ending(duration)
    still = _Stillness(ending.still)
    for step in range(max(1, round(ending.seconds / period))):
        scan = session.scan()
        measured = front_distance(scan, half_angle)
        true = front_distance(scan, half_angle, true=True)
        was_holding = law.holding
        v_cmd = law.step(measured, period if step else 0.0)
        if law.holding and not was_holding:
            stop_time = session.t - start_t
        elif not law.holding:
            stop_time = None
        odom = session.odometry()
        for key, value in (("t", session.t - start_t), ("measured", measured), ("true", true), ("v_cmd", v_cmd),
                           ("v", odom.v), ("x", odom.x), ("y", odom.y), ("yaw", odom.yaw)):
            series[key].append(value)
        if every:
            series["scan"].append(scan_row(scan) if step % every == 0 else None)
        if still.long_enough(law.holding, odom):
            break
        session.cmd_vel(v_cmd, 0.0)
        session.run(period)
    scan = session.scan()   # the state at the end; the last command still holds
    final = front_distance(scan, half_angle, true=True)
    odom = session.odometry()
    for key, value in (("t", session.t - start_t), ("measured", front_distance(scan, half_angle)),
                       ("true", final), ("v_cmd", session.drive.command[0]), ("v", odom.v), ("x", odom.x),
                       ("y", odom.y), ("yaw", odom.yaw)):
        series[key].append(value)
    if every:
        series["scan"].append(scan_row(scan))
    trues = [d for d in series["true"] if d is not None]
    nearest = min(trues) if trues else None
    last_second = series["v"][-(round(rate) + 1):]
    target = law.target
    return StopAtWallResult(
        target=target, kp=law.kp, ki=law.ki, kd=law.kd, final_distance=final, min_distance=nearest,
        overshoot=max(0.0, target - nearest) if nearest is not None else 0.0,
        steady_state_error=final - target if final is not None else None,
        settling_time=_settling_time(series["t"], series["true"], final, band) if final is not None else None,
        band=band, stop_band=law.stop_band, stop_time=stop_time,
        stopped=law.holding and all(abs(v) < STOPPED_SPEED for v in last_second),
        within_tolerance=final is not None and abs(final - target) <= tolerance, tolerance=tolerance,
        contacts=session.touches.to_list(), series=series, start_t=start_t)


class _Stillness:
    """Whether a holding robot has been still for ``seconds`` (None: never asked to end early)."""

    def __init__(self, seconds: float | None):
        self.seconds, self.since, self.at = seconds, None, None

    def long_enough(self, holding: bool, odom) -> bool:
        if self.seconds is None:
            return False
        still = holding and abs(odom.v) < STILL_SPEED and abs(odom.omega) < STILL_SPEED
        if still and self.at is not None and math.hypot(odom.x - self.at[0], odom.y - self.at[1]) > STILL_DRIFT:
            still = False
        if not still:
            self.since, self.at = None, None
            return False
        if self.since is None:
            self.since, self.at = odom.t, (odom.x, odom.y)
        return odom.t - self.since >= self.seconds - 1e-9


def _scan_every(rate: float) -> int:
    """Record every how many samples taken at ``rate`` Hz so as to keep at most :data:`SCAN_RECORD_RATE` a
    second."""
    return max(1, math.ceil(rate / SCAN_RECORD_RATE - 1e-9))


def _settling_time(times: list[float], values: list, final: float, band: float) -> float | None:
    """The first time after which every value stays within ``final ± band`` (the control-textbook settling
    time: measured against the value the response settles at, so a P controller's offset does not hide it)."""
    settled = None
    for t, d in zip(times, values):
        inside = d is not None and abs(d - final) <= band
        if not inside:
            settled = None
        elif settled is None:
            settled = t
    return settled
