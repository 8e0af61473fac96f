"""The simulator on ROS 2: a :class:`~worldgen.sim.session.Session` that looks, to any rclpy node, like a TurtleBot3
in Gazebo on Humble (Gazebo Classic's gazebo_ros plugins) or Jazzy (Gazebo Sim through ros_gz_bridge), spoken over
DDS with PyPI's cyclonedds (:mod:`.participant`, :mod:`.msgs`).

Topics, types, rates, frames and QoS are the stack's rows of :mod:`worldgen.interface.topics`; message contents
are :mod:`worldgen.interface.robot`'s; the step loop is :mod:`worldgen.interface.loop`'s. Each robot's topics are in
its namespace, ``/clock``, ``/tf`` and ``/tf_static`` shared. A message is made only while some reader matches its
writer (as rclcpp publishers with no subscription cost nothing). What a student's node would get nothing from in
real Gazebo — a Twist publisher on Jazzy's TwistStamped ``cmd_vel``, a best-effort publisher on a reliable
subscription — moves nothing here either, and the trace holds a finding that says why.

Run as ``python -m worldgen.ros2 CONFIG.json`` (:mod:`.__main__`; see :func:`main`): the config of
:func:`worldgen.bridge.world.write_config` plus ``stack``, ``domain``, ``discovery`` (``range``: localhost or subnet, ``peers``: ROS_STATIC_PEERS), ``start_file`` (hold simulated time at 0
until it exists, or until ``expect`` other DDS participants have matched some topic of the robot's) and ``cmd_vel``
(jazzy: ``twist`` when the bridge is configured for Twist).
"""

from __future__ import annotations

import json
import os
import sys
import threading
import time
from pathlib import Path

from ..core.errors import WorldgenError
from ..interface.camera import CameraIO
from ..interface.loop import Wire, run_loop
from ..interface.simulator import (NO_TIMING, graded_of, open_session, person_of, session_robots,
                                  write_trace)
from ..interface.signals import deliver_interrupts, ignore_interrupts
from ..interface.robot import PLUGINS, RobotIO
from ..interface.topics import TASK_INPUTS, Qos, camera_topics, clock_every, frame, join, near_topic, topics
from . import msgs
from .encode import build, velocity
from .discovery import announce
from .participant import Discovery, Participant, endpoint_qos
from .typehash import type_hash

START_WAIT = 30.0        # s of real time to wait for the start
SETTLE = 1.0             # s of real time after the nodes' endpoints first match, at most, for the rest to match
                         # (a node driving the robot and reading what the task needs starts it sooner; on a busy
                         # machine a node's cmd_vel writer matched 0.2 s after its scan reader, too late)
MATCHED_BOTH = 0.05      # s at least: a match the simulator sees may not yet be one the node sees (DDS matches
                         # each side on its own)
LOOK_EVERY = 0.25        # s of real time between looks at the others' endpoints


class DdsRobot:
    """One robot's writers and its ``cmd_vel`` reader (see the module docstring)."""

    def __init__(self, wire: "DdsWire", io: RobotIO, stack: str, cmd_type: str):
        self.wire, self.io, self.ns = wire, io, io.ns
        table = topics(stack)
        self.writers = {key: wire.writer(join(io.ns, t.name), t.type, t.qos)
                        for key, t in table.items() if t.direction == "out" and t.per_robot}
        cmd = table["cmd_vel"]
        self.cmd_name, self.cmd_type = join(io.ns, cmd.name), cmd_type
        self.cmd_reader = wire.reader(self.cmd_name, cmd_type, cmd.qos, self.on_cmd_vel)
        self.cameras: list = []

    @property
    def robot(self):
        return self.io.robot

    def on_cmd_vel(self, reader) -> None:   # a cyclonedds thread
        for sample in reader.take(N=64):
            v, w = velocity(sample)
            self.io.command(v, w)

    def heard(self, key: str) -> bool:
        return self.writers[key].get_publication_matched_status().current_count > 0

    def publish_drive(self, t: float) -> None:
        tf_writer = self.wire.writers["tf"]
        out = self.io.drive(t, odom=self.heard("odom"),
                            tf=tf_writer.get_publication_matched_status().current_count > 0,
                            joint_states=self.heard("joint_states"))
        if "odom" in out:
            self.wire.send(self.writers["odom"], msgs.Odometry, out["odom"])
        if "tf" in out:
            self.wire.send(tf_writer, msgs.TFMessage, {"transforms": out["tf"]})
        if "joint_states" in out:
            self.wire.send(self.writers["joint_states"], msgs.JointState, out["joint_states"])

    def publish_imu(self, dt: float, t: float) -> None:
        if not self.heard("imu"):
            self.io.imu_unheard()
            return
        self.wire.send(self.writers["imu"], msgs.Imu, self.io.imu(dt, t))

    def publish_scan(self, session) -> bool:
        listened = self.heard("scan")
        values = self.io.scan(session)
        if listened:
            self.wire.send(self.writers["scan"], msgs.LaserScan, values)
        return listened


class DdsCamera:
    """One camera's image and camera_info writers (the stack's names: ``camera/image_raw``)."""

    def __init__(self, wire: "DdsWire", io: CameraIO, stack: str, ns: str):
        self.wire, self.io, self.every = wire, io, io.every
        table = camera_topics(stack, join(ns, "camera/image_raw"), join(ns, "camera/camera_info"))
        if stack == "jazzy":   # Gazebo Sim's camera: the link's frame (gz_frame_id), for the Waffle Pi too
            io.frame_id = frame(io.frame_id.rpartition("/")[0], "camera_rgb_frame") if "/" in io.frame_id else \
                "camera_rgb_frame"
        self.writers = {key: wire.writer(t.name, t.type, t.qos) for key, t in table.items()}

    def publish(self, session, t: float) -> bool:
        wanted = [k for k, w in self.writers.items() if w.get_publication_matched_status().current_count > 0]
        if not wanted:
            return False
        rgb = self.io.picture(session)
        if "image" in wanted:
            self.wire.send(self.writers["image"], msgs.Image, self.io.image(rgb, t))
        if "info" in wanted:
            self.wire.send(self.writers["info"], msgs.CameraInfo, self.io.info(t))
        return True


class DdsWire(Wire):
    """The simulator's DDS side: the participant, the shared writers, the robots, the findings about the nodes'
    endpoints, and the trace."""

    def __init__(self, session, config: dict, participant: Participant):
        self.session, self.config, self.dp = session, config, participant
        self.stack = config["stack"]
        self.clock_every = clock_every(self.stack, session.time_step)
        self.lock = threading.Lock()
        self.paused = False
        self.stopped = threading.Event()
        self.findings: list[dict] = []
        self.watcher, self.looked = None, 0.0
        table = topics(self.stack)
        self.writers = {key: self.writer(t.name, t.type, t.qos) for key, t in table.items() if not t.per_robot}
        cmd_type = table["cmd_vel"].type
        if self.stack == "jazzy" and config.get("cmd_vel") == "twist":
            cmd_type = "geometry_msgs/msg/Twist"
        self.robots: list[DdsRobot] = []
        for robot, entry in session_robots(session, config):
            model = entry.get("robot") or config.get("robot") or "burger"
            io = RobotIO(robot, entry.get("ns", "/"), (entry.get("tf_prefix") or entry.get("ns", "")).strip("/"),
                         lock=self.lock, record_scans=bool(config.get("record_scans")), plugins=PLUGINS[self.stack],
                         model=model if model in ("burger", "waffle", "waffle_pi") else "burger")
            dds_robot = DdsRobot(self, io, self.stack, cmd_type)
            dds_robot.cameras = [DdsCamera(self, CameraIO(robot, c, io.ns, io.prefix, session.time_step), self.stack,
                                           io.ns)
                                 for c in robot.profile.cameras if c.link in robot.link_index]
            self.robots.append(dds_robot)
        self.graded_robot = graded_of(self.robots, config.get("graded"))
        self.graded = self.graded_robot.io
        self.person = person_of(session, config)

    # -- endpoints -----------------------------------------------------------------------------------------

    def writer(self, name: str, ros_type: str, qos: Qos):
        return self.dp.writer(name, msgs.TYPES[ros_type], qos, type_hash=self.type_hash(ros_type))

    def reader(self, name: str, ros_type: str, qos: Qos, on_data):
        from cyclonedds.core import Listener
        from cyclonedds.sub import DataReader

        return DataReader(self.dp.dp, self.dp.topic(name, msgs.TYPES[ros_type]),
                          endpoint_qos(qos, self.type_hash(ros_type)), listener=Listener(on_data_available=on_data))

    def type_hash(self, ros_type: str) -> str | None:
        if self.stack != "jazzy":   # Humble's rmw puts no type hash in USER_DATA
            return None
        return type_hash(ros_type)

    def send(self, writer, cls, values: dict) -> None:
        writer.write(build(cls, values))

    # -- the step loop's Wire ------------------------------------------------------------------------------

    def shut_down(self) -> bool:
        return self.stopped.is_set()

    def drain(self) -> None:
        """Between two steps: a look at the other participants' endpoints, a few times a second."""
        now = time.monotonic()
        if self.watcher is not None and now - self.looked > LOOK_EVERY:
            self.looked = now
            self.watcher.look()

    def commanded(self) -> bool:
        return self.graded_robot.cmd_reader.get_subscription_matched_status().current_count > 0

    def publish_static(self) -> None:
        t = self.session.t
        self.send(self.writers["tf_static"], msgs.TFMessage,
                  {"transforms": [tf for r in self.robots for tf in r.io.static_transforms(t)]})

    def publish_clock(self) -> None:
        self.send(self.writers["clock"], msgs.Clock, {"clock": self.session.t})

    def publish_drive(self) -> None:
        t = self.session.t
        for robot in self.robots:
            robot.io.now = t
            robot.publish_drive(t)
        if self.person is not None:
            self.person.record(t)

    def fast_heard(self) -> bool:
        return any(robot.heard("imu") for robot in self.robots)

    def publish_fast(self, dt: float) -> None:
        for robot in self.robots:
            robot.publish_imu(dt, self.session.t)

    def result(self) -> dict:
        graded = self.graded.result()
        return dict(graded, person=self.person.path if self.person else [], robot=self.config.get("robot") or "burger",
                    robots=[r.io.result() for r in self.robots], findings=self.findings)


class Watcher:
    """The other participants and their endpoints, from DDS's built-in topics: who has come (the start), and
    endpoints a Gazebo would ignore (a finding each, once): a publisher of another type on a robot's ``cmd_vel``, a
    best-effort publisher on it (the plugin's subscription is reliable), a reliable subscriber to a best-effort
    topic of the robot's (Humble's ``/clock``)."""

    def __init__(self, wire: DdsWire):
        from cyclonedds.builtin import BuiltinDataReader, BuiltinTopicDcpsParticipant, BuiltinTopicDcpsPublication, \
            BuiltinTopicDcpsSubscription

        self.wire = wire
        dp = wire.dp.dp
        self.own = dp.guid
        self.participants = BuiltinDataReader(dp, BuiltinTopicDcpsParticipant)
        self.publications = BuiltinDataReader(dp, BuiltinTopicDcpsPublication)
        self.subscriptions = BuiltinDataReader(dp, BuiltinTopicDcpsSubscription)
        self.others: set = set()
        self.on_clock: set = set()   # the participants that subscribe to /clock (use_sim_time)
        self.subscribed: set = set()   # the topics others subscribe to ("rt/scan" …)
        self.published: dict = {}      # the topics anyone publishes: whether the simulator itself does
        self.said: set = set()
        self.cmd_topics = {"rt" + r.cmd_name: r for r in wire.robots}
        table = topics(wire.stack)
        self.best_effort = {"rt" + t.full_name(r.ns): t for r in wire.robots for t in table.values()
                            if t.direction == "out" and not t.qos.reliable}

    def look(self) -> None:
        for sample in self.participants.take(N=256):
            if getattr(sample, "key", None) is not None and sample.key != self.own:
                self.others.add(sample.key)
        for sample in self.publications.take(N=256):
            name = getattr(sample, "topic_name", None) or ""   # None for an endpoint that has gone
            if name:
                self.published[name] = self.published.get(name, False) or sample.participant_key == self.own
            robot = self.cmd_topics.get(name)
            if robot is not None and sample.participant_key != self.own:
                self._publication(robot, sample)
            elif robot is None and name.startswith("rt/") and name.endswith("/cmd_vel"):
                self._no_robot(name[2:])
        for sample in self.subscriptions.take(N=256):
            if getattr(sample, "topic_name", None) == "rt/clock":
                self.on_clock.add(sample.participant_key)
            if getattr(sample, "topic_name", None) and sample.participant_key != self.own:
                self.subscribed.add(sample.topic_name)
            topic = self.best_effort.get(getattr(sample, "topic_name", ""))
            if topic is not None and sample.participant_key != self.own and _reliable(sample.qos):
                self._say(("reliable", topic.name), "warning",
                          f"a node subscribes to {topic.name} as reliable, but Gazebo publishes it best effort "
                          f"({topic.qos.describe()}): that subscription receives nothing",
                          "subscribe with qos_profile_sensor_data (or leave /clock to use_sim_time)")

    def _publication(self, robot: DdsRobot, sample) -> None:
        theirs = msgs.ros_type_name(sample.type_name) if "::dds_::" in sample.type_name else sample.type_name
        ours = robot.cmd_type
        if theirs != ours:
            how = "geometry_msgs/msg/TwistStamped (header.stamp = now, the twist under .twist)" \
                if ours.endswith("TwistStamped") else ours
            self._say(("type", robot.cmd_name, theirs), "error",
                      f"a node publishes {theirs} on {robot.cmd_name}, but the simulated {self.wire.stack} TurtleBot3 "
                      f"takes {ours} there (as Gazebo's does): the robot does not move",
                      f"publish {how}")
        elif not _reliable(sample.qos):
            self._say(("qos", robot.cmd_name), "error",
                      f"a node publishes {robot.cmd_name} best effort, but Gazebo's subscription is reliable: "
                      "the robot does not move", "publish cmd_vel with the default QoS (depth 10)")

    def clock_followers(self, rate: float) -> None:
        """At a rate other than real time: a finding when some node's participant never subscribed to /clock
        (its timers and sleeps follow the wall clock, so it acts at another pace than in Gazebo)."""
        ignoring = len(self.others - self.on_clock)
        if rate != 1.0 and ignoring:
            pace = "as fast as it goes" if rate <= 0 else f"at {rate:g}x real time"
            self._say(("clock",), "info",
                      f"{ignoring} of the {len(self.others)} node processes do not follow /clock (use_sim_time is "
                      f"off): simulated time ran {pace}, their timers and sleeps on the wall clock",
                      "grade at --rate 1, or run the node with use_sim_time (_use_sim_time:=true after it)")

    def unheard(self) -> None:
        """A finding per topic a node subscribes to that nothing publishes, when its name is near one the
        simulator publishes (a typo: ``/scans``, ``/imus``): that subscription never hears a message."""
        ours = sorted(name[2:] for name, own in self.published.items() if own and name.startswith("rt/"))
        for name in sorted(self.subscribed):
            if not name.startswith("rt/") or name in self.published:
                continue
            near = near_topic(name[2:], ours)
            if near:
                self._say(("unheard", name), "warning", f"a node subscribes to {name[2:]}, which nothing publishes; "
                                                        f"did you mean {near}?",
                          f"subscribe to {near} (is the topic's name misspelt?)")

    def _no_robot(self, topic: str) -> None:
        """A velocity command for a namespace where no robot lives (a typo in ``__ns:=``, say)."""
        there = ", ".join(sorted(r.cmd_name for r in self.wire.robots))
        self._say(("nobody", topic), "error",
                  f"a node publishes {topic}, but no robot lives in {topic.rsplit('/', 1)[0] or '/'}: the robots "
                  f"take {there}", "check the node's namespace (__ns:=) and its cmd_vel remapping")

    def _say(self, key, severity: str, message: str, fix: str) -> None:
        if key not in self.said:
            self.said.add(key)
            with self.wire.lock:
                self.wire.findings.append({"check": "ros2", "severity": severity, "message": message, "fix": fix})


def _reliable(qos) -> bool:
    from cyclonedds.core import Policy

    try:
        return isinstance(qos[Policy.Reliability], Policy.Reliability.Reliable)
    except (KeyError, TypeError):
        return True   # DDS's default for a reader is best effort, for a writer reliable: only writers lack it


def matched(wire: DdsWire) -> int:
    """How many endpoints of others match the robot's own (its writers and cmd_vel readers)."""
    count = 0
    for robot in wire.robots:
        count += robot.cmd_reader.get_subscription_matched_status().current_count
        count += sum(w.get_publication_matched_status().current_count for w in robot.writers.values())
    return count


def matches(wire: DdsWire) -> tuple:
    """Every endpoint of the robots' matched count, in a fixed order (what changes while nodes still join)."""
    return tuple((r.cmd_reader.get_subscription_matched_status().current_count,
                  *(w.get_publication_matched_status().current_count for w in r.writers.values()))
                 for r in wire.robots)


def does_the_task(wire: DdsWire, need: str | None) -> bool:
    """Whether some node drives the graded robot and, when the task needs a topic of it (``need``), reads it."""
    robot = wire.graded_robot
    drives = robot.cmd_reader.get_subscription_matched_status().current_count > 0
    return drives and (need is None or need not in robot.writers or robot.heard(need))


def wait_for_start(wire: DdsWire, watcher: Watcher, config: dict) -> None:
    """Hold simulated time at 0 (publishing /clock) until the start file exists, or until ``expect`` other
    participants are there, some endpoint of theirs matches the robot's, and they are ready: the matches the same
    as at the previous look, some node driving the graded robot and reading what the task (``task``) needs
    (:data:`worldgen.interface.topics.TASK_INPUTS`), :data:`MATCHED_BOTH` after the first match at least; or
    :data:`SETTLE` after it."""
    start_file, expect = config.get("start_file"), int(config.get("expect") or 0)
    if not start_file and not expect:   # worldgen sim: at once
        return
    need = TASK_INPUTS.get(config.get("task") or "")
    deadline = time.monotonic() + START_WAIT
    seen, previous, clock_at = None, None, 0.0
    while time.monotonic() < deadline and not wire.stopped.is_set():
        now = time.monotonic()
        if now >= clock_at:
            wire.publish_clock()
            clock_at = now + 0.02
        watcher.look()
        if start_file and os.path.exists(start_file):
            return
        if expect and len(watcher.others) >= expect and matched(wire):
            seen = seen or now
            state, previous = previous, matches(wire)
            if now - seen >= SETTLE or (now - seen >= MATCHED_BOTH and state == previous and
                                         does_the_task(wire, need)):
                return
        time.sleep(0.005)


def _pids(config: dict) -> list:
    """The nodes' process ids (the run writes them once they are started), for pacing at rate max."""
    try:
        return json.loads(Path(config["pids_file"]).read_text(encoding="utf-8")) if config.get("pids_file") else []
    except (OSError, ValueError):
        return []


def main(argv: list) -> int:
    config = json.loads(Path(argv[0]).read_text(encoding="utf-8"))
    try:
        session = open_session(config)
    except WorldgenError as err:
        print(f"worldgen: error: {err}", file=sys.stderr, flush=True)
        return 2
    given = config.get("discovery") or {}
    discovery = Discovery("localhost" if given.get("range") in (None, "off") else given["range"],
                          tuple(given.get("peers") or ()))
    duration = config.get("duration")
    timing = dict(NO_TIMING)
    with session, Participant(int(config["domain"]), discovery) as participant:
        wire = DdsWire(session, config, participant)
        graph = announce(participant, wire)
        watcher = Watcher(wire)
        wire.publish_static()
        try:
            deliver_interrupts()
            wait_for_start(wire, watcher, config)
            print("worldgen-sim: running", file=sys.stderr, flush=True)
            wire.watcher = watcher
            timing = run_loop(wire, float(config.get("rate") or 0.0), duration, _pids(config),
                              udp=True)
            watcher.look()
            watcher.clock_followers(float(config.get("rate") or 0.0))
            watcher.unheard()
        except KeyboardInterrupt:
            pass
        finally:
            ignore_interrupts()
            with wire.lock:
                if config.get("trace"):
                    write_trace(config["trace"], dict(wire.result(), timing=timing))
            graph.close()
    return 0
