"""What a ROS 2 launch file starts in Gazebo, read from its actions: the world (gazebo_ros's ``gzserver.launch.py``
``world`` argument, ros_gz_sim's ``gz_sim.launch.py`` ``gz_args``, or a ``gazebo``/``gz sim`` command line) and
the robots it spawns (gazebo_ros's ``spawn_entity.py`` and ros_gz_sim's ``create`` with ``-x -y -z -Y``).

Plain functions over plain strings, so each rule can be tested alone; :mod:`.reader_py` hands them the
values it has resolved.
"""

from __future__ import annotations

import re
import shlex
from typing import List, Optional, Sequence, Tuple

from ..spec.model import ROBOT_MODELS

# (package, executable) of the nodes that spawn a robot into Gazebo Classic or Gazebo Sim
SPAWNERS = {("gazebo_ros", "spawn_entity.py"), ("ros_gz_sim", "create"), ("ros_ign_gazebo", "create")}
POSE_FLAGS = {"-x": 0, "-y": 1, "-z": 2, "-Y": 3}
NAME_FLAGS = ("-entity", "-name")
GAZEBO_PACKAGES = ("gazebo_ros", "ros_gz_sim", "ros_ign_gazebo")
# the stock launch files that start a simulator: file name → (simulator, the launch argument giving the world)
GAZEBO_LAUNCH = {
    "gzserver.launch.py": ("gazebo", "world"),
    "gazebo.launch.py": ("gazebo", "world"),
    "gzclient.launch.py": ("gazebo", None),
    "gz_sim.launch.py": ("gz-sim", "gz_args"),
    "gz_server.launch.py": ("gz-sim", "world_sdf_file"),
    "ign_gazebo.launch.py": ("gz-sim", "ign_args"),
}
# stock launch files that spawn the TurtleBot3 at the pose passed to them: (package, file) → (x arg, y arg, z)
STOCK_SPAWN = {("turtlebot3_gazebo", "spawn_turtlebot3.launch.py"): ("x_pose", "y_pose", 0.01)}
# gz sim's options that take a value (the world file is the word that is neither an option nor a value)
GZ_VALUE_OPTIONS = {"-z", "--iterations", "--network-role", "--network-secondaries", "--record-path",
                    "--record-topic", "--playback", "--render-engine", "--render-engine-gui", "--render-engine-server",
                    "--gui-config", "--physics-engine", "--seed", "--initial-sim-time",
                    "--render-engine-gui-api-backend", "--render-engine-server-api-backend"}
# gazebo (Classic)'s options that take a value
GAZEBO_VALUE_OPTIONS = {"-s", "--server-plugin", "-g", "--gui-plugin", "-e", "--physics", "--record_path",
                        "--record_period", "--record_filter", "--seed", "--iters", "-o", "--profile", "--lockstep"}
MODEL_IN_TEXT = re.compile(r"turtlebot3_(waffle_pi|waffle|burger)(?![A-Za-z0-9])")


def words(text: str) -> List[str]:
    """A command line's words, split as a shell splits them (at spaces when its quotes do not close)."""
    try:
        return shlex.split(text)
    except ValueError:
        return text.split()


def gz_world(text: str) -> Optional[str]:
    """The world file in ``gz sim`` arguments (``-r -s -v2 /path/world.sdf``), or None (``-g -v2``: a GUI
    only). ``-v`` takes a verbosity after it only when that is a number."""
    found = None
    parts = words(text)
    skip = False
    for i, word in enumerate(parts):
        if skip:
            skip = False
            continue
        if word.startswith("-"):
            following = parts[i + 1] if i + 1 < len(parts) else ""
            skip = word in GZ_VALUE_OPTIONS or (word in ("-v", "--verbose") and following.isdigit())
            continue
        found = word
    return found


def gazebo_world(parts: Sequence[str]) -> Optional[str]:
    """The world in a Gazebo Classic command line's arguments (``--verbose world.world -s libgazebo_ros_init.so``):
    the first word ending ``.world``/``.sdf``, else the last that is neither an option nor its value."""
    found = None
    skip = False
    for i, word in enumerate(parts):
        if skip:
            skip = False
            continue
        if word.startswith("-"):
            skip = word in GAZEBO_VALUE_OPTIONS
            continue
        if word.endswith((".world", ".sdf")):
            return word
        found = word
    return found


def command_kind(cmd: Sequence) -> Tuple[Optional[str], int]:
    """What an ``ExecuteProcess`` command line runs — "gazebo", "gz-sim", "ros2-run" or None — and how many of its
    first words name the program (its arguments follow them). Words that are not strings name nothing."""
    names = [w if isinstance(w, str) else "" for w in cmd[:2]]
    program = names[0].rsplit("/", 1)[-1] if names else ""
    second = names[1] if len(names) > 1 else ""
    if program in ("gazebo", "gzserver"):
        return "gazebo", 1
    if (program, second) in (("gz", "sim"), ("ign", "gazebo")):
        return "gz-sim", 2
    if (program, second) == ("ros2", "run"):
        return "ros2-run", 2
    return None, 1


def robot_model(values) -> Optional[str]:
    """The TurtleBot3 model named by a spawn's entity name or model file (``burger``, ``turtlebot3_waffle``,
    ``…/turtlebot3_waffle_pi/model.sdf``), if any."""
    for value in values:
        if not isinstance(value, str):
            continue
        if value in ROBOT_MODELS:
            return value
        found = MODEL_IN_TEXT.search(value)
        if found:
            return found.group(1)
    return None


def flag_value(parts: Sequence, flag: str):
    """The word after ``flag`` in a spawn node's arguments (None when absent)."""
    for i, word in enumerate(parts[:-1]):
        if word == flag:
            return parts[i + 1]
    return None


def mentions_simulator(text: str) -> bool:
    """Whether a launch file's name or path suggests it starts a simulator (for includes that cannot be read)."""
    return re.search(r"gazebo|gz|world|sim", text, re.IGNORECASE) is not None
