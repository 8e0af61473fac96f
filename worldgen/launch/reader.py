"""Reading launch files back: the world, the robot model and every spawn pose they start.

A ROS 2 Python launch file (``*.launch.py``, ``*_launch.py``) is read by :mod:`.reader_py` (statically,
never run) into the same :class:`~.model.LaunchInfo`; everything below is about roslaunch XML files.

:func:`read_launch` evaluates a launch file the way roslaunch does for what matters here — args and their
defaults, ``$(arg)``/``$(env)``/``$(optenv)``/``$(find)``/``$(dirname)``/``$(anon)``, groups and namespaces,
``if``/``unless``, includes with passed args — and reports the world, the robot model and every ``spawn_model``
pose, with findings for whatever cannot be resolved instead of failing. ``$(find PKG)`` looks in the package
holding the launch file, then its sibling packages in the same catkin source tree, then ``ROS_PACKAGE_PATH``
(see :mod:`worldgen.core.packages`).

The substitutions and conditions are :mod:`.substitution_xml`'s; the walk over a file's elements, following
includes, is :mod:`.walk_xml`'s; what is found is a :class:`~.model.LaunchInfo`.
"""

from __future__ import annotations

import os
import re
from pathlib import Path
from typing import Mapping, Sequence

from ..core import packages as rospkg
from .model import LaunchInfo
from .walk_xml import LaunchRead, load_launch
from .substitution_xml import Lookup


def package_index(launch_path: str | Path, ros_package_path: Sequence[str | Path] | None = None
                  ) -> rospkg.PackageIndex:
    """Where ``$(find PKG)`` looks for a launch file: the package holding the file first, then its sibling
    packages in the same catkin source tree, then ``ros_package_path`` (default: the process's
    ``ROS_PACKAGE_PATH``)."""
    own = rospkg.owning_package(launch_path)
    roots = [own, rospkg.source_tree(own)] if own is not None else []
    roots += rospkg.ros_package_path() if ros_package_path is None else [Path(p) for p in ros_package_path]
    return rospkg.PackageIndex(roots)


def read_launch(path: str | Path, args: Mapping[str, str] | None = None, *,
                ros_package_path: Sequence[str | Path] | None = None,
                environ: Mapping[str, str] | None = None) -> LaunchInfo:
    """Read a roslaunch XML file: world, robot model, spawn poses, args, nodes (see :class:`LaunchInfo`); a ROS 2
    Python launch file is read by :func:`.reader_py.read_launch_py`.

    ``args`` are command-line overrides (``x_pos:=1.5`` → ``{"x_pos": "1.5"}``); ``ros_package_path`` and
    ``environ`` default to the process's. Raises WorldFileError (with the line) for a file roslaunch could not
    parse either: malformed XML, a root other than ``<launch>``, an ``<arg>``/``<node>``/``<include>`` missing
    its required attributes, circular includes. Unresolvable references become findings, and only what depends
    on them stays unknown (roslaunch stops at the first one: an unset ``$(env TURTLEBOT3_MODEL)`` default fails
    it even when ``model:=`` is passed).
    """
    path = Path(path)
    environ = os.environ if environ is None else environ
    if is_python_launch(path):
        from .reader_py import read_launch_py   # (the Python reader's modules: only for a launch.py)

        return read_launch_py(path, args, finder=package_index(path, ros_package_path), environ=environ)
    read = LaunchRead(Lookup(package_index(path, ros_package_path), environ), LaunchInfo(path=path))
    load_launch(read, path, {k: str(v) for k, v in (args or {}).items()}, "/", None)
    info = read.info
    if info.robots:
        info.spawn, info.model = info.robots[0].pose, info.robots[0].robot
    if info.model is None:
        info.model = info.args.get("model")
    model_arg = read.raw_args.get("model")
    if info.model is None and model_arg:
        env = re.search(r"\$\((?:opt)?env\s+(\w+)", model_arg)
        info.model_env = env.group(1) if env else None
    if info.spawn is None and not info.robots and "x_pos" in info.args:   # args only: a file that includes the spawn
        try:
            info.spawn = tuple(float(info.args.get(k) or 0.0) for k in ("x_pos", "y_pos", "z_pos", "yaw"))
        except ValueError:
            read.note("launch-spawn", "error", "x_pos/y_pos/z_pos/yaw are not numbers", path,
                      None, "give the spawn args numeric defaults")
    return info



PYTHON_LAUNCH_SUFFIXES = (".launch.py", "_launch.py")


def is_python_launch(path: str | Path) -> bool:
    """Whether ``path`` names a ROS 2 Python launch file (``NAME.launch.py`` or ``NAME_launch.py``)."""
    return Path(path).name.lower().endswith(PYTHON_LAUNCH_SUFFIXES)


NODES_ONLY = "starts no Gazebo world and spawns no robot (nodes only): nothing to simulate"


def nothing_to_simulate(path: str | Path, info: LaunchInfo) -> str | None:
    """Why a launch file has nothing to simulate on its own, or None when it has a world to check: it names no
    world and spawns no robot (a package's launch file running nodes beside a world started elsewhere), or — a
    Python launch file, whose read says whether it starts a simulator — it spawns a robot into a simulator it
    does not start (a part other launch files include). An XML file is taken to start one when it mentions
    gazebo anywhere."""
    if info.world_ref is not None:
        return None
    if is_python_launch(path):
        if info.simulator is not None:
            return None
        return NODES_ONLY if not info.robots else ("spawns a robot but starts no simulator or world (a part that "
                                                   "other launch files include): nothing to simulate on its own")
    if info.robots or info.spawn is not None:
        return None
    try:
        text = Path(path).read_text(encoding="utf-8", errors="replace")
    except OSError:
        return None
    return None if "gazebo" in text else NODES_ONLY
