"""What the ROS 2 launch API's calls are when a launch file is read without running it: actions, substitutions,
conditions and description sources as plain records, taught to :mod:`worldgen.pyread.evaluate` as :data:`LAUNCH_CALLS`.

``Node(...)``, ``IncludeLaunchDescription(...)``, ``DeclareLaunchArgument(...)``, ``GroupAction(...)`` … become an
:class:`Action` of their kind with their arguments as read; ``LaunchConfiguration``, ``PathJoinSubstitution``,
``EnvironmentVariable`` and ``FindPackageShare`` become substitutions that :mod:`.reader_py` evaluates
where ros2 launch would, when the action runs; ``get_package_share_directory`` is answered at once, as it is when
the file runs. A ``LaunchDescription`` collects the actions added to it. Calls of the launch API that do not
bear on the world or the robot (``LogInfo``, ``SetParameter`` …) are actions of kind ``other``.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Dict, List

from ..pyread.values import Call, Ctx, Unknown


@dataclass
class Config:
    """``LaunchConfiguration(name, default=...)``: a launch argument's value, read where it is used."""

    name: Any
    default: Any = None
    line: int | None = None
    what = "a LaunchConfiguration"

    def method(self, ctx: Ctx, name: str, call: Call):
        if name == "perform" and ctx.state is not None:   # inside an OpaqueFunction: the value now
            return ctx.state.resolve(self, call.line)
        return Unknown(f"LaunchConfiguration.{name}() is not followed", call.line)


@dataclass
class Subst:
    """A substitution: ``join`` (PathJoinSubstitution: parts), ``env`` (EnvironmentVariable: name, default),
    ``share`` (FindPackageShare: the package)."""

    kind: str
    parts: Any
    line: int | None = None
    default: Any = None

    @property
    def what(self) -> str:
        return {"join": "a PathJoinSubstitution", "env": "an EnvironmentVariable",
                "share": "a FindPackageShare"}.get(self.kind, "a substitution")


@dataclass
class Cond:
    """An action's ``condition=``: ``if``/``unless`` a value is true, or a launch argument ``equals`` a value
    (``negate`` for LaunchConfigurationNotEquals)."""

    kind: str
    value: Any
    line: int | None = None
    expected: Any = None
    negate: bool = False


@dataclass
class Source:
    """``PythonLaunchDescriptionSource(path)`` and its kin (``kind``: python, xml, yaml, frontend, any)."""

    kind: str
    path: Any
    line: int | None = None


@dataclass
class Action:
    """A launch action as written: its ``kind`` (node, process, include, declare, set_config, group, push_ns,
    timer, handler, opaque, other), the line it is made at, its arguments, its condition, and the read it was
    made in (``ctx``: an OpaqueFunction's function is called in it)."""

    kind: str
    line: int | None
    fields: Dict[str, Any] = field(default_factory=dict)
    condition: Any = None
    ctx: Any = None

    @property
    def what(self) -> str:
        return f"a launch action ({self.kind})"


@dataclass
class Description:
    """A ``LaunchDescription``: the actions given to it and added with ``add_action``/``add_entity``."""

    actions: List[Any] = field(default_factory=list)
    what = "a LaunchDescription"

    def method(self, ctx: Ctx, name: str, call: Call):
        if name in ("add_action", "add_entity"):
            self.actions.append(call.arg(0, "action"))
            return None
        if name == "add_launch_description":
            self.actions.append(call.arg(0, "launch_description"))
            return None
        return Unknown(f"LaunchDescription.{name}() is not followed", call.line)


# ------------------------------------------------------------------------------------------------ the calls

def _config(ctx: Ctx, call: Call):
    return Config(call.arg(0, "variable_name"), call.arg(None, "default"), call.line)


def _action(kind: str, **names):
    """A handler making an Action of ``kind``; ``names`` maps field → (position, keyword[, old keyword])."""
    def make(ctx: Ctx, call: Call):
        fields = {}
        for key, spec in names.items():
            position, keyword = spec[0], spec[1]
            value = call.arg(position, keyword)
            for older in spec[2:]:   # Dashing/Eloquent spellings: node_executable, node_name …
                if value is None:
                    value = call.kwargs.get(older)
            fields[key] = value
        return Action(kind, call.line, fields, call.kwargs.get("condition"), ctx)
    return make


def _description(ctx: Ctx, call: Call):
    given = call.arg(0, "initial_entities")
    if given is None:
        return Description()
    if isinstance(given, (list, tuple)):
        return Description(list(given))
    return Description([given])


def _source(kind: str):
    def make(ctx: Ctx, call: Call):
        return Source(kind, call.arg(0, "launch_file_path"), call.line)
    return make


def _share_now(ctx: Ctx, call: Call):
    """``get_package_share_directory(pkg)``: answered when the file runs, so now."""
    package = call.arg(0, "package_name")
    if not isinstance(package, str):
        return Unknown("get_package_share_directory() of a package name that cannot be known", call.line)
    return ctx.state.share(package, call.line) if ctx.state is not None else \
        Unknown(f"package {package!r} not looked up", call.line, f"‹{package}›", package=package)


def _text(ctx: Ctx, call: Call):
    return call.arg(0, "text", "")


def _cond(kind: str, negate: bool = False):
    def make(ctx: Ctx, call: Call):
        if kind == "equals":
            return Cond(kind, call.arg(0, "launch_configuration_name"), call.line,
                        call.arg(1, "expected_value"), negate)
        return Cond(kind, call.arg(0, "predicate_expression"), call.line)
    return make


def _handler(ctx: Ctx, call: Call):
    """``OnProcessExit(target_action=…, on_exit=[…])`` and its kin: the actions it starts (a timer-like group)."""
    for key in ("on_exit", "on_start", "on_completion", "on_stdout", "on_stderr"):
        if key in call.kwargs:
            return Action("timer", call.line, {"actions": call.kwargs[key]}, None, ctx)
    if call.name.endswith("OnShutdown"):
        return Action("other", call.line)
    return Action("timer", call.line, {"actions": call.arg(1, "on_exit")}, None, ctx)


def _not_run(what: str):
    def make(ctx: Ctx, call: Call):
        return Unknown(f"{what} is not evaluated here (launch files are read, never run)", call.line,
                       f"‹{call.name.rsplit('.', 1)[-1]}›")
    return make


def _other(ctx: Ctx, call: Call):
    return Action("other", call.line, {}, call.kwargs.get("condition"), ctx)


LAUNCH_CALLS = {
    "LaunchConfiguration": _config,
    "DeclareLaunchArgument": _action("declare", name=(0, "name"), default=(None, "default_value")),
    "SetLaunchConfiguration": _action("set_config", name=(0, "name"), value=(1, "value")),
    "Node": _action("node", package=(None, "package"), executable=(None, "executable", "node_executable"),
                    name=(None, "name", "node_name"), namespace=(None, "namespace", "node_namespace"),
                    arguments=(None, "arguments"), parameters=(None, "parameters"),
                    remappings=(None, "remappings")),
    "ExecuteProcess": _action("process", cmd=(None, "cmd")),
    "IncludeLaunchDescription": _action("include", source=(0, "launch_description_source"),
                                        arguments=(1, "launch_arguments")),
    "GroupAction": _action("group", actions=(0, "actions"), scoped=(None, "scoped")),
    "PushRosNamespace": _action("push_ns", namespace=(0, "namespace")),
    "PushROSNamespace": _action("push_ns", namespace=(0, "namespace")),
    "TimerAction": _action("timer", actions=(None, "actions")),
    "RegisterEventHandler": _action("handler", handler=(0, "event_handler")),
    "OpaqueFunction": _action("opaque", function=(0, "function"), args=(None, "args"), kwargs=(None, "kwargs")),
    "OnProcessExit": _handler, "OnProcessStart": _handler, "OnExecutionComplete": _handler,
    "OnProcessIO": _handler, "OnShutdown": _handler,
    "LaunchDescription": _description,
    "PythonLaunchDescriptionSource": _source("python"),
    "XMLLaunchDescriptionSource": _source("xml"),
    "YAMLLaunchDescriptionSource": _source("yaml"),
    "FrontendLaunchDescriptionSource": _source("frontend"),
    "AnyLaunchDescriptionSource": _source("any"),
    "PathJoinSubstitution": lambda ctx, call: Subst("join", call.arg(0, "substitutions"), call.line),
    "EnvironmentVariable": lambda ctx, call: Subst("env", call.arg(0, "name"), call.line,
                                                   call.arg(None, "default_value")),
    "FindPackageShare": lambda ctx, call: Subst("share", call.arg(0, "package"), call.line),
    "TextSubstitution": _text,
    "get_package_share_directory": _share_now,
    "IfCondition": _cond("if"),
    "UnlessCondition": _cond("unless"),
    "LaunchConfigurationEquals": _cond("equals"),
    "LaunchConfigurationNotEquals": _cond("equals", negate=True),
    "PythonExpression": _not_run("PythonExpression"),
    "Command": _not_run("Command (it runs a program)"),
    "FindExecutable": _not_run("FindExecutable"),
    "FindPackagePrefix": _not_run("FindPackagePrefix"),
    "get_package_prefix": _not_run("get_package_prefix()"),
    "LogInfo": _other, "SetParameter": _other, "SetEnvironmentVariable": _other,
    "AppendEnvironmentVariable": _other, "SetUseSimTime": _other, "SetRemap": _other,
    "Shutdown": _other, "EmitEvent": _other, "UnsetLaunchConfiguration": _other,
}

