"""geometry_msgs Pose and Twist ↔ plain numbers, as gazebo_ros reads and writes them."""

from __future__ import annotations

import math


def pose7(msg) -> tuple:
    p, q = msg.position, msg.orientation
    quat = (q.x, q.y, q.z, q.w)
    if not any(quat) or not all(math.isfinite(v) for v in quat):   # Gazebo normalises a zero quaternion to identity
        quat = (0.0, 0.0, 0.0, 1.0)
    n = math.sqrt(sum(v * v for v in quat))
    return (p.x, p.y, p.z, *(v / n for v in quat))


def fill_pose(msg, pose) -> None:
    msg.position.x, msg.position.y, msg.position.z = pose[:3]
    msg.orientation.x, msg.orientation.y, msg.orientation.z, msg.orientation.w = pose[3:]


def fill_twist(msg, linear, angular) -> None:
    msg.linear.x, msg.linear.y, msg.linear.z = linear
    msg.angular.x, msg.angular.y, msg.angular.z = angular
