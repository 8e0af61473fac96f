"""Which package provides a module, as the students' stack names it: ROS 1 on Debian or ROS Noetic's apt repository
(:data:`.table.TABLE`), or ROS 2 Humble or Jazzy, where a ROS package ``X`` is ``ros-DISTRO-X`` from ROS's apt
repository, and Jazzy's core ones also come from PyPI as ``ros-jazzy-X`` wheels (a third party's repackaging:
rclpy and the common messages; no cv_bridge, tf2_ros or launch). Plain Python libraries are Ubuntu's
``python3-…`` packages, or pip's names in a venv.

A :class:`Naming` answers what the preflight, ``worldgen run`` and ``worldgen doctor`` say: the package to install,
what a table shows as the provider, and the fix of a finding."""

from __future__ import annotations

from dataclasses import dataclass

from .table import TABLE, install_hint, provider, unknown_hint

# ROS 2 Python packages students' nodes import (any other X_msgs / X_srvs / X_interfaces follows the same rule).
ROS2_PACKAGES = frozenset({
    "rclpy", "launch", "launch_ros", "ament_index_python", "tf2_ros", "tf2_py", "tf2_geometry_msgs",
    "tf_transformations", "cv_bridge", "image_geometry", "message_filters", "rosidl_runtime_py", "rosbag2_py",
    "laser_geometry", "nav2_simple_commander", "builtin_interfaces", "rcl_interfaces", "action_msgs",
})
# Those PyPI's Jazzy wheels provide (``ros-jazzy-NAME``; rclpy with its Fast DDS extra).
JAZZY_WHEELS = frozenset({
    "rclpy", "std_msgs", "sensor_msgs", "geometry_msgs", "nav_msgs", "rosgraph_msgs", "std_srvs",
    "visualization_msgs", "builtin_interfaces", "rcl_interfaces", "action_msgs", "ament_index_python",
})
# Plain Python libraries by their pip name where it differs from the module's.
PIP_NAMES = {"cv2": "opencv-python", "yaml": "PyYAML", "PIL": "Pillow", "sklearn": "scikit-learn",
             "skimage": "scikit-image", "serial": "pyserial"}
# What a ROS 2 class machine needs for the class's nodes (``worldgen doctor --ros …`` with no node).
ROS2_RUNTIME = ("rclpy", "std_msgs", "geometry_msgs", "sensor_msgs", "nav_msgs", "rosgraph_msgs", "std_srvs",
                "numpy")


@dataclass(frozen=True)
class Naming:
    """How one stack names providers: ``stack`` is ``noetic`` (then ``apt_ros``: ROS's own apt repository, else
    Debian's), ``humble`` or ``jazzy``."""

    stack: str = "noetic"
    apt_ros: bool = False

    @property
    def ros2(self) -> bool:
        return self.stack != "noetic"

    @property
    def column(self) -> str:
        return f"provided by (apt / pip, ROS 2 {self.stack.capitalize()})" if self.ros2 else \
            "provided by (Debian / ROS Noetic)"

    def _ros2_apt(self, module: str) -> str | None:
        if module in ROS2_PACKAGES or module.endswith(("_msgs", "_srvs", "_interfaces")):
            return f"ros-{self.stack}-{module.replace('_', '-')}"
        known = TABLE.get(module)
        if known is not None and known.debian and known.debian.startswith("python3-") and not known.python3:
            return known.debian
        return None

    def _ros2_pip(self, module: str) -> str | None:
        if module in ROS2_PACKAGES or module.endswith(("_msgs", "_srvs", "_interfaces")):
            if module not in JAZZY_WHEELS or self.stack != "jazzy":   # PyPI has Jazzy's wheels only
                return None
            return "'ros-jazzy-rclpy[fastrtps]'" if module == "rclpy" else f"ros-jazzy-{module.replace('_', '-')}"
        if module == "tf_transformations":
            return None
        known = TABLE.get(module)
        return PIP_NAMES.get(module, module) if known is not None and known.debian else None

    def package(self, module: str) -> str | None:
        """The apt package to install for ``module`` (None: none known)."""
        if self.ros2:
            return self._ros2_apt(module)
        known = provider(module)
        return known.package(self.apt_ros) if known is not None else None

    def shown(self, module: str) -> str:
        """What a table shows as the provider."""
        if not self.ros2:
            known = provider(module)
            return known.shown if known is not None else "– (not known to worldgen)"
        apt, pip = self._ros2_apt(module), self._ros2_pip(module)
        if apt is None and pip is None:
            return "– (not known to worldgen)"
        return f"{apt or '–'} / {pip or '–'}"

    def hint(self, module: str) -> str:
        """What to do about a missing ``module``, as a finding's fix."""
        if not self.ros2:
            return install_hint(module, self.apt_ros)
        apt, pip = self._ros2_apt(module), self._ros2_pip(module)
        if module == "tf_transformations":
            return f"apt install ros-{self.stack}-tf-transformations python3-transforms3d"
        if apt is None and pip is None:
            return unknown_hint(module, ROS2_PACKAGES)
        parts = [f"apt install {apt}" + (f" (with ROS 2 {self.stack.capitalize()}'s apt repository)"
                                         if apt and apt.startswith("ros-") else "")] if apt else []
        if pip:
            parts.append(f"in a venv: pip install {pip}")
        elif apt and apt.startswith("ros-"):
            parts.append("PyPI's ROS wheels do not have it")
        return "; ".join(parts)
