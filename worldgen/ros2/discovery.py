"""The ROS 2 graph over DDS: the simulator's nodes announced on ``ros_discovery_info``, and the others' read back.

A ROS 2 node is not a DDS entity: every rmw participant publishes, on the DDS topic ``ros_discovery_info``
(``rmw_dds_common/msg/ParticipantEntitiesInfo``), the nodes it holds and the GIDs of each node's readers and
writers. ``ros2 node list``, rclpy's ``get_node_names_and_namespaces()`` and ``ros2 topic info -v`` join that with
the endpoints DDS discovers; without it the simulator's endpoints show under ``_NODE_NAME_UNKNOWN_`` and its
participant as ``_CREATED_BY_BARE_DDS_APP_``. The QoS is rmw's (rmw_fastrtps_cpp ``init_rmw_context_impl.cpp``,
rmw_cyclonedds the same): the writer reliable, transient local, keep last 1 (a late joiner gets the last state);
the reader reliable, transient local, keep all (the topic is keyless: every participant's sample is one instance).

:class:`Graph` does both directions on one :class:`~.participant.Participant`: :meth:`Graph.add` and
:meth:`Graph.publish` announce nodes; :meth:`Graph.look` reads the others' nodes and DDS's built-in publication and
subscription topics, so :meth:`Graph.subscribers` says which nodes subscribe to a topic (a readiness check: the
student's node has subscribed to ``/scan``). :func:`announce` names the simulator's endpoints as the stack's Gazebo
nodes do (``/ros_gz_bridge`` on Jazzy, each gazebo_ros plugin's node on Humble, ``/robot_state_publisher``).
"""

from __future__ import annotations

import threading
from dataclasses import dataclass
from typing import Any, Iterable

from ..interface.topics import camera_topics, topics
from . import msgs
from .participant import Participant, endpoint_qos, gid
from .typehash import type_hash as hash_of

TOPIC = "ros_discovery_info"
UNKNOWN = "_NODE_NAME_UNKNOWN_"   # what rmw names an endpoint no participant has announced


@dataclass(frozen=True)
class _RosQos:
    reliable: bool = True
    depth: int = 1
    transient_local: bool = True


@dataclass(frozen=True)
class NodeInfo:
    """A node as some participant announces it: namespace, name and its endpoints' GIDs (16 bytes each)."""

    namespace: str
    name: str
    readers: tuple = ()
    writers: tuple = ()
    participant: bytes = b""

    @property
    def full_name(self) -> str:
        return f"{self.namespace.rstrip('/')}/{self.name}"


def split_name(full_name: str) -> tuple[str, str]:
    """``/tb3_0/ros_gz_bridge`` -> (``/tb3_0``, ``ros_gz_bridge``); ``/gazebo`` -> (``/``, ``gazebo``)."""
    namespace, _, name = ("/" + full_name.strip("/")).rpartition("/")
    return namespace or "/", name


def _gid_of(endpoint: Any) -> bytes:
    return bytes(endpoint) if isinstance(endpoint, (bytes, bytearray)) else gid(endpoint)


def ros_topic_name(dds_topic: str) -> str | None:
    """``rt/scan`` -> ``/scan``; None for a DDS topic that is not a ROS topic (services, ``ros_discovery_info``)."""
    return dds_topic[2:] if dds_topic.startswith("rt/") else None


class Graph:
    """Our nodes on ``ros_discovery_info`` and the ROS graph the others announce (see the module docstring).
    ``distro`` picks the discovery types' shape (Humble's GID is 24 bytes, Jazzy's 16)."""

    def __init__(self, participant: Participant, distro: str = "jazzy") -> None:
        from cyclonedds.builtin import (BuiltinDataReader, BuiltinTopicDcpsParticipant, BuiltinTopicDcpsPublication,
                                        BuiltinTopicDcpsSubscription)
        from cyclonedds.core import InstanceState, ReadCondition, SampleState, ViewState
        from cyclonedds.pub import DataWriter
        from cyclonedds.sub import DataReader


        self.participant = participant
        self.distro = distro
        self._gid_t, self._node_t, self._info_t, self._gid_size = msgs.DISCOVERY[distro]
        type_hash = None
        if distro == "jazzy":
            type_hash = hash_of("rmw_dds_common/msg/ParticipantEntitiesInfo")
        dp = participant.dp
        topic = participant.topic(TOPIC, self._info_t, prefix="")
        self.writer = DataWriter(dp, topic, endpoint_qos(_RosQos(), type_hash))
        self.reader = DataReader(dp, topic, endpoint_qos(_RosQos(depth=0), type_hash))
        alive = SampleState.Any | ViewState.Any | InstanceState.Alive
        self._builtin = {}
        for key, builtin in (("participants", BuiltinTopicDcpsParticipant),
                             ("publications", BuiltinTopicDcpsPublication),
                             ("subscriptions", BuiltinTopicDcpsSubscription)):
            reader = BuiltinDataReader(dp, builtin)
            self._builtin[key] = (reader, ReadCondition(reader, alive))
        self.lock = threading.Lock()
        self._ours: dict = {}      # full name -> (reader gids, writer gids), in the order added
        self._theirs: dict = {}    # participant gid -> tuple of NodeInfo
        self._endpoints: dict = {"publications": {}, "subscriptions": {}}   # gid -> (ROS topic, ROS type)

    # -- ours ---------------------------------------------------------------------------------------------------

    def add(self, full_name: str, readers: Iterable[Any] = (), writers: Iterable[Any] = ()) -> None:
        """Name ``full_name`` (``/robot_state_publisher``) as the node of ``readers`` and ``writers`` (cyclonedds
        entities or GIDs); a node added again keeps its endpoints and gains these. :meth:`publish` announces."""
        split_name(full_name)
        with self.lock:
            have_r, have_w = self._ours.setdefault("/" + full_name.strip("/"), ([], []))
            have_r.extend(g for g in map(_gid_of, readers) if g not in have_r)
            have_w.extend(g for g in map(_gid_of, writers) if g not in have_w)

    def message(self) -> Any:
        """Our ParticipantEntitiesInfo: the participant's GID and each node's endpoints, nodes sorted by name."""
        def g(raw: bytes) -> Any:
            return self._gid_t(data=raw.ljust(self._gid_size, b"\0"))

        with self.lock:
            nodes = [self._node_t(node_namespace=ns, node_name=name, reader_gid_seq=[g(r) for r in readers],
                                  writer_gid_seq=[g(w) for w in writers])
                     for (ns, name), (readers, writers) in sorted(
                         (split_name(full), ends) for full, ends in self._ours.items())]
        return self._info_t(gid=g(self.participant.gid), node_entities_info_seq=nodes)

    def publish(self) -> None:
        """Announce our nodes (again after :meth:`add`): the writer keeps the last one for late joiners."""
        self.writer.write(self.message())

    # -- theirs -------------------------------------------------------------------------------------------------

    def look(self) -> None:
        """Read what has come: others' announcements, the alive participants and endpoints."""
        own = self.participant.gid
        for sample in self.reader.take(N=1024):
            raw = bytes(sample.gid.data)[:16]
            if raw == own:
                continue
            nodes = tuple(NodeInfo(n.node_namespace, n.node_name,
                                   tuple(bytes(r.data)[:16] for r in n.reader_gid_seq),
                                   tuple(bytes(w.data)[:16] for w in n.writer_gid_seq), raw)
                          for n in sample.node_entities_info_seq)
            with self.lock:
                self._theirs[raw] = nodes
        reader, alive = self._builtin["participants"]
        present = {p.key.bytes for p in reader.read(N=4096, condition=alive)}
        endpoints: dict = {}
        for kind in ("publications", "subscriptions"):
            reader, alive = self._builtin[kind]
            found = {}
            for e in reader.read(N=4096, condition=alive):
                topic = ros_topic_name(e.topic_name)
                if topic is not None and e.participant_key.bytes != own:
                    try:
                        ros_type = msgs.ros_type_name(e.type_name)
                    except ValueError:
                        ros_type = e.type_name
                    found[e.key.bytes] = (topic, ros_type)
            endpoints[kind] = found
        with self.lock:
            self._theirs = {p: nodes for p, nodes in self._theirs.items() if p in present}
            self._endpoints = endpoints

    def nodes(self) -> list[NodeInfo]:
        """The others' nodes, by full name (as of the last :meth:`look`)."""
        with self.lock:
            return sorted((n for nodes in self._theirs.values() for n in nodes), key=lambda n: n.full_name)

    def node_names(self) -> list[str]:
        return [n.full_name for n in self.nodes()]

    def _node_of(self, endpoint: bytes, kind: str) -> str:
        for node in self.nodes():
            if endpoint in (node.readers if kind == "subscriptions" else node.writers):
                return node.full_name
        return UNKNOWN

    def subscribers(self, topic: str) -> list[str]:
        """The nodes of others subscribed to the ROS topic ``topic`` (``UNKNOWN`` for a bare DDS reader)."""
        return self._by_topic(topic, "subscriptions")

    def publishers(self, topic: str) -> list[str]:
        """The nodes of others publishing the ROS topic ``topic``."""
        return self._by_topic(topic, "publications")

    def _by_topic(self, topic: str, kind: str) -> list[str]:
        with self.lock:
            gids = [g for g, (name, _) in self._endpoints[kind].items() if name == topic]
        return sorted(self._node_of(g, kind) for g in gids)

    def topics_of(self, full_name: str) -> dict[str, list[tuple[str, str]]]:
        """What the node ``full_name`` of another participant subscribes and publishes: ``{"subscriptions":
        [(topic, type)…], "publications": […]}``, sorted."""
        node = next((n for n in self.nodes() if n.full_name == "/" + full_name.strip("/")), None)
        if node is None:
            return {"subscriptions": [], "publications": []}
        with self.lock:
            return {"subscriptions": sorted(self._endpoints["subscriptions"][g] for g in node.readers
                                            if g in self._endpoints["subscriptions"]),
                    "publications": sorted(self._endpoints["publications"][g] for g in node.writers
                                           if g in self._endpoints["publications"])}

    def close(self) -> None:
        """Nothing of its own to free: its entities go with the participant."""


def _in_namespace(ns: str, node: str) -> str:
    return node if ns in ("", "/") else f"/{ns.strip('/')}/{node.strip('/')}"


def announce(participant: Participant, wire: Any) -> Graph:
    """Announce the simulator's endpoints (``worldgen.ros2.node``'s wire: its shared writers, each robot's writers,
    ``cmd_vel`` reader and cameras) under the nodes the stack's Gazebo has (:mod:`worldgen.interface.topics`'s
    ``node`` column), a robot's in its namespace; the :class:`Graph`, published."""
    graph = Graph(participant, "humble" if wire.stack == "humble" else "jazzy")
    table = topics(wire.stack)
    for key, writer in wire.writers.items():
        graph.add(table[key].node, writers=[writer])
    cameras = camera_topics(wire.stack, "image", "info")
    for robot in wire.robots:
        for key, writer in robot.writers.items():
            graph.add(_in_namespace(robot.ns, table[key].node), writers=[writer])
        graph.add(_in_namespace(robot.ns, table["cmd_vel"].node), readers=[robot.cmd_reader])
        for camera in robot.cameras:
            for key, writer in camera.writers.items():
                graph.add(_in_namespace(robot.ns, cameras[key].node), writers=[writer])
    graph.publish()
    return graph
