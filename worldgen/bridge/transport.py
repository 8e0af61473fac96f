"""What a run needs of a transport, the wire between students' nodes and the simulated robot: ROS 1 over rospy
(:mod:`worldgen.ros1.transport`) or ROS 2 over DDS (:mod:`worldgen.ros2.transport`). The command line picks one
(``--ros``) and hands it down; runs, rubrics, reports and folder grading never import a transport themselves."""

from __future__ import annotations

from pathlib import Path
from typing import Sequence

from .outcome import NodeSpec, Outcome, RunOptions
from .world import World


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

    def apt_ros(self) -> bool:
        """Whether missing modules are named as ROS's own apt packages (``ros-noetic-…``) rather than Debian's."""
        return False

    def resolve_nodes(self, items: Sequence[str], python: str, search: Sequence[str | Path] = ()) -> list[NodeSpec]:
        raise NotImplementedError

    def run_nodes(self, world: World, nodes: list[NodeSpec], options: RunOptions) -> Outcome:
        raise NotImplementedError
