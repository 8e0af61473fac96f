"""The ros_gz_bridge parameter file of a Jazzy package: which Gazebo Sim topics reach ROS 2 and back.

``parameter_bridge --ros-args -p config_file:=FILE`` reads a YAML list, one entry per topic, each with
``ros_topic_name``, ``gz_topic_name``, ``ros_type_name``, ``gz_type_name`` and ``direction`` (``GZ_TO_ROS`` or
``ROS_TO_GZ``). The topics are those of turtlebot3_gazebo's jazzy bridge files (its
``params/turtlebot3_<model>_bridge.yaml``), the same for burger, waffle and waffle_pi: the clock, the wheel joint
states, odometry and its TF (DiffDrive), the velocity command, the IMU and the LiDAR scan. Relative names on
both sides, so a namespace moves them all.

``cmd_vel`` is ``geometry_msgs/msg/TwistStamped`` on the ROS side, as there; ``twist`` writes
``geometry_msgs/msg/Twist`` (what Humble, Noetic and older class nodes publish).
"""

from __future__ import annotations

from typing import NamedTuple

BRIDGE_FILE = "turtlebot3_bridge.yaml"   # in the world package's params/ folder


class BridgedTopic(NamedTuple):
    """One bridged topic: its name (the same on both sides), its ROS and Gazebo types, which way it goes and
    which Gazebo system publishes or reads it."""

    name: str
    ros_type: str
    gz_type: str
    direction: str
    source: str


def bridged_topics(cmd_vel: str = "stamped") -> tuple[BridgedTopic, ...]:
    """The bridge's topics, in the order they are written; ``cmd_vel`` is ``stamped`` or ``twist``."""
    if cmd_vel not in ("stamped", "twist"):
        raise ValueError(f"cmd_vel is 'stamped' or 'twist', not {cmd_vel!r}")
    twist = "geometry_msgs/msg/TwistStamped" if cmd_vel == "stamped" else "geometry_msgs/msg/Twist"
    return (
        BridgedTopic("clock", "rosgraph_msgs/msg/Clock", "gz.msgs.Clock", "GZ_TO_ROS", "the simulator"),
        BridgedTopic("joint_states", "sensor_msgs/msg/JointState", "gz.msgs.Model", "GZ_TO_ROS",
                     "the robot's JointStatePublisher system"),
        BridgedTopic("odom", "nav_msgs/msg/Odometry", "gz.msgs.Odometry", "GZ_TO_ROS", "the DiffDrive system"),
        BridgedTopic("tf", "tf2_msgs/msg/TFMessage", "gz.msgs.Pose_V", "GZ_TO_ROS", "the DiffDrive system"),
        BridgedTopic("cmd_vel", twist, "gz.msgs.Twist", "ROS_TO_GZ", "read by the DiffDrive system"),
        BridgedTopic("imu", "sensor_msgs/msg/Imu", "gz.msgs.IMU", "GZ_TO_ROS", "the robot's IMU sensor"),
        BridgedTopic("scan", "sensor_msgs/msg/LaserScan", "gz.msgs.LaserScan", "GZ_TO_ROS",
                     "the robot's gpu_lidar sensor"),
    )


def bridge_yaml(cmd_vel: str = "stamped") -> str:
    """The bridge's parameter file (YAML text; the same bytes for the same ``cmd_vel``)."""
    lines = ["# ros_gz_bridge topics for a TurtleBot3 in Gazebo Sim, written by worldgen.",
             "# Started by the package's launch files as:",
             "#   ros2 run ros_gz_bridge parameter_bridge --ros-args -p config_file:=<this file>"]
    if cmd_vel == "stamped":
        lines.append("# cmd_vel takes geometry_msgs/msg/TwistStamped; 'worldgen ... --cmd-vel twist' writes Twist.")
    else:
        lines.append("# cmd_vel takes geometry_msgs/msg/Twist (--cmd-vel twist); Jazzy's TurtleBot3 default is "
                     "TwistStamped.")
    for topic in bridged_topics(cmd_vel):
        lines += ["", f"# {topic.source}",
                  f'- ros_topic_name: "{topic.name}"',
                  f'  gz_topic_name: "{topic.name}"',
                  f'  ros_type_name: "{topic.ros_type}"',
                  f'  gz_type_name: "{topic.gz_type}"',
                  f"  direction: {topic.direction}"]
    return "\n".join(lines) + "\n"
