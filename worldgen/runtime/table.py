"""Which package provides a module students' rospy nodes import, and the class runtime.

:data:`TABLE` maps a top-level module to the package that provides it on Debian and Ubuntu (``apt install``;
Debian packages ROS 1's Python as ``python3-*``) and on a ROS Noetic machine (Ubuntu 20.04 with ROS's own apt
repository: ``ros-noetic-*`` for ROS packages, Ubuntu's ``python3-*`` for the rest). Every Debian name here was
checked with ``apt-cache policy`` on Debian 12 (bookworm); where Debian has no such package the entry says so and
says what to do instead (:attr:`Provider.note`). Message packages not listed follow a rule (:func:`provider`):
``X_msgs`` → ``python3-X-msgs`` / ``ros-noetic-X-msgs``, marked ``guessed`` since nobody checked that Debian has
it. ``gazebo_msgs`` is never missing under worldgen: ``worldgen sim`` and ``worldgen run`` generate it (see
:mod:`worldgen.ros1.gazebo_types`).

:data:`CLASS_RUNTIME` is **the class runtime**: the Debian packages that give rospy nodes what a ROS Noetic
desktop (``ros-noetic-desktop-full``) gives them — rospy and the common messages, tf and tf2, actionlib,
message_filters, cv_bridge and OpenCV, numpy, scipy, matplotlib, PIL, yaml, tkinter. ``.ci/run`` installs exactly
these, and the README's apt line names exactly these (a test checks the three agree). About 770 MB installed
with ``--no-install-recommends`` on Debian 12, OpenCV the bulk of it.
"""

from __future__ import annotations

import difflib
from dataclasses import dataclass
from typing import Iterable


@dataclass(frozen=True)
class Provider:
    """Where a module comes from: the Debian/Ubuntu package (None: Debian has none), the ROS Noetic one (None:
    not a package there either), what to do otherwise (``note``), whether worldgen itself provides it at run
    time (``worldgen``), whether the names come from the ``*_msgs`` rule rather than this table (``guessed``), and
    for a Python 2 name, the Python 3 one (``python3``)."""

    debian: str | None
    noetic: str | None
    note: str = ""
    worldgen: bool = False
    guessed: bool = False
    python3: str = ""   # a Python 2 name: what it is called in Python 3

    def package(self, noetic: bool = False) -> str | None:
        """The package to install on this kind of system (``noetic``: ROS's own apt repository)."""
        return self.noetic if noetic else self.debian

    @property
    def shown(self) -> str:
        """``python3-tf / ros-noetic-tf``; one name when both are the same; ``–`` for none."""
        if self.worldgen:
            return f"worldgen (ROS Noetic: {self.noetic})"
        if self.python3:
            return f"– (Python 2's name; Python 3: {self.python3})"
        if self.debian == self.noetic:
            return self.debian or "–"
        return f"{self.debian or '–'} / {self.noetic or '–'}"


def _ros(name: str) -> Provider:
    """A ROS 1 package ``name``: ``python3-NAME`` on Debian, ``ros-noetic-NAME`` on Noetic (dashes for
    underscores)."""
    dashed = name.replace("_", "-")
    return Provider(f"python3-{dashed}", f"ros-noetic-{dashed}")


def _same(package: str) -> Provider:
    """A Python library Debian and Ubuntu 20.04 both package under one name."""
    return Provider(package, package)


def _source(noetic: str, repository: str) -> Provider:
    return Provider(None, noetic, f"no Debian package: on Debian, clone {repository} into your catkin workspace's "
                                  "src/ and build it with catkin_make")


def _renamed(python3: str) -> Provider:
    return Provider(None, None, f"Python 2's name: ROS Noetic runs Python 3, where it is {python3}",
                    python3=python3)


TABLE: dict[str, Provider] = {
    # ROS 1's own Python
    **{name: _ros(name) for name in (
        "rospy", "rosbag", "roslib", "rosgraph", "rosnode", "rostopic", "rosservice", "rosparam", "roslaunch",
        "rosmsg", "genpy", "message_filters", "actionlib", "dynamic_reconfigure", "tf", "tf2_ros",
        "tf2_geometry_msgs", "tf2_sensor_msgs", "tf2_kdl", "tf_conversions", "angles", "cv_bridge",
        "image_geometry", "laser_geometry", "interactive_markers", "topic_tools", "rostest", "rosunit",
        "nodelet", "bondpy")},
    "rospkg": _same("python3-rospkg"),
    "tf2_py": Provider("python3-tf2", "ros-noetic-tf2-py"),
    "PyKDL": _same("python3-pykdl"),
    # messages and services (any other X_msgs: see provider())
    **{name: _ros(name) for name in (
        "std_msgs", "geometry_msgs", "sensor_msgs", "nav_msgs", "std_srvs", "rosgraph_msgs", "tf2_msgs",
        "actionlib_msgs", "visualization_msgs", "diagnostic_msgs", "trajectory_msgs", "shape_msgs", "stereo_msgs",
        "move_base_msgs", "map_msgs", "pcl_msgs")},
    "gazebo_msgs": Provider(None, "ros-noetic-gazebo-msgs", "no Debian package; worldgen sim and worldgen run "
                                                            "generate it, so nodes run through worldgen have it",
                            worldgen=True),
    "turtlebot3_msgs": _source("ros-noetic-turtlebot3-msgs", "https://github.com/ROBOTIS-GIT/turtlebot3_msgs "
                                                             "(branch noetic-devel)"),
    "control_msgs": _source("ros-noetic-control-msgs", "https://github.com/ros-controls/control_msgs "
                                                       "(branch kinetic-devel)"),
    "turtlesim": _source("ros-noetic-turtlesim", "https://github.com/ros/ros_tutorials (branch noetic-devel)"),
    "smach": _source("ros-noetic-smach", "https://github.com/ros/executive_smach (branch noetic-devel)"),
    "smach_ros": _source("ros-noetic-smach-ros", "https://github.com/ros/executive_smach (branch noetic-devel)"),
    # Python libraries (Ubuntu's own packages on a Noetic machine)
    "numpy": _same("python3-numpy"),
    "scipy": _same("python3-scipy"),
    "matplotlib": _same("python3-matplotlib"),
    "cv2": _same("python3-opencv"),
    "PIL": _same("python3-pil"),
    "yaml": _same("python3-yaml"),
    "tkinter": _same("python3-tk"),
    "sklearn": _same("python3-sklearn"),
    "pandas": _same("python3-pandas"),
    "serial": _same("python3-serial"),
    "sympy": _same("python3-sympy"),
    "pygame": _same("python3-pygame"),
    "requests": _same("python3-requests"),
    "psutil": _same("python3-psutil"),
    "distutils": _same("python3-distutils"),
    # Python 2 names in old tutorials' nodes
    "Tkinter": _renamed("tkinter"),
    "tkMessageBox": _renamed("tkinter.messagebox"),
    "Queue": _renamed("queue"),
    "ConfigParser": _renamed("configparser"),
    "urllib2": _renamed("urllib.request"),
    "cPickle": _renamed("pickle"),
    "StringIO": _renamed("io.StringIO"),
    "thread": _renamed("_thread (or threading)"),
}

# The class runtime (see the module docstring): sorted, as .ci/run and the README list it.
CLASS_RUNTIME: tuple[str, ...] = (
    "python3-actionlib", "python3-actionlib-msgs", "python3-angles", "python3-cv-bridge",
    "python3-diagnostic-msgs", "python3-dynamic-reconfigure", "python3-geometry-msgs", "python3-image-geometry",
    "python3-laser-geometry", "python3-matplotlib", "python3-message-filters", "python3-move-base-msgs",
    "python3-nav-msgs", "python3-numpy", "python3-opencv", "python3-pil", "python3-pykdl", "python3-rosbag",
    "python3-roslib", "python3-rospy", "python3-scipy", "python3-sensor-msgs", "python3-shape-msgs",
    "python3-std-msgs", "python3-std-srvs", "python3-stereo-msgs", "python3-tf", "python3-tf-conversions",
    "python3-tf2-geometry-msgs", "python3-tf2-msgs", "python3-tf2-ros", "python3-tk", "python3-trajectory-msgs",
    "python3-visualization-msgs", "python3-yaml",
)


def provider(module: str) -> Provider | None:
    """The provider of a top-level ``module``: the table's, else the ``*_msgs`` rule's (``guessed``), else None
    (worldgen does not know)."""
    found = TABLE.get(module)
    if found is not None:
        return found
    if module.endswith("_msgs") and module.replace("_", "").isalnum():
        dashed = module.replace("_", "-")
        return Provider(f"python3-{dashed}", f"ros-noetic-{dashed}", guessed=True)
    return None


def runtime_modules() -> list[str]:
    """The modules the class runtime provides (those whose Debian package is in :data:`CLASS_RUNTIME`), sorted
    case-insensitively."""
    return sorted((m for m, p in TABLE.items() if p.debian in CLASS_RUNTIME), key=lambda m: (m.lower(), m))


def unknown_hint(module: str, known: Iterable[str] = ()) -> str:
    """What to do about a missing ``module`` no package worldgen knows provides: the import to fix when it is a
    letter or two off a module that worldgen knows (:data:`TABLE`, ``known``: ``rospyy`` for rospy), else how to
    find its package."""
    find = (f"find it with apt-cache search {module.lower().replace('_', '-')}, or pip install it for the Python "
            f"that runs the nodes")
    near = difflib.get_close_matches(module, sorted({*TABLE, *known}), n=1, cutoff=0.8)
    if near:
        return f"did you mean {near[0]}? fix the import; if {module} is what you meant, {find}"
    return f"worldgen does not know which package provides {module}: {find}"


def install_hint(module: str, noetic: bool = False) -> str:
    """What to do about a missing ``module``, as a finding's fix: ``apt install python3-tf (ROS Noetic:
    ros-noetic-tf)``; the table's note where there is no package; a ``pip``/``apt-cache search`` hint for a module
    worldgen does not know."""
    found = provider(module)
    if found is None:
        return unknown_hint(module)
    if found.debian is None and found.noetic is None:
        return found.note
    if found.debian is None:
        return f"{found.note} (ROS Noetic: apt install {found.noetic})"
    first, other = (found.noetic, found.debian) if noetic else (found.debian, found.noetic)
    text = f"apt install {first}"
    if other and other != first:
        text += f" ({'Debian' if noetic else 'ROS Noetic'}: {other})"
    if found.guessed:
        text += f"; if apt-cache policy {first} finds none, build the package in your catkin workspace"
    return text
