"""The state of one read of a ROS 2 Python launch file (:mod:`.reader_py`): what is found so far, the
findings and their fixes (:class:`PyRead`), and where the walk is — its launch configurations, namespace and file —
with substitutions performed as ros2 launch performs them there (:class:`Scope`): ``LaunchConfiguration`` (passed,
else the ``DeclareLaunchArgument`` default, else its own ``default=``), ``PathJoinSubstitution``,
``FindPackageShare``, ``EnvironmentVariable`` and lists of them (concatenated)."""

from __future__ import annotations

import os
import posixpath
from dataclasses import dataclass, field
from pathlib import Path, PurePosixPath
from typing import Dict, List, Mapping, Optional

from ..core.errors import WorldFileError
from ..core.packages import PackageIndex
from .model import Findings, Fixes, LaunchInfo
from .values_py import Config, Subst
from .walk_xml import STOCK_PACKAGES
from ..pyread.stdlib import env_value
from ..pyread.values import MAX_NESTING, MAX_WORK, Ctx, Located, Symbol, Unknown, first_unknown, shown

ROS2_STOCK = STOCK_PACKAGES | {"ros_gz_sim", "ros_gz_bridge", "ros_gz_image", "ros_ign_gazebo", "turtlebot3_bringup",
                               "robot_state_publisher"}
STATIC_FIX = ("write it without loops or calls of other modules, with constants or DeclareLaunchArgument defaults "
              "(worldgen reads launch files, never runs them), or give the spawn with --spawn X,Y")
ROS2_FIXES = Fixes(stock=ROS2_STOCK,
                   find="put the package {package} in this workspace, or source the ROS 2 install that has it "
                        "(AMENT_PREFIX_PATH)",
                   env="export {env} (or give a default: os.environ.get({env!r}, …))",
                   arg="pass it (name:=value) or give its DeclareLaunchArgument a default_value",
                   static=STATIC_FIX)


@dataclass
class PyRead(Findings):
    """One read of a launch file and what it includes: what is found so far and the files being read."""

    finder: PackageIndex
    environ: Mapping[str, str]
    info: LaunchInfo
    stack: List[Path] = field(default_factory=list)
    loaded: int = 0
    packages: Dict[str, Optional[Path]] = field(default_factory=dict)
    env_reads: Dict[str, tuple] = field(default_factory=dict)       # name → (value, file, line), first read
    skipped: Dict[tuple, list] = field(default_factory=dict)        # (file, kind) → [(line, what, reason)]
    top_args: Dict[str, object] = field(default_factory=dict)       # the top file's launch arguments
    steps: int = 0                                                   # actions and parts walked (see spend)
    open_lists: set = field(default_factory=set)                     # ids of the lists being walked or resolved
    FIXES = ROS2_FIXES

    def spend(self, count: int, path: Path, line: int | None = None) -> None:
        """Count ``count`` more items walked or resolved: WorldFileError past MAX_WORK (lists that hold
        themselves, or share one list a million times over, would otherwise take forever)."""
        self.steps += count
        if self.steps > MAX_WORK:
            raise WorldFileError(f"the launch file takes more work to read than worldgen does ({MAX_WORK:,} steps): "
                                 "its actions or substitutions are lists inside lists many times over", path=path,
                                 line=line, hint="build each action and list once; a launch file holds few")

    def share(self, package: str, line: int | None):
        """The folder ``get_package_share_directory(package)`` names here, or an Unknown."""
        if package not in self.packages:
            found = self.finder.find(package)
            if found is None:   # AMENT_PREFIX_PATH: the environment's, else the process's (as ROS_PACKAGE_PATH)
                prefixes = self.environ.get("AMENT_PREFIX_PATH", os.environ.get("AMENT_PREFIX_PATH", ""))
                for prefix in prefixes.split(":"):
                    candidate = Path(prefix) / "share" / package
                    if prefix.strip() and (candidate / "package.xml").is_file():
                        found = candidate
                        break
            self.packages[package] = found
        folder = self.packages[package]
        if folder is None:
            return Unknown(f"package {package!r} not found", line, f"‹{package}›", package=package)
        return Located.make(str(folder), package)


@dataclass
class Scope:
    """Where the walk is: the file, its launch configurations (shared with includes, as ros2 launch shares
    them; a scoped GroupAction copies them), the namespace, and the read of the file (``ctx``)."""

    read: PyRead
    path: Path
    configs: Dict[str, object]
    ns: str
    ctx: Optional[Ctx] = None
    nesting: int = 0   # lists, groups and descriptions walked inside one another

    def share(self, package: str, line: int | None):
        return self.read.share(package, line)

    def resolve(self, value, line: int | None = None, depth: int = 0):
        """A substitution's text as ros2 launch would perform it here, or an Unknown."""
        if depth > MAX_NESTING:
            return Unknown("substitutions nested too deeply to read", line)
        if isinstance(value, (Unknown, str)):
            return value
        if isinstance(value, bool):
            return "true" if value else "false"
        if isinstance(value, (int, float, PurePosixPath)):
            return str(value)
        if isinstance(value, (list, tuple)):
            if id(value) in self.read.open_lists:
                return Unknown("a list that holds itself", line)
            self.read.spend(1 + len(value), self.path, line)
            self.read.open_lists.add(id(value))
            try:
                parts = [self.resolve(v, line, depth + 1) for v in value]
            finally:
                self.read.open_lists.discard(id(value))
            unknown = first_unknown(parts)
            joined = "".join(shown(p) for p in parts)
            if unknown is not None:
                return unknown.like(joined)
            return Located.make(joined, parts[0].package) if parts and isinstance(parts[0], Located) else joined
        if isinstance(value, Config):
            return self._config(value, line, depth + 1)
        if isinstance(value, Subst):
            return self._subst(value, line, depth + 1)
        if isinstance(value, Symbol):
            return Unknown(f"{value.name} is not defined in this file", line)
        return Unknown(f"{type(value).__name__} is not a substitution", line)

    def _config(self, config: Config, line, depth: int):
        name = self.resolve(config.name, line, depth)
        if isinstance(name, Unknown):
            return name
        if name in self.configs:
            value = self.configs[name]
        elif config.default is not None:
            value = self.resolve(config.default, line, depth)
        else:
            value = Unknown(f"launch argument {name!r} has no value: it is not passed, and no DeclareLaunchArgument "
                            "default or default= gives one", config.line or line, f"‹{name}›")
        if self.path == self.read.info.path:
            self.read.top_args.setdefault(name, value)
        return value

    def _subst(self, subst: Subst, line, depth: int):
        if subst.kind == "join":
            given = subst.parts if isinstance(subst.parts, (list, tuple)) else [subst.parts]
            parts = [self.resolve(p, line, depth) for p in given]
            unknown = first_unknown(parts)
            if unknown is not None:
                return unknown.like("/".join(shown(p) for p in parts))
            if not parts:
                return ""
            joined = posixpath.join(*parts)
            return Located.make(joined, parts[0].package) if isinstance(parts[0], Located) else joined
        if subst.kind == "share":
            package = self.resolve(subst.parts, line, depth)
            return package if isinstance(package, Unknown) else self.share(package, subst.line)
        if subst.kind == "env":
            name = self.resolve(subst.parts, line, depth)
            default = self.resolve(subst.default, line, depth) if subst.default is not None else None
            if isinstance(name, Unknown):
                return name
            value = env_value(self.ctx, name, subst.line, default, required=default is None)
            self.read.env_reads.setdefault(name, (value if isinstance(value, str) else None, self.path, subst.line))
            return value
        return Unknown(f"a {subst.kind} substitution is not read here", line)
