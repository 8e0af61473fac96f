"""The class's ROS 2 packages (Humble or Jazzy), ready for ``colcon build``: ``WORKSPACE/src/intro_robo/``.

The same class as :mod:`worldgen.packages.course_ros1` (ROS 1), as ament_python packages of :mod:`worldgen.packages.ament`:

* ``lab_a_spin_circles`` — the node ``spin_in_circles`` (``lab_a_spin_circles/spin_in_circles.py``, an rclpy
  node, entry point ``spin_in_circles``): a constant velocity on ``cmd_vel``;
* ``lab_a_stop_at_wall`` — the node ``stop_at_wall``: the law of :mod:`worldgen.core.stoplaw` on the LiDAR's
  front distance (``inf`` and ``0`` both "nothing seen"), ``scan`` subscribed with the sensor-data QoS;
* ``class_meeting_02_custom_gazebo_world`` — the enclosed room (``worlds/enclosed_room.world`` for Humble,
  ``worlds/enclosed_room.sdf`` for Gazebo Sim on Jazzy, with the bridge's ``params/turtlebot3_bridge.yaml``)
  and ``launch/turtlebot3_in_enclosed_room.launch.py``.

Each lab package also has ``launch/NODE.launch.py``, starting the class world with its node. ROS 2 has no catkin
metapackage, so ``intro_robo/`` is a plain folder that colcon searches. On Jazzy the nodes publish
``TwistStamped`` (what the bridge takes) unless ``cmd_vel`` is ``twist``.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

from ..core.resources import examples_dir, render_template
from .ament import ament_package_files, ament_request, spec_world_files
from .course_ros1 import LICENSE, REPOSITORY, SPIN, STOP, VERSION, WORLD_PACKAGE
from ..launch.writer_xml import parse_node
from ..launch.writer_py import launch_py
from .catkin import PackageArgs, PackageFiles
from ..launch.targets import cmd_vel_type
from ..core.fsio import write_tree

DEPENDENCIES = ("rclpy", "std_msgs", "geometry_msgs", "sensor_msgs")


def course_ros2_files(ros: str, cmd_vel: str | None = None, maintainer: str | None = None) -> PackageFiles:
    """Every file of the class's ROS 2 packages for ``ros`` (humble, jazzy), relative to ``src/intro_robo``."""
    stamped = cmd_vel_type(ros, cmd_vel) == "stamped"

    def request(name: str, description: str, exec_only=()):
        req = ament_request(PackageArgs(name, DEPENDENCIES, version=VERSION, description=description,
                                        licenses=(LICENSE,), maintainers=(maintainer,) if maintainer else ()))
        return replace(req, exec_only=tuple(exec_only))

    grouped, world_file, spawn = spec_world_files(examples_dir() / "enclosed_room.yaml", WORLD_PACKAGE, ros,
                                                  cmd_vel=cmd_vel)
    world_pkg = ament_package_files(
        request(WORLD_PACKAGE, "Class meeting 02: a custom Gazebo world (a closed room) and the launch file that "
                               "puts a TurtleBot3 in it"), ros, **grouped)

    def lab(name: str, node_name: str, params: dict, description: str) -> PackageFiles:
        node = parse_node(f"{name}/{node_name}")
        launch_name = f"{node.name}.launch.py"
        launch = launch_py(world_file, WORLD_PACKAGE, ros, "optenv", spawn, nodes=[node], launch_name=launch_name,
                           home=name)
        code = render_template(f"ros2/nodes/{node_name}.py.j2", package=name, stamped=stamped, **params)
        return ament_package_files(request(name, description, exec_only=[WORLD_PACKAGE]), ros,
                                   launches={launch_name: launch}, nodes={node_name: code})

    spin = lab("lab_a_spin_circles", "spin_in_circles", SPIN,
               "Lab A: drive a TurtleBot3 in circles by publishing a velocity on cmd_vel")
    stop = lab("lab_a_stop_at_wall", "stop_at_wall", STOP,
               "Lab A: drive a TurtleBot3 to a wall and stop there, with proportional control on the LiDAR")
    merged = PackageFiles({}, set())
    for folder, pkg in (("lab_a_spin_circles", spin), ("lab_a_stop_at_wall", stop), (WORLD_PACKAGE, world_pkg)):
        placed = pkg.under(folder)
        merged.files.update(placed.files)
        merged.executable |= placed.executable
    return PackageFiles(dict(sorted(merged.files.items())), merged.executable)


def write_course_ros2(workspace: str | Path, ros: str, *, cmd_vel: str | None = None, force: bool = False,
                  maintainer: str | None = None) -> Path:
    """Write ``WORKSPACE/src/intro_robo`` (the ROS 2 packages) all at once (nothing on error). An existing
    ``intro_robo`` folder is refused unless ``force``, which replaces it. Returns the folder."""
    pkg = course_ros2_files(ros, cmd_vel, maintainer)
    return write_tree(Path(workspace) / "src" / REPOSITORY, pkg.files, force=force, executable=pkg.executable)
