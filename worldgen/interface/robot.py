"""One simulated robot as Gazebo's TurtleBot3 plugins present it, whatever the transport: the contents of its
messages (odometry, tf, joint states, IMU, scan), what a velocity command does, and what it did (the trace
:mod:`worldgen.bridge.metrics` reads).

A robot in namespace ``ns`` has its topics under ``ns/`` (:func:`.topics.join`); every frame carries its tf prefix
(:func:`.topics.frame`): the ``tf_prefix`` parameter found from its namespace upwards on ROS 1, else the namespace
without slashes, gazebo_ros's rule. Message values are nested dicts in ROS 2's field names, times as float seconds
(see :mod:`worldgen.interface`).
"""

from __future__ import annotations

import math
import threading
import xml.etree.ElementTree as ET
from dataclasses import dataclass

import numpy as np

from ..sim.lidar import front_distance, lidar_info, scan_row
from .topics import frame

GRAVITY = 9.8
ODOM_COV = [1e-5, 0, 0, 0, 0, 0, 0, 1e-5, 0, 0, 0, 0, 0, 0, 1e12, 0, 0, 0, 0, 0, 0, 1e12, 0, 0,
            0, 0, 0, 0, 1e12, 0, 0, 0, 0, 0, 0, 1e-3]   # what gazebo_ros_diff_drive puts in both covariances


@dataclass(frozen=True)
class Plugins:
    """How a stack's Gazebo plugins fill the robot's messages where the stacks differ (docs/ros2_stacks.md):
    ``wheel_odometry``: odometry counted from the spawn pose, z 0 and yaw only (Gazebo Sim's DiffDrive), else the
    true pose in the world (gazebo_ros_diff_drive's odometrySource world); ``odom_covariance`` (None: zeros);
    ``imu_frame``: the IMU's frame id, ``{model}`` standing for the robot model (None: its link);
    ``imu_covariance``: the diagonal of the angular velocity and linear acceleration covariances; ``effort``:
    joint_states carries efforts (zeros) as Gazebo Sim's JointStatePublisher does; ``twist_covariance``: the
    odometry's twist carries the pose's covariance (ROS 2's gazebo_ros_diff_drive) or zeros (ROS 1's);
    ``joint_velocity``: joint_states carries the wheels' velocities (ROS 1's diff drive fills positions only).

    ``imu_sensor``: the IMU is a Gazebo IMU sensor (Humble's gazebo_ros_imu_sensor, Gazebo Sim's Imu system):
    proper acceleration (gravity included, +9.8 up at rest) and rates in the sensor's frame. Otherwise it is
    Noetic's TurtleBot3 IMU, the model plugin libgazebo_ros_imu (gazebo_plugins/src/gazebo_ros_imu.cpp): the link's
    world velocity differenced between updates (no gravity: about 0 at rest) and the world angular velocity, each
    turned by the link's rotation (``RotateVector``, not its inverse, as the plugin does), covariances zero."""

    wheel_odometry: bool = False
    odom_covariance: tuple | None = tuple(ODOM_COV)
    twist_covariance: bool = True
    imu_frame: str | None = None
    imu_covariance: tuple = (0.0, 0.0)
    imu_sensor: bool = True
    effort: bool = False
    joint_velocity: bool = True


PLUGINS = {
    "noetic": Plugins(twist_covariance=False, imu_sensor=False, joint_velocity=False),
    "humble": Plugins(imu_covariance=(4e-8, 2.89e-4)),
    "jazzy": Plugins(wheel_odometry=True, odom_covariance=None, imu_frame="{model}/imu_link/tb3_imu",
                     imu_covariance=(4e-8, 2.89e-4), effort=True),
}


def diagonal(value: float) -> list[float]:
    return [value, 0.0, 0.0, 0.0, value, 0.0, 0.0, 0.0, value]


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


def header(t: float, frame_id: str) -> dict:
    return {"stamp": t, "frame_id": frame_id}


def vector(xyz) -> dict:
    return {"x": float(xyz[0]), "y": float(xyz[1]), "z": float(xyz[2])}


def quaternion(q) -> dict:
    return {"x": float(q[0]), "y": float(q[1]), "z": float(q[2]), "w": float(q[3])}


class RobotIO:
    """One robot's messages, commands and trace (see the module docstring). A transport calls :meth:`command`
    from its own threads; everything else runs in the step loop."""

    def __init__(self, robot, ns: str = "/", tf_prefix: str = "", *, record_scans: bool = False, lock=None,
                 plugins: Plugins = PLUGINS["noetic"], model: str = "burger"):
        self.robot, self.ns, self.prefix, self.plugins = robot, ns, tf_prefix, plugins
        self.lock = lock or threading.Lock()
        profile = robot.profile
        self.base = profile.base_frame
        self.axes = joint_axes(robot.urdf)
        self.wheel_joints = {j.name: j for j in profile.joints
                             if j.name in (profile.drive.left_joint, profile.drive.right_joint)}
        self.imu_link = "imu_link" if "imu_link" in robot.link_index else self.base
        self.imu_frame = plugins.imu_frame.format(model=model) if plugins.imu_frame else \
            frame(tf_prefix, self.imu_link)
        self.trace: dict = {"odom": [], "scans": [], "cmd": []}
        self.record_scans = record_scans and robot.lidar is not None
        if self.record_scans:   # every published scan, for a replay (see scan)
            self.trace.update(lidar=lidar_info(robot.lidar), ranges=[])
        self.answered = threading.Event()   # set by each command: the answer to a scan at rate max
        self.cmd_count = 0
        self.last_velocity = None
        self.now = 0.0

    # -- in ------------------------------------------------------------------------------------------------

    def command(self, v: float, w: float) -> bool:
        """A velocity command into gazebo_ros_diff_drive's model; False (ignored) when not finite: the plugin
        would take NaN and wreck the model, and a finding says the node sent it."""
        v, w = float(v), float(w)
        if not (math.isfinite(v) and math.isfinite(w)):
            return False
        self.robot.drive.command = (v, w)
        with self.lock:
            self.cmd_count += 1
            self.trace["cmd"].append([self.now, v, w])
        self.answered.set()
        return True

    def reset(self) -> None:
        """Back at the spawn pose, at rest (reset_world)."""
        self.robot.reset()
        self.last_velocity = None

    # -- out -----------------------------------------------------------------------------------------------

    def transform(self, parent: str, child: str, xyz, quat, t: float) -> dict:
        return {"header": header(t, frame(self.prefix, parent)), "child_frame_id": frame(self.prefix, child),
                "transform": {"translation": vector(xyz), "rotation": quaternion(quat)}}

    def static_transforms(self, t: float) -> list[dict]:
        """The fixed joints of the description, as robot_state_publisher sends them on /tf_static."""
        return [self.transform(j.parent, j.child, j.xyz, quat_rpy(*j.rpy), t)
                for j in self.robot.profile.joints if j.type == "fixed"]

    def drive(self, t: float, *, odom: bool, tf: bool, joint_states: bool) -> dict:
        """The diff-drive plugin's update at ``t``: a line of the trace, and the messages asked for (``odom``,
        ``tf``: the transforms of odom → base and the wheels, ``joint_states``)."""
        r = self.robot
        (x, y, z), quat = r.link_pose(r.base_index)
        lin, ang = r.base_velocity()
        yaw = math.atan2(2 * (quat[3] * quat[2] + quat[0] * quat[1]), 1 - 2 * (quat[1] ** 2 + quat[2] ** 2))
        vx = math.cos(yaw) * lin[0] + math.sin(yaw) * lin[1]
        vy = math.cos(yaw) * lin[1] - math.sin(yaw) * lin[0]
        self.trace["odom"].append([t, x, y, yaw, vx, ang[2], *r.drive.command])
        out: dict = {}
        position, orientation = self.odom_pose((x, y, z), quat, yaw)
        if odom:
            twist = {"linear": vector((vx, vy, 0.0)), "angular": vector((0.0, 0.0, ang[2]))}
            cov = list(self.plugins.odom_covariance or [0.0] * 36)
            out["odom"] = {"header": header(t, frame(self.prefix, "odom")),
                           "child_frame_id": frame(self.prefix, self.base),
                           "pose": {"pose": {"position": vector(position), "orientation": quaternion(orientation)},
                                    "covariance": cov},
                           "twist": {"twist": twist,
                                     "covariance": cov if self.plugins.twist_covariance else [0.0] * 36}}
        if tf or joint_states:
            (pl, pr), (wl, wr) = r.wheel_states()
        if tf:
            transforms = [self.transform("odom", self.base, position, orientation, t)]
            for joint, angle in zip((r.profile.drive.left_joint, r.profile.drive.right_joint), (pl, pr)):
                j = self.wheel_joints.get(joint)
                if j is not None:
                    q = quat_mul(quat_rpy(*j.rpy), axis_quat(self.axes.get(joint, (0, 0, 1)), angle))
                    transforms.append(self.transform(j.parent, j.child, j.xyz, q, t))
            out["tf"] = transforms
        if joint_states:
            out["joint_states"] = {"header": header(t, ""),
                                   "name": [r.profile.drive.left_joint, r.profile.drive.right_joint],
                                   "position": [pl, pr], "velocity": [wl, wr] if self.plugins.joint_velocity else [],
                                   "effort": [0.0, 0.0] if self.plugins.effort else []}
        return out

    def odom_pose(self, xyz, quat, yaw: float):
        """The pose odometry reports: the true one, or (wheel odometry) the one counted from the spawn pose."""
        if not self.plugins.wheel_odometry:
            return xyz, quat
        x0, y0, yaw0 = self.robot.spawn
        c, s = math.cos(yaw0), math.sin(yaw0)
        dx, dy = xyz[0] - x0, xyz[1] - y0
        heading = math.atan2(math.sin(yaw - yaw0), math.cos(yaw - yaw0))
        return (c * dx + s * dy, -s * dx + c * dy, 0.0), (0.0, 0.0, math.sin(heading / 2), math.cos(heading / 2))

    def imu(self, dt: float, t: float) -> dict:
        """The IMU at ``t``: true orientation, body rates, and the acceleration (differenced over ``dt``) with
        gravity, in the IMU link's frame."""
        import pybullet as pb   # the simulation's own, already loaded

        r = self.robot
        lin, ang = r.base_velocity()
        accel = (0.0, 0.0, 0.0)
        if self.last_velocity is not None:
            accel = tuple((a - b) / dt for a, b in zip(lin, self.last_velocity))
        self.last_velocity = lin
        _, quat = r.link_pose(self.imu_link)
        rot = np.array(pb.getMatrixFromQuaternion(quat)).reshape(3, 3)
        if self.plugins.imu_sensor:
            body_w = rot.T @ np.asarray(ang)
            body_a = rot.T @ (np.asarray(accel) + np.array([0.0, 0.0, GRAVITY]))
        else:   # Noetic's libgazebo_ros_imu, quirks included (see Plugins)
            body_w = rot @ np.asarray(ang)
            body_a = rot @ np.asarray(accel)
        gyro, accel_cov = self.plugins.imu_covariance
        return {"header": header(t, self.imu_frame), "orientation": quaternion(quat),
                "angular_velocity": vector(body_w.tolist()), "linear_acceleration": vector(body_a.tolist()),
                "angular_velocity_covariance": diagonal(gyro), "linear_acceleration_covariance": diagonal(accel_cov)}

    def imu_unheard(self) -> None:
        """No one listens to the IMU: the next acceleration starts afresh."""
        self.last_velocity = None

    def scan(self, session) -> dict:
        """One scan at the session's time, and a line of the trace. Recording scans, the trace's ``ranges`` also
        gets ``[t, ox, oy, yaw, [mm, …]]``, the ranges as published (:func:`worldgen.sim.lidar.scan_row`)."""
        r = self.robot
        scan = session.scan_of(r)
        msg = {"header": header(session.t, frame(self.prefix, scan.frame_id)), "angle_min": scan.angle_min,
               "angle_max": r.lidar.max_angle, "angle_increment": scan.angle_increment, "time_increment": 0.0,
               "scan_time": 0.0, "range_min": scan.range_min, "range_max": scan.range_max, "ranges": scan.ranges,
               "intensities": [0.0] * len(scan.ranges)}
        true = [d for d in scan.true_ranges if math.isfinite(d)]
        front = front_distance(scan, true=True)
        first = scan.true_ranges[0]
        self.trace["scans"].append([session.t, first if math.isfinite(first) else None, front,
                                    min(true) if true else None, session.clearance_of(r)])
        if self.record_scans:
            self.trace["ranges"].append([round(session.t, 3), *scan_row(scan)])
        return msg

    def result(self) -> dict:
        """This robot's part of the trace file."""
        return dict(self.trace, cmd_vel_messages=self.cmd_count, contacts=self.robot.touches.to_list(),
                    spawn=list(self.robot.spawn), ns=self.ns, name=self.robot.name)
