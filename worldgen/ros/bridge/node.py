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

Services ``/gazebo/reset_world`` and ``/gazebo/reset_simulation`` (std_srvs/Empty) put the robot back at its
spawn pose (simulated time keeps running: rewinding ``/clock`` would throw every node's ``rospy.Rate``).

``/clock`` goes out every other 1/240 s step, 120 Hz of simulated time: Gazebo's gazebo_ros publishes it at
100 Hz, ``rospy.Rate`` loops up to 30 Hz wake within 8 ms of when they should, and publishing every step would
double the clock traffic every node receives for nothing. The physics step stays the session's 1/240 s.

``rate`` paces simulated time at that many times real time; 0 runs as fast as it goes, and then, after each scan
that some node listens to, waits (at most 50 ms of real time) for the ``/cmd_vel`` that answers it, so that a
node reacting to scans reacts within the same scan period, as it does in Gazebo at real time.

Run as ``python -m worldgen.ros.bridge.node CONFIG.json`` (see :func:`main`); a trace of what the robot did is
written to the config's ``trace`` file at the end, for :mod:`.metrics`.
"""

from __future__ import annotations

import json
import math
import os
import sys
import threading
import time
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np

CLOCK_EVERY = 2          # physics steps per /clock and /imu message
BACKLOG = int(os.environ.get("WG_BACKLOG", "4096"))  # bytes unread by the nodes: they are falling behind
CHECK_EVERY = float(os.environ.get("WG_CHECK", "0.05"))  # s of real time between looks at the nodes' sockets
ANSWER_WAIT = 0.05       # s of real time to wait for the cmd_vel answering a scan at rate max
START_WAIT = 30.0        # s of real time to wait for the start signal
GRAVITY = 9.8
ODOM_COV = [1e-5, 0, 0, 0, 0, 0, 0, 1e-5, 0, 0, 0, 0, 0, 0, 1e12, 0, 0, 0, 0, 0, 0, 1e12, 0, 0,
            0, 0, 0, 0, 1e12, 0, 0, 0, 0, 0, 0, 1e-3]   # what gazebo_ros_diff_drive puts in both covariances


def _quat_rpy(roll: float, pitch: float, yaw: float):
    cr, sr = math.cos(roll / 2), math.sin(roll / 2)
    cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
    cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
    return (sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy, cr * cp * sy - sr * sp * cy,
            cr * cp * cy + sr * sp * sy)


def _quat_mul(a, b):
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return (aw * bx + ax * bw + ay * bz - az * by, aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw, aw * bw - ax * bx - ay * by - az * bz)


def _axis_quat(axis, angle: float):
    n = math.sqrt(sum(a * a for a in axis)) or 1.0
    s = math.sin(angle / 2) / n
    return (axis[0] * s, axis[1] * s, axis[2] * s, math.cos(angle / 2))


def joint_axes(urdf: str) -> dict[str, tuple[float, float, float]]:
    """Each joint's ``<axis xyz>`` (URDF's default 1 0 0 when absent)."""
    axes = {}
    for joint in ET.fromstring(urdf).findall("joint"):
        axis = joint.find("axis")
        text = axis.get("xyz") if axis is not None else None
        axes[joint.get("name", "")] = tuple(float(v) for v in text.split()) if text else (1.0, 0.0, 0.0)
    return axes


class Bridge:
    """The node's state: the session, its publishers, and what it recorded."""

    def __init__(self, rospy, session, config: dict):
        from geometry_msgs.msg import Twist
        from nav_msgs.msg import Odometry
        from rosgraph_msgs.msg import Clock
        from sensor_msgs.msg import Imu, JointState, LaserScan
        from std_srvs.srv import Empty, EmptyResponse
        from tf2_msgs.msg import TFMessage

        self.rospy, self.session, self.config = rospy, session, config
        self.msg = {"Clock": Clock, "LaserScan": LaserScan, "Odometry": Odometry, "TFMessage": TFMessage,
                    "JointState": JointState, "Imu": Imu}
        self.empty_response = EmptyResponse
        pub = rospy.Publisher
        self.pubs = {"clock": pub("/clock", Clock, queue_size=10), "scan": pub("/scan", LaserScan, queue_size=5),
                     "odom": pub("/odom", Odometry, queue_size=10), "tf": pub("/tf", TFMessage, queue_size=100),
                     "tf_static": pub("/tf_static", TFMessage, queue_size=10, latch=True),
                     "joint_states": pub("/joint_states", JointState, queue_size=10),
                     "imu": pub("/imu", Imu, queue_size=10)}
        self.lock = threading.Lock()
        self.answered = threading.Event()
        self.reset_requested = threading.Event()
        self.reset_done = threading.Event()
        self.cmd_count = 0
        self.cmd_first = None
        self.bag = None
        if config.get("bag"):
            import rosbag
            self.bag = rosbag.Bag(config["bag"], "w")
        self.cmd_sub = rospy.Subscriber("/cmd_vel", Twist, self.on_cmd_vel, queue_size=10)
        for name in ("/gazebo/reset_world", "/gazebo/reset_simulation"):
            rospy.Service(name, Empty, self.on_reset)
        profile = session.profile
        self.base = profile.base_frame
        self.axes = joint_axes(session.urdf)
        self.wheel_joints = {j.name: j for j in profile.joints
                             if j.name in (profile.drive.left_joint, profile.drive.right_joint)}
        self.imu_link = "imu_link" if "imu_link" in session.link_index else self.base
        self.trace = {"odom": [], "scans": [], "person": [], "cmd": []}
        self.last_velocity = None
        self.person = None
        if config.get("person"):
            p = config["person"]
            self.person = (session.add_mover(p["radius"], p["height"], "person", self.person_xy(0.0)), p)

    # -- callbacks (rospy's threads) -----------------------------------------------------------------------

    def on_cmd_vel(self, msg) -> None:
        v, w = float(msg.linear.x), float(msg.angular.z)
        if not (math.isfinite(v) and math.isfinite(w)):
            return   # the plugin would take NaN and wreck the model; a finding says the node sent it
        self.session.drive.command = (v, w)
        with self.lock:
            self.cmd_count += 1
            self.trace["cmd"].append([self.session.t, v, w])
            if self.bag is not None:
                self.bag.write("/cmd_vel", msg, self.rospy.Time.from_sec(self.session.t))
        self.answered.set()

    def on_reset(self, _request):
        self.reset_done.clear()
        self.reset_requested.set()
        self.reset_done.wait(5.0)
        return self.empty_response()

    # -- messages ------------------------------------------------------------------------------------------

    def stamp(self):
        return self.rospy.Time.from_sec(self.session.t)

    def transform(self, parent: str, child: str, xyz, quat, stamp):
        from geometry_msgs.msg import TransformStamped

        tf = TransformStamped()
        tf.header.stamp, tf.header.frame_id, tf.child_frame_id = stamp, parent, child
        tf.transform.translation.x, tf.transform.translation.y, tf.transform.translation.z = xyz
        r = tf.transform.rotation
        r.x, r.y, r.z, r.w = quat
        return tf

    def publish_static(self) -> None:
        stamp = self.stamp()
        transforms = [self.transform(j.parent, j.child, j.xyz, _quat_rpy(*j.rpy), stamp)
                      for j in self.session.profile.joints if j.type == "fixed"]
        self.pubs["tf_static"].publish(self.msg["TFMessage"](transforms=transforms))

    def publish_clock(self) -> None:
        self.pubs["clock"].publish(self.msg["Clock"](clock=self.stamp()))

    def publish_drive(self) -> None:
        """/odom, /tf and /joint_states (the diff-drive plugin's update), and a line of the trace."""
        s, stamp = self.session, self.stamp()
        (x, y, z), quat = s.link_pose(s.base_index)
        lin, ang = s.base_velocity()
        yaw = math.atan2(2 * (quat[3] * quat[2] + quat[0] * quat[1]), 1 - 2 * (quat[1] ** 2 + quat[2] ** 2))
        vx = math.cos(yaw) * lin[0] + math.sin(yaw) * lin[1]
        vy = math.cos(yaw) * lin[1] - math.sin(yaw) * lin[0]
        self.trace["odom"].append([s.t, x, y, yaw, vx, ang[2], *s.drive.command])
        if self.pubs["odom"].get_num_connections() or self.bag is not None:
            odom = self.msg["Odometry"]()
            odom.header.stamp, odom.header.frame_id, odom.child_frame_id = stamp, "odom", self.base
            p = odom.pose.pose
            p.position.x, p.position.y, p.position.z = x, y, z
            p.orientation.x, p.orientation.y, p.orientation.z, p.orientation.w = quat
            odom.pose.covariance = ODOM_COV
            odom.twist.twist.linear.x, odom.twist.twist.linear.y = vx, vy
            odom.twist.twist.angular.z = ang[2]
            odom.twist.covariance = ODOM_COV
            self.pubs["odom"].publish(odom)
            if self.bag is not None:
                with self.lock:
                    if self.bag is not None:
                        self.bag.write("/odom", odom, stamp)
        tf_wanted, js_wanted = self.pubs["tf"].get_num_connections(), self.pubs["joint_states"].get_num_connections()
        if tf_wanted or js_wanted:
            (pl, pr), (wl, wr) = s.wheel_states()
        if tf_wanted:
            transforms = [self.transform("odom", self.base, (x, y, z), quat, stamp)]
            for joint, angle in zip((s.profile.drive.left_joint, s.profile.drive.right_joint), (pl, pr)):
                j = self.wheel_joints.get(joint)
                if j is not None:
                    q = _quat_mul(_quat_rpy(*j.rpy), _axis_quat(self.axes.get(joint, (0, 0, 1)), angle))
                    transforms.append(self.transform(j.parent, j.child, j.xyz, q, stamp))
            self.pubs["tf"].publish(self.msg["TFMessage"](transforms=transforms))
        if js_wanted:
            js = self.msg["JointState"]()
            js.header.stamp = stamp
            js.name = [s.profile.drive.left_joint, s.profile.drive.right_joint]
            js.position, js.velocity, js.effort = [pl, pr], [wl, wr], []
            self.pubs["joint_states"].publish(js)
        if self.person is not None:
            self.trace["person"].append([s.t, *self.person_xy(s.t)])

    def publish_imu(self, dt: float) -> None:
        s = self.session
        if not self.pubs["imu"].get_num_connections():
            self.last_velocity = None
            return
        lin, ang = s.base_velocity()
        accel = (0.0, 0.0, 0.0)
        if self.last_velocity is not None:
            accel = tuple((a - b) / dt for a, b in zip(lin, self.last_velocity))
        self.last_velocity = lin
        _, quat = s.link_pose(self.imu_link)
        import pybullet as pb

        rot = np.array(pb.getMatrixFromQuaternion(quat)).reshape(3, 3)
        body_w = rot.T @ np.asarray(ang)
        body_a = rot.T @ (np.asarray(accel) + np.array([0.0, 0.0, GRAVITY]))
        imu = self.msg["Imu"]()
        imu.header.stamp, imu.header.frame_id = self.stamp(), self.imu_link
        imu.orientation.x, imu.orientation.y, imu.orientation.z, imu.orientation.w = quat
        imu.angular_velocity.x, imu.angular_velocity.y, imu.angular_velocity.z = body_w.tolist()
        imu.linear_acceleration.x, imu.linear_acceleration.y, imu.linear_acceleration.z = body_a.tolist()
        self.pubs["imu"].publish(imu)

    def publish_scan(self) -> bool:
        """One scan on /scan (and a trace line); True when some node listens to it."""
        from ...sim.lidar import front_distance

        s = self.session
        scan = s.scan()
        msg = self.msg["LaserScan"]()
        msg.header.stamp, msg.header.frame_id = self.stamp(), scan.frame_id
        msg.angle_min, msg.angle_max, msg.angle_increment = scan.angle_min, s.lidar.max_angle, scan.angle_increment
        msg.time_increment, msg.scan_time = 0.0, 0.0
        msg.range_min, msg.range_max = scan.range_min, scan.range_max
        msg.ranges = scan.ranges
        msg.intensities = [0.0] * len(scan.ranges)
        listened = self.pubs["scan"].get_num_connections() > 0
        self.pubs["scan"].publish(msg)
        if self.bag is not None:
            with self.lock:
                if self.bag is not None:
                    self.bag.write("/scan", msg, msg.header.stamp)
        true = [r for r in scan.true_ranges if math.isfinite(r)]
        front = front_distance(scan, true=True)
        self.trace["scans"].append([s.t, scan.true_ranges[0] if math.isfinite(scan.true_ranges[0]) else None,
                                    front, min(true) if true else None, s.clearance()])
        return listened

    def person_xy(self, t: float) -> tuple[float, float]:
        p = self.config["person"]
        angle = p["phase"] + p["speed"] * t / p["loop_radius"]
        return (p["centre"][0] + p["loop_radius"] * math.cos(angle), p["centre"][1] + p["loop_radius"] * math.sin(angle))


def wait_for_start(rospy, bridge: Bridge, param: str) -> None:
    """Hold simulated time at 0 (publishing /clock) until ``param`` is true on the master: the nodes under
    test are up, as with Gazebo started paused and then unpaused."""
    deadline = time.monotonic() + START_WAIT
    while time.monotonic() < deadline and not rospy.is_shutdown():
        bridge.publish_clock()
        if rospy.get_param(param, False):
            return
        time.sleep(0.02)


def run_loop(rospy, bridge: Bridge, rate: float, duration: float | None, pids=()) -> dict:
    """Step the session, publishing as the module docstring says, until ``duration`` simulated seconds have
    passed (None: until shut down). Returns the timing numbers."""
    s = bridge.session
    end_step = None if duration is None else round(duration / s.time_step)
    wall0, step, interrupted = time.monotonic(), 0, False
    bridge.publish_clock()
    bridge.publish_drive()
    try:
        _steps(rospy, bridge, rate, end_step, list(pids))
    except KeyboardInterrupt:
        interrupted = True
    wall = time.monotonic() - wall0
    return {"sim_time_s": s.t, "wall_time_s": wall, "real_time_factor": s.t / wall if wall > 0 else None,
            "interrupted": interrupted}


def unread_bytes(pids: list[int]) -> int:
    """Bytes waiting unread in the TCP sockets of processes ``pids`` (Linux: their socket inodes in /proc/PID/fd,
    matched with the rx_queue column of /proc/net/tcp{,6}); 0 where /proc cannot tell."""
    inodes = set()
    for pid in pids:
        try:
            for fd in os.listdir(f"/proc/{pid}/fd"):
                try:
                    target = os.readlink(f"/proc/{pid}/fd/{fd}")
                except OSError:
                    continue
                if target.startswith("socket:["):
                    inodes.add(target[8:-1])
        except OSError:
            continue
    total = 0
    for table in ("/proc/net/tcp", "/proc/net/tcp6"):
        try:
            lines = Path(table).read_text().splitlines()[1:]
        except OSError:
            continue
        for line in lines:
            fields = line.split()
            if len(fields) > 9 and fields[9] in inodes:
                total += int(fields[4].split(":")[1], 16)
    return total


class Governor:
    """Paces simulated time: at ``rate`` × real time, or, at rate 0 (max), as fast as the watched processes (the
    nodes under test) keep up: when more than :data:`BACKLOG` bytes of messages wait unread in their sockets, they
    are falling behind, and the pace drops below what was achieved; when nothing waits, it rises again, up to no
    limit. (A node that lags reacts late in simulated time, which Gazebo at real time never shows.)"""

    def __init__(self, rate: float, pids: list[int]):
        self.rate, self.pids = rate, list(pids)
        self.anchor_wall, self.anchor_sim = time.monotonic(), 0.0
        self.limit = rate if rate > 0 else None   # None: no limit
        self.last_check = self.anchor_wall
        self.previous = 0

    def pace(self, sim_t: float) -> None:
        now = time.monotonic()
        if self.rate <= 0 and self.pids and now - self.last_check >= CHECK_EVERY:
            now_waiting = unread_bytes(self.pids)
            waiting, self.previous = min(now_waiting, self.previous), now_waiting   # what persists, not a message in flight
            achieved = (sim_t - self.anchor_sim) / max(now - self.anchor_wall, 1e-6)
            if waiting > BACKLOG:
                self.limit = max(1.0, min(achieved, self.limit or achieved) * 0.7)
            elif waiting == 0 and self.limit is not None:
                self.limit = self.limit * 1.5 if self.limit < 200 else None
            self.anchor_wall, self.anchor_sim, self.last_check = now, sim_t, now
        if self.limit is not None:
            ahead = self.anchor_wall + (sim_t - self.anchor_sim) / self.limit - now
            if ahead > 0.0005:
                time.sleep(ahead)


def _steps(rospy, bridge: Bridge, rate: float, end_step: int | None, pids: list[int]) -> None:
    s = bridge.session
    dt = s.time_step
    drive_every = s._update_every
    scan_every = max(1, round(1.0 / (s.lidar.update_rate * dt))) if s.lidar is not None else 0
    person = bridge.person
    governor = Governor(rate, pids)
    step = 0
    while not rospy.is_shutdown() and (end_step is None or step < end_step):
        if bridge.reset_requested.is_set():
            bridge.reset_requested.clear()
            s.reset_robot()
            bridge.last_velocity = None
            bridge.reset_done.set()
        if person is not None:
            s.move_body(person[0], *bridge.person_xy(s.t + dt))
        s.run(dt)
        step += 1
        if step % CLOCK_EVERY == 0:
            bridge.publish_clock()
            bridge.publish_imu(dt * CLOCK_EVERY)
            governor.pace(s.t)
        if step % drive_every == 0:
            bridge.publish_drive()
        if scan_every and step % scan_every == 0:
            bridge.answered.clear()
            listened = bridge.publish_scan()
            if rate <= 0 and listened and bridge.cmd_sub.get_num_connections():
                bridge.answered.wait(ANSWER_WAIT)


def _write_json(path: str, data: dict) -> None:
    tmp = f"{path}.part"
    with open(tmp, "w", encoding="utf-8") as fh:
        json.dump(data, fh)
    os.replace(tmp, path)


def main(argv: list[str]) -> int:
    """``CONFIG.json`` holds: scene_file (a pickled Scene), robot, spawn [x, y, yaw], no_hit, rate (0 = max),
    duration (s or null), trace (file or null), bag (file or null), start_param (null: start at once), person
    (null or the loop), set_sim_time (bool)."""
    from ...core.errors import WorldgenError
    from ...core.scene import Scene
    from .rosenv import import_rospy

    config = json.loads(Path(argv[0]).read_text(encoding="utf-8"))
    try:
        rospy = import_rospy()
        from ...sim.session import Session

        session = Session(Scene.load(config["scene_file"]), config.get("robot") or "burger",
                          tuple(config["spawn"]), no_hit=config.get("no_hit", "inf"), seed=config.get("seed", 0))
    except WorldgenError as err:
        print(f"worldgen: error: {err}", file=sys.stderr, flush=True)
        return 2
    with session:
        rospy.init_node("gazebo", disable_signals=True, anonymous=False)
        if config.get("set_sim_time", True):
            rospy.set_param("/use_sim_time", True)
        bridge = Bridge(rospy, session, config)
        bridge.publish_static()
        timing = {"sim_time_s": 0.0, "wall_time_s": 0.0, "real_time_factor": None, "interrupted": True}
        try:
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


def finish(rospy, bridge: Bridge, config: dict, timing: dict) -> None:
    """Write the trace and close the bag (under the lock the callbacks take), then leave the master."""
    with bridge.lock:
        if config.get("trace"):
            trace = dict(bridge.trace, cmd_vel_messages=bridge.cmd_count, timing=timing,
                         contacts=bridge.session.touches.to_list(), spawn=list(bridge.session.spawn),
                         robot=config.get("robot") or "burger")
            _write_json(config["trace"], trace)
        if bridge.bag is not None:
            bridge.bag.close()
            bridge.bag = None
    rospy.signal_shutdown("worldgen sim done")


def _interrupt(signum, frame):
    raise KeyboardInterrupt(f"signal {signum}")


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
    try:
        sys.exit(main(sys.argv[1:]))
    except KeyboardInterrupt:   # interrupted before the loop started: nothing to write
        sys.exit(0)
