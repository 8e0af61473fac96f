"""A built world put into a ROS package (``worldgen build --package``): the world file and its launch file, and
for Jazzy the bridge's parameter file, placed in the package folder, for catkin (roslaunch XML) and ament (launch.py)
packages alike."""

from __future__ import annotations

from pathlib import Path
from typing import Sequence

from ..launch.writer_py import world_package_files
from ..launch.writer_xml import check_package_ref, default_launch_name, launch_xml, package_name_of


def package_world_files(pkg_dir: str | Path, world_name: str, world_text: str, spawn: Sequence[float],
                        ros: str = "noetic", model: str = "optenv", cmd_vel: str | None = None) -> dict[Path, str]:
    """The files that put a built world into the package folder ``pkg_dir`` (path → text, for
    :func:`worldgen.core.fsio.write_files`): for ``noetic`` ``worlds/NAME.world`` and
    ``launch/turtlebot3_in_NAME.launch``; for ROS 2 those of :func:`worldgen.launch.writer_py.world_package_files`.
    Raises InputError for a package folder whose name cannot name a ROS package."""
    pkg_dir = Path(pkg_dir)
    package = check_package_ref(package_name_of(pkg_dir))
    if ros == "noetic":
        world_file = f"{world_name}.world"
        launch_name = default_launch_name(world_file)
        files = {f"worlds/{world_file}": world_text,
                 f"launch/{launch_name}": launch_xml(world_file, package, model, spawn, launch_name=launch_name)}
    else:
        files = world_package_files(world_name, world_text, package, ros, spawn, model, cmd_vel)
    return {pkg_dir / rel: text for rel, text in files.items()}
