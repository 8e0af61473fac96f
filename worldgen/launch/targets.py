"""The three ROS + Gazebo targets worldgen writes for, and what differs between them.

| target | ROS | simulator | world | launch file | packages |
|---|---|---|---|---|---|
| ``noetic`` | ROS 1 Noetic | Gazebo Classic 11 | ``NAME.world``, SDF 1.6 | ``NAME.launch`` (roslaunch XML) | catkin |
| ``humble`` | ROS 2 Humble | Gazebo Classic 11 (gazebo_ros) | ``NAME.world``, SDF 1.6 | ``NAME.launch.py`` | ament_python |
| ``jazzy`` | ROS 2 Jazzy | Gazebo Sim Harmonic (ros_gz) | ``NAME.sdf``, SDF 1.8 | ``NAME.launch.py`` + bridge YAML | ament_python |

Jazzy's TurtleBot3 takes ``cmd_vel`` as ``geometry_msgs/msg/TwistStamped`` through the bridge (as
turtlebot3_gazebo's jazzy bridge files have it); ``--cmd-vel twist`` bridges plain ``Twist`` instead, and the class
nodes publish whichever the bridge takes. Humble's gazebo_ros diff drive and Noetic's take ``Twist``.
"""

from __future__ import annotations

from ..core.errors import InputError

ROS_TARGETS = ("noetic", "humble", "jazzy")
DEFAULT_ROS = "noetic"
ROS2_TARGETS = ("humble", "jazzy")
CMD_VEL_CHOICES = ("stamped", "twist")
WORLD_SUFFIX = {"noetic": ".world", "humble": ".world", "jazzy": ".sdf"}
SDF_VERSION = {"noetic": "1.6", "humble": "1.6", "jazzy": "1.8"}


def check_ros(ros: str) -> str:
    """``ros`` if it is a target worldgen writes for; InputError otherwise."""
    if ros not in ROS_TARGETS:
        raise InputError(f"unknown ROS target {ros!r}", hint=f"use --ros {' or '.join(ROS_TARGETS)}")
    return ros


def cmd_vel_type(ros: str, cmd_vel: str | None = None) -> str:
    """What the robot's ``cmd_vel`` takes on the target ``ros``: ``stamped`` (TwistStamped) or ``twist``.

    Jazzy: ``stamped`` unless ``cmd_vel`` is ``twist``. Noetic and Humble: ``twist``; asking them for ``stamped``
    is an InputError, as their Gazebo plugin reads Twist only."""
    check_ros(ros)
    if cmd_vel is not None and cmd_vel not in CMD_VEL_CHOICES:
        raise InputError(f"unknown --cmd-vel {cmd_vel!r}", hint="use --cmd-vel stamped or --cmd-vel twist")
    if ros == "jazzy":
        return cmd_vel or "stamped"
    if cmd_vel == "stamped":
        raise InputError(f"--cmd-vel stamped is for --ros jazzy: {ros}'s Gazebo diff drive takes a Twist",
                         hint="leave out --cmd-vel, or pass --ros jazzy")
    return "twist"


def world_file_name(name: str, ros: str) -> str:
    """``NAME.world`` (Gazebo Classic) or ``NAME.sdf`` (Gazebo Sim) for the world named ``name``."""
    return name + WORLD_SUFFIX[check_ros(ros)]


def world_text(classic_world: str, ros: str) -> str:
    """The world text for ``ros`` from the Gazebo Classic world the writer made (SDF 1.6 or as asked): the same
    text for Noetic and Humble, the Gazebo Sim world (:func:`worldgen.sdf.gzsim.gzsim_world`) for Jazzy."""
    if check_ros(ros) != "jazzy":
        return classic_world
    from ..sdf.gzsim import gzsim_world

    return gzsim_world(classic_world)
