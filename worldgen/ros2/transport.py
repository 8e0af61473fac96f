"""ROS 2 Humble or Jazzy as a transport (:class:`~worldgen.bridge.transport.Transport`): students' rclpy nodes on a
private DDS domain, the simulator speaking DDS itself (:mod:`.node`). Importing this module needs no cyclonedds;
running does (checked first, with the extra to install)."""

from __future__ import annotations

from pathlib import Path
from typing import Sequence

from ..bridge.outcome import NodeSpec, Outcome, RunOptions
from ..bridge.transport import Transport
from ..bridge.world import World
from .nodes import resolve_nodes
from .pyenv import node_python, require_cyclonedds
from .run import run_nodes


class Ros2(Transport):
    retry = ("every private DDS domain",)

    def __init__(self, stack: str, cmd_vel: str | None = None):
        self.stack, self.cmd_vel = stack, cmd_vel
        stamped = stack == "jazzy" and cmd_vel != "twist"
        self.cmd_type = "geometry_msgs/msg/TwistStamped" if stamped else "geometry_msgs/msg/Twist"

    def node_python(self) -> str:
        require_cyclonedds()
        return node_python(self.stack)

    def resolve_nodes(self, items: Sequence[str], python: str, search: Sequence[str | Path] = ()) -> list[NodeSpec]:
        return resolve_nodes(items, python, search)

    def run_nodes(self, world: World, nodes: list[NodeSpec], options: RunOptions, head=None) -> Outcome:
        return run_nodes(world, nodes, options, self.stack, self.cmd_vel)
