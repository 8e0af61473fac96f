"""What a launch file just written names that is not there yet, said when ``worldgen launch`` writes it: a
``--node`` of the launch file's own package with no such script in the package (roslaunch cannot start it; a
student often writes the launch file first and the node next), and a ``--package`` that neither the launch
file's workspace nor ``ROS_PACKAGE_PATH`` holds, or that holds no ``worlds/WORLD`` (``$(find PKG)`` will not find
the world). Each is a warning of what ``worldgen validate`` of the same file reports as an error, said at once,
with what to do; the file is still written. ROS 1 only: a ROS 2 package is found once installed, and its
executables are its setup.py's.
"""

from __future__ import annotations

from pathlib import Path
from typing import Iterable

from .model import NodeRef
from .reader import package_index


def unfound(launch_file: Path, package: str, package_dir: Path | None, world_name: str, nodes: Iterable[NodeRef],
            ros: str) -> list[str]:
    """Warnings (one line each, with what to do) for what ``launch_file`` (of ``package``, in the package folder
    ``package_dir``, or outside any package: None) names and will not find."""
    if ros != "noetic":
        return []
    if package_dir is None:
        return _package_unfound(launch_file, package, world_name)
    return [f"{package}/{node.type} is not in {package_dir} yet: roslaunch cannot start the node {node.name} until "
            f"it is (write scripts/{node.type} there and chmod +x it)"
            for node in nodes if node.package == package and not any(p.is_file() for p in package_dir.rglob(node.type))]


def _package_unfound(launch_file: Path, package: str, world_name: str) -> list[str]:
    found = package_index(launch_file).find(package)
    if found is None:
        return [f"the package {package} is neither in the workspace of {launch_file} nor on ROS_PACKAGE_PATH: "
                f"roslaunch will not find $(find {package})/worlds/{world_name} (build the world into the package with "
                f"worldgen build SPEC --package DIR, then write its launch file from there)"]
    if not (found / "worlds" / world_name).is_file():
        return [f"the package {package} ({found}) has no worlds/{world_name}: roslaunch will not find the world "
                f"(build it there with worldgen build SPEC --package {found})"]
    return []
