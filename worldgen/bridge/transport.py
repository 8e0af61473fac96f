"""What a run needs of a transport, the wire between students' nodes and the simulated robot: ROS 1 over rospy
(:mod:`worldgen.ros1.transport`) or ROS 2 over DDS (:mod:`worldgen.ros2.transport`). The command line picks one
(``--ros``) and hands it down; runs, rubrics, reports and folder grading never import a transport themselves."""

from __future__ import annotations

import contextlib
from pathlib import Path
from typing import Callable, Sequence, TypeVar

from ..core.errors import InputError
from ..runtime.naming import Naming
from .outcome import NodeSpec, Outcome, RunOptions
from .world import World


START_TRIES = 3   # a run whose start-up lost a race for a port to another job: this many tries in all
T = TypeVar("T")


class Transport:
    """One stack's way of running nodes. ``stack`` is ``noetic``, ``humble`` or ``jazzy``; ``cmd_type`` the message
    the robot takes on ``cmd_vel``; ``retry`` the start-up errors worth a second try (a port another job took)."""

    stack = ""
    cmd_type = "geometry_msgs/Twist"
    retry: tuple = ()

    def node_python(self) -> str:
        """The Python that runs students' nodes; InputError naming what to install when there is none (checked
        before anything starts)."""
        raise NotImplementedError

    def naming(self) -> Naming:
        """How missing modules' packages are named for this stack (:mod:`worldgen.runtime.naming`)."""
        return Naming(self.stack)

    def resolve_nodes(self, items: Sequence[str], python: str, search: Sequence[str | Path] = ()) -> list[NodeSpec]:
        raise NotImplementedError

    def head_start(self):
        """A context manager: what a run may start before its world and nodes are known (its processes' Python
        starts and imports), handed to :meth:`run_nodes` as ``head`` (None: nothing). Nothing by default."""
        return contextlib.nullcontext()

    def run_nodes(self, world: World, nodes: list[NodeSpec], options: RunOptions, head=None) -> Outcome:
        raise NotImplementedError


def tried(transport: Transport, attempt: Callable[[], T]) -> T:
    """``attempt()``, started again (up to :data:`START_TRIES` in all) when it fails at start-up with one of the
    transport's ``retry`` errors: a free port that another job took first (a master of a run beside it, or a
    connection's own port), which a second start on another port does not meet."""
    for tries in range(1, START_TRIES + 1):
        try:
            return attempt()
        except InputError as err:
            if tries == START_TRIES or not any(text in str(err) for text in transport.retry):
                raise
    raise AssertionError("unreachable")
