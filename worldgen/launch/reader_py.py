"""Reading ROS 2 Python launch files (``*.launch.py``) without running them: the world, the robots and their
spawn poses, the robot model — the same :class:`~.model.LaunchInfo` the roslaunch XML reader gives.

The file is parsed with :mod:`ast` and read by :mod:`worldgen.pyread.evaluate` (never executed or imported): module-level
assignments, then ``generate_launch_description()`` (and the functions of the file it calls), with the launch API
taught by :mod:`.values_py`. The description it returns is then walked in order, as ros2 launch would run
it: ``DeclareLaunchArgument`` defaults, ``LaunchConfiguration`` values where they are used, conditions,
``GroupAction``/``PushRosNamespace``, timers and event handlers, ``OpaqueFunction``s, and includes — gazebo_ros's
``gzserver.launch.py`` (``world``) and ros_gz_sim's ``gz_sim.launch.py`` (``gz_args``) read as the world, other
Python launch files followed with the arguments passed to them. Spawns are :mod:`.gazebo_py`'s.

``get_package_share_directory('pkg')``/``FindPackageShare('pkg')`` name the package's folder: the package holding
the file, its siblings in the workspace, ``ROS_PACKAGE_PATH``, then ``AMENT_PREFIX_PATH``'s ``share/pkg`` (an
ament_python package's files are found where its ``setup.py`` installs them from: :mod:`worldgen.pyread.setup_py`).

Whatever cannot be read this way — a loop, a call it cannot follow, a package that is not there — is a finding
naming what and where (file:line), and what depends on it stays unknown: no spawn pose means validate checks the
world as one with no spawn.
"""

from __future__ import annotations

import ast
import posixpath
from dataclasses import dataclass
from pathlib import Path
from typing import Dict, List, Mapping, Optional

from ..core.errors import WorldFileError
from ..core.packages import PackageIndex, manifest_name, owning_package
from .model import LaunchInfo, NodeRef, RobotSpawn, join_ns
from .gazebo_py import (GAZEBO_LAUNCH, GAZEBO_PACKAGES, NAME_FLAGS, POSE_FLAGS, SPAWNERS, STOCK_SPAWN,
                               command_kind, flag_value, gazebo_world, gz_world, mentions_simulator, robot_model,
                               words)
from .scope_py import STATIC_FIX, PyRead, Scope
from .values_py import LAUNCH_CALLS, Action, Cond, Config, Description, Source
from .walk_xml import count_include
from ..pyread.evaluate import call_function, parse_python, read_module
from ..pyread.setup_py import installed_source
from ..pyread.stdlib import env_value
from ..pyread.values import MAX_NESTING, Ctx, Function, Located, Unknown, first_unknown, not_run, shown


# ----------------------------------------------------------------------------------------------- the read

def read_launch_py(path: str | Path, args: Mapping[str, str] | None = None, *, finder: PackageIndex,
                   environ: Mapping[str, str]) -> LaunchInfo:
    """Read a ROS 2 Python launch file (see the module docstring). ``args`` are ``name:=value`` overrides.
    Raises WorldFileError for a file Python or ros2 launch could not load either: one that does not parse, has
    no ``generate_launch_description()``, or includes itself."""
    path = Path(path)
    read = PyRead(finder, environ, LaunchInfo(path=path))
    configs: Dict[str, object] = {k: str(v) for k, v in (args or {}).items()}
    try:
        load(read, path, configs, "/", None)
    except RecursionError:   # every nesting is bounded; this is the backstop for their product
        raise WorldFileError("the launch file and what it includes nest too deeply to read", path=path,
                             hint="include and nest fewer levels") from None
    _skipped_findings(read)
    info = read.info
    info.args = {name: (value if isinstance(value, str) else None) for name, value in read.top_args.items()}
    if info.robots:
        info.spawn, info.model = info.robots[0].pose, info.robots[0].robot
    model = read.env_reads.get("TURTLEBOT3_MODEL")
    if info.model is None and model is not None:
        value, where, line = model
        if value:
            info.model = value
        else:
            info.model_env = "TURTLEBOT3_MODEL"
            read.note("launch-env", "info", "the robot model is not known: environment variable TURTLEBOT3_MODEL is "
                      "not set", where, line, "export TURTLEBOT3_MODEL=burger (or waffle, waffle_pi)")
    if info.model is None:
        info.model = info.args.get("model")
    return info


def load(read: PyRead, path: Path, configs: Dict[str, object], ns: str, line: int | None, nesting: int = 0) -> None:
    """Read the launch file ``path`` (its launch configurations ``configs``, in namespace ``ns``, included
    ``nesting`` actions deep) into ``read``."""
    count_include(read, path, line, "IncludeLaunchDescription")
    tree = parse_python(path, "launch file")
    scope = Scope(read, path, configs, ns, nesting=nesting)
    ctx = Ctx(path, read.environ, LAUNCH_CALLS, on_skip=_on_skip(read), state=scope)
    scope.ctx = ctx
    read.stack.append(path.resolve())
    module = read_module(ctx, tree)
    entry = module.names.get("generate_launch_description")
    if not isinstance(entry, Function):
        raise WorldFileError("the launch file has no generate_launch_description() function, which ros2 launch "
                             "calls", path=path, hint="define generate_launch_description() returning a "
                                                     "LaunchDescription")
    result = call_function(ctx, entry, [], {}, entry.node.lineno)
    for name, (value, at) in ctx.env_reads.items():
        read.env_reads.setdefault(name, (value, path, at))
    if isinstance(result, Unknown) and result.reason.startswith("an exception is raised"):
        read.note("launch-static", "error", f"generate_launch_description() raises an exception at line "
                  f"{result.line}: ros2 launch stops there", path, result.line,
                  "fix what makes it raise (an environment variable, a launch argument?)")
    elif isinstance(result, Unknown):
        read.unresolved(result, "generate_launch_description() returns something that cannot be read", path,
                        entry.node.lineno)
    else:
        walk(read, [result], scope)
    read.stack.pop()


def walk(read: PyRead, items, scope: Scope) -> None:
    """The actions ``items`` in order, as ros2 launch runs them (groups, lists and descriptions inside one another
    at most MAX_NESTING deep: a LaunchDescription added to itself is refused there)."""
    if scope.nesting > MAX_NESTING:
        read.note("launch-static", "warning", f"launch actions nest more than {MAX_NESTING} deep (a LaunchDescription "
                  "holding itself?); the deeper ones are not read", scope.path, None, "add each action once")
        return
    scope.nesting += 1
    read.spend(1 + len(items), scope.path)
    try:
        for item in items:
            if isinstance(item, Unknown):
                read.unresolved(item, "a launch action cannot be read", scope.path, item.line)
            elif isinstance(item, (Description, list, tuple)):
                inner = item.actions if isinstance(item, Description) else item
                if id(inner) in read.open_lists:
                    read.note("launch-static", "warning", "a list of launch actions holds itself; it is read once",
                              scope.path, None, "add each action once")
                    continue
                read.open_lists.add(id(inner))
                try:
                    walk(read, inner, scope)
                finally:
                    read.open_lists.discard(id(inner))
            elif isinstance(item, Action) and _holds(read, item, scope):
                ACTIONS.get(item.kind, _ignore)(read, item, scope)
    finally:
        scope.nesting -= 1


def _ignore(read: PyRead, action: Action, scope: Scope) -> None:
    return None


def _holds(read: PyRead, action: Action, scope: Scope) -> bool:
    """Whether an action's condition holds (one that cannot be evaluated is assumed to, and reported)."""
    cond = action.condition
    if cond is None:
        return True
    if not isinstance(cond, Cond):
        read.unresolved(cond if isinstance(cond, Unknown) else Unknown("a condition that cannot be read",
                                                                        action.line),
                        "condition= assumed satisfied", scope.path, action.line)
        return True
    if cond.kind == "equals":
        value = scope.resolve(Config(cond.value, None, cond.line), action.line)
        expected = scope.resolve(cond.expected, action.line)
        if isinstance(value, Unknown) or isinstance(expected, Unknown):
            read.unresolved(first_unknown((value, expected)), "condition= assumed satisfied", scope.path,
                            action.line)
            return True
        return (value == expected) != cond.negate
    value = scope.resolve(cond.value, action.line)
    if isinstance(value, Unknown):
        read.unresolved(value, "condition= assumed satisfied", scope.path, action.line)
        return True
    text = value.strip().lower()
    if text not in ("true", "1", "false", "0"):
        read.note("launch-arg", "error", f"the condition {value!r} is neither true nor false (ros2 launch stops on "
                  "it)", scope.path, action.line, "use true/false or 1/0")
        return True
    return (text in ("true", "1")) == (cond.kind == "if")


def _declare(read: PyRead, action: Action, scope: Scope) -> None:
    name = scope.resolve(action.fields.get("name"), action.line)
    if isinstance(name, Unknown):
        read.unresolved(name, "DeclareLaunchArgument's name", scope.path, action.line)
        return
    if name not in scope.configs and action.fields.get("default") is not None:
        scope.configs[name] = scope.resolve(action.fields["default"], action.line)
    if scope.path == read.info.path:
        read.top_args[name] = scope.configs.get(name)


def _set_config(read: PyRead, action: Action, scope: Scope) -> None:
    name = scope.resolve(action.fields.get("name"), action.line)
    if isinstance(name, str):
        scope.configs[name] = scope.resolve(action.fields.get("value"), action.line)


def _group(read: PyRead, action: Action, scope: Scope) -> None:
    scoped = action.fields.get("scoped")
    inner = Scope(read, scope.path, dict(scope.configs) if scoped is not False else scope.configs, scope.ns,
                  scope.ctx, scope.nesting)
    walk(read, [action.fields.get("actions") or []], inner)


def _push_ns(read: PyRead, action: Action, scope: Scope) -> None:
    ns = scope.resolve(action.fields.get("namespace"), action.line)
    if isinstance(ns, str):
        scope.ns = join_ns(scope.ns, ns)


def _timer(read: PyRead, action: Action, scope: Scope) -> None:
    walk(read, [action.fields.get("actions") or []], scope)


def _handler(read: PyRead, action: Action, scope: Scope) -> None:
    walk(read, [action.fields.get("handler")], scope)


def _opaque(read: PyRead, action: Action, scope: Scope) -> None:
    """``OpaqueFunction(function=f)``: ``f(context)`` followed, ``.perform(context)`` answered from here."""
    function = action.fields.get("function")
    if not isinstance(function, Function) or action.ctx is None:
        read.unresolved(function if isinstance(function, Unknown) else
                        Unknown("its function is not one this file defines", action.line),
                        "OpaqueFunction not followed", scope.path, action.line)
        return
    ctx = action.ctx
    before, ctx.state = ctx.state, scope
    extra, keywords = action.fields.get("args"), action.fields.get("kwargs")
    arguments = ["‹context›"] + (list(extra) if isinstance(extra, (list, tuple)) else [])
    try:
        result = call_function(ctx, function, arguments, keywords if isinstance(keywords, dict) else {}, action.line)
    finally:
        ctx.state = before
    if isinstance(result, Unknown):
        read.unresolved(result, "the OpaqueFunction's actions cannot be read", scope.path, action.line)
    elif result is not None:
        walk(read, [result], scope)


def _node(read: PyRead, action: Action, scope: Scope) -> None:
    fields = action.fields
    package, executable = (scope.resolve(fields.get(k), action.line) for k in ("package", "executable"))
    if isinstance(package, Unknown) or isinstance(executable, Unknown):
        read.unresolved(first_unknown((package, executable)), "Node's package or executable", scope.path,
                        action.line)
        return
    name = scope.resolve(fields["name"], action.line) if fields.get("name") is not None else executable
    ns = scope.ns
    if fields.get("namespace") is not None:
        given = scope.resolve(fields["namespace"], action.line)
        ns = join_ns(ns, given) if isinstance(given, str) else ns
    arguments = fields.get("arguments") or []
    if isinstance(arguments, str):
        arguments = words(arguments)
    parts = [scope.resolve(a, action.line) for a in arguments] if isinstance(arguments, (list, tuple)) else \
        [arguments if isinstance(arguments, Unknown) else Unknown("the arguments are not a list", action.line)]
    known = first_unknown(parts) is None
    shown_name = name if isinstance(name, str) else executable
    read.info.nodes.append(NodeRef(package, executable, shown_name, ns, " ".join(parts) if known else None,
                                   action.line, remaps=_pairs(fields.get("remappings"), scope, action.line),
                                   params=_params(fields.get("parameters"), scope, action.line)))
    if (package, executable) in SPAWNERS:
        spawn(read, executable, parts, scope, action.line, join_ns(ns, shown_name), ns)


def _pairs(given, scope: Scope, line: int | None) -> tuple:
    """A Node's ``remappings=[(from, to), …]``, the pairs that resolve to text."""
    found = []
    for item in given if isinstance(given, (list, tuple)) else []:
        if isinstance(item, (list, tuple)) and len(item) == 2:
            pair = tuple(scope.resolve(v, line) for v in item)
            if all(isinstance(v, str) for v in pair):
                found.append(pair)
    return tuple(found)


def _params(given, scope: Scope, line: int | None) -> tuple:
    """A Node's ``parameters=[{name: value}, …]``: the (name, text) pairs that resolve (files of parameters are
    left to the node: ros2 launch would read them)."""
    found = []
    for item in given if isinstance(given, (list, tuple)) else []:
        if not isinstance(item, dict):
            continue
        for key, value in item.items():
            name, text = scope.resolve(key, line), scope.resolve(value, line)
            if isinstance(name, str) and isinstance(text, str):
                found.append((name, text))
    return tuple(found)


def spawn(read: PyRead, executable: str, parts: list, scope: Scope, line: int | None, node: str, ns: str) -> None:
    """A spawn node's robot: ``-x -y -z -Y`` (0 when absent, as the spawners take them), its entity name and
    model; a pose word that cannot be resolved or read leaves the pose unknown, with a finding."""
    pose: Optional[List[float]] = [0.0, 0.0, 0.0, 0.0]
    unknown: Dict[str, tuple] = {}   # reason → (flags, the Unknown): one finding for what shares a cause
    for i, word in enumerate(parts):
        after_flag = i > 0 and isinstance(parts[i - 1], str) and parts[i - 1].startswith("-")
        if isinstance(word, Unknown) and not after_flag:
            unknown.setdefault(word.reason, ([], word))[0].append("the spawn pose")
            pose = None
        if not isinstance(word, str) or word not in POSE_FLAGS:
            continue
        value = parts[i + 1] if i + 1 < len(parts) else None
        if isinstance(value, Unknown):
            unknown.setdefault(value.reason, ([], value))[0].append(word)
            pose = None
            continue
        try:
            number = float(value)
        except (TypeError, ValueError):
            read.note("launch-spawn", "error", f"{executable} {word} {value!r} is not a number", scope.path, line,
                      "give the pose as numbers (or a LaunchConfiguration with a numeric default)")
            pose = None
            continue
        if pose is not None:
            pose[POSE_FLAGS[word]] = number
    for flags, value in unknown.values():
        read.unresolved(value, f"{executable} {', '.join(flags)}", scope.path, line)
    entity = next((flag_value(parts, f) for f in NAME_FLAGS if flag_value(parts, f) is not None), None)
    robot = robot_model([entity] + [flag_value(parts, f) for f in ("-file", "-database", "-topic")])
    namespace = flag_value(parts, "-robot_namespace")
    read.info.robots.append(RobotSpawn(node, entity if isinstance(entity, str) else None,
                                       flag_value(parts, "-topic") if isinstance(flag_value(parts, "-topic"), str)
                                       else None, robot, None if pose is None else tuple(pose), line, ns or "/",
                                       None, (), namespace if isinstance(namespace, str) else None))


def _process(read: PyRead, action: Action, scope: Scope) -> None:
    """``ExecuteProcess(cmd=[…])``: ``gazebo WORLD``, ``gz sim WORLD`` or ``ros2 run PKG EXE ARGS``."""
    cmd = action.fields.get("cmd")
    parts = [scope.resolve(p, action.line) for p in cmd] if isinstance(cmd, (list, tuple)) else []
    kind, lead = command_kind(parts)
    rest = parts[lead:]
    if kind in ("gazebo", "gz-sim"):
        if read.info.simulator in (None, "unknown"):
            read.info.simulator = kind
        unknown = first_unknown(rest)
        if unknown is not None:
            return world(read, unknown, "the world on the simulator's command line", scope, action.line)
        found = gazebo_world(rest) if kind == "gazebo" else gz_world(" ".join(rest))
        if found is not None:
            world(read, found, "the world on the simulator's command line", scope, action.line)
    elif kind == "ros2-run" and len(rest) >= 2 and (rest[0], rest[1]) in SPAWNERS:
        spawn(read, rest[1], rest[2:], scope, action.line, f"/{rest[1]}", scope.ns)


def _include(read: PyRead, action: Action, scope: Scope) -> None:
    """``IncludeLaunchDescription``: a simulator's stock launch file read for its world; another Python launch
    file followed with the arguments passed to it (set in the shared configurations, as ros2 launch does)."""
    source = action.fields.get("source")
    kind, given = (source.kind, source.path) if isinstance(source, Source) else ("any", source)
    target = scope.resolve(given, action.line)
    text = shown(target)
    base = posixpath.basename(text.rstrip("/"))
    package = target.package if isinstance(target, (Located, Unknown)) else None
    passed = _launch_arguments(read, action, scope)
    stock = GAZEBO_LAUNCH.get(base)
    if stock is not None and (package in GAZEBO_PACKAGES or not Path(text).is_file()):
        simulator, world_arg = stock
        if world_arg is not None:
            read.info.simulator = simulator
            if world_arg in passed:
                value = passed[world_arg]
                if world_arg.endswith("_args"):   # gz sim's options apart from the world, known or not
                    value = gz_world(value) if isinstance(value, str) else _gz_world_unknown(value)
                if value is not None:
                    world(read, value, f"{base}'s {world_arg}", scope, action.line)
        return
    if isinstance(target, Unknown):
        if (package, base) in STOCK_SPAWN and target.package:
            return _stock_spawn(read, target, base, passed, scope, action.line)
        read.unresolved(target, f"the included {text} is not read", scope.path, action.line)
        if mentions_simulator(text) and read.info.simulator is None:
            read.info.simulator = "unknown"
        return
    path = _share_file(read, target)
    if path is None:
        read.note("launch-include", "warning", f"the included file {text} does not exist", scope.path, action.line,
                  "fix the path of the IncludeLaunchDescription")
        return
    if kind in ("xml", "yaml", "frontend") or not path.name.endswith(".py"):
        read.note("launch-include", "info", f"the included {path.name} is a ROS 2 XML or YAML launch file, which "
                  "is not read here", scope.path, action.line, "write it as a Python launch file to check it")
        if mentions_simulator(text) and read.info.simulator is None:
            read.info.simulator = "unknown"
        return
    read.info.includes.append(path)
    scope.configs.update(passed)
    load(read, path, scope.configs, scope.ns, action.line, scope.nesting)


def _launch_arguments(read: PyRead, action: Action, scope: Scope) -> Dict[str, object]:
    """An include's ``launch_arguments`` (a dict's ``.items()`` or a list of pairs), resolved here."""
    given = action.fields.get("arguments")
    if given is None:
        return {}
    if isinstance(given, dict):
        given = list(given.items())
    if not isinstance(given, (list, tuple)):
        read.unresolved(given if isinstance(given, Unknown) else Unknown("launch_arguments is not a list of pairs",
                                                                          action.line),
                        "the include's launch_arguments", scope.path, action.line)
        return {}
    passed: Dict[str, object] = {}
    for pair in given:
        if isinstance(pair, (list, tuple)) and len(pair) == 2:
            name = scope.resolve(pair[0], action.line)
            if isinstance(name, str):
                passed[name] = scope.resolve(pair[1], action.line)
    return passed


def _stock_spawn(read: PyRead, target: Unknown, base: str, passed: dict, scope: Scope, line: int | None) -> None:
    """A stock spawn launch file that is not installed here (turtlebot3_gazebo's spawn_turtlebot3.launch.py):
    the robot it spawns at the pose passed to it, said in an info finding."""
    x_arg, y_arg, z = STOCK_SPAWN[(target.package, base)]
    values = [passed.get(x_arg, "0.0"), passed.get(y_arg, "0.0")]
    model = env_value(scope.ctx, "TURTLEBOT3_MODEL", line) if scope.ctx is not None else None
    read.env_reads.setdefault("TURTLEBOT3_MODEL", (model, scope.path, line))
    pose = None
    unknown = first_unknown(values)
    if unknown is not None:
        read.unresolved(unknown, f"{base} {x_arg}/{y_arg}", scope.path, line)
    else:
        try:
            pose = (float(values[0]), float(values[1]), z, 0.0)
        except ValueError:
            read.note("launch-spawn", "error", f"{base}: {x_arg} {values[0]!r} or {y_arg} {values[1]!r} is not a "
                      "number", scope.path, line, "pass numbers")
    read.note("launch-find", "info", f"the included {shown(target)} is not read ({target.reason}): as shipped, it "
              f"spawns the TurtleBot3 at the {x_arg}, {y_arg} passed to it"
              + (f" ({values[0]}, {values[1]})" if pose is not None else ""), scope.path, line,
              f"put the package {target.package} in this workspace to read it")
    read.info.robots.append(RobotSpawn(f"{base}", model, None, model if robot_model([model]) == model else None, pose,
                                       line, scope.ns or "/"))


def _gz_world_unknown(value):
    """The world among ``gz sim`` arguments that are not all known (``-r -s -v2 ‹pkg›/worlds/room.sdf``): the same
    unknown, shown as the world's word alone; other values as they are."""
    if isinstance(value, Unknown) and value.shown:
        found = gz_world(value.shown)
        return value.like(found) if found is not None else None
    return value


def world(read: PyRead, value, what: str, scope: Scope, line: int | None) -> None:
    """The world the simulator is started with: its reference, package and (when absolute) path."""
    if read.info.world_ref is not None:
        return
    if isinstance(value, Unknown):
        read.info.world_ref = shown(value)
        read.info.package = value.package
        read.unresolved(value, what, scope.path, line)
        return
    text = str(value).strip()
    read.info.world_ref = text
    read.info.package = value.package if isinstance(value, Located) else _package_of(text)
    if not posixpath.isabs(text):
        read.note("launch-world", "info", f"the world {text!r} is found through the simulator's resource path",
                  scope.path, line, "give the world as os.path.join(get_package_share_directory(PKG), 'worlds', "
                                    "NAME) to check it")
        return
    read.info.world_path = _share_file(read, value) or Path(text)


def _package_of(text: str) -> Optional[str]:
    """The name of the package holding the file ``text`` (None when it is in none)."""
    own = owning_package(text, levels=4) if posixpath.isabs(text) else None
    return manifest_name(own / "package.xml") if own is not None else None


def _share_file(read: PyRead, value) -> Optional[Path]:
    """The file a path names: itself when it exists, else, for a path in an ament_python package's share
    folder, the file its setup.py installs there; None when neither exists."""
    path = Path(str(value))
    if path.exists():
        return path
    if isinstance(value, Located) and read.packages.get(value.package) is not None:
        root = read.packages[value.package]
        try:
            relative = path.relative_to(root)
        except ValueError:
            return None
        return installed_source(root, relative)
    return None


# ------------------------------------------------------------------------------------- code that is not run

def _on_skip(read: PyRead):
    def hook(ctx: Ctx, kind: str, node, frame, reason) -> None:
        what = _weighty_code(node, frame)
        if what is not None:
            read.skipped.setdefault((str(ctx.path), kind), []).append((getattr(node, "lineno", None), what, reason))
    return hook


def _weighty_code(node, frame) -> Optional[str]:
    """What code that is not run builds that could start the simulator or spawn a robot (None: nothing that
    bears on the check)."""
    for inner in ast.walk(node):
        if isinstance(inner, ast.Return):
            return "the launch description returned"
        if not isinstance(inner, ast.Call):
            continue
        callee = inner.func.attr if isinstance(inner.func, ast.Attribute) else getattr(inner.func, "id", "")
        if callee in ("IncludeLaunchDescription", "OpaqueFunction"):
            return callee
        texts = {c.value for c in ast.walk(inner) if isinstance(c, ast.Constant) and isinstance(c.value, str)}
        if callee in ("Node", "ExecuteProcess") and texts & {"spawn_entity.py", "create", "gazebo", "gzserver",
                                                             "gz", "ign"}:
            return f"{callee} ({', '.join(sorted(texts & {'spawn_entity.py', 'create', 'gazebo', 'gzserver', 'gz'}))})"
        given = list(inner.args) + [k.value for k in inner.keywords]   # what is added, not what it is added to
        names = sorted({a.id for arg in given for a in ast.walk(arg) if isinstance(a, ast.Name)})
        if callee in ("add_action", "add_entity", "append", "extend", "GroupAction", "LaunchDescription",
                      "TimerAction") and any(_weighty_value(frame.lookup(n)) for n in names):
            return f"{callee}({', '.join(n for n in names if _weighty_value(frame.lookup(n)))})"
    return None


def _weighty_value(value, depth: int = 0, seen: set | None = None) -> bool:
    """Whether ``value`` holds a spawn, an include or code of its own (each container looked into once)."""
    seen = set() if seen is None else seen
    if depth > 8 or id(value) in seen:
        return False
    seen.add(id(value))
    if isinstance(value, Unknown):
        return not value.skipped
    if isinstance(value, Action):
        if value.kind == "node":
            return value.fields.get("executable") in ("spawn_entity.py", "create")
        if value.kind in ("include", "opaque", "process"):
            return True
        return any(_weighty_value(v, depth + 1, seen) for v in value.fields.values())
    if isinstance(value, Description):
        return any(_weighty_value(v, depth + 1, seen) for v in value.actions)
    if isinstance(value, (list, tuple)):
        return any(_weighty_value(v, depth + 1, seen) for v in value)
    return False


def _skipped_findings(read: PyRead) -> None:
    """One finding per file and kind of code not run that builds launch actions, naming each place."""
    for (where, kind), entries in sorted(read.skipped.items(), key=lambda item: (item[0][0], item[1][0][0] or 0)):
        places = "; ".join(not_run(kind, _At(line)) + (f" (its condition cannot be told: {reason})" if reason else "")
                           + f" builds {what}" for line, what, reason in entries)
        read.note("launch-static", "warning", f"{places}: not run here (worldgen reads launch files, never runs "
                  "them), so what it starts or spawns is not known", Path(where), entries[0][0], STATIC_FIX)


@dataclass(frozen=True)
class _At:
    lineno: Optional[int]


ACTIONS = {
    "declare": _declare, "set_config": _set_config, "group": _group, "push_ns": _push_ns, "timer": _timer,
    "handler": _handler, "opaque": _opaque, "node": _node, "process": _process, "include": _include,
}
