"""What ``worldgen run --ros humble|jazzy … NODE…`` starts: each NODE is an rclpy ``.py`` file (run with the Python
that has rclpy, :mod:`.pyenv`), a ``PKG/EXECUTABLE`` of a colcon workspace's install (found as ``ros2 run`` finds it:
``<prefix>/lib/<PKG>/<EXECUTABLE>`` under ``AMENT_PREFIX_PATH``, or under ``install/`` beside a workspace given
with ``--launch``), or a ``.launch.py``'s Node actions as the static reader resolves them (executable, name,
namespace, arguments, remappings, the parameters that resolve; the file is never executed), less the ones worldgen
stands in for (Gazebo, the spawner, robot_state_publisher, ros_gz_bridge). A launch file's node of an ament_python
package in the same source tree runs from its source, through its ``setup.py`` entry point, when it is not built.

An argument holding ``:=`` belongs to the node before it, as on a ``ros2 run`` command line after ``--ros-args``:
``_name:=value`` (ROS 1's private-parameter spelling) and ``-p``-style ``name:=value`` of a known parameter become
``-p name:=value``, anything else a remapping ``-r from:=to``.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Sequence

from ..bridge.outcome import NodeSpec, check_python_file, group_args
from ..core.errors import InputError
from ..core.packages import PackageIndex, owning_package, source_tree
from ..launch.reader_py import read_launch_py
from ..pyread.setup_py import read_setup

# Packages whose nodes the simulator stands in for when a launch file starts them.
STAND_INS = frozenset({"gazebo_ros", "ros_gz_sim", "ros_gz_bridge", "ros_gz_image", "robot_state_publisher",
                       "joint_state_publisher", "turtlebot3_gazebo", "turtlebot3_description", "rviz2", "xacro",
                       "tf2_ros"})


def ros_args(args: Sequence[str]) -> list[str]:
    """``name:=value`` items as ``--ros-args`` (see the module docstring); none: nothing."""
    if not args:
        return []
    out = ["--ros-args"]
    for item in args:
        name, _, value = item.partition(":=")
        if name.startswith("__"):            # __ns:=, __node:= (ROS 1's __name:=) keep their meaning
            key = {"__name": "__node"}.get(name, name)
            out += ["-r", f"{key}:={value}"]
        elif name.startswith("_"):
            out += ["-p", f"{name[1:]}:={value}"]
        else:
            out += ["-r", f"{name}:={value}"]
    return out


def resolve_nodes(items: Sequence[str], python: str, search: Sequence[str | Path] = ()) -> list[NodeSpec]:
    """Every NODE argument as the processes it starts; InputError for a missing or non-Python file, an unknown
    package or executable."""
    if not items:
        raise InputError("no node given", hint="give the node to run: a .py file, PKG/EXECUTABLE or a .launch.py file")
    specs: list[NodeSpec] = []
    for item, args in group_args(items):
        path = Path(item)
        if item.endswith(".launch.py") or item.endswith("_launch.py"):
            specs += _launch_nodes(path, python, args)
        elif path.suffix in (".launch", ".xml"):
            raise InputError("is a ROS 1 launch file: --ros humble|jazzy runs rclpy nodes", path=path,
                             hint="give the .launch.py file or the node's .py file, or leave out --ros")
        elif path.exists() or "/" not in item or item.startswith("."):
            check_python_file(path)
            specs.append(NodeSpec(path.stem, [python, str(path.resolve())], ros_args(args), str(path)))
        else:
            specs.append(_installed(item, python, ros_args(args)))
    names = [s.name for s in specs]
    for i, spec in enumerate(specs):
        if names.count(spec.name) > 1:
            spec.name = f"{spec.name}_{i + 1}"
    return specs


def prefixes(extra: Sequence[str | Path] = ()) -> list[Path]:
    """Install prefixes to look in: ``extra``, then ``AMENT_PREFIX_PATH``'s."""
    found = [Path(p) for p in extra]
    found += [Path(p) for p in os.environ.get("AMENT_PREFIX_PATH", "").split(os.pathsep) if p]
    return found


def _installed(item: str, python: str, args: list[str], name: str | None = None,
               extra: Sequence[str | Path] = (), sources: Sequence[Path] = ()) -> NodeSpec:
    package, _, executable = item.partition("/")
    from_source = _from_source(package, executable, python, args, name, sources)
    if from_source is not None:
        return from_source
    for prefix in prefixes(extra):
        target = prefix / "lib" / package / executable
        if target.is_file():
            head = target.read_bytes()[:200].split(b"\n", 1)[0]
            env = {}
            sites = sorted((prefix / "lib").glob("python3*/site-packages"))
            if sites:
                env["PYTHONPATH"] = os.pathsep.join([str(sites[-1])] + [p for p in
                                                     os.environ.get("PYTHONPATH", "").split(os.pathsep) if p])
            command = [python, str(target)] if b"python" in head or target.suffix == ".py" else [str(target)]
            return NodeSpec(name or executable, command, args, str(target), env=env)
    raise InputError(f"{item}: no such file, and no installed executable {executable!r} of package {package!r}",
                     hint="build the workspace with colcon and source install/setup.bash (AMENT_PREFIX_PATH), or "
                          "give the node's .py file")


def _from_source(package: str, executable: str, python: str, args: list[str], name: str | None,
                 sources: Sequence[Path]) -> NodeSpec | None:
    """An ament_python package's console script run from its source, as its installed entry point would run it
    (``setup.py``'s ``console_scripts``, read statically): a class's submissions are handed in unbuilt."""
    if not sources:
        return None
    folder = PackageIndex(list(sources)).find(package)
    if folder is None or not (folder / "setup.py").is_file():
        return None
    target = read_setup(folder / "setup.py").entry_points.get(executable)
    if not target or ":" not in target:
        return None
    module, _, function = target.partition(":")
    file = folder.joinpath(*module.split(".")).with_suffix(".py")
    if not file.is_file() or not module.replace(".", "").replace("_", "").isalnum() or not function.isidentifier():
        return None
    code = (f"import sys; sys.path.insert(0, {str(folder)!r}); sys.argv[0] = {executable!r}; "
            f"from {module} import {function}; sys.exit({function}())")
    return NodeSpec(name or executable, [python, "-c", code], args, str(file))


def _launch_nodes(path: Path, python: str, args: list[str]) -> list[NodeSpec]:
    if not path.is_file():
        raise InputError("no such launch file", path=path, hint="check the path")
    passed = dict(arg.split(":=", 1) for arg in args)
    own = owning_package(path)
    sources = [own, source_tree(own)] if own is not None else []
    info = read_launch_py(path, passed, finder=PackageIndex(sources), environ=os.environ)
    install = [p / "install" / pkg for p in path.resolve().parents for pkg in
               ((p / "install").iterdir() if (p / "install").is_dir() else [])][:64]
    specs = []
    for node in info.nodes:
        if node.package in STAND_INS:
            continue
        extra = [f"__node:={node.name}"] + ([f"__ns:={node.ns}"] if node.ns not in ("", "/") else [])
        extra += [f"{a}:={b}" for a, b in node.remaps] + [f"_{k}:={v}" for k, v in node.params]
        node_args = (node.args.split() if node.args else []) + ros_args(extra)
        spec = _installed(f"{node.package}/{node.type}", python, node_args, node.name, install, sources)
        spec.launch = f"{path}:{node.line}"
        specs.append(spec)
    if not specs:
        raise InputError("the launch file starts no node of its own (only Gazebo and robot-description ones)",
                         path=path, hint="give the node's .py file, or a launch file that starts it")
    specs[0].notes = [f for f in info.findings if f.severity != "info"]
    return specs
