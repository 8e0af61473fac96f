"""What ``worldgen run … NODE…`` starts: each NODE is a ``.py`` file (run with the Python that has rospy), a
``PKG/TYPE`` executable of a catkin package (found as ``rosrun`` finds it), or a ``.launch`` file (its nodes, less
the Gazebo and robot-description ones this simulator stands in for, each as roslaunch starts it: its ``args``,
``<remap>``s, ``<env>``s, name and namespace; the parameters the file sets go on the master first). An argument
holding ``:=`` belongs to the node before it: after a ``.py`` file or ``PKG/TYPE`` it is the node's argument
(``_kp:=0.8``, ``scan:=/base_scan``), as on a ``rosrun`` command line; after a launch file it is the file's arg
(``distance:=0.65``), as on a ``roslaunch`` command line.
"""

from __future__ import annotations

import os
import re
import shlex
from pathlib import Path
from typing import Sequence

from ..bridge.outcome import NodeSpec, check_python_file, group_args
from ..core.errors import InputError
from ..core.findings import Finding
from ..core import packages

# Packages whose nodes worldgen itself stands in for when a launch file starts them.
STAND_INS = frozenset({"gazebo_ros", "robot_state_publisher", "joint_state_publisher", "xacro", "rviz",
                       "turtlebot3_gazebo", "turtlebot3_description", "turtlebot3_bringup", "tf", "tf2_ros"})
_PKG_TYPE = re.compile(r"^[A-Za-z][A-Za-z0-9_]*/[^/\s]+$")


def resolve_nodes(items: Sequence[str], python: str, search: Sequence[str | Path] = ()) -> list[NodeSpec]:
    """Every NODE argument as the processes it starts (see the module docstring); InputError for a missing or
    non-Python file, an unknown package or executable. ``search`` are extra package roots (tried before
    ``ROS_PACKAGE_PATH``)."""
    if not items:
        raise InputError("no node given", hint="give the node to run: a .py file, PKG/TYPE or a .launch file")
    specs: list[NodeSpec] = []
    for item, args in group_args(items):
        path = Path(item)
        if item.endswith((".launch.py", "_launch.py")):
            raise InputError("is a ROS 2 launch file: worldgen run starts ROS 1 (rospy) nodes", path=path,
                             hint="give the ROS 1 .launch file or the node's .py file (validate reads a launch.py)")
        if path.suffix in (".launch", ".xml") or item.endswith(".launch.xml"):
            specs += _launch_nodes(path, python, search, args)
        elif path.exists() or not _PKG_TYPE.match(item) or item.startswith("."):
            specs.append(_python_file(path, python, args))
        else:
            specs.append(_package_node(item, python, search, args))
    names = [s.name for s in specs]
    for i, spec in enumerate(specs):   # two nodes of one file: tell their logs apart
        if names.count(spec.name) > 1:
            spec.name = f"{spec.name}_{i + 1}"
    return specs


def _python_file(path: Path, python: str, args: list[str], name: str | None = None) -> NodeSpec:
    check_python_file(path)
    head = path.read_bytes()[:200].split(b"\n", 1)[0]
    if path.suffix != ".py" and b"python" not in head:
        if not os.access(path, os.X_OK):
            raise InputError("is not a Python node, nor executable", path=path, hint="give a rospy node's .py file")
        return NodeSpec(name or path.stem, [str(path.resolve())], args, str(path))
    return NodeSpec(name or path.stem, [python, str(path.resolve())], args, str(path))


def _index(search: Sequence[str | Path]):
    return packages.PackageIndex([Path(p) for p in search] + packages.ros_package_path())


def _package_node(item: str, python: str, search: Sequence[str | Path], args: list[str],
                  name: str | None = None) -> NodeSpec:
    package, _, node_type = item.partition("/")
    if not node_type or "/" in node_type or node_type in (".", ".."):
        raise InputError(f"{item}: the node's type must be the name of an executable in package {package}",
                         hint='write <node pkg="PKG" type="NAME.py">, as rosrun PKG NAME.py would find it')
    folder = _index(search).find(package)
    if folder is None:
        raise InputError(f"{item}: no such file, and no package named {package!r}",
                         hint="put its workspace on ROS_PACKAGE_PATH (source devel/setup.bash), or give the .py file")
    found = sorted(p for p in folder.rglob(node_type) if p.is_file())
    if not found:
        raise InputError(f"package {package} has no executable named {node_type!r}", path=folder,
                         hint="check the name (rosrun PKG TYPE would fail too)")
    target = found[0]
    if target.suffix != ".py" and os.access(target, os.X_OK) and not target.read_bytes()[:2] == b"#!":
        return NodeSpec(name or target.stem, [str(target.resolve())], args, str(target))   # a compiled node
    spec = _python_file(target, python, args, name or Path(node_type).stem)
    if not os.access(target, os.X_OK):
        spec.notes = [Finding("launch-node", "error", f"{package}/{node_type} is not executable: roslaunch and rosrun "
                                                      "cannot start it (worldgen ran it with Python all the same)",
                              where=str(target), fix=f"chmod +x {shlex.quote(str(target))}")]
    return spec


def _launch_nodes(path: Path, python: str, search: Sequence[str | Path], args: list[str]) -> list[NodeSpec]:
    from ..launch.reader import read_launch

    if not path.is_file():
        raise InputError("no such launch file", path=path, hint="check the path")
    passed = dict(arg.split(":=", 1) for arg in args)
    info = read_launch(path, passed)
    unknown = sorted(set(passed) - set(info.args))
    if unknown:
        raise InputError(f"the launch file has no arg {unknown[0]!r}", path=path,
                         hint=f"its args are: {', '.join(sorted(info.args)) or 'none'}")

    own = packages.owning_package(path)
    roots = list(search) + ([own, packages.source_tree(own)] if own is not None else [])
    specs = []
    for node in info.nodes:
        if node.package in STAND_INS:
            continue
        extra = _words(node.args or "") + [f"{a}:={b}" for a, b in node.remaps] + [f"__name:={node.name}"]
        if node.ns not in ("", "/"):
            extra.append(f"__ns:={node.ns}")
        spec = _package_node(f"{node.package}/{node.type}", python, roots, extra, node.name)
        spec.params, spec.env = info.params, dict(node.env)
        spec.required, spec.respawn, spec.launch = node.required, node.respawn, f"{path}:{node.line}"
        specs.append(spec)
    if not specs:
        raise InputError("the launch file starts no node of its own (only Gazebo and robot-description ones)",
                         path=path, hint="give the node's .py file, or a launch file that starts it")
    specs[0].notes = [f for f in info.findings if f.check in ("launch-param", "launch-remap", "launch-node") or
                      f.severity != "info"] + specs[0].notes
    return specs


def _words(args: str) -> list[str]:
    """A node's ``args`` split as a shell would (roslaunch's way), or at spaces when its quotes do not close."""
    try:
        return shlex.split(args)
    except ValueError:
        return args.split()
