"""``worldgen validate``'s simulated checks as one job: spawn the robot in the scene, let it settle, take a
360-beam scan, spin in place, then stop at the wall ahead; what it measured comes back as a
:class:`~worldgen.check.sim_results.SimNumbers` record, which :func:`worldgen.check.checks.sim_findings` judges.

:func:`simulate` is what the validating process starts in a child (``run_isolated(
"worldgen.check.sim_job:simulate", kwargs)``). The parent hands over the scene it already read, pickled into
its own private temporary folder, so the simulator drives in exactly the scene the geometric checks looked at;
or, to start before the parent has read it, the child reads the same world itself and says what it read
(:func:`scene_digest`), for the parent to check. :func:`sim_numbers` is the same job on a scene in this process.
"""

from __future__ import annotations

import hashlib
import math
import pickle
import time
from pathlib import Path

from ..core.scene import Scene
from ..core.stoplaw import StopLaw
from ..robots.profile import robot_profile
from .sim_results import Scanned, Settled, SimNumbers, Spun, Stopped, touches

SETTLE_SECONDS = 1.0
STOP_TARGET = 0.5           # m: stop-at-wall drives to this distance from the wall ahead
SPIN_OMEGA = 1.5            # rad/s: within both the burger's (2.84) and the waffle's (1.82) limits
STOP_KP = 1.0
STOP_SPEED = 0.22           # m/s: the burger's top speed
FACE_TOLERANCE = math.radians(2)
WHOLE_UP_TO = 2000          # shapes: a world with more is simulated with only what is in reach (in_reach)
REACH_MARGIN = 1.0          # m: the robot's own size, and what settling and spinning in place may move it
STILL_TO_JUDGE = 1.0        # s: stop-at-wall ends once the robot has held still this long (nothing changes after)


def simulate(scene_file: str | None = None, robot: str = "burger", spawn: list[float] = (0.0, 0.0, 0.0),
             no_hit: str = "inf", stage_file: str | None = None, urdf: str | None = None,
             world: dict | None = None) -> dict:
    """The job in a child process: :func:`sim_numbers` on the scene pickled in ``scene_file`` (written by the
    parent into its own temporary folder), with the robot's URDF text when the parent has processed it; the
    record as JSON-able values (:meth:`SimNumbers.to_dict`).

    With ``world`` instead ({"path", "text" (a spec's SDF, or None), "model_paths"}, a
    :class:`~worldgen.check.sources.WorldSource`) the child reads the world itself, while the parent reads it
    too, and adds ``scene_digest`` (:func:`scene_digest` of what it read): the parent compares it with its own
    scene's, and simulates its own scene after all when they differ (the file changed between the reads)."""
    if scene_file is not None:
        return sim_numbers(Scene.load(scene_file), robot, spawn, no_hit, stage_file, urdf).to_dict()
    from .sources import WorldSource

    _write_stage(stage_file, "reading the world")
    scene = WorldSource(Path(world["path"]), world.get("text")).read(world.get("model_paths", ()))
    numbers = sim_numbers(scene, robot, spawn, no_hit, stage_file, urdf).to_dict()
    numbers["scene_digest"] = scene_digest(scene)
    return numbers


def scene_digest(scene: Scene) -> str:
    """A digest of everything in ``scene`` (its pickle, as :meth:`Scene.save` writes it)."""
    return hashlib.sha256(pickle.dumps(scene, protocol=pickle.HIGHEST_PROTOCOL)).hexdigest()


def _write_stage(stage_file: str | None, text: str) -> None:
    if stage_file:
        with open(stage_file, "w", encoding="utf-8") as fh:
            fh.write(text)


def sim_numbers(scene: Scene, robot: str = "burger", spawn=(0.0, 0.0, 0.0), no_hit: str = "inf",
                stage_file: str | None = None, urdf: str | None = None) -> SimNumbers:
    """Run the simulated checks on ``scene`` and return what they measured.

    Spawns ``robot`` at ``spawn`` (x, y, yaw), lets it settle, takes a 360-beam scan, spins in place, then drives
    to :data:`STOP_TARGET` from the nearest wall ahead (turning to face the nearest wall first
    when nothing is within range ahead). Each stage is written to ``stage_file`` before it starts, so that a
    crash can be reported as "while <stage>".
    """
    from ..sim.behaviours import settle, spin   # pybullet: only the child process needs it
    from ..sim.session import Session

    def stage(text: str) -> None:
        _write_stage(stage_file, text)

    started = time.perf_counter()
    if urdf is not None:
        scene = in_reach(scene, spawn, urdf)
    stage("loading the world and the robot")
    ran, failed, scanned, stopped = [], {}, None, None
    with Session(scene, robot, tuple(spawn), no_hit=no_hit, urdf=urdf) as session:
        stage("letting the robot settle")
        rest = settle(session, SETTLE_SECONDS)
        ran.append("settle")
        settled = Settled(time=SETTLE_SECONDS, z=rest.z, moved=rest.drift,
                          tilt_deg=math.degrees(max(abs(rest.roll), abs(rest.pitch))),
                          contact_points=touches(rest.contacts))
        ran.append("lidar")
        if session.lidar is None:
            failed["lidar"] = "the robot has no LiDAR (no ray sensor and no base_scan link)"
        else:
            stage("scanning with the LiDAR")
            scanned = _scan_numbers(session.scan())
        stage("spinning in place")
        turn = spin(session, seconds=2 * math.pi / SPIN_OMEGA, omega=SPIN_OMEGA)
        ran.append("spin")
        spun = Spun(drift=turn.max_drift, turned=turn.turned, touched=_touched(turn.contacts),
                    contact_points=touches(turn.contacts))
        if session.lidar is not None:
            stage("driving to the wall")
            stopped = _stop_at_wall(session)
            ran.append("stop-at-wall")
        sim_seconds = session.t
    numbers = SimNumbers(ran=tuple(ran), failed=failed, settle=settled, lidar=scanned, spin=spun, stop=stopped,
                         sim_seconds=sim_seconds, wall_seconds=time.perf_counter() - started)
    stage("done")
    return numbers


def stop_seconds(range_max: float) -> float:
    """The longest stop-at-wall run: long enough to cross the whole LiDAR range (what is ahead may change as the
    robot passes obstacles)."""
    return (range_max - STOP_TARGET) / STOP_SPEED + 10.0


def reach(urdf: str) -> float:
    """How far from its spawn (horizontally) anything can touch the robot or meet its LiDAR during the job: the
    farthest stop-at-wall can drive it, at :data:`STOP_SPEED` for :func:`stop_seconds`, then the LiDAR's range,
    and :data:`REACH_MARGIN` for the robot's own size and what settling and spinning in place may move it."""
    lidar = robot_profile(urdf).lidar
    if lidar is None:   # no stop-at-wall: settle and spin in place
        return REACH_MARGIN
    return STOP_SPEED * stop_seconds(lidar.range_max) + lidar.range_max + REACH_MARGIN


def in_reach(scene: Scene, spawn, urdf: str) -> Scene:
    """``scene`` as the job simulates it from ``spawn``: whole, up to :data:`WHOLE_UP_TO` shapes; past that, only
    the shapes within :func:`reach` (a grid of thousands of cells then loads and steps as fast as a room).
    Loading fewer shapes groups them into other compound bodies, which moves the simulated numbers by about
    1e-5 m and can tip a robot spawned inside a wall from one outcome to the other, so worlds of a usual size
    are simulated whole, exactly as before."""
    if len(scene.shapes) <= WHOLE_UP_TO:
        return scene
    return scene.around(spawn[0], spawn[1], reach(urdf))


def _scan_numbers(scan) -> Scanned:
    from ..sim.lidar import front_distance   # pybullet: only the child process needs it

    true = scan.true_ranges
    hits = [(r, i) for i, r in enumerate(true) if math.isfinite(r)]
    misses = [i for i, r in enumerate(true) if not math.isfinite(r)]
    nearest = min(hits) if hits else None
    return Scanned(beams=len(true), no_hit=len(misses), range_max=scan.range_max,
                   no_hit_reading=scan.ranges[misses[0]] if misses else None,
                   no_hit_bearings_deg=tuple(math.degrees(scan.angle_min + i * scan.angle_increment)
                                             for i in misses[:1]),
                   nearest=nearest[0] if nearest else None,
                   nearest_bearing_deg=math.degrees(scan.angle_min + nearest[1] * scan.angle_increment)
                   if nearest else None,
                   farthest=max(hits)[0] if hits else None,
                   front_no_hit=front_distance(scan, true=True) is None,
                   ranges_sample=tuple(scan.ranges[i] for i in range(0, len(scan.ranges), 90)))


def _touched(contacts: list[dict]) -> tuple[str, ...]:
    return tuple(sorted({c["shape"] for c in contacts}))


def _stop_at_wall(session) -> Stopped:
    """Face the nearest wall when nothing is in range straight ahead, then run the P controller to the target."""
    from ..sim.behaviours import Ending, stop_at_wall   # pybullet: only the child process needs it
    from ..sim.lidar import front_distance

    scan = session.scan(noise=False)
    ahead = front_distance(scan, true=True)
    turned = False
    if ahead is None:
        hits = [(r, i) for i, r in enumerate(scan.true_ranges) if math.isfinite(r)]
        if not hits:
            return Stopped(no_wall=True, range=scan.range_max)
        _, i = min(hits)
        _face(session, scan.angle_min + i * scan.angle_increment)
        turned = True
        ahead = front_distance(session.scan(noise=False), true=True)
        if ahead is None:
            return Stopped(no_wall=True, range=scan.range_max)
    duration = stop_seconds(scan.range_max)
    start_t = session.t
    run = stop_at_wall(session, StopLaw(target=STOP_TARGET, kp=STOP_KP, max_speed=STOP_SPEED),
                       duration=Ending(duration, still=STILL_TO_JUDGE))
    return Stopped(distance=run.final_distance, touched=_touched(run.contacts),
                   contact_points=touches(run.contacts), time=session.t - start_t, start_distance=ahead,
                   turned_to_face=turned, overshoot=run.overshoot,
                   heading_deg=math.degrees(session.odometry().yaw))


def _face(session, bearing: float) -> None:
    """Turn in place until the robot faces ``bearing`` (rad, relative to its heading now)."""
    target = session.odometry().yaw + bearing
    for _ in range(200):   # at most 20 s
        error = math.remainder(target - session.odometry().yaw, math.tau)
        if abs(error) < FACE_TOLERANCE:
            break
        session.cmd_vel(0.0, max(-SPIN_OMEGA, min(SPIN_OMEGA, 2.0 * error)))
        session.run(0.1)
    session.cmd_vel(0.0, 0.0)
    session.run(0.3)
