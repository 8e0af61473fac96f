"""ROS 2 packages: ``ros2 pkg create --build-type ament_python``-compatible scaffolding for the class.

What ``ros2 pkg create --build-type ament_python NAME --dependencies DEPS…`` writes, in our own words: package.xml
in format 3 (the ``xml-model`` schema line, one ``<depend>`` per dependency, the ament_python test dependencies
ament_copyright, ament_flake8, ament_pep257 and python3-pytest, ``<export><build_type>ament_python``; no
buildtool dependency), ``setup.py``, ``setup.cfg`` (scripts into ``lib/NAME``, where ``ros2 run`` looks),
``resource/NAME`` (the empty ament index marker), ``NAME/__init__.py`` and ``test/`` with the three linters'
tests. Its defaults too: version 0.0.0, description "TODO: Package description", license "TODO: License
declaration", the current user as maintainer (``USER@todo.todo``); and it refuses a package named ``test``.

Added for the class, as :mod:`worldgen.packages.catkin` adds them to a catkin package: ``launch/`` and ``worlds/``
folders (Jazzy: ``params/`` for the bridge too) that ``setup.py`` installs to ``share/NAME/`` — every file in
them, found again at each build, so files added later install too — and nodes as modules ``NAME/NODE.py`` with
``console_scripts`` entry points ``NODE = NAME.NODE:main``. A package with launch files exec_depends on what they
start (:data:`LAUNCH_DEPENDS`).

Options of ``worldgen scaffold`` map onto ros2 pkg create's: DEPENDENCIES and ``-s`` → ``<depend>``, ``-D`` →
``--description``, ``-l`` → ``--license``, ``-m`` → maintainer; ``-V`` and ``-a`` are ours. Boost components and
``--meta`` have no meaning here and are refused.
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Mapping

from ..core.errors import InputError
from ..core.resources import render_template
from ..launch.writer_py import check_ros2, world_package_files
from .catkin import PackageArgs, PackageFiles, PackageRequest, package_request, spec_world
from ..launch.targets import cmd_vel_type, world_text
from ..core.fsio import check_free, write_tree

TEST_DEPENDS = ("ament_copyright", "ament_flake8", "ament_pep257", "python3-pytest")
# What the launch files start, per target (exec_depend): Gazebo and its ROS side, the state publisher, xacro for
# the URDF, turtlebot3_description (the URDF) and turtlebot3_gazebo (the robot's Gazebo model with its plugins).
LAUNCH_DEPENDS = {
    "humble": ("gazebo_ros", "robot_state_publisher", "turtlebot3_description", "turtlebot3_gazebo", "xacro"),
    "jazzy": ("robot_state_publisher", "ros_gz_bridge", "ros_gz_sim", "turtlebot3_description",
              "turtlebot3_gazebo", "xacro"),
}
DEFAULT_DESCRIPTION = "TODO: Package description"
DEFAULT_LICENSE = "TODO: License declaration"
ROS1_ONLY = {"rospy": "rclpy", "roscpp": "rclcpp", "catkin": None}


def ament_request(args: PackageArgs) -> PackageRequest:
    """``worldgen scaffold --ros humble|jazzy``'s arguments → a checked :class:`PackageRequest` (its
    ``catkin_deps`` are the ``<depend>`` names; ``rosdistro`` is not read). Raises InputError for what ros2 pkg
    create refuses (the name ``test``), for boost components and ``--meta``, and for ROS 1 packages among the
    dependencies."""
    if args.name == "test":
        raise InputError("an ament_python package cannot be named 'test' (its tests are in test/)",
                         hint="choose another name")
    if args.meta:
        raise InputError("ROS 2 has no catkin metapackages", hint="leave out --meta")
    if args.boost_comps:
        raise InputError("-b/--boost-comps is for catkin (CMake) packages; this is an ament_python package",
                         hint="leave out -b")
    deps = tuple(args.dependencies) + tuple(args.sys_deps)
    for dep in deps:
        if dep in ROS1_ONLY:
            instead = ROS1_ONLY[dep]
            raise InputError(f"{dep} is ROS 1; a ROS 2 package does not depend on it",
                             hint=f"depend on {instead} instead" if instead else f"leave out {dep}")
    return package_request(PackageArgs(
        args.name, deps, version=args.version,
        description=DEFAULT_DESCRIPTION if args.description is None else args.description,
        licenses=tuple(args.licenses) or (DEFAULT_LICENSE,), authors=args.authors, maintainers=args.maintainers))


def package_xml(req: PackageRequest, launch_depends=()) -> str:
    """package.xml (format 3) for ``req``, exec_depending on ``launch_depends`` and ``req.exec_only`` besides
    its ``<depend>``s (names given as a depend are not repeated)."""
    depends = sorted(set(req.catkin_deps))
    execs = sorted((set(launch_depends) | set(req.exec_only)) - set(depends))
    return render_template("ros2/package/package.xml.j2", name=req.name, version=req.version,
                           description=req.description, maintainers=req.maintainers, licenses=req.licenses,
                           authors=req.authors, depends=depends, exec_depends=execs, test_depends=TEST_DEPENDS)


def setup_py(req: PackageRequest, data_dirs, nodes) -> str:
    """setup.py: the package, its data folders (installed file by file to share/NAME/) and its nodes as
    console scripts."""
    maintainer = req.maintainers[0]
    literals = {"version": python_str(req.version), "maintainer": python_str(maintainer.name, 15),
                "maintainer_email": python_str(maintainer.email or "", 21),
                "description": python_str(req.description, 16), "license": python_str(", ".join(req.licenses), 12)}
    return render_template("ros2/package/setup.py.j2", name=req.name, data_dirs=list(data_dirs),
                           nodes=sorted(nodes), py=literals)


def python_str(text: str, column: int = 0, width: int = 99) -> str:
    """``text`` as a Python string literal starting at ``column``; one too long for a ``width``-column line is
    split into parenthesised pieces (one per line, at spaces), which Python joins back into the same string."""
    literal = repr(text)
    if column + len(literal) + 1 <= width:
        return literal
    pieces, line = [], ""
    for word in re.findall(r"\S+\s*|\s+", text):
        if line and len(repr(line + word)) + 8 > width:
            pieces.append(line)
            line = ""
        line += word
    pieces.append(line)
    return "(\n" + "\n".join(" " * 8 + repr(p) for p in pieces) + ")"


def ament_package_files(req: PackageRequest, ros: str, *, worlds: Mapping[str, str] | None = None,
                        launches: Mapping[str, str] | None = None, params: Mapping[str, str] | None = None,
                        nodes: Mapping[str, str] | None = None) -> PackageFiles:
    """Every file of the ament_python package ``req`` for ``ros`` (humble, jazzy): the ros2 pkg create files
    (see the module docstring), ``worlds/NAME``, ``launch/NAME`` and ``params/NAME`` files, and the node
    modules ``NAME/NODE.py`` (``nodes``: NODE → source) with their entry points. Empty data folders hold a
    ``.gitkeep`` so that git keeps them; none of the files is executable (the entry points are)."""
    check_ros2(ros)
    worlds, launches, params, nodes = (dict(worlds or {}), dict(launches or {}), dict(params or {}),
                                       dict(nodes or {}))
    data_dirs = ["launch", "worlds"] + (["params"] if ros == "jazzy" else [])
    if params and ros != "jazzy":
        raise ValueError("only a Jazzy package has bridge parameters")
    for node in nodes:
        if not node.isidentifier() or node == "__init__":
            raise InputError(f"a node module cannot be named {node!r}", hint="use letters, digits and '_'")
    files: dict[str, str] = {
        "package.xml": package_xml(req, LAUNCH_DEPENDS[ros] if launches else ()),
        "setup.py": setup_py(req, data_dirs, nodes),
        "setup.cfg": render_template("ros2/package/setup.cfg.j2", name=req.name),
        f"resource/{req.name}": "",
        f"{req.name}/__init__.py": "",
    }
    for test in ("copyright", "flake8", "pep257"):
        files[f"test/test_{test}.py"] = render_template(f"ros2/package/test_{test}.py.j2")
    files.update({f"{req.name}/{n}.py": code for n, code in nodes.items()})
    files.update({f"worlds/{n}": t for n, t in worlds.items()})
    files.update({f"launch/{n}": t for n, t in launches.items()})
    files.update({f"params/{n}": t for n, t in params.items()})
    for folder in data_dirs:
        if not any(f.startswith(folder + "/") for f in files):
            files[f"{folder}/.gitkeep"] = ""
    return PackageFiles(dict(sorted(files.items())), set())


def spec_world_files(spec_path: str | Path, package: str, ros: str, model: str = "optenv",
                     cmd_vel: str | None = None) -> tuple[dict[str, dict[str, str]], str, tuple]:
    """The spec's world in a ROS 2 package ``package``: ``{"worlds": …, "launches": …, "params": …}`` (file name
    → text, ready for :func:`ament_package_files`), the world's file name and the spawn pose its launch file
    has."""
    world_file, classic_text, spawn, model = spec_world(spec_path, model)
    files = world_package_files(Path(world_file).stem, world_text(classic_text, ros), package, ros, spawn, model,
                                cmd_vel)
    grouped: dict[str, dict[str, str]] = {"worlds": {}, "launches": {}, "params": {}}
    for rel, text in files.items():
        folder, _, file_name = rel.partition("/")
        grouped[{"worlds": "worlds", "launch": "launches", "params": "params"}[folder]][file_name] = text
    return grouped, next(iter(grouped["worlds"])), spawn


def create_ament_package(parent: str | Path, req: PackageRequest, ros: str, *,
                         world_spec: str | Path | None = None, cmd_vel: str | None = None,
                         force: bool = False) -> Path:
    """Write the ament_python package ``req`` into ``parent/NAME`` all at once (nothing on error); with
    ``world_spec`` its world, launch file (and Jazzy's bridge parameters) too. An existing folder is refused
    unless ``force`` (then it is replaced)."""
    check_ros2(ros)
    cmd_vel_type(ros, cmd_vel)
    target = Path(parent) / req.name
    check_free([target], force)
    extra: dict[str, dict[str, str]] = {}
    if world_spec is not None:
        extra = spec_world_files(world_spec, req.name, ros, cmd_vel=cmd_vel)[0]
    pkg = ament_package_files(req, ros, **extra)
    return write_tree(target, pkg.files, force=force, executable=pkg.executable)
