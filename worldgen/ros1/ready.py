"""When the students' nodes of a ROS 1 run are ready for simulated time to start: each has joined the master and
its links with the simulator are up, so that the first scan reaches it and its first command reaches the robot.

Looked at every :data:`POLL` seconds (:data:`POLL_JOINING` until every node has joined), from outside: the
master's ``getSystemState`` (which node publishes and subscribes what) and the simulator's own ``getBusInfo``
(which of its connections are established, and with whom). A node (any name the master knows but the
simulator's) is *ready* when

* every topic it shares with the simulator — subscribed to one the simulator publishes (``/clock`` included),
  or publishing one the simulator subscribes to — has its connection established;
* what it registered is the same as at the previous look (a node registers its topics one call at a time);
* and it does what the task needs: it publishes ``cmd_vel`` and, for a task judged on the LiDAR
  (:data:`worldgen.interface.topics.TASK_INPUTS`), subscribes to ``scan``. A node that does neither (a helper of
  a launch file, a node listening under another name) is taken as ready :data:`SETTLE` seconds after it first
  showed, the fixed wait every node used to get.

The run starts once every node is ready and they are as many as the running processes (once a process has
exited, once as many nodes as still run are ready), or after ``timeout``: the nodes' first messages are neither
lost to a link still being made nor delayed by a wait they do not need.
"""

from __future__ import annotations

import socket
import time
import xmlrpc.client
from dataclasses import dataclass, field

from ..bridge.supervise import check_stopping
from ..interface.topics import TASK_INPUTS

CALLER = "/worldgen"
SIMULATOR = "/gazebo"
POLL = 0.01            # s between looks once every node has joined
POLL_JOINING = 0.03    # s between looks before (a node's Python takes a few tenths of a second to start)
SETTLE = 0.3           # s after a node shows before it is taken as ready anyway
IGNORED = ("/rosout",)  # what every node publishes and the simulator never subscribes to


@dataclass
class Node:
    """One node as the master and the simulator see it: the topics it takes from and gives to the simulator."""

    takes: set = field(default_factory=set)     # topics the simulator publishes that it subscribes to
    gives: set = field(default_factory=set)     # topics the simulator subscribes to that it publishes
    others: set = field(default_factory=set)    # anything else it registered

    def signature(self) -> tuple:
        return tuple(sorted(self.takes)), tuple(sorted(self.gives)), tuple(sorted(self.others))


def _call(uri: str, method: str, *args):
    """``method(CALLER, *args)`` on the XML-RPC server at ``uri``: its value, or None when it cannot answer."""
    old = socket.getdefaulttimeout()
    socket.setdefaulttimeout(2.0)
    try:
        code, _, value = getattr(xmlrpc.client.ServerProxy(uri), method)(CALLER, *args)
    except (OSError, xmlrpc.client.Error, ValueError, TypeError):
        return None
    finally:
        socket.setdefaulttimeout(old)
    return value if code == 1 else None


def graph(state) -> dict[str, Node]:
    """Every node of the master's ``getSystemState`` answer but the simulator, with what it shares with it."""
    publishers, subscribers, services = state
    sim_pubs = {topic for topic, names in publishers if SIMULATOR in names}
    sim_subs = {topic for topic, names in subscribers if SIMULATOR in names}
    nodes: dict[str, Node] = {}
    for topic, names in subscribers:
        for name in names:
            node = nodes.setdefault(name, Node())
            (node.takes if topic in sim_pubs else node.others).add(topic)
    for topic, names in publishers:
        for name in names:
            node = nodes.setdefault(name, Node())
            if topic in sim_subs:
                node.gives.add(topic)
            elif topic not in IGNORED:
                node.others.add(topic)
    for _, names in services:
        for name in names:
            nodes.setdefault(name, Node())
    nodes.pop(SIMULATOR, None)
    return nodes


def _base(topic: str) -> str:
    return topic.rstrip("/").rsplit("/", 1)[-1]


class Readiness:
    """The looks at one run's graph (see the module docstring): :meth:`ready` answers from one more look."""

    def __init__(self, master_uri: str, task: str | None):
        self.master_uri = master_uri
        self.need = TASK_INPUTS.get(task or "")
        self.simulator_uri: str | None = None
        self.node_uris: dict[str, str] = {}
        self.first_seen: dict[str, float] = {}
        self.previous: dict[str, tuple] = {}
        self.joined = False   # as many nodes as processes known to the master, at the last look

    def _links(self) -> set[tuple[str, str]] | None:
        """The simulator's established connections: (topic, the other end: a node's name for what it publishes,
        a node's URI for what it subscribes to)."""
        if self.simulator_uri is None:
            self.simulator_uri = _call(self.master_uri, "lookupNode", SIMULATOR)
            if self.simulator_uri is None:
                return None
        info = _call(self.simulator_uri, "getBusInfo")
        if info is None:
            return None
        return {(row[4], row[1]) for row in info if len(row) > 5 and row[5]}

    def _uri(self, name: str) -> str | None:
        if name not in self.node_uris:
            uri = _call(self.master_uri, "lookupNode", name)
            if uri is None:
                return None
            self.node_uris[name] = uri
        return self.node_uris[name]

    def _linked(self, name: str, node: Node, links: set) -> bool:
        if any((topic, name) not in links for topic in node.takes):
            return False
        uri = self._uri(name) if node.gives else None
        return all((topic, uri) in links for topic in node.gives)

    def _does_the_task(self, node: Node) -> bool:
        drives = any(_base(t) == "cmd_vel" for t in node.gives)
        return drives and (self.need is None or any(_base(t) == self.need for t in node.takes))

    def ready(self, running: int, exited: int = 0) -> bool:
        """Whether, from one more look, every node known is ready and they are at least ``running`` (the
        processes still running); once ``exited`` processes have ended (their names may stay with the master,
        their links gone), whether ``running`` nodes are ready."""
        state = _call(self.master_uri, "getSystemState")
        if state is None:
            return False
        nodes, now = graph(state), time.monotonic()
        self.joined = len(nodes) >= running
        if not self.joined:   # some still starting: no need to ask the simulator yet
            return False
        links = self._links()
        if links is None:
            return False
        settled = 0
        for name, node in nodes.items():
            self.first_seen.setdefault(name, now)
            signature, self.previous[name] = self.previous.get(name), node.signature()
            steady = signature == node.signature()
            waited = now - self.first_seen[name] >= SETTLE
            if steady and self._linked(name, node, links) and (waited or self._does_the_task(node)):
                settled += 1
        if exited:
            return settled >= running
        return settled == len(nodes) and len(nodes) >= running


def wait_until_ready(readiness: Readiness, children, timeout: float) -> bool:
    """Look until :meth:`Readiness.ready` for the node processes ``children`` (each with ``running``) or
    ``timeout`` seconds; whether the nodes were found ready."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        running = sum(c.running for c in children)
        if readiness.ready(running, len(children) - running):
            return True
        check_stopping()
        time.sleep(POLL if readiness.joined else POLL_JOINING)
    return False
