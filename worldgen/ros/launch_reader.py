"""Reading roslaunch XML files back: the world, the robot model and every spawn pose they start.

:func:`read_launch` evaluates a launch file the way roslaunch does for what matters here — args and their
defaults, ``$(arg)``/``$(env)``/``$(optenv)``/``$(find)``/``$(dirname)``/``$(anon)``, groups and namespaces,
``if``/``unless``, includes with passed args — and reports the world, the robot model and every ``spawn_model``
pose, with findings for whatever cannot be resolved instead of failing. ``$(find PKG)`` looks in the package
holding the launch file, then its sibling packages in the same catkin source tree, then ``ROS_PACKAGE_PATH``
(see :mod:`worldgen.core.packages`).
"""

from __future__ import annotations

import os
import re
import shlex
from dataclasses import dataclass, field
from pathlib import Path
from typing import Mapping, Sequence

from ..core import packages as rospkg
from ..core.errors import WorldFileError
from ..core.findings import Finding
from .launch import NodeRef, join_ns
from ..core.spawnpose import Pose


@dataclass(frozen=True)
class RobotSpawn:
    """One ``gazebo_ros/spawn_model`` node: its full name, the ``-model`` name, the ``-param`` it reads the
    description from, the robot model (burger/waffle/…) when known and the pose (None when unresolved)."""

    node: str
    model_name: str | None
    param: str | None
    robot: str | None
    pose: Pose | None
    line: int | None = None


@dataclass
class LaunchInfo:
    """What a launch file starts, as far as worlds and robots go.

    ``world_path`` is the world file passed to gazebo_ros as ``world_name`` (None when it cannot be resolved or
    none is passed); ``world_ref`` is that value with args expanded but ``$(find)`` kept; ``package`` is the
    package named by its ``$(find PKG)``. ``robots`` lists every spawn_model node (in file order, includes
    followed); ``model`` and ``spawn`` are the first robot's (for one-robot files: *the* robot), falling back to
    the ``model`` and ``x_pos``/``y_pos``/``z_pos``/``yaw`` args when no spawn node could be read.
    ``model_env`` names the environment variable the model depends on when it was not set. ``args`` are the
    top-level args' values (None when unresolved). ``findings`` say what could not be resolved and why.
    """

    path: Path
    world_path: Path | None = None
    world_ref: str | None = None
    package: str | None = None
    model: str | None = None
    model_env: str | None = None
    spawn: Pose | None = None
    args: dict[str, str | None] = field(default_factory=dict)
    robots: list[RobotSpawn] = field(default_factory=list)
    nodes: list[NodeRef] = field(default_factory=list)
    includes: list[Path] = field(default_factory=list)
    findings: list[Finding] = field(default_factory=list)


class _Unresolved(Exception):
    """A substitution that cannot be evaluated here (unset arg or env var, unknown package, ``$(eval)``)."""

    def __init__(self, reason: str, env: str | None = None, package: str | None = None):
        super().__init__(reason)
        self.reason, self.env, self.package = reason, env, package


_SUBST = re.compile(r"\$\((\w+)((?:\s+[^()\s]*)*)\s*\)")
_XACRO_MODEL = re.compile(r"turtlebot3_([A-Za-z0-9_]+)\.urdf(?:\.xacro)?\b")
_GAZEBO_FLAGS = {"-x": 0, "-y": 1, "-z": 2, "-Y": 3}
_MAX_INCLUDE_DEPTH = 16
_STOCK_PACKAGES = frozenset({"gazebo_ros", "xacro", "turtlebot3_description", "turtlebot3_gazebo"})


def package_index(launch_path: str | Path, ros_package_path: Sequence[str | Path] | None = None
                  ) -> rospkg.PackageIndex:
    """Where ``$(find PKG)`` looks for a launch file: the package holding the file first, then its sibling
    packages in the same catkin source tree, then ``ros_package_path`` (default: the process's
    ``ROS_PACKAGE_PATH``)."""
    own = rospkg.owning_package(launch_path)
    roots = [own, rospkg.source_tree(own)] if own is not None else []
    roots += rospkg.ros_package_path() if ros_package_path is None else [Path(p) for p in ros_package_path]
    return rospkg.PackageIndex(roots)


def _parse_xml(path: Path, what: str = "launch file"):
    from ..core.safexml import parse_bytes

    try:
        data = Path(path).read_bytes()
    except OSError as err:
        raise WorldFileError(f"cannot read the {what}: {err.strerror or err}", path=path,
                             hint="check the path") from None
    return parse_bytes(data, path, what=what,
                       hint="fix the XML (every tag closed, attributes quoted, '<' and '&' escaped)",
                       empty_hint="a launch file holds one <launch> element")


@dataclass
class _Scope:
    """One launch file being evaluated: its args and where it is."""

    path: Path
    args: dict[str, str | _Unresolved]
    passed: dict[str, str | _Unresolved]
    ns: str


class _Reader:
    """Evaluates launch files into one :class:`LaunchInfo`, following includes."""

    def __init__(self, top: Path, finder: rospkg.PackageIndex, environ: Mapping[str, str]):
        self.finder = finder
        self.environ = environ
        self.info = LaunchInfo(path=top)
        self.params: dict[str, str] = {}   # full name → text (unresolved parts marked, see expand_lenient)
        self.stack: list[Path] = []
        self.raw_args: dict[str, str | None] = {}   # the top-level args as written

    # -- findings ------------------------------------------------------------------------------------------
    def note(self, check: str, severity: str, message: str, scope: _Scope, line: int | None, fix: str | None):
        where = f"{scope.path}:{line}" if line else str(scope.path)
        finding = Finding(check, severity, message, where=where, fix=fix)
        if finding not in self.info.findings:
            self.info.findings.append(finding)

    def unresolved(self, err: _Unresolved, what: str, scope: _Scope, line: int | None):
        if err.package:
            # Gazebo's and the TurtleBot3's own packages are missing on most machines that are not robot PCs.
            severity = "info" if err.package in _STOCK_PACKAGES else "warning"
            self.note("launch-find", severity, f"{what}: {err.reason}", scope, line,
                      f"put the package {err.package} in this catkin workspace or on ROS_PACKAGE_PATH")
        elif err.env:
            self.note("launch-env", "info", f"{what}: {err.reason}", scope, line,
                      f"export {err.env} (or pass the arg on the command line)")
        else:
            self.note("launch-arg", "warning", f"{what}: {err.reason}", scope, line,
                      "pass the arg (name:=value) or give it a default")

    # -- substitutions -------------------------------------------------------------------------------------
    def expand(self, text: str, scope: _Scope, find: bool = False) -> str:
        """``text`` with every substitution evaluated; ``$(find)`` only when ``find`` (it is kept otherwise).
        Raises _Unresolved for the first one that cannot be evaluated."""
        if text.strip().startswith("$(eval "):
            raise _Unresolved("$(eval …) expressions are not evaluated here")
        return _SUBST.sub(lambda m: self.substitute(m, scope, find), text)

    def expand_lenient(self, text: str, scope: _Scope) -> tuple[str, list[_Unresolved]]:
        """Like :meth:`expand`, but each substitution that cannot be evaluated becomes the marker ``\\0N\\0``
        (N indexes the returned errors), so the parts that can be read still are."""
        errors: list[_Unresolved] = []

        def one(match: re.Match) -> str:
            try:
                return self.substitute(match, scope, False)
            except _Unresolved as err:
                errors.append(err)
                return f"\0{len(errors) - 1}\0"

        if text.strip().startswith("$(eval "):
            return "\x000\x00", [_Unresolved("$(eval …) expressions are not evaluated here")]
        return _SUBST.sub(one, text), errors

    def substitute(self, match: re.Match, scope: _Scope, find: bool) -> str:
        command, rest = match.group(1), match.group(2).split()
        if command == "arg" and len(rest) == 1:
            value = scope.args.get(rest[0])
            if value is None:
                raise _Unresolved(f"arg {rest[0]!r} is not declared")
            if isinstance(value, _Unresolved):
                raise value
            return value
        if command == "env" and len(rest) == 1:
            if rest[0] not in self.environ:
                raise _Unresolved(f"environment variable {rest[0]} is not set", env=rest[0])
            return self.environ[rest[0]]
        if command == "optenv" and rest:
            return self.environ.get(rest[0], " ".join(rest[1:]))
        if command == "dirname" and not rest:
            return str(scope.path.resolve().parent)
        if command == "anon" and len(rest) == 1:
            return f"{rest[0]}_anon"
        if command == "find" and len(rest) == 1:
            if not find:
                return match.group(0)
            found = self.finder.find(rest[0])
            if found is None:
                raise _Unresolved(f"package {rest[0]!r} not found", package=rest[0])
            return str(found)
        raise _Unresolved(f"cannot evaluate {match.group(0)}")

    def condition(self, el, scope: _Scope) -> bool:
        for attr, want in (("if", True), ("unless", False)):
            raw = el.get(attr)
            if raw is None:
                continue
            try:
                value = self.expand(raw, scope, find=True).strip().lower()
            except _Unresolved as err:
                self.unresolved(err, f"<{el.tag} {attr}=…> assumed satisfied", scope, el.sourceline)
                continue
            if value not in ("true", "1", "false", "0"):
                raise WorldFileError(f"<{el.tag} {attr}=\"{raw}\"> is neither true nor false", path=scope.path,
                                     line=el.sourceline, hint="use true/false or 1/0")
            if (value in ("true", "1")) != want:
                return False
        return True

    # -- elements ------------------------------------------------------------------------------------------
    def load(self, path: Path, passed: dict[str, str | _Unresolved], ns: str, line: int | None) -> None:
        path = Path(path)
        if path.resolve() in self.stack:
            raise WorldFileError("a launch file includes itself", path=path, line=line,
                                 hint="remove the circular <include>")
        if len(self.stack) >= _MAX_INCLUDE_DEPTH:
            raise WorldFileError("includes nest too deeply", path=path, line=line, hint="remove circular includes")
        root = _parse_xml(path)
        if root.tag != "launch":
            raise WorldFileError(f"the root element is <{root.tag}>, not <launch>", path=path,
                                 line=root.sourceline, hint="a launch file holds one <launch> element")
        self.stack.append(path.resolve())
        scope = _Scope(path, {}, passed, ns)
        self.walk(root, scope)
        self.stack.pop()
        if len(self.stack) == 0:
            self.info.args = {k: (None if isinstance(v, _Unresolved) else self._found_path(v, scope))
                              for k, v in scope.args.items()}

    def _found_path(self, value: str, scope: _Scope) -> str | None:
        try:
            return self.expand(value, scope, find=True)
        except _Unresolved:
            return None

    def walk(self, parent, scope: _Scope) -> None:
        for el in parent:
            if not isinstance(el.tag, str) or not self.condition(el, scope):
                continue
            handler = getattr(self, f"on_{el.tag}", None)
            if handler is not None:
                handler(el, scope)

    def on_arg(self, el, scope: _Scope) -> None:
        name = el.get("name")
        if not name:
            raise WorldFileError("<arg> without a name", path=scope.path, line=el.sourceline,
                                 hint='write <arg name="..." default="..."/>')
        if el.get("value") is not None and el.get("default") is not None:
            raise WorldFileError(f"<arg name=\"{name}\"> has both value and default", path=scope.path,
                                 line=el.sourceline, hint="keep one of them")
        value: str | _Unresolved
        if el.get("value") is not None:
            value = self._try(el.get("value"), scope)
        elif name in scope.passed:
            value = scope.passed[name]
        elif el.get("default") is not None:
            value = self._try(el.get("default"), scope)
        else:
            value = _Unresolved(f"arg {name!r} has no value (it must be passed: {name}:=...)")
        scope.args[name] = value
        if len(self.stack) == 1:
            self.raw_args[name] = el.get("value", el.get("default"))

    def _try(self, text: str, scope: _Scope) -> str | _Unresolved:
        try:
            return self.expand(text, scope)
        except _Unresolved as err:
            return err

    def on_group(self, el, scope: _Scope) -> None:
        ns = join_ns(scope.ns, self._try_str(el.get("ns") or "", scope))
        self.walk(el, _Scope(scope.path, scope.args, scope.passed, ns))   # args are shared with the file

    def on_param(self, el, scope: _Scope) -> None:
        name = el.get("name")
        if not name:
            return
        raw = el.get("command") or el.get("value") or el.get("textfile") or ""
        self.params[join_ns(scope.ns, self._try_str(name, scope))] = self.expand_lenient(raw, scope)[0]

    def _try_str(self, text: str, scope: _Scope) -> str:
        value = self._try(text, scope)
        return text if isinstance(value, _Unresolved) else value

    def on_include(self, el, scope: _Scope) -> None:
        raw = el.get("file")
        if not raw:
            raise WorldFileError("<include> without a file", path=scope.path, line=el.sourceline,
                                 hint='write <include file="$(find PKG)/launch/NAME.launch">')
        passed: dict[str, str | _Unresolved] = {}
        if el.get("pass_all_args", "").lower() in ("true", "1"):
            passed.update(scope.args)
        for child in el:
            if isinstance(child.tag, str) and child.tag == "arg" and child.get("name") and self.condition(child, scope):
                passed[child.get("name")] = self._try(child.get("value", child.get("default", "")), scope)
        if "world_name" in passed and self.info.world_ref is None:
            self.world(passed["world_name"], _child_line(el, "world_name"), scope)
        ns = join_ns(scope.ns, self._try_str(el.get("ns") or "", scope))
        try:
            target = Path(self.expand(raw, scope, find=True))
        except _Unresolved as err:
            self.unresolved(err, f"<include file=\"{raw}\"> not followed", scope, el.sourceline)
            return
        if not target.is_file():
            self.note("launch-include", "warning", f"included file {target} does not exist", scope,
                      el.sourceline, "fix the path of the <include>")
            return
        self.info.includes.append(target)
        self.load(target, passed, ns, el.sourceline)

    def world(self, value: str | _Unresolved, line: int | None, scope: _Scope) -> None:
        if isinstance(value, _Unresolved):
            self.unresolved(value, "world_name", scope, line)
            return
        self.info.world_ref = value
        found = re.match(r"\s*\$\(find\s+([^)\s]+)\)", value)
        self.info.package = found.group(1) if found else None
        try:
            resolved = self.expand(value, scope, find=True).strip()
        except _Unresolved as err:
            self.unresolved(err, f"world_name {value}", scope, line)
            return
        if not os.path.isabs(resolved):
            self.note("launch-world", "info", f"world_name {resolved!r} is found through Gazebo's resource path",
                      scope, line, "give the world as $(find PKG)/worlds/NAME.world to check it")
            return
        self.info.world_path = Path(resolved)

    def on_node(self, el, scope: _Scope) -> None:
        pkg, node_type, name = el.get("pkg"), el.get("type"), el.get("name")
        if not pkg or not node_type:
            raise WorldFileError("<node> without pkg or type", path=scope.path, line=el.sourceline,
                                 hint='write <node pkg="PKG" type="EXECUTABLE" name="NAME"/>')
        ns = join_ns(scope.ns, self._try_str(el.get("ns") or "", scope))
        args, errors = self.expand_lenient(el.get("args") or "", scope)
        node = NodeRef(pkg, node_type, self._try_str(name or node_type, scope), ns,
                       None if errors else args, el.sourceline)
        self.info.nodes.append(node)
        if (pkg, node_type) == ("gazebo_ros", "spawn_model"):
            self.spawn(node, args, errors, scope, el.sourceline)

    def spawn(self, node: NodeRef, args: str, errors: list[_Unresolved], scope: _Scope, line: int | None) -> None:
        """Record a spawn_model node: its -x -y -z -Y pose (0 when not given, as spawn_model does), -model and
        -param. A pose number that cannot be resolved or read leaves the pose unknown, with a finding."""
        words = shlex.split(args)
        pose: list[float] | None = [0.0, 0.0, 0.0, 0.0]
        model_name = param = None
        for i, word in enumerate(words):
            following = words[i + 1] if i + 1 < len(words) else None
            if word in _GAZEBO_FLAGS:
                marker = re.search(r"\0(\d+)\0", following or "")
                if marker:
                    self.unresolved(errors[int(marker.group(1))], f"spawn_model {node.full_name} {word}", scope,
                                    line)
                    pose = None
                    continue
                try:
                    value = float(following)
                except (TypeError, ValueError):
                    self.note("launch-spawn", "error", f"spawn_model {word} {following!r} is not a number", scope,
                              line, "give the pose as numbers (or $(arg NAME) with a numeric default)")
                    pose = None
                    continue
                if pose is not None:
                    pose[_GAZEBO_FLAGS[word]] = value
            elif word == "-model":
                model_name = None if following is None or "\0" in following else following
            elif word == "-param":
                param = None if following is None or "\0" in following else following
        for i, word in enumerate(words):   # an unresolved word that is no flag's value may hold the pose itself
            marker = re.search(r"\0(\d+)\0", word)
            if marker and not (i > 0 and words[i - 1].startswith("-")):
                self.unresolved(errors[int(marker.group(1))], f"spawn_model {node.full_name}: pose unknown",
                                scope, line)
                pose = None
        robot = self.robot_of(param, node.ns)
        self.info.robots.append(RobotSpawn(node.full_name, model_name, param, robot,
                                           None if pose is None else (pose[0], pose[1], pose[2], pose[3]), line))

    def robot_of(self, param: str | None, ns: str) -> str | None:
        if not param:
            return None
        text = self.params.get(param if param.startswith("/") else join_ns(ns, param))
        found = _XACRO_MODEL.search(text or "")
        return found.group(1) if found else None


def _child_line(el, arg_name: str) -> int | None:
    for child in el:
        if isinstance(child.tag, str) and child.tag == "arg" and child.get("name") == arg_name:
            return child.sourceline
    return el.sourceline


def read_launch(path: str | Path, args: Mapping[str, str] | None = None, *,
                ros_package_path: Sequence[str | Path] | None = None,
                environ: Mapping[str, str] | None = None) -> LaunchInfo:
    """Read a roslaunch XML file: world, robot model, spawn poses, args, nodes (see :class:`LaunchInfo`).

    ``args`` are command-line overrides (``x_pos:=1.5`` → ``{"x_pos": "1.5"}``); ``ros_package_path`` and
    ``environ`` default to the process's. Raises WorldFileError (with the line) for a file roslaunch could not
    parse either: malformed XML, a root other than ``<launch>``, an ``<arg>``/``<node>``/``<include>`` missing
    its required attributes, circular includes. Unresolvable references become findings, and only what depends
    on them stays unknown (roslaunch stops at the first one: an unset ``$(env TURTLEBOT3_MODEL)`` default fails
    it even when ``model:=`` is passed).
    """
    path = Path(path)
    environ = os.environ if environ is None else environ
    reader = _Reader(path, package_index(path, ros_package_path), environ)
    reader.load(path, {k: str(v) for k, v in (args or {}).items()}, "/", None)
    info = reader.info
    if info.robots:
        info.spawn, info.model = info.robots[0].pose, info.robots[0].robot
    if info.model is None:
        info.model = info.args.get("model")
    model_arg = reader.raw_args.get("model")
    if info.model is None and model_arg:
        env = re.search(r"\$\((?:opt)?env\s+(\w+)", model_arg)
        info.model_env = env.group(1) if env else None
    if info.spawn is None and not info.robots and "x_pos" in info.args:   # args only: a file that includes the spawn
        try:
            info.spawn = tuple(float(info.args.get(k) or 0.0) for k in ("x_pos", "y_pos", "z_pos", "yaw"))
        except ValueError:
            reader.note("launch-spawn", "error", "x_pos/y_pos/z_pos/yaw are not numbers", _Scope(path, {}, {}, "/"),
                        None, "give the spawn args numeric defaults")
    return info

