"""ROS 1 Noetic as a transport (:class:`~worldgen.bridge.transport.Transport`): rospy nodes with a private master
each run, the simulator a rospy node (:mod:`.node`)."""

from __future__ import annotations

import os
import sys
from pathlib import Path
from typing import Sequence

from ..bridge.outcome import NodeSpec, Outcome, RunOptions
from ..bridge.preflight import node_findings
from ..bridge.transport import Transport
from ..bridge.world import World
from ..core.errors import WorldgenError
from ..runtime.naming import Naming
from .nodes import resolve_nodes
from .rosenv import ENV_PYTHON, SYSTEM_PYTHON, distro_package, find_rospy, node_python
from .run import head_start, run_nodes


class Ros1(Transport):
    stack = "noetic"
    cmd_type = "geometry_msgs/Twist"
    retry = ("rosmaster could not start",)

    def node_python(self) -> str:
        find_rospy()   # InputError naming the package when rospy is missing
        return node_python()

    def naming(self) -> Naming:
        return Naming("noetic", apt_ros=noetic())

    def resolve_nodes(self, items: Sequence[str], python: str, search: Sequence[str | Path] = ()) -> list[NodeSpec]:
        return resolve_nodes(items, python, search)

    def head_start(self):
        return head_start()

    def run_nodes(self, world: World, nodes: list[NodeSpec], options: RunOptions, head=None) -> Outcome:
        return run_nodes(world, nodes, options, head=head)


ROS1 = Ros1()


def noetic() -> bool:
    """Whether this system takes ROS from ROS's own apt repository (``ros-noetic-*`` names first)."""
    return distro_package().startswith("ros-")


def launch_warnings(launch: Path) -> list[str]:
    """For ``worldgen sim`` with a launch file: a warning line per missing module of the launch file's own
    nodes (those worldgen does not stand in for); nothing when they cannot be found or rospy is missing (sim
    says so itself)."""
    try:
        python = node_python()
        found = node_findings(resolve_nodes([str(launch)], python), python, naming=Naming("noetic", noetic()))
    except WorldgenError:
        return []
    return [f"worldgen sim: warning: {f.where}: {f.message}" + (f" (fix: {f.fix})" if f.fix else "")
            for f in found]


def doctor_python() -> str:
    """The Python ``worldgen doctor`` checks: the one that runs nodes (see :func:`.rosenv.node_python`), or,
    when none imports rospy, the one that would be tried first (so that its report shows rospy missing)."""
    try:
        return node_python()
    except WorldgenError:
        pass
    for python in (os.environ.get(ENV_PYTHON), SYSTEM_PYTHON):
        if python and os.access(python, os.X_OK):
            return python
    return sys.executable
