"""The simulator node: a :class:`~worldgen.sim.session.Session` that looks, to any rospy node, like Gazebo with
the TurtleBot3 plugins (``../shared/reference/turtlebot3.md`` §6 and §11).

================  ===========================  =============================================================
topic             type                         what, when (simulated time)
================  ===========================  =============================================================
``/clock``        rosgraph_msgs/Clock          every other physics step (120 Hz; see below)
``/scan``         sensor_msgs/LaserScan        5 Hz, frame ``base_scan``, 360 beams 0…6.28319, 0.12–3.5 m
``/odom``         nav_msgs/Odometry            30 Hz (the diff-drive plugin's updateRate), ``odom`` →
                                               ``base_footprint``, ground truth (odometrySource world)
``/tf``           tf2_msgs/TFMessage           30 Hz: ``odom`` → ``base_footprint`` and the wheel joints
``/tf_static``    tf2_msgs/TFMessage           latched: every fixed joint of the description
``/joint_states`` sensor_msgs/JointState       30 Hz: ``wheel_left_joint``, ``wheel_right_joint``
``/imu``          sensor_msgs/Imu              120 Hz, frame ``imu_link``: true orientation, body rates,
                                               linear acceleration with gravity (+9.8 m/s² up at rest)
``/cmd_vel``      geometry_msgs/Twist (in)     into gazebo_ros_diff_drive's model (:mod:`worldgen.sim.drive`)
================  ===========================  =============================================================

A robot with a camera (the Waffle Pi's Raspberry Pi camera, the Waffle's R200 colour image) also has
``/camera/rgb/image_raw``, ``/camera/rgb/camera_info`` and ``/camera/rgb/image_raw/compressed`` at 30 Hz, drawn
only while some node subscribes (:mod:`.camera_topics`).

Every robot of the run (one, or several from a launch file's ``<group ns>``s) has these topics in its namespace
with its frames prefixed (:mod:`.robot_topics`); ``/clock``, ``/tf`` and ``/tf_static`` are shared. Gazebo's own
services and ``/gazebo/model_states`` are :mod:`.gazebo_api`'s; ``reset_world`` and ``reset_simulation`` put
the robots back at their spawn poses (simulated time keeps running: rewinding ``/clock`` would throw every
node's ``rospy.Rate``), ``pause_physics`` stops simulated time until ``unpause_physics``.

``/clock`` goes out every other 1/240 s step, 120 Hz of simulated time: Gazebo's gazebo_ros publishes it at
100 Hz, ``rospy.Rate`` loops up to 30 Hz wake within 8 ms of when they should, and publishing every step would
double the clock traffic every node receives for nothing. The physics step stays the session's 1/240 s.

``rate`` paces simulated time at that many times real time (:mod:`.pacing`); 0 runs as fast as it goes, and
then, after each scan that some node listens to, waits (at most 50 ms of real time) for the ``/cmd_vel`` that
answers it, so that a node reacting to scans reacts within the same scan period, as it does in Gazebo at real
time. Camera pictures are drawn in the step they are due, so their cost slows the pace as any other work does.

Run as ``python -m worldgen.bridge.node CONFIG.json`` (see :func:`main`); a trace of what the robot did is
written to the config's ``trace`` file at the end, for :mod:`.metrics`.
"""

from __future__ import annotations

import json
import os
import sys
import threading
import time
from pathlib import Path

from .pacing import Backlog, Governor
from .robot_topics import RobotTopics

CLOCK_EVERY = 2          # physics steps per /clock and /imu message
ANSWER_WAIT = 0.05       # s of real time to wait for the cmd_vel answering a scan at rate max
START_WAIT = 30.0        # s of real time to wait for the start signal
PAUSED_CLOCK = 0.1       # s of real time between /clock messages while paused


class Bridge:
    """The node's state: the session, the robots' topics, Gazebo's interface, and what was recorded."""

    def __init__(self, rospy, session, config: dict):
        from nav_msgs.msg import Odometry
        from rosgraph_msgs.msg import Clock
        from sensor_msgs.msg import Imu, JointState, LaserScan
        from tf2_msgs.msg import TFMessage

        self.rospy, self.session, self.config = rospy, session, config
        self.msg = {"Clock": Clock, "LaserScan": LaserScan, "Odometry": Odometry, "TFMessage": TFMessage,
                    "JointState": JointState, "Imu": Imu}
        pub = rospy.Publisher
        self.pubs = {"clock": pub("/clock", Clock, queue_size=10), "tf": pub("/tf", TFMessage, queue_size=100),
                     "tf_static": pub("/tf_static", TFMessage, queue_size=10, latch=True)}
        self.lock = threading.Lock()
        self.paused = False
        self.bag = None
        if config.get("bag"):
            import rosbag
            self.bag = rosbag.Bag(config["bag"], "w")
        robots = config.get("robots") or [{}]
        self.robots: list[RobotTopics] = []
        self.removed: list[dict] = []
        for i, entry in enumerate(robots):
            robot = session.robots[0] if i == 0 else session.add_robot(
                entry.get("robot") or "burger", entry["spawn"], name=entry.get("name") or f"robot_{i}",
                mappings=entry.get("mappings"))
            if i == 0 and entry.get("name"):
                robot.name = entry["name"]
            self.robots.append(RobotTopics(rospy, self.msg, robot, entry.get("ns", "/"), self.tf_prefix(entry),
                                           self.bag if i == 0 else None, self.lock,
                                           record_scans=bool(config.get("record_scans"))))
            self.add_cameras(self.robots[-1])
        self.graded = self._graded(config.get("graded"))
        from .gazebo_api import GazeboApi

        self.api = GazeboApi(rospy, self)
        self.trace = {"person": []}
        self.person = None
        if config.get("person"):
            p = config["person"]
            self.person = (session.add_mover(p["radius"], p["height"], "person", self.person_xy(0.0)), p)

    def _graded(self, which) -> RobotTopics:
        for topics in self.robots:
            if which in (topics.ns, topics.ns.strip("/"), topics.robot.name):
                return topics
        return self.robots[0]

    def tf_prefix(self, entry: dict) -> str:
        """A robot's tf prefix: the config's, else the ``tf_prefix`` parameter searched from its namespace
        upwards, else the namespace without slashes (gazebo_ros's rule)."""
        if entry.get("tf_prefix") is not None:
            return entry["tf_prefix"].strip("/")
        ns = entry.get("ns", "/")
        if ns in ("", "/"):
            return ""
        try:
            key = self.rospy.search_param(ns.rstrip("/") + "/tf_prefix")
            if key:
                return str(self.rospy.get_param(key)).strip("/")
        except Exception:   # noqa: BLE001  (no master answer: fall back to the namespace)
            pass
        return ns.strip("/")

    # -- robots joining and leaving while it runs (spawn_urdf_model, delete_model) ------------------------------

    def add_robot(self, name: str, *, urdf: str, spawn, ns: str, z: float = 0.0) -> RobotTopics:
        robot = self.session.add_robot("burger", spawn, name=name, urdf=urdf, z=z)
        topics = RobotTopics(self.rospy, self.msg, robot, ns, self.tf_prefix({"ns": ns}), None, self.lock,
                             record_scans=bool(self.config.get("record_scans")))
        topics.now = self.session.t
        self.add_cameras(topics, strict=False)
        self.robots.append(topics)
        self.publish_static()
        return topics

    def add_cameras(self, topics: RobotTopics, *, strict: bool = True) -> None:
        """The robot's cameras on ROS (:mod:`.camera_topics`), the OpenGL context made now: InputError naming what
        to install when it cannot be (``strict``), else a warning and a robot whose cameras publish nothing."""
        cameras = [c for c in topics.robot.profile.cameras if c.link in topics.robot.link_index]
        if not cameras:
            return
        from ..core.errors import WorldgenError
        from .camera_topics import CameraTopics

        try:
            self.session.open_cameras()
        except WorldgenError as err:
            if strict:
                raise
            print(f"worldgen sim: warning: {topics.robot.name}'s camera publishes nothing: {err}", file=sys.stderr,
                  flush=True)
            return
        topics.cameras = [CameraTopics(self.rospy, topics.robot, c, topics.ns, topics.prefix, self.session.time_step)
                          for c in cameras]

    def remove_robot(self, topics: RobotTopics) -> None:
        topics.close()
        self.robots.remove(topics)
        self.removed.append(topics.result())
        self.session.remove_robot(topics.robot)
        self.publish_static()

    def reset_world(self) -> None:
        """Every robot at its spawn pose, at rest, its command zero; world models where they started."""
        for topics in self.robots:
            topics.robot.reset()
            topics.last_velocity = None
        self.session.models.reset()

    # -- messages ------------------------------------------------------------------------------------------

    def stamp(self):
        return self.rospy.Time.from_sec(self.session.t)

    def publish_static(self) -> None:
        stamp = self.stamp()
        transforms = [tf for topics in self.robots for tf in topics.static_transforms(stamp)]
        self.pubs["tf_static"].publish(self.msg["TFMessage"](transforms=transforms))

    def publish_clock(self) -> None:
        self.pubs["clock"].publish(self.msg["Clock"](clock=self.stamp()))

    def publish_drive(self) -> None:
        stamp, t = self.stamp(), self.session.t
        for topics in self.robots:
            topics.now = t
            topics.publish_drive(t, stamp, self.pubs["tf"])
        if self.person is not None:
            self.trace["person"].append([t, *self.person_xy(t)])

    def publish_fast(self, dt: float) -> None:
        """What goes out every other step: /clock, each robot's /imu, Gazebo's model and link states."""
        self.publish_clock()
        stamp = self.stamp()
        for topics in self.robots:
            topics.publish_imu(dt, stamp)
        self.api.publish_states()

    def publish_scans(self) -> bool:
        """Each robot's scan; True when some node listens to the graded robot's."""
        stamp, listened = self.stamp(), False
        for topics in self.robots:
            topics.answered.clear()
            heard = topics.publish_scan(self.session, stamp)
            listened = listened or (heard and topics is self.graded)
        return listened

    def publish_cameras(self, step: int) -> None:
        """The pictures due at physics step ``step`` that some node looks at."""
        stamp = None
        for topics in self.robots:
            for camera in topics.cameras:
                if step % camera.every == 0:
                    stamp = stamp or self.stamp()
                    camera.publish(self.session, stamp)

    def person_xy(self, t: float) -> tuple[float, float]:
        import math

        p = self.config["person"]
        angle = p["phase"] + p["speed"] * t / p["loop_radius"]
        return (p["centre"][0] + p["loop_radius"] * math.cos(angle), p["centre"][1] + p["loop_radius"] * math.sin(angle))

    def result(self) -> dict:
        """The trace file: the graded robot's rows at the top level (what :mod:`.metrics` reads), every robot's
        under ``robots``."""
        graded = self.graded.result()
        return dict(graded, person=self.trace["person"], robot=self.config.get("robot") or "burger",
                    robots=[t.result() for t in self.robots] + self.removed)


def model_name(robot: str | None) -> str:
    """The model name a robot gets in Gazebo's lists: ``turtlebot3_burger`` as the class's launch files spawn it."""
    robot = robot or "burger"
    return f"turtlebot3_{robot}" if robot in ("burger", "waffle", "waffle_pi") else "turtlebot3"


def wait_for_start(rospy, bridge: Bridge, param: str) -> None:
    """Hold simulated time at 0 (publishing /clock) until ``param`` is true on the master: the nodes under
    test are up, as with Gazebo started paused and then unpaused."""
    deadline = time.monotonic() + START_WAIT
    while time.monotonic() < deadline and not rospy.is_shutdown():
        bridge.publish_clock()
        bridge.api.drain()
        if rospy.get_param(param, False):
            return
        time.sleep(0.02)


def run_loop(rospy, bridge: Bridge, rate: float, duration: float | None, pids=()) -> dict:
    """Step the session, publishing as the module docstring says, until ``duration`` simulated seconds have
    passed (None: until shut down). Returns the timing numbers."""
    s = bridge.session
    end_step = None if duration is None else round(duration / s.time_step)
    wall0, interrupted = time.monotonic(), False
    bridge.publish_clock()
    bridge.publish_drive()
    try:
        _steps(rospy, bridge, rate, end_step, list(pids))
    except KeyboardInterrupt:
        interrupted = True
    wall = time.monotonic() - wall0
    return {"sim_time_s": s.t, "wall_time_s": wall, "real_time_factor": s.t / wall if wall > 0 else None,
            "interrupted": interrupted}


def _steps(rospy, bridge: Bridge, rate: float, end_step: int | None, pids: list[int]) -> None:
    backlog = Backlog(pids) if rate <= 0 and pids else None
    try:
        _step_loop(rospy, bridge, rate, end_step, backlog)
    finally:
        if backlog is not None:
            backlog.stop()


def _step_loop(rospy, bridge: Bridge, rate: float, end_step: int | None, backlog: Backlog | None) -> None:
    s = bridge.session
    dt = s.time_step
    drive_every = s._update_every
    scan_every = max(1, round(1.0 / (s.lidar.update_rate * dt))) if s.lidar is not None else 0
    person = bridge.person
    governor = Governor(rate, backlog)
    step = 0
    while not rospy.is_shutdown() and (end_step is None or step < end_step):
        bridge.api.drain()
        if bridge.paused:
            bridge.publish_clock()   # the clock stands still
            time.sleep(PAUSED_CLOCK)
            governor = Governor(rate, backlog, s.t)   # paced afresh from where it stopped
            continue
        if person is not None:
            s.move_body(person[0], *bridge.person_xy(s.t + dt))
        s.run(dt)
        step += 1
        if step % CLOCK_EVERY == 0:
            bridge.publish_fast(dt * CLOCK_EVERY)
            governor.pace(s.t)
        if step % drive_every == 0:
            bridge.publish_drive()
        bridge.publish_cameras(step)
        if scan_every and step % scan_every == 0:
            listened = bridge.publish_scans()
            if rate <= 0 and listened and bridge.graded.cmd_sub.get_num_connections():
                bridge.graded.answered.wait(ANSWER_WAIT)


def _write_json(path: str, data: dict) -> None:
    tmp = f"{path}.part"
    with open(tmp, "w", encoding="utf-8") as fh:
        json.dump(data, fh)
    os.replace(tmp, path)


def main(argv: list[str]) -> int:
    """``CONFIG.json`` holds: scene_file (a pickled Scene), robot, spawn [x, y, yaw], robots (null, or one entry
    per robot: name, ns, robot, spawn, tf_prefix, mappings; the first is robot/spawn's), graded (the namespace or
    name of the robot the trace is about), no_hit, rate (0 = max), duration (s or null), trace (file or null), bag
    (file or null), start_param (null: start at once), person (null or the loop), set_sim_time (bool),
    gazebo_msgs (a folder to import gazebo_msgs from, or null), record_scans (bool: every robot's trace gets
    ``lidar`` and every published scan under ``ranges``, see :meth:`.RobotTopics.publish_scan`)."""
    from ..core.errors import WorldgenError
    from ..core.scene import Scene
    from .rosenv import import_rospy

    keep_freed_memory()
    config = json.loads(Path(argv[0]).read_text(encoding="utf-8"))
    if config.get("gazebo_msgs"):
        sys.path.insert(0, config["gazebo_msgs"])
    try:
        rospy = import_rospy()
        from ..sim.session import Session

        first = (config.get("robots") or [{}])[0]
        session = Session(Scene.load(config["scene_file"]), first.get("robot") or config.get("robot") or "burger",
                          tuple(first.get("spawn") or config["spawn"]), no_hit=config.get("no_hit", "inf"),
                          seed=config.get("seed", 0),
                          mappings=first.get("mappings"), name=first.get("name") or model_name(config.get("robot")))
        if _has_camera(session, config):
            session.open_cameras()   # no OpenGL: one line naming the packages, before joining the master
    except WorldgenError as err:
        print(f"worldgen: error: {err}", file=sys.stderr, flush=True)
        return 2
    with session:
        rospy.init_node("gazebo", disable_signals=True, anonymous=False)
        if config.get("set_sim_time", True):
            rospy.set_param("/use_sim_time", True)
        try:
            bridge = Bridge(rospy, session, config)
        except WorldgenError as err:
            print(f"worldgen: error: {err}", file=sys.stderr, flush=True)
            return 2
        bridge.publish_static()
        timing = {"sim_time_s": 0.0, "wall_time_s": 0.0, "real_time_factor": None, "interrupted": True}
        try:
            _deliver_interrupts()   # one that came while starting is raised here, where it is handled
            if config.get("start_param"):
                wait_for_start(rospy, bridge, config["start_param"])
            print("worldgen-sim: running", file=sys.stderr, flush=True)
            pids = rospy.get_param("/worldgen/pids", []) if config.get("start_param") else []
            timing = run_loop(rospy, bridge, float(config.get("rate") or 0.0), config.get("duration"), pids)
        except KeyboardInterrupt:
            pass
        finally:
            _ignore_interrupts()   # a second signal must not cut the trace short
            finish(rospy, bridge, config, timing)
    return 0


def _has_camera(session, config: dict) -> bool:
    """Whether any robot of the config has a camera (the first one is the session's)."""
    from ..robots import robot_urdf
    from ..robots.profile import robot_profile

    if session.main.profile.cameras:
        return True
    others = (config.get("robots") or [{}])[1:]
    return any(robot_profile(robot_urdf(e.get("robot") or "burger", e.get("mappings"))).cameras for e in others)


def keep_freed_memory() -> None:
    """Have glibc keep freed memory for reuse instead of giving it back to the system. Every camera picture makes
    a few buffers of a megabyte (its bytes, rospy's serialisation); glibc would map each afresh and return it, and
    touching a fresh megabyte page by page costs about a millisecond, more than the picture's own copies
    (1.9 ms → 0.1 ms per 640 × 480 message). Big blocks come from the heap (below 32 MB) and up to 256 MB of free
    heap is kept. Nothing happens where there is no glibc."""
    import ctypes
    import ctypes.util

    m_trim_threshold, m_mmap_threshold = -1, -3
    try:
        libc = ctypes.CDLL(ctypes.util.find_library("c") or "libc.so.6")
        libc.mallopt(m_mmap_threshold, 32 * 1024 * 1024)
        libc.mallopt(m_trim_threshold, 256 * 1024 * 1024)
    except (OSError, AttributeError):
        pass


def finish(rospy, bridge: Bridge, config: dict, timing: dict) -> None:
    """Write the trace and close the bag (under the lock the callbacks take), then leave the master."""
    with bridge.lock:
        if config.get("trace"):
            _write_json(config["trace"], dict(bridge.result(), timing=timing))
        if bridge.bag is not None:
            bridge.bag.close()
            bridge.bag = None
            for topics in bridge.robots:
                topics.bag = None
    rospy.signal_shutdown("worldgen sim done")


def _interrupt(signum, frame):
    raise KeyboardInterrupt(f"signal {signum}")


STOP_SIGNALS = ("SIGINT", "SIGTERM", "SIGHUP")


def _hold_interrupts() -> None:
    """Hold the stop signals until :func:`_deliver_interrupts`: while the node starts, a KeyboardInterrupt could be
    raised inside an import's clean-up callback, where Python prints it as "Exception ignored" and carries on."""
    import signal

    signal.pthread_sigmask(signal.SIG_BLOCK, {getattr(signal, s) for s in STOP_SIGNALS})


def _deliver_interrupts() -> None:
    import signal

    signal.pthread_sigmask(signal.SIG_UNBLOCK, {getattr(signal, s) for s in STOP_SIGNALS})


def _ignore_interrupts() -> None:
    import signal

    for sig in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP):
        try:
            signal.signal(sig, signal.SIG_IGN)
        except ValueError:
            pass


if __name__ == "__main__":
    import signal

    signal.signal(signal.SIGTERM, _interrupt)
    signal.signal(signal.SIGHUP, _interrupt)
    _hold_interrupts()
    try:
        sys.exit(main(sys.argv[1:]))
    except KeyboardInterrupt:   # interrupted before the loop started: nothing to write
        sys.exit(0)
