"""What both launch readers and the writers share: a node a launch file starts (:class:`NodeRef`) and its
full name (:func:`join_ns`); what :func:`worldgen.launch.reader.read_launch` finds in a launch file (the world,
the robots it spawns, its args, nodes and includes: :class:`LaunchInfo`); and the findings a read adds for
whatever could not be resolved (:class:`Findings`, with each reader's :class:`Fixes`)."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import ClassVar, FrozenSet, Optional

from ..core.findings import Finding
from ..core.spawnpose import Pose


@dataclass(frozen=True)
class NodeRef:
    """A node started by a launch file: ``pkg/type`` run under ``name`` (in namespace ``ns`` when read back),
    with what roslaunch gives it besides: ``args``, its ``<remap>``s (``from``, ``to``) and ``<env>``s, and whether
    it is ``required`` (its exit ends the launch) or ``respawn`` (started again when it exits); a launch.py Node's
    ``remappings`` are its ``remaps`` and its dict ``parameters`` that resolve its ``params``."""

    package: str
    type: str
    name: str
    ns: str = "/"
    args: str | None = None
    line: int | None = None
    remaps: tuple = ()
    env: tuple = ()
    required: bool = False
    respawn: bool = False
    params: tuple = ()        # a launch.py Node's parameters that resolve to text: (name, value) pairs

    @property
    def full_name(self) -> str:
        return join_ns(self.ns, self.name)


def join_ns(ns: str, name: str) -> str:
    """The full graph name of ``name`` in namespace ``ns`` (``/`` + segments; an absolute ``name`` stays)."""
    if name.startswith("/"):
        return "/" + name.strip("/")
    parts = [p for p in ns.split("/") + name.split("/") if p]
    return "/" + "/".join(parts)



@dataclass(frozen=True)
class RobotSpawn:
    """One ``gazebo_ros/spawn_model`` node: its full name, the ``-model`` name, the ``-param`` it reads the
    description from, the robot model (burger/waffle/…) when known and the pose (None when unresolved), and
    what a simulator needs to give the robot its own topics and frames."""

    node: str
    model_name: str | None
    param: str | None
    robot: str | None
    pose: Pose | None
    line: int | None = None
    ns: str = "/"                        # the namespace spawn_model runs in: the robot's plugins' namespace
    tf_prefix: str | None = None         # the tf_prefix parameter found from ns upwards (None: none set)
    xacro_args: tuple = ()               # name:=value mappings of the description's xacro command
    robot_namespace: str | None = None   # spawn_model's -robot_namespace, when given


@dataclass
class LaunchInfo:
    """What a launch file starts, as far as worlds and robots go.

    ``world_path`` is the world file passed to gazebo_ros as ``world_name`` (None when it cannot be resolved or
    none is passed); ``world_ref`` is that value with args expanded but ``$(find)`` kept; ``package`` is the
    package named by its ``$(find PKG)``. ``robots`` lists every spawn_model node (in file order, includes
    followed); ``model`` and ``spawn`` are the first robot's (for one-robot files: *the* robot), falling back to
    the ``model`` and ``x_pos``/``y_pos``/``z_pos``/``yaw`` args when no spawn node could be read.
    ``model_env`` names the environment variable the model depends on when it was not set. ``simulator`` is the
    simulator a ROS 2 launch file starts (``gazebo`` for Gazebo Classic, ``gz-sim``; ``unknown`` when an include
    that cannot be read may start one; None when none is seen, and for roslaunch XML files). ``args`` are the
    top-level args' values (None when unresolved). ``params`` are the parameters roslaunch would set on the
    master (full name → value, typed, in the order set; nodes' private ones under their names), as far as they
    resolve. ``findings`` say what could not be resolved and why.
    """

    path: Path
    world_path: Path | None = None
    world_ref: str | None = None
    package: str | None = None
    model: str | None = None
    model_env: str | None = None
    spawn: Pose | None = None
    simulator: str | None = None
    args: dict[str, str | None] = field(default_factory=dict)
    robots: list[RobotSpawn] = field(default_factory=list)
    nodes: list[NodeRef] = field(default_factory=list)
    params: dict = field(default_factory=dict)
    includes: list[Path] = field(default_factory=list)
    findings: list[Finding] = field(default_factory=list)


@dataclass(frozen=True)
class Fixes:
    """What a reader tells a student to do about a reference it could not resolve, by kind: a package
    (``{package}`` filled in), an environment variable (``{env}``), a launch argument, and — for a reader whose
    unknowns also come from code it cannot follow — ``static``. ``stock`` packages are missing on most machines
    that are not robot PCs, so their absence is info rather than a warning."""

    stock: FrozenSet[str]
    find: str
    env: str
    arg: str
    static: Optional[str] = None


class Findings:
    """The findings of one read of a launch file (both readers): ``note`` adds one at a file and line, each
    once; ``unresolved`` turns what could not be resolved — anything with a ``reason`` and, when they are the
    cause, the ``package`` or ``env`` missing — into a finding with the fix for its kind."""

    info: LaunchInfo
    FIXES: ClassVar[Fixes]

    def note(self, check: str, severity: str, message: str, path: Path, line: int | None,
             fix: str | None = None) -> None:
        finding = Finding(check, severity, message, where=f"{path}:{line}" if line else str(path), fix=fix)
        if finding not in self.info.findings:
            self.info.findings.append(finding)

    def unresolved(self, cause, what: str, path: Path, line: int | None) -> None:
        """A finding for ``cause`` (nothing for code that is not run: that is reported where it is skipped)."""
        if getattr(cause, "skipped", False):
            return
        fixes, reason = self.FIXES, cause.reason
        if cause.package:
            self.note("launch-find", "info" if cause.package in fixes.stock else "warning", f"{what}: {reason}",
                      path, line, fixes.find.format(package=cause.package))
        elif cause.env:
            self.note("launch-env", "info", f"{what}: {reason}", path, line, fixes.env.format(env=cause.env))
        elif fixes.static is None or reason.startswith("launch argument"):
            self.note("launch-arg", "warning", f"{what}: {reason}", path, line, fixes.arg)
        else:
            at = getattr(cause, "line", None)
            at = f" (line {at})" if at and at != line else ""
            self.note("launch-static", "warning", f"{what}: {reason}{at}", path, line, fixes.static)
