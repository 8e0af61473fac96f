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

import re

from ..core.errors import InputError, WorldgenError
from ..core.inputs import read_capped

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


# The Gazebo Sim systems a TurtleBot3 needs its world to name, and what is lost without each. Gazebo Sim loads the
# systems a world's <plugin>s name and no others; a world naming none gets the defaults of server.config (physics,
# user commands, the scene broadcaster), which render no sensor.
TURTLEBOT3_SYSTEMS = (("physics", "nothing moves"), ("usercommands", "the robot cannot be spawned"),
                      ("sensors", "the LiDAR publishes no /scan"), ("imu", "the IMU publishes no /imu"))
_GZ_LIBRARY = re.compile(r"(?:gz-sim|ignition-gazebo|ign-gazebo)\d*-(.+?)-system")
_GZ_CLASS = re.compile(r"(?:gz::sim|ignition::gazebo)::systems::(\w+)")


def gz_sim_systems(world) -> set:
    """The Gazebo Sim systems the ``<world>`` element ``world`` names as plugins (``physics``, ``usercommands``,
    ``sensors`` …: lower case, without dashes), by library (``gz-sim-sensors-system``, ``libignition-gazebo6-…``)
    or by class (``gz::sim::systems::Sensors``)."""
    found = set()
    for plugin in world.iterchildren("plugin"):
        for pattern, text in ((_GZ_LIBRARY, plugin.get("filename") or ""), (_GZ_CLASS, plugin.get("name") or "")):
            match = pattern.search(text.lower() if pattern is _GZ_LIBRARY else text)
            if match:
                found.add(match.group(1).replace("-", "").replace("_", "").lower())
    return found


def check_world_target(path, ros: str) -> None:
    """InputError when the world file ``path`` is not for the simulator ``ros`` starts: Jazzy (Gazebo Sim) needs
    a world naming the systems a TurtleBot3 uses (:data:`TURTLEBOT3_SYSTEMS`); Noetic and Humble (Gazebo Classic)
    cannot load a Gazebo Sim world's systems. A file that is no world is left to the world reader to refuse."""
    from ..core.safexml import parse_bytes

    try:
        root = parse_bytes(read_capped(path, what="world file"), path)
    except (OSError, WorldgenError):
        return
    world = root.find("world") if root.tag == "sdf" else (root if root.tag == "world" else None)
    if world is None:
        return
    systems = gz_sim_systems(world)
    if check_ros(ros) != "jazzy":
        if systems:
            raise InputError(f"is a Gazebo Sim world (it names the systems {', '.join(sorted(systems))}), and "
                             f"--ros {ros} starts Gazebo Classic, which cannot load them", path=path,
                             hint="pass --ros jazzy, or give the .world built without --ros jazzy")
        return
    if not systems:
        raise InputError("is a Gazebo Classic world: it names no Gazebo Sim system, so Gazebo Sim (--ros jazzy) "
                         "runs it with its default systems, which render no sensor (the TurtleBot3's /scan and "
                         "/imu stay silent)", path=path,
                         hint="build it for Jazzy: worldgen build SPEC --ros jazzy writes NAME.sdf")
    missing = [(name, lost) for name, lost in TURTLEBOT3_SYSTEMS if name not in systems]
    if missing:
        raise InputError("is a Gazebo Sim world without the " + ", ".join(name for name, _ in missing) +
                         " system" + ("s" if len(missing) > 1 else "") + " (Gazebo Sim runs only the systems a "
                         "world names): " + "; ".join(lost for _, lost in missing), path=path,
                         hint="add them as worldgen's Jazzy worlds do (worldgen build SPEC --ros jazzy): "
                              "<plugin filename='gz-sim-NAME-system' name='gz::sim::systems::Name'/>")
