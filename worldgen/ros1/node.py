"""The simulator node: a :class:`~worldgen.sim.session.Session` that looks, to any rospy node, like Gazebo with
the TurtleBot3 plugins (``../shared/reference/turtlebot3.md`` §6 and §11).

================  ===========================  =============================================================
topic             type                         what, when (simulated time)
================  ===========================  =============================================================
``/clock``        rosgraph_msgs/Clock          every other physics step (120 Hz); at ``--rate max`` as often as
                                               a node can tell (:mod:`worldgen.interface.loop`)
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

What is due when, and the pace, are the step loop's (:mod:`worldgen.interface.loop`); what each message holds is
the robot interface's (:mod:`worldgen.interface.robot`); this module puts them on rospy.

Run as ``python -m worldgen.ros1 CONFIG.json`` (:mod:`.__main__`) (see :func:`main`); a trace of what the robot did is
written to the config's ``trace`` file at the end, for :mod:`.metrics`.
"""

from __future__ import annotations

import json
import os
import sys
import threading
import time
import types
import warnings
from pathlib import Path

from ..core.errors import WorldgenError
from ..interface.camera import CameraIO
from ..interface.loop import Wire, run_loop
from ..interface.simulator import (NO_TIMING, graded_of, open_session, person_of, session_robots,
                                  write_trace)
from ..interface.signals import deliver_interrupts, ignore_interrupts, pending_interrupt
from ..interface.robot import RobotIO
from ..interface.topics import join, near_topic, topics as stack_topics
from .camera_topics import CameraTopics
from .gazebo_api import GazeboApi
from .messages import fill, message_class, ros_time
from .robot_topics import RobotTopics
from .rosenv import import_rospy

START_WAIT = 30.0        # s of real time to wait for the start signal


class Bridge(Wire):
    """The node's state: the session, the robots' topics, Gazebo's interface, and what was recorded."""

    def __init__(self, rospy, session, config: dict):
        self.rospy, self.session, self.config = rospy, session, config
        table = stack_topics("noetic")
        self.pubs = {key: rospy.Publisher(t.name, message_class(t.type), queue_size=t.qos.depth,
                                          latch=t.qos.transient_local)
                     for key, t in table.items() if not t.per_robot and key != "clock"}
        with warnings.catch_warnings():   # rospy warns of a publisher without queue_size: this one is on purpose
            warnings.simplefilter("ignore")
            # /clock written from this thread: rospy's queue would wake its writer thread for every 12 bytes
            self.pubs["clock"] = rospy.Publisher(table["clock"].name, message_class(table["clock"].type))
        self.lock = threading.Lock()
        self.paused = False
        self.bag = None
        if config.get("bag"):
            import rosbag   # Debian's, beside rospy: only when a bag is asked for

            self.bag = rosbag.Bag(config["bag"], "w")
        self.robots: list[RobotTopics] = []
        self.removed: list[dict] = []
        for i, (robot, entry) in enumerate(session_robots(session, config)):
            io = RobotIO(robot, entry.get("ns", "/"), self.tf_prefix(entry), lock=self.lock,
                         record_scans=bool(config.get("record_scans")))
            self.robots.append(RobotTopics(rospy, io, self.bag if i == 0 else None))
            self.add_cameras(self.robots[-1])
        self.graded_robot = graded_of(self.robots, config.get("graded"))
        self.graded = self.graded_robot.io
        self.api = GazeboApi(rospy, self)
        self.person = person_of(session, config)

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
        io = RobotIO(robot, ns, self.tf_prefix({"ns": ns}), lock=self.lock,
                     record_scans=bool(self.config.get("record_scans")))
        io.now = self.session.t
        topics = RobotTopics(self.rospy, io)
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
        try:
            self.session.open_cameras()
        except WorldgenError as err:
            if strict:
                raise
            print(f"worldgen sim: warning: {topics.robot.name}'s camera publishes nothing: {err}", file=sys.stderr,
                  flush=True)
            return
        topics.cameras = [CameraTopics(self.rospy, CameraIO(topics.robot, c, topics.ns, topics.io.prefix,
                                                             self.session.time_step)) for c in cameras]

    def remove_robot(self, topics: RobotTopics) -> None:
        topics.close()
        self.robots.remove(topics)
        self.removed.append(topics.io.result())
        self.session.remove_robot(topics.robot)
        self.publish_static()

    def reset_world(self) -> None:
        """Every robot at its spawn pose, at rest, its command zero; world models where they started."""
        for topics in self.robots:
            topics.io.reset()
        self.session.models.reset()

    # -- messages (the step loop's Wire) ---------------------------------------------------------------------

    def stamp(self):
        return ros_time(self.rospy, self.session.t)

    def shut_down(self) -> bool:
        return self.rospy.is_shutdown()

    def drain(self) -> None:
        self.api.drain()

    def commanded(self) -> bool:
        return self.graded_robot.cmd_sub.get_num_connections() > 0

    def _send(self, key: str, values: dict) -> None:
        publisher = self.pubs[key]
        publisher.publish(fill(publisher.data_class(), values, self.rospy))

    def publish_static(self) -> None:
        t = self.session.t
        self._send("tf_static", {"transforms": [tf for topics in self.robots for tf in topics.static_transforms(t)]})

    def publish_clock(self) -> None:
        self.pubs["clock"].publish(self.pubs["clock"].data_class(clock=self.stamp()))

    def publish_drive(self) -> None:
        t = self.session.t
        for topics in self.robots:
            topics.io.now = t
            topics.publish_drive(t, self.pubs["tf"])
        if self.person is not None:
            self.person.record(t)

    def fast_heard(self) -> bool:
        """Whether some node listens to a robot's IMU or Gazebo's model or link states."""
        return any(topics.pubs["imu"].get_num_connections() for topics in self.robots) or self.api.states_heard()

    def publish_fast(self, dt: float) -> None:
        """What goes out every other step: each robot's /imu, Gazebo's model and link states."""
        for topics in self.robots:
            topics.publish_imu(dt, self.session.t)
        self.api.publish_states()

    def result(self) -> dict:
        """The trace file: the graded robot's rows at the top level (what :mod:`.metrics` reads), every robot's
        under ``robots``."""
        graded = self.graded.result()
        commanded = bool(graded.get("cmd_vel_messages"))
        return dict(graded, person=self.person.path if self.person else [], robot=self.config.get("robot") or "burger",
                    robots=[t.io.result() for t in self.robots] + self.removed,
                    findings=self.stray_commands(commanded) + self.unheard())

    def stray_commands(self, commanded: bool = True) -> list[dict]:
        """A finding per ``cmd_vel`` some node publishes where no robot lives (a typo in ``__ns:=``, say), or with
        a type the robot does not take (a TwistStamped), and, when the robot was never commanded, per velocity
        command published on a topic no robot takes (a typo in the topic's name: ``/cmdvel``)."""
        try:
            published = sorted(self.rospy.get_published_topics())
        except Exception:   # noqa: BLE001  (no master answer: nothing to say)
            return []
        taken = sorted(join(t.ns, "cmd_vel") for t in self.robots)
        found = []
        for name, kind in published:
            if name in taken:
                if kind != CMD_TYPE:
                    found.append({"check": "node", "severity": "error",
                                  "message": f"a node publishes {kind} on {name}, but the simulated TurtleBot3 takes "
                                             f"{CMD_TYPE} there (as Gazebo's does): the robot does not move",
                                  "fix": f"publish {CMD_TYPE} (from geometry_msgs.msg import Twist)"})
                continue
            if name.endswith("/cmd_vel"):
                found.append({"check": "node", "severity": "error",
                              "message": f"a node publishes {name}, but no robot lives in "
                                         f"{name.rsplit('/', 1)[0] or '/'}: the robots take {', '.join(taken)}",
                              "fix": "check the node's namespace (__ns:=) and its cmd_vel remapping"})
            elif not commanded and kind in VELOCITY_TYPES:
                found.append({"check": "node", "severity": "error",
                              "message": f"a node publishes {kind} on {name}, which no robot takes: the robots "
                                         f"take {', '.join(taken)}",
                              "fix": f"publish on {taken[0]} (is the topic's name misspelt?)"})
        return found

    def unheard(self) -> list[dict]:
        """A finding per topic some node subscribes to that nothing publishes, when its name is near one the
        simulator publishes (a typo: ``/scans``, ``/imus``): that subscription never hears a message."""
        try:
            import rosgraph

            own = self.rospy.get_name()   # the simulator's node: /gazebo
            publishers, subscribers, _ = rosgraph.Master(own).getSystemState()
        except Exception:   # noqa: BLE001  (no master answer: nothing to say)
            return []
        ours = sorted(topic for topic, names in publishers if own in names)
        published = {topic for topic, _ in publishers}
        found = []
        for topic, names in sorted(subscribers):
            who = ", ".join(sorted(n for n in names if n != own))
            near = near_topic(topic, ours) if topic not in published and who else None
            if near:
                found.append({"check": "node", "severity": "warning",
                              "message": f"{who} subscribes to {topic}, which nothing publishes; did you mean "
                                         f"{near}?", "fix": f"subscribe to {near} (is the topic's name misspelt?)"})
        return found


VELOCITY_TYPES = ("geometry_msgs/Twist", "geometry_msgs/TwistStamped")   # what a robot's cmd_vel takes
CMD_TYPE = "geometry_msgs/Twist"      # what the simulated TurtleBot3's cmd_vel takes under ROS 1, as Gazebo's


def wait_for_start(rospy, bridge: Bridge, file: str) -> None:
    """Hold simulated time at 0 (publishing /clock) until ``file`` exists: the nodes under test are ready, as with
    Gazebo started paused and then unpaused."""
    deadline = time.monotonic() + START_WAIT
    clock_at = 0.0
    while time.monotonic() < deadline and not rospy.is_shutdown():
        if time.monotonic() >= clock_at:
            bridge.publish_clock()
            clock_at = time.monotonic() + 0.02
        bridge.drain()
        if os.path.exists(file):
            return
        time.sleep(0.005)


def join_master(rospy) -> None:
    """``rospy.init_node`` as ``/gazebo``: without simulated time of its own (its messages carry the session's
    time; a /clock subscription would be a second connection on every /clock message, and a thread reading them),
    and without rospy's tenth-of-a-second naps while it waits for its own registration (a run starts its nodes
    only once the simulator has joined)."""
    import rospy.impl.init as init_impl

    real = init_impl.time if getattr(init_impl, "time", None) is time else None
    if real is not None:
        init_impl.time = types.SimpleNamespace(sleep=lambda seconds: time.sleep(min(seconds, 0.002)))
    try:
        rospy.init_node("gazebo", disable_signals=True, anonymous=False, disable_rostime=True)
    finally:
        if real is not None:
            init_impl.time = real


def wait_for_file(path: Path) -> bool:
    """Until ``path`` exists (``worldgen run`` starts the simulator before it has read the world, and writes its
    config whole once it has); False when a stop signal comes first or after :data:`START_WAIT`."""
    deadline = time.monotonic() + START_WAIT
    while not path.exists():
        if pending_interrupt() or time.monotonic() > deadline:
            return False
        time.sleep(0.005)
    return True


def wait_for_master(param: str, token: str) -> bool:
    """Until the master (``ROS_MASTER_URI``) holds ``token`` in ``param``: it is up and the run's parameters are
    set (the simulator starts beside the master, see :mod:`.run`). False when a stop signal comes first (held
    while starting, see :mod:`worldgen.interface.signals`) or after :data:`START_WAIT`."""
    import xmlrpc.client

    master = xmlrpc.client.ServerProxy(os.environ.get("ROS_MASTER_URI", ""))
    deadline = time.monotonic() + START_WAIT
    while time.monotonic() < deadline and not pending_interrupt():
        try:
            code, _, value = master.getParam("/gazebo", param)
            if code == 1 and value == token:
                return True
        except (OSError, xmlrpc.client.Error):
            pass
        time.sleep(0.01)
    return False


def main(argv: list[str]) -> int:
    """``CONFIG.json`` holds: scene_file (a pickled Scene), robot, spawn [x, y, yaw], robots (null, or one entry
    per robot: name, ns, robot, spawn, tf_prefix, mappings; the first is robot/spawn's), graded (the namespace or
    name of the robot the trace is about), no_hit, rate (0 = max), duration (s or null), trace (file or null), bag
    (file or null), start_file (null: start at once; else once the file exists), up_param (null, or [parameter,
    token]: join the master once it holds the token, see :func:`wait_for_master`), joined_file (null, or a file
    made once it has joined the master), person (null or the loop), set_sim_time (bool), gazebo_msgs (a folder to
    import gazebo_msgs from, or null), record_scans (bool: every robot's trace gets ``lidar`` and every published
    scan under ``ranges``, see :meth:`.RobotTopics.publish_scan`)."""
    keep_freed_memory()
    if not wait_for_file(Path(argv[0])):
        return 0   # stopped, or no config, before the run began: nothing to write
    config = json.loads(Path(argv[0]).read_text(encoding="utf-8"))
    if config.get("gazebo_msgs"):
        sys.path.insert(0, config["gazebo_msgs"])
    try:
        rospy = import_rospy()

        session = open_session(config)   # no OpenGL for a camera: one line naming the packages, before the master
    except WorldgenError as err:
        print(f"worldgen: error: {err}", file=sys.stderr, flush=True)
        return 2
    with session:
        if config.get("up_param") and not wait_for_master(*config["up_param"]):
            return 0   # stopped, or no master, before the run began: nothing to write
        join_master(rospy)
        if config.get("joined_file"):
            Path(config["joined_file"]).touch()   # the run may start the nodes (they wait for its topics)
        if config.get("set_sim_time", True):
            rospy.set_param("/use_sim_time", True)
        try:
            bridge = Bridge(rospy, session, config)
        except WorldgenError as err:
            print(f"worldgen: error: {err}", file=sys.stderr, flush=True)
            return 2
        bridge.publish_static()
        timing = dict(NO_TIMING)
        try:
            deliver_interrupts()   # one that came while starting is raised here, where it is handled
            held = config.get("start_file")
            if held:
                wait_for_start(rospy, bridge, held)
            print("worldgen-sim: running", file=sys.stderr, flush=True)
            pids = rospy.get_param("/worldgen/pids", []) if held else []
            timing = run_loop(bridge, float(config.get("rate") or 0.0), config.get("duration"), pids)
        except KeyboardInterrupt:
            pass
        finally:
            ignore_interrupts()   # a second signal must not cut the trace short
            finish(rospy, bridge, config, timing)
    return 0


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
    """Close the bag, then write the trace (under the lock the callbacks take), then leave the master. The trace
    comes last: once it is there the run's result is whole, and ``worldgen run`` ends every process at once."""
    with bridge.lock:
        if bridge.bag is not None:
            bridge.bag.close()
            bridge.bag = None
            for topics in bridge.robots:
                topics.bag = None
        if config.get("trace"):
            write_trace(config["trace"], dict(bridge.result(), timing=timing))
    rospy.signal_shutdown("worldgen sim done")
