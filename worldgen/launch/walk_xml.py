"""The launch-file walker: one file's elements in order — ``<arg>``, ``<group>``, ``<param>``, ``<rosparam>``,
``<remap>``, ``<env>``, ``<include>`` (followed), ``<node>`` (with its own params, remaps and env;
``gazebo_ros/spawn_model`` read for its pose, model and description) — into a :class:`~.model.LaunchInfo`,
with ``$(...)`` and ``if``/``unless`` evaluated by :mod:`.substitution_xml` and parameters typed and named by
:mod:`.params_xml`.

Read top-down: :func:`load_launch` parses a file and walks it (:func:`walk`), which hands each element in
effect to its reader (:data:`ELEMENTS`).
"""

from __future__ import annotations

import os
import re
import shlex
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable, Dict, List, Optional

from ..core.errors import WorldFileError
from .model import Findings, Fixes, LaunchInfo, NodeRef, RobotSpawn, join_ns
from .params_xml import ParamError, load_yaml, param_name, rosparam_sets, set_value, storable, \
    typed_value
from .substitution_xml import (ArgValue, Lookup, Scope, Unresolved, condition, expand, expand_lenient,
                           expand_or_keep, try_expand)
from ..core.inputs import read_capped, read_text_capped

XACRO_MODEL = re.compile(r"turtlebot3_([A-Za-z0-9_]+)\.urdf(?:\.xacro)?\b")
GAZEBO_FLAGS = {"-x": 0, "-y": 1, "-z": 2, "-Y": 3}
MAX_INCLUDE_DEPTH = 16
MAX_LAUNCH_FILES = 1000   # launch files read for one, counting each include of each (a fan-out grows exponentially)
STOCK_PACKAGES = frozenset({"gazebo_ros", "xacro", "turtlebot3_description", "turtlebot3_gazebo"})
ROS1_FIXES = Fixes(stock=STOCK_PACKAGES,
                   find="put the package {package} in this catkin workspace or on ROS_PACKAGE_PATH",
                   env="export {env} (or pass the arg on the command line)",
                   arg="pass the arg (name:=value) or give it a default")


@dataclass
class LaunchRead(Findings):
    """One read of a launch file and its includes: what is found so far and the files being read."""

    lookup: Lookup
    info: LaunchInfo
    params: Dict[str, str] = field(default_factory=dict)   # full name → text (unresolved parts marked)
    stack: List[Path] = field(default_factory=list)         # the files being read, outermost first
    raw_args: Dict[str, Optional[str]] = field(default_factory=dict)   # the top-level args as written
    loaded: int = 0                                          # launch files read so far, includes counted
    FIXES = ROS1_FIXES


def parse_launch_xml(path: Path, what: str = "launch file"):
    """The root element of the XML file ``path``; WorldFileError when it cannot be read or is not XML."""
    from ..core.safexml import parse_bytes

    try:
        data = read_capped(path, what=what)
    except OSError as err:
        raise WorldFileError(f"cannot read the {what}: {err.strerror or err}", path=path,
                             hint="check the path") from None
    return parse_bytes(data, path, what=what,
                       hint="fix the XML (every tag closed, attributes quoted, '<' and '&' escaped)",
                       empty_hint="a launch file holds one <launch> element")


def load_launch(read: LaunchRead, path: Path, passed: Dict[str, ArgValue], ns: str, line: int | None,
                outer: Scope | None = None) -> None:
    """Read the launch file ``path`` (given the args ``passed`` to it, in namespace ``ns``, inside the scope
    ``outer`` whose remaps and env carry over) into ``read``; the top-level file's args become
    ``read.info.args``."""
    path = Path(path)
    count_include(read, path, line, "<include>")
    root = parse_launch_xml(path)
    if root.tag != "launch":
        raise WorldFileError(f"the root element is <{root.tag}>, not <launch>", path=path,
                             line=root.sourceline, hint="a launch file holds one <launch> element")
    read.stack.append(path.resolve())
    scope = Scope(path, {}, passed, ns, outer.remaps if outer else (), outer.env if outer else ())
    walk(read, root, scope)
    read.stack.pop()
    if len(read.stack) == 0:
        read.info.args = {k: (None if isinstance(v, Unresolved) else _found_path(read, v, scope))
                          for k, v in scope.args.items()}


def count_include(read, path: Path, line: int | None, element: str) -> None:
    """One more launch file read for ``read`` (a launch file's read: its ``stack`` of files being read and the
    count of files ``loaded``, XML or Python): WorldFileError for a file that includes itself, includes nested past
    :data:`MAX_INCLUDE_DEPTH`, or more than :data:`MAX_LAUNCH_FILES` files read for one. ``element`` is what
    includes a file there (``<include>``, ``IncludeLaunchDescription``)."""
    if path.resolve() in read.stack:
        raise WorldFileError("a launch file includes itself", path=path, line=line,
                             hint=f"remove the circular {element}")
    if len(read.stack) >= MAX_INCLUDE_DEPTH:
        raise WorldFileError("includes nest too deeply", path=path, line=line, hint="remove circular includes")
    read.loaded += 1
    if read.loaded > MAX_LAUNCH_FILES:
        raise WorldFileError(f"more than {MAX_LAUNCH_FILES} launch files are read for this one (includes inside "
                             "includes, each counted)", path=path, line=line,
                             hint="include fewer files (see Limits in the README)")


def _found_path(read: LaunchRead, value: str, scope: Scope) -> str | None:
    try:
        return expand(read.lookup, value, scope, find=True)
    except Unresolved:
        return None


def walk(read: LaunchRead, parent, scope: Scope, elements=None) -> None:
    """Every element under ``parent`` whose ``if``/``unless`` holds, to its reader in ``elements`` (default
    :data:`ELEMENTS`)."""
    for el in parent:
        if not isinstance(el.tag, str) or not condition(read.lookup, el, scope, read.unresolved):
            continue
        handler = (ELEMENTS if elements is None else elements).get(el.tag)
        if handler is not None:
            handler(read, el, scope)


def read_arg(read: LaunchRead, el, scope: Scope) -> None:
    """``<arg>``: its value (fixed), the value passed to the file, or its default — or Unresolved."""
    name = el.get("name")
    if not name:
        raise WorldFileError("<arg> without a name", path=scope.path, line=el.sourceline,
                             hint='write <arg name="..." default="..."/>')
    if el.get("value") is not None and el.get("default") is not None:
        raise WorldFileError(f"<arg name=\"{name}\"> has both value and default", path=scope.path,
                             line=el.sourceline, hint="keep one of them")
    value: ArgValue
    if el.get("value") is not None:
        value = try_expand(read.lookup, el.get("value"), scope)
    elif name in scope.passed:
        value = scope.passed[name]
    elif el.get("default") is not None:
        value = try_expand(read.lookup, el.get("default"), scope)
    else:
        value = Unresolved(f"arg {name!r} has no value (it must be passed: {name}:=...)")
    scope.args[name] = value
    if len(read.stack) == 1:
        read.raw_args[name] = el.get("value", el.get("default"))


def read_group(read: LaunchRead, el, scope: Scope) -> None:
    """``<group>``: its elements, in its namespace."""
    ns = join_ns(scope.ns, expand_or_keep(read.lookup, el.get("ns") or "", scope))
    walk(read, el, scope.inner(ns))   # args are shared with the file


def read_param(read: LaunchRead, el, scope: Scope) -> None:
    """``<param>``: its text kept (a robot description's xacro command, say, to find the robot model), and its
    value, typed as roslaunch types it, among the parameters the launch file sets (``read.info.params``)."""
    name = el.get("name")
    if not name:
        return
    raw = el.get("command") or el.get("value") or el.get("textfile") or ""
    try:
        full = param_name(expand_or_keep(read.lookup, name, scope), scope.ns, scope.node)
    except ParamError as err:
        read.note("launch-param", "warning", f"<param name=\"{name}\">: {err}", scope.path, el.sourceline,
                  "put it inside the <node> it is for, or drop the ~")
        return
    read.params[full] = expand_lenient(read.lookup, raw, scope)[0]
    if el.get("command") is not None:   # roslaunch runs it; a robot description's xacro: our robot stands in
        if "xacro" not in el.get("command") and "robot_description" not in full:
            read.note("launch-param", "info", f"param {full} comes from a command, which is not run here", scope.path,
                      el.sourceline, "give the value itself (value=, textfile= or a <rosparam>)")
        return
    if el.get("binfile") is not None:
        read.note("launch-param", "info", f"param {full} is a binfile, which is not loaded here", scope.path,
                  el.sourceline, None)
        return
    if el.get("textfile") is not None:
        text = _file_text(read, el.get("textfile"), f"param {full} textfile", scope, el.sourceline)
        if text is not None:
            set_value(read.info.params, full, text)
        return
    if el.get("value") is None:
        return
    try:
        value = typed_value(expand(read.lookup, el.get("value"), scope, find=True), el.get("type"))
    except Unresolved as err:
        read.unresolved(err, f"param {full}", scope.path, el.sourceline)
        return
    except ParamError as err:
        read.note("launch-param", "error", f"param {full}: {err}", scope.path, el.sourceline,
                  "fix the value or its type= (roslaunch stops on it)")
        return
    _store(read, full, value, scope, el.sourceline)


def read_rosparam(read: LaunchRead, el, scope: Scope) -> None:
    """``<rosparam>``: a YAML document (inline or ``file=``) loaded into ``ns``/``param`` (a node's private
    namespace inside a ``<node>``). ``command="delete"`` and ``dump`` run before roslaunch sets any parameter, on
    what the master held already: on the fresh master of a run, nothing, so neither changes what is set."""
    command = (el.get("command") or "load").strip()
    try:
        ns = param_name(expand_or_keep(read.lookup, el.get("ns") or "", scope), scope.ns, scope.node) \
            if el.get("ns") else (scope.node or scope.ns)
        param = el.get("param")
        full = param_name(expand_or_keep(read.lookup, param, scope), ns, None) if param else None
    except ParamError as err:
        read.note("launch-param", "warning", f"<rosparam>: {err}", scope.path, el.sourceline,
                  "put it inside the <node> it is for, or drop the ~")
        return
    if command != "load":
        return
    if el.get("file") is not None:
        text = _file_text(read, el.get("file"), "<rosparam file>", scope, el.sourceline)
    else:
        text = el.text or ""
    if text is None:
        return
    if (el.get("subst_value") or "").strip().lower() in ("true", "1"):   # the file's text too, as roslaunch does
        try:
            text = expand(read.lookup, text, scope, find=True)
        except Unresolved as err:
            read.unresolved(err, "<rosparam subst_value>", scope.path, el.sourceline)
            return
    try:
        pairs = rosparam_sets(load_yaml(text), ns, full)
    except ParamError as err:
        read.note("launch-param", "error", f"<rosparam>: {err}", scope.path, el.sourceline,
                  "fix the YAML (roslaunch stops on it)")
        return
    for name, value in pairs:
        _store(read, name, value, scope, el.sourceline)


def _store(read: LaunchRead, name: str, value, scope: Scope, line: int | None) -> None:
    why = storable(value)
    if why is not None:
        read.note("launch-param", "warning", f"param {name} is not set: {why}", scope.path, line,
                  "give it a value the parameter server can hold")
        return
    set_value(read.info.params, name, value)


def _file_text(read: LaunchRead, raw: str, what: str, scope: Scope, line: int | None) -> str | None:
    """The text of the file a ``textfile=``/``file=`` names (``$(find)`` resolved), or None with a finding."""
    try:
        path = Path(expand(read.lookup, raw, scope, find=True))
    except Unresolved as err:
        read.unresolved(err, what, scope.path, line)
        return None
    try:
        return read_text_capped(path, what="parameter file")
    except OSError as err:
        reason = err.strerror or str(err)
    except UnicodeDecodeError:
        reason = "not UTF-8 text"
    read.note("launch-param", "warning", f"{what} {path}: {reason}", scope.path, line, "fix the path")
    return None


def read_remap(read: LaunchRead, el, scope: Scope) -> None:
    """``<remap from to>``: for the nodes declared after it in this scope (a node's own: for that node)."""
    source, target = el.get("from"), el.get("to")
    if not source or not target:
        read.note("launch-remap", "warning", "<remap> needs both from= and to=", scope.path, el.sourceline,
                  'write <remap from="scan" to="/base_scan"/>')
        return
    scope.remaps = scope.remaps + ((expand_or_keep(read.lookup, source, scope),
                                    expand_or_keep(read.lookup, target, scope)),)


def read_env(read: LaunchRead, el, scope: Scope) -> None:
    """``<env name value>``: an environment variable for the nodes declared after it in this scope."""
    if el.get("name"):
        scope.env = scope.env + ((el.get("name"), expand_or_keep(read.lookup, el.get("value") or "", scope)),)


def read_include(read: LaunchRead, el, scope: Scope) -> None:
    """``<include>``: the args passed (``world_name`` read as the world), then the included file followed."""
    raw = el.get("file")
    if not raw:
        raise WorldFileError("<include> without a file", path=scope.path, line=el.sourceline,
                             hint='write <include file="$(find PKG)/launch/NAME.launch">')
    passed: Dict[str, ArgValue] = {}
    if el.get("pass_all_args", "").lower() in ("true", "1"):
        passed.update(scope.args)
    for child in el:
        if isinstance(child.tag, str) and child.tag == "arg" and child.get("name") and \
                condition(read.lookup, child, scope, read.unresolved):
            passed[child.get("name")] = try_expand(read.lookup, child.get("value", child.get("default", "")), scope)
    if "world_name" in passed and read.info.world_ref is None:
        read_world_name(read, passed["world_name"], _child_line(el, "world_name"), scope)
    ns = join_ns(scope.ns, expand_or_keep(read.lookup, el.get("ns") or "", scope))
    try:
        target = Path(expand(read.lookup, raw, scope, find=True))
    except Unresolved as err:
        read.unresolved(err, f"<include file=\"{raw}\"> not followed", scope.path, el.sourceline)
        return
    if not target.is_file():
        read.note("launch-include", "warning", f"included file {target} does not exist", scope.path,
                  el.sourceline, "fix the path of the <include>")
        return
    read.info.includes.append(target)
    load_launch(read, target, passed, ns, el.sourceline, scope)


def read_world_name(read: LaunchRead, value: ArgValue, line: int | None, scope: Scope) -> None:
    """The ``world_name`` passed to gazebo_ros: the world's reference, package and (when absolute) path."""
    if isinstance(value, Unresolved):
        read.unresolved(value, "world_name", scope.path, line)
        return
    read.info.world_ref = value
    found = re.match(r"\s*\$\(find\s+([^)\s]+)\)", value)
    read.info.package = found.group(1) if found else None
    try:
        resolved = expand(read.lookup, value, scope, find=True).strip()
    except Unresolved as err:
        read.unresolved(err, f"world_name {value}", scope.path, line)
        return
    if not os.path.isabs(resolved):
        read.note("launch-world", "info", f"world_name {resolved!r} is found through Gazebo's resource path",
                  scope.path, line, "give the world as $(find PKG)/worlds/NAME.world to check it")
        return
    read.info.world_path = Path(resolved)


def read_node(read: LaunchRead, el, scope: Scope) -> None:
    """``<node>``: recorded, and read as a robot spawn when it is ``gazebo_ros/spawn_model``."""
    pkg, node_type, name = el.get("pkg"), el.get("type"), el.get("name")
    if not pkg or not node_type:
        raise WorldFileError("<node> without pkg or type", path=scope.path, line=el.sourceline,
                             hint='write <node pkg="PKG" type="EXECUTABLE" name="NAME"/>')
    ns = join_ns(scope.ns, expand_or_keep(read.lookup, el.get("ns") or "", scope))
    args, errors = expand_lenient(read.lookup, el.get("args") or "", scope)
    name = expand_or_keep(read.lookup, name or node_type, scope)
    own = Scope(scope.path, scope.args, scope.passed, ns, scope.remaps, scope.env, join_ns(ns, name))
    walk(read, el, own, NODE_ELEMENTS)   # its params (private), remaps and env
    required, respawn = _flag(read, el, "required", scope), _flag(read, el, "respawn", scope)
    if required and respawn:
        read.note("launch-node", "error", f"node {join_ns(ns, name)} is both required and respawn (roslaunch "
                  "refuses the file)", scope.path, el.sourceline, "keep one of required=\"true\" and respawn=\"true\"")
    node = NodeRef(pkg, node_type, name, ns, None if errors else args, el.sourceline, own.remaps, own.env,
                   required, respawn)
    read.info.nodes.append(node)
    if (pkg, node_type) == ("gazebo_ros", "spawn_model"):
        read_spawn(read, node, args, errors, scope, el.sourceline)


def _flag(read: LaunchRead, el, attr: str, scope: Scope) -> bool:
    return expand_or_keep(read.lookup, el.get(attr) or "false", scope).strip().lower() in ("true", "1")


def read_spawn(read: LaunchRead, node: NodeRef, args: str, errors: List[Unresolved], scope: Scope,
               line: int | None) -> None:
    """Record a spawn_model node: its -x -y -z -Y pose (0 when not given, as spawn_model does), -model and
    -param. A pose number that cannot be resolved or read leaves the pose unknown, with a finding."""
    try:
        words = shlex.split(args)
    except ValueError:   # an unclosed quote: roslaunch's own split would stop there; the words as spaces give them
        read.note("launch-spawn", "warning", f"spawn_model {node.full_name}: its args have an unclosed quote",
                  scope.path, line, "close the quote in args=\"…\"")
        words = args.split()
    pose: Optional[List[float]] = [0.0, 0.0, 0.0, 0.0]
    model_name = param = None
    for i, word in enumerate(words):
        following = words[i + 1] if i + 1 < len(words) else None
        if word in GAZEBO_FLAGS:
            marker = re.search(r"\0(\d+)\0", following or "")
            if marker:
                read.unresolved(errors[int(marker.group(1))], f"spawn_model {node.full_name} {word}", scope.path, line)
                pose = None
                continue
            try:
                value = float(following)
            except (TypeError, ValueError):
                read.note("launch-spawn", "error", f"spawn_model {word} {following!r} is not a number", scope.path,
                          line, "give the pose as numbers (or $(arg NAME) with a numeric default)")
                pose = None
                continue
            if pose is not None:
                pose[GAZEBO_FLAGS[word]] = value
        elif word == "-model":
            model_name = None if following is None or "\0" in following else following
        elif word == "-param":
            param = None if following is None or "\0" in following else following
    for i, word in enumerate(words):   # an unresolved word that is no flag's value may hold the pose itself
        marker = re.search(r"\0(\d+)\0", word)
        if marker and not (i > 0 and words[i - 1].startswith("-")):
            read.unresolved(errors[int(marker.group(1))], f"spawn_model {node.full_name}: pose unknown",
                            scope.path, line)
            pose = None
    robot = robot_of(read, param, node.ns)
    namespace = next((words[i + 1] for i, w in enumerate(words[:-1]) if w == "-robot_namespace"), None)
    read.info.robots.append(RobotSpawn(node.full_name, model_name, param, robot,
                                       None if pose is None else (pose[0], pose[1], pose[2], pose[3]), line,
                                       node.ns or "/", tf_prefix_of(read, node.ns), xacro_args(read, param, node.ns),
                                       namespace))


def tf_prefix_of(read: LaunchRead, ns: str) -> str | None:
    """The ``tf_prefix`` parameter a node in ``ns`` finds searching upwards (ROS's searchParam), if any."""
    parts = [p for p in (ns or "/").split("/") if p]
    for depth in range(len(parts), -1, -1):
        key = "/" + "/".join(parts[:depth] + ["tf_prefix"])
        if key in read.params and "\0" not in read.params[key]:
            return read.params[key].strip()
    return None


def xacro_args(read: LaunchRead, param: str | None, ns: str) -> tuple:
    """The ``name:=value`` arguments of the xacro command the description ``param`` is made with."""
    if not param:
        return ()
    text = read.params.get(param if param.startswith("/") else join_ns(ns, param)) or ""
    if "xacro" not in text:
        return ()
    return tuple(w for w in text.split() if ":=" in w and not w.startswith("__") and "\0" not in w)


def robot_of(read: LaunchRead, param: str | None, ns: str) -> str | None:
    """The TurtleBot3 model (burger/waffle/…) whose xacro the description ``param`` is made from, if known."""
    if not param:
        return None
    text = read.params.get(param if param.startswith("/") else join_ns(ns, param))
    found = XACRO_MODEL.search(text or "")
    return found.group(1) if found else None


def _child_line(el, arg_name: str) -> int | None:
    for child in el:
        if isinstance(child.tag, str) and child.tag == "arg" and child.get("name") == arg_name:
            return child.sourceline
    return el.sourceline


# The elements the walker reads; any other (machine, test, …) adds nothing here.
ELEMENTS: Dict[str, Callable[[LaunchRead, object, Scope], None]] = {
    "arg": read_arg,
    "group": read_group,
    "param": read_param,
    "rosparam": read_rosparam,
    "remap": read_remap,
    "env": read_env,
    "include": read_include,
    "node": read_node,
}
# Inside a <node>: its private parameters, remaps and environment.
NODE_ELEMENTS = {tag: ELEMENTS[tag] for tag in ("param", "rosparam", "remap", "env")}
