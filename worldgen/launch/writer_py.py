"""ROS 2 launch files (``*.launch.py``) for a world and a TurtleBot3: Humble with Gazebo Classic, Jazzy with Gazebo
Sim. The ROS 1 (roslaunch XML) writer is :mod:`worldgen.launch.writer_xml`; the two share its names and checks.

The shape is the one of turtlebot3_gazebo's humble and jazzy launch files, in one file:

* the model from ``TURTLEBOT3_MODEL`` read when the launch starts (``optenv``: burger when it is unset; ``env``:
  it must be set, as their files have it; or a fixed model);
* launch arguments ``x_pose``, ``y_pose``, ``z_pose``, ``yaw`` (the spawn pose), ``use_sim_time`` (true) and
  ``gui`` (true: the Gazebo window);
* Humble: gazebo_ros's ``gzserver.launch.py`` with ``world`` = ``share/PKG/worlds/WORLD`` and
  ``gzclient.launch.py`` unless ``gui:=false``;
  Jazzy: ros_gz_sim's ``gz_sim.launch.py`` twice, the server (``gz_args`` ``-r -s -v2 WORLD``) and the GUI
  (``-g -v2``, unless ``gui:=false``), with ``GZ_SIM_RESOURCE_PATH`` extended by turtlebot3_gazebo's models;
* ``robot_state_publisher`` with ``robot_description`` = ``xacro`` of turtlebot3_description's
  ``urdf/turtlebot3_MODEL.urdf`` (its ROS 2 URDFs are xacro files with a ``namespace`` argument);
* the robot spawned from turtlebot3_gazebo's ``models/turtlebot3_MODEL/model.sdf`` — the ROS 2 description URDFs
  carry no Gazebo plugins, that model has the drive, LiDAR, IMU and joint states — by ``spawn_entity.py -entity
  … -file …`` (Humble) or ``ros_gz_sim create -name … -file …`` (Jazzy), with ``-x -y -z -Y`` from the arguments;
* Jazzy: ``ros_gz_bridge parameter_bridge`` with ``config_file:=share/PKG/params/turtlebot3_bridge.yaml``
  (:mod:`worldgen.launch.gz_bridge_params`);
* extra nodes (``--node PKG/EXECUTABLE[:NAME]``), each with ``use_sim_time``.

Python values are only written from names checked against narrow patterns, so the file is valid Python (and
flake8-clean under ament_flake8's rules) for every input that passes the checks.
"""

from __future__ import annotations

from pathlib import Path
from typing import Sequence

from ..core.errors import InputError
from ..core.numbers import format_number
from ..core.resources import render_template
from .gz_bridge_params import BRIDGE_FILE, bridge_yaml, bridged_topics
from .model import NodeRef
from .writer_xml import MODEL_CHOICES, check_package_ref, check_world_name, package_name_of
from .targets import ROS2_TARGETS, cmd_vel_type, world_file_name

LAUNCH_SUFFIX = ".launch.py"
RESERVED_NODE_NAMES = ("robot_state_publisher", "gazebo", "gzserver", "gzclient", "create", "spawn_entity",
                       "parameter_bridge")


def default_launch_py_name(world_file: str) -> str:
    """``turtlebot3_in_<world stem>.launch.py``, the class's naming."""
    return f"turtlebot3_in_{Path(world_file).name.split('.')[0]}{LAUNCH_SUFFIX}"


def check_ros2(ros: str) -> str:
    """``ros`` if it is a ROS 2 target (humble, jazzy); InputError otherwise."""
    if ros not in ROS2_TARGETS:
        raise InputError(f"{ros!r} is not a ROS 2 target", hint=f"use {' or '.join(ROS2_TARGETS)}")
    return ros


def launch_py(world_file: str, package: str, ros: str, model: str = "optenv", spawn: Sequence[float] = (0.0, 0.0),
              nodes: Sequence[NodeRef] = (), launch_name: str | None = None, home: str | None = None) -> str:
    """The ``.writer_xml.py`` text for ``share/PACKAGE/worlds/WORLD`` and a TurtleBot3 on ``ros`` (humble, jazzy).

    ``model``, ``spawn``, ``nodes`` and ``home`` mean what they mean for :func:`worldgen.launch.writer_xml.launch_xml`
    (``home`` is named in the ``ros2 launch HOME NAME`` line of the docstring). Raises InputError for a bad
    target, model, package, world name or a duplicate node name.
    """
    check_ros2(ros)
    if model not in MODEL_CHOICES:
        raise InputError(f"unknown robot model {model!r}", hint=f"use one of {', '.join(MODEL_CHOICES)}")
    check_package_ref(package)
    home = check_package_ref(home or package)
    world = check_world_name(world_file)
    if "\\" in world:
        raise InputError(f"world file name {world_file!r} cannot be written into a Python launch file",
                         hint="rename the world file: letters, digits, '_', '-' and '.' only")
    pose = [float(v) for v in spawn] + [0.0] * (4 - len(spawn))
    seen = set(RESERVED_NODE_NAMES)
    for node in nodes:
        if node.name in seen:
            raise InputError(f"two nodes would be named {node.name!r}",
                             hint="give each --node its own name: --node PKG/EXECUTABLE:NAME")
        seen.add(node.name)
    bridged = ", ".join(t.name for t in bridged_topics())
    return render_template(
        "ros2/launch/turtlebot3_world.launch.py.j2", ros=ros, world=world, package=package, home=home,
        launch_name=launch_name or default_launch_py_name(world), model=model, bridge_file=BRIDGE_FILE,
        bridged=bridged, x=format_number(pose[0]), y=format_number(pose[1]), z=format_number(pose[2]),
        yaw=format_number(pose[3]), nodes=list(nodes))


def world_package_files(world_name: str, world_text: str, package: str, ros: str, spawn: Sequence[float],
                        model: str = "optenv", cmd_vel: str | None = None) -> dict[str, str]:
    """What puts a built world into a ROS 2 package, relative path → text: ``worlds/NAME.world`` (Humble) or
    ``worlds/NAME.sdf`` (Jazzy; ``world_text`` is already the Gazebo Sim world), its launch file
    ``launch/turtlebot3_in_NAME.launch.py`` and, for Jazzy, the bridge's ``params/turtlebot3_bridge.yaml``."""
    check_ros2(ros)
    world_file = world_file_name(world_name, ros)
    launch_name = default_launch_py_name(world_file)
    files = {f"worlds/{world_file}": world_text,
             f"launch/{launch_name}": launch_py(world_file, package, ros, model, spawn, launch_name=launch_name)}
    if ros == "jazzy":
        files[f"params/{BRIDGE_FILE}"] = bridge_yaml(cmd_vel_type(ros, cmd_vel))
    else:
        cmd_vel_type(ros, cmd_vel)   # refuses --cmd-vel stamped
    return files


def without_same_params(files: dict[Path, str]) -> dict[Path, str]:
    """``files`` less the bridge parameter files (``params/…``) already on disk with exactly this text: one
    package's worlds all share ``params/turtlebot3_bridge.yaml``, so writing a second world's files does not
    need ``--force`` for it. A parameter file that differs (``--cmd-vel``) is kept, and refused without
    ``--force`` as any other existing file."""
    kept = {}
    for path, text in files.items():
        if path.parent.name == "params" and path.is_file() and not path.is_symlink():
            try:
                if path.read_bytes() == text.encode("utf-8"):
                    continue
            except OSError:
                pass
        kept[path] = text
    return kept
