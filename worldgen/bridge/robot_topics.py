"""One simulated robot's ROS side: what the TurtleBot3's Gazebo plugins publish and subscribe for it, in its
namespace, and what it did (the trace :mod:`.metrics` reads).

A robot in namespace ``ns`` (``/`` for the one robot of the class's launch files; ``/tb3_0`` for a robot spawned
in ``<group ns="tb3_0">``) gets ``ns/scan``, ``ns/odom``, ``ns/imu``, ``ns/joint_states`` and ``ns/cmd_vel``, as
gazebo_ros's plugins do with the robot namespace spawn_model gives them. ``/tf`` and ``/tf_static`` stay global,
and every frame is prefixed with the robot's tf prefix — the ``tf_prefix`` parameter found from its namespace
upwards, else the namespace itself without slashes (gazebo_ros's rule), so ``tb3_0/odom`` → ``tb3_0/base_footprint``
and, for the fixed joints robot_state_publisher would publish, ``tb3_0/base_footprint`` → ``tb3_0/base_link``.
"""

from __future__ import annotations

import math
import threading
import xml.etree.ElementTree as ET

import numpy as np

GRAVITY = 9.8
ODOM_COV = [1e-5, 0, 0, 0, 0, 0, 0, 1e-5, 0, 0, 0, 0, 0, 0, 1e12, 0, 0, 0, 0, 0, 0, 1e12, 0, 0,
            0, 0, 0, 0, 1e12, 0, 0, 0, 0, 0, 0, 1e-3]   # what gazebo_ros_diff_drive puts in both covariances


def quat_rpy(roll: float, pitch: float, yaw: float):
    cr, sr = math.cos(roll / 2), math.sin(roll / 2)
    cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
    cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
    return (sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy, cr * cp * sy - sr * sp * cy,
            cr * cp * cy + sr * sp * sy)


def quat_mul(a, b):
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return (aw * bx + ax * bw + ay * bz - az * by, aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw, aw * bw - ax * bx - ay * by - az * bz)


def axis_quat(axis, angle: float):
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


def topic(ns: str, name: str) -> str:
    return f"{ns.rstrip('/')}/{name}" if ns not in ("", "/") else f"/{name}"


def frame(prefix: str, name: str) -> str:
    return f"{prefix}/{name}" if prefix else name


class RobotTopics:
    """The publishers, the ``cmd_vel`` subscriber and the trace of one robot (see the module docstring)."""

    def __init__(self, rospy, msgs: dict, robot, ns: str = "/", tf_prefix: str = "", bag=None, lock=None,
                 record_scans: bool = False):
        from geometry_msgs.msg import Twist

        self.rospy, self.msg, self.robot, self.ns, self.prefix = rospy, msgs, robot, ns, tf_prefix
        self.bag, self.lock = bag, lock or threading.Lock()
        pub = rospy.Publisher
        self.pubs = {"scan": pub(topic(ns, "scan"), msgs["LaserScan"], queue_size=5),
                     "odom": pub(topic(ns, "odom"), msgs["Odometry"], queue_size=10),
                     "joint_states": pub(topic(ns, "joint_states"), msgs["JointState"], queue_size=10),
                     "imu": pub(topic(ns, "imu"), msgs["Imu"], queue_size=10)}
        self.answered = threading.Event()
        self.cmd_count = 0
        self.cmd_sub = rospy.Subscriber(topic(ns, "cmd_vel"), Twist, self.on_cmd_vel, queue_size=10)
        profile = robot.profile
        self.base = profile.base_frame
        self.axes = joint_axes(robot.urdf)
        self.wheel_joints = {j.name: j for j in profile.joints
                             if j.name in (profile.drive.left_joint, profile.drive.right_joint)}
        self.imu_link = "imu_link" if "imu_link" in robot.link_index else self.base
        self.trace = {"odom": [], "scans": [], "cmd": []}
        self.record_scans = record_scans and robot.lidar is not None
        if self.record_scans:   # every published scan, for a replay (see publish_scan)
            from ..sim.lidar import lidar_info

            self.trace.update(lidar=lidar_info(robot.lidar), ranges=[])
        self.last_velocity = None
        self.now = 0.0
        self.cameras: list = []   # its CameraTopics (:mod:`.camera_topics`), which the node adds

    def close(self) -> None:
        for camera in self.cameras:
            camera.close()
        self.cmd_sub.unregister()
        for publisher in self.pubs.values():
            publisher.unregister()

    # -- cmd_vel (a rospy thread) ----------------------------------------------------------------------------

    def on_cmd_vel(self, msg) -> None:
        v, w = float(msg.linear.x), float(msg.angular.z)
        if not (math.isfinite(v) and math.isfinite(w)):
            return   # the plugin would take NaN and wreck the model; a finding says the node sent it
        self.robot.drive.command = (v, w)
        with self.lock:
            self.cmd_count += 1
            self.trace["cmd"].append([self.now, v, w])
            if self.bag is not None:
                self.bag.write(topic(self.ns, "cmd_vel"), msg, self.rospy.Time.from_sec(self.now))
        self.answered.set()

    # -- messages --------------------------------------------------------------------------------------------

    def transform(self, parent: str, child: str, xyz, quat, stamp):
        from geometry_msgs.msg import TransformStamped

        tf = TransformStamped()
        tf.header.stamp, tf.header.frame_id = stamp, frame(self.prefix, parent)
        tf.child_frame_id = frame(self.prefix, child)
        tf.transform.translation.x, tf.transform.translation.y, tf.transform.translation.z = xyz
        r = tf.transform.rotation
        r.x, r.y, r.z, r.w = quat
        return tf

    def static_transforms(self, stamp) -> list:
        """The fixed joints of the description, as robot_state_publisher sends them on /tf_static."""
        return [self.transform(j.parent, j.child, j.xyz, quat_rpy(*j.rpy), stamp)
                for j in self.robot.profile.joints if j.type == "fixed"]

    def _write_bag(self, name: str, msg, stamp) -> None:
        if self.bag is not None:
            with self.lock:
                if self.bag is not None:
                    self.bag.write(topic(self.ns, name), msg, stamp)

    def publish_drive(self, t: float, stamp, tf_pub) -> None:
        """The diff-drive plugin's update: odom, tf and joint_states, and a line of the trace."""
        r = self.robot
        (x, y, z), quat = r.link_pose(r.base_index)
        lin, ang = r.base_velocity()
        yaw = math.atan2(2 * (quat[3] * quat[2] + quat[0] * quat[1]), 1 - 2 * (quat[1] ** 2 + quat[2] ** 2))
        vx = math.cos(yaw) * lin[0] + math.sin(yaw) * lin[1]
        vy = math.cos(yaw) * lin[1] - math.sin(yaw) * lin[0]
        self.trace["odom"].append([t, x, y, yaw, vx, ang[2], *r.drive.command])
        if self.pubs["odom"].get_num_connections() or self.bag is not None:
            odom = self.msg["Odometry"]()
            odom.header.stamp, odom.header.frame_id = stamp, frame(self.prefix, "odom")
            odom.child_frame_id = frame(self.prefix, self.base)
            p = odom.pose.pose
            p.position.x, p.position.y, p.position.z = x, y, z
            p.orientation.x, p.orientation.y, p.orientation.z, p.orientation.w = quat
            odom.pose.covariance = ODOM_COV
            odom.twist.twist.linear.x, odom.twist.twist.linear.y = vx, vy
            odom.twist.twist.angular.z = ang[2]
            odom.twist.covariance = ODOM_COV
            self.pubs["odom"].publish(odom)
            self._write_bag("odom", odom, stamp)
        tf_wanted, js_wanted = tf_pub.get_num_connections(), self.pubs["joint_states"].get_num_connections()
        if tf_wanted or js_wanted:
            (pl, pr), (wl, wr) = r.wheel_states()
        if tf_wanted:
            transforms = [self.transform("odom", self.base, (x, y, z), quat, stamp)]
            for joint, angle in zip((r.profile.drive.left_joint, r.profile.drive.right_joint), (pl, pr)):
                j = self.wheel_joints.get(joint)
                if j is not None:
                    q = quat_mul(quat_rpy(*j.rpy), axis_quat(self.axes.get(joint, (0, 0, 1)), angle))
                    transforms.append(self.transform(j.parent, j.child, j.xyz, q, stamp))
            tf_pub.publish(self.msg["TFMessage"](transforms=transforms))
        if js_wanted:
            js = self.msg["JointState"]()
            js.header.stamp = stamp
            js.name = [r.profile.drive.left_joint, r.profile.drive.right_joint]
            js.position, js.velocity, js.effort = [pl, pr], [wl, wr], []
            self.pubs["joint_states"].publish(js)

    def publish_imu(self, dt: float, stamp) -> None:
        if not self.pubs["imu"].get_num_connections():
            self.last_velocity = None
            return
        r = self.robot
        lin, ang = r.base_velocity()
        accel = (0.0, 0.0, 0.0)
        if self.last_velocity is not None:
            accel = tuple((a - b) / dt for a, b in zip(lin, self.last_velocity))
        self.last_velocity = lin
        _, quat = r.link_pose(self.imu_link)
        import pybullet as pb

        rot = np.array(pb.getMatrixFromQuaternion(quat)).reshape(3, 3)
        body_w = rot.T @ np.asarray(ang)
        body_a = rot.T @ (np.asarray(accel) + np.array([0.0, 0.0, GRAVITY]))
        imu = self.msg["Imu"]()
        imu.header.stamp, imu.header.frame_id = stamp, frame(self.prefix, self.imu_link)
        imu.orientation.x, imu.orientation.y, imu.orientation.z, imu.orientation.w = quat
        imu.angular_velocity.x, imu.angular_velocity.y, imu.angular_velocity.z = body_w.tolist()
        imu.linear_acceleration.x, imu.linear_acceleration.y, imu.linear_acceleration.z = body_a.tolist()
        self.pubs["imu"].publish(imu)

    def publish_scan(self, session, stamp) -> bool:
        """One scan (and a trace line); True when some node listens to it. Recording scans, the trace's
        ``ranges`` also gets ``[t, ox, oy, yaw, [mm, …]]``, the ranges as published
        (:func:`worldgen.sim.lidar.scan_row`)."""
        from ..sim.lidar import front_distance, scan_row

        r = self.robot
        scan = session.scan_of(r)
        msg = self.msg["LaserScan"]()
        msg.header.stamp, msg.header.frame_id = stamp, frame(self.prefix, scan.frame_id)
        msg.angle_min, msg.angle_max, msg.angle_increment = scan.angle_min, r.lidar.max_angle, scan.angle_increment
        msg.time_increment, msg.scan_time = 0.0, 0.0
        msg.range_min, msg.range_max = scan.range_min, scan.range_max
        msg.ranges = scan.ranges
        msg.intensities = [0.0] * len(scan.ranges)
        listened = self.pubs["scan"].get_num_connections() > 0
        self.pubs["scan"].publish(msg)
        self._write_bag("scan", msg, stamp)
        true = [d for d in scan.true_ranges if math.isfinite(d)]
        front = front_distance(scan, true=True)
        self.trace["scans"].append([session.t, scan.true_ranges[0] if math.isfinite(scan.true_ranges[0]) else None,
                                    front, min(true) if true else None, session.clearance_of(r)])
        if self.record_scans:
            self.trace["ranges"].append([round(session.t, 3), *scan_row(scan)])
        return listened

    def result(self) -> dict:
        """This robot's part of the trace file."""
        return dict(self.trace, cmd_vel_messages=self.cmd_count, contacts=self.robot.touches.to_list(),
                    spawn=list(self.robot.spawn), ns=self.ns, name=self.robot.name)
