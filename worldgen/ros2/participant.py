"""The simulator's one DDS participant on a ROS 2 domain, made with PyPI's Cyclone DDS (no ROS install).

ROS 2 nodes (rclpy on Fast DDS, from the Jazzy/Kilted wheels or a ROS install) see the simulator through the DDS
conventions rmw follows, which this module applies: a ROS topic ``/scan`` is the DDS topic ``rt/scan``; samples are
XCDR1 (plain CDR); each endpoint's USER_DATA carries ``typehash=RIHS01_<hex>;`` (Jazzy's graph reads the type hash
from it); the participant's USER_DATA carries ``enclave=/;`` as rmw's does. An endpoint's GID, as ROS 2 lists it in
``ros_discovery_info`` and ``ros2 topic info -v``, is its 16-byte DDS GUID (:func:`gid`).

Discovery must work whatever a student's shell says (``ROS_LOCALHOST_ONLY``, ``ROS_AUTOMATIC_DISCOVERY_RANGE``,
``ROS_STATIC_PEERS``). The participant lives on the loopback interface and announces itself by unicast to every
participant port of localhost, every second (:func:`cyclone_config`): peers limited to localhost send to localhost
themselves; peers on the default (subnet) range only multicast, and find it by its announcement (with Cyclone's
default period, 30 s, a node started after the first burst waited that long). Measured with the Jazzy (Fast DDS 2.14)
and Kilted (Fast DDS 3.2) wheels: found under every setting but ``OFF``, which by design finds nothing outside its
own process. A ``subnet`` discovery (``worldgen sim`` in such a shell) adds the machine's own interface with
multicast, for peers on other machines. Fast DDS 3 (Kilted) sends XTypes type information Cyclone rejects for
types with sequences, so type information from eProsima (vendor 1.15) is ignored and types match by name.
"""

from __future__ import annotations

import os
import threading
from dataclasses import dataclass
from typing import Any, Mapping

RANGES = ("localhost", "subnet", "off")
# A camera picture (921 600 bytes at 640 x 480 rgb8) in Cyclone's default 1 344-byte fragments overruns a Fast DDS
# reader's socket buffer on loopback (Fast DDS peers on one machine talk through shared memory, which Cyclone cannot
# use): 8 of 49 pictures arrived at 30 Hz. In fragments of 62 000 bytes within 65 500-byte datagrams, 40 of 43 did,
# the rest sent before the reader matched (measured with the Jazzy wheels).
MAX_MESSAGE, FRAGMENT = "65500B", "62000B"
ENCLAVE_USER_DATA = b"enclave=/;"
# Participant indices announced to on each peer host: one per ROS process (each rclpy context is a participant);
# a class's grading run holds the simulator, the student's nodes and a probe or two.
MAX_PARTICIPANT_INDEX = 32
# A peer limited to the subnet announces itself by multicast only, which a localhost participant does not hear: it
# finds the peer by announcing itself to every localhost port, so it announces often (Cyclone's default is 30 s).
SPDP_INTERVAL = "1s"


class DdsError(Exception):
    """The DDS layer could not be set up (a domain in use with another configuration, a bad domain id)."""


@dataclass(frozen=True)
class Discovery:
    """Where DDS discovery reaches: ``range`` is ``localhost``, ``subnet`` or ``off`` as rcl names them;
    ``static_peers`` are host names or addresses (``ROS_STATIC_PEERS``, ``;``-separated)."""

    range: str = "localhost"
    static_peers: tuple = ()

    @classmethod
    def from_env(cls, env: Mapping[str, str] | None = None) -> Discovery:
        """What rcl (Jazzy) makes of the environment: ``ROS_LOCALHOST_ONLY=1`` wins and drops static peers;
        ``ROS_AUTOMATIC_DISCOVERY_RANGE`` unset or ``SYSTEM_DEFAULT`` is the subnet, an unknown value localhost."""
        env = os.environ if env is None else env
        if env.get("ROS_LOCALHOST_ONLY", "") == "1":
            return cls("localhost", ())
        value = env.get("ROS_AUTOMATIC_DISCOVERY_RANGE", "")
        rng = {"": "subnet", "SYSTEM_DEFAULT": "subnet", "SUBNET": "subnet", "LOCALHOST": "localhost",
               "OFF": "off"}.get(value, "localhost")
        peers = tuple(p.strip() for p in env.get("ROS_STATIC_PEERS", "").split(";") if p.strip())
        return cls(rng, peers if rng != "off" else ())


def cyclone_config(discovery: Discovery = Discovery(), external: bool = True) -> str:
    """The Cyclone DDS XML for ``discovery`` (see the module docstring). A ``subnet`` discovery adds the machine's
    own network interface beside the loopback one when ``external`` (a machine with none refuses it:
    :class:`_Domains` retries without)."""
    if discovery.range not in RANGES:
        raise DdsError(f"unknown discovery range {discovery.range!r}: use one of {', '.join(RANGES)}")
    external = external and discovery.range == "subnet"
    interfaces = '<NetworkInterface address="127.0.0.1"/>'
    if external:
        interfaces += '<NetworkInterface autodetermine="true" priority="default" multicast="default"/>'
    multicast = "spdp" if external else "false"
    peers = ["localhost"] + [p for p in discovery.static_peers if p not in ("localhost", "127.0.0.1")]
    peer_xml = "".join(f'<Peer address="{_xml_attr(p)}"/>' for p in peers)
    return ("<CycloneDDS><Domain id=\"any\">"
            f"<General><Interfaces>{interfaces}</Interfaces><AllowMulticast>{multicast}</AllowMulticast>"
            f"<MaxMessageSize>{MAX_MESSAGE}</MaxMessageSize><FragmentSize>{FRAGMENT}</FragmentSize></General>"
            f"<Discovery><ParticipantIndex>auto</ParticipantIndex><SPDPInterval>{SPDP_INTERVAL}</SPDPInterval>"
            "<InitialLocatorPruneDelay>inf</InitialLocatorPruneDelay>"
            f"<MaxAutoParticipantIndex>{MAX_PARTICIPANT_INDEX}</MaxAutoParticipantIndex>"
            f"<Peers>{peer_xml}</Peers></Discovery>"
            "<Compatibility><IgnoreTypeInformation>1.15</IgnoreTypeInformation></Compatibility>"
            "</Domain></CycloneDDS>")


def _xml_attr(text: str) -> str:
    return text.replace("&", "&amp;").replace('"', "&quot;").replace("<", "&lt;")


def ros_topic(name: str, prefix: str = "rt") -> str:
    """The DDS topic of a ROS topic: ``/scan`` -> ``rt/scan`` (``rq``/``rr`` for a service's request/reply); an
    empty ``prefix`` takes ``name`` as the DDS name itself (``ros_discovery_info``)."""
    if not prefix:
        return name
    if not name.startswith("/"):
        raise DdsError(f"ROS topic {name!r} is not absolute: give it with its namespace, as /{name}")
    return f"{prefix}{name}"


def gid(entity: Any) -> bytes:
    """The endpoint's (or participant's) 16-byte GID as rmw publishes it: its DDS GUID, prefix then entity id."""
    return entity.guid.bytes


def endpoint_qos(qos: Any, type_hash: str | None = None) -> Any:
    """A cyclonedds Qos for a ROS QoS given as data (``reliable``, ``depth``, ``transient_local`` attributes, like
    :class:`worldgen.interface.topics.Qos`; a depth of 0 keeps all), XCDR1 only, with ``typehash=…;`` in USER_DATA
    when ``type_hash``."""
    from cyclonedds.core import Policy
    from cyclonedds.qos import Qos
    from cyclonedds.util import duration

    policies = [
        Policy.Reliability.Reliable(duration(milliseconds=100)) if qos.reliable else Policy.Reliability.BestEffort,
        Policy.Durability.TransientLocal if qos.transient_local else Policy.Durability.Volatile,
        Policy.History.KeepLast(int(qos.depth)) if qos.depth > 0 else Policy.History.KeepAll,
        Policy.DataRepresentation(use_cdrv0_representation=True),
    ]
    if type_hash:
        policies.append(Policy.Userdata(f"typehash={type_hash};".encode("ascii")))
    return Qos(*policies)


class _Domains:
    """Cyclone allows one configured domain per id in a process: the domains made here, shared by the
    participants on them and deleted with the last one."""

    def __init__(self) -> None:
        self.lock = threading.Lock()
        self.open: dict = {}   # domain id -> [Domain, Discovery, config, users]

    def acquire(self, domain_id: int, discovery: Discovery) -> str:
        """Open ``domain_id`` for ``discovery`` (or share it when open with the same); the config it got."""
        from cyclonedds.core import DDSException
        from cyclonedds.domain import Domain

        with self.lock:
            entry = self.open.get(domain_id)
            if entry is not None:
                if entry[1] != discovery:
                    raise DdsError(f"DDS domain {domain_id} is already open in this process with another discovery "
                                   "setting: close its participant first")
                entry[3] += 1
                return entry[2]
            for external in (True, False):   # a machine with only a loopback interface refuses the subnet's
                config = cyclone_config(discovery, external)
                try:
                    self.open[domain_id] = [Domain(domain_id, config), discovery, config, 1]
                    return config
                except DDSException as exc:
                    error = exc
            raise DdsError(f"cannot open DDS domain {domain_id}: {error}; ROS domain ids are 0-232 (0-101 are safe "
                           "on every machine)")

    def release(self, domain_id: int) -> None:
        with self.lock:
            entry = self.open.get(domain_id)
            if entry is None:
                return
            entry[3] -= 1
            if entry[3] == 0:
                del self.open[domain_id]
                _delete(entry[0])


_DOMAINS = _Domains()


def _delete(entity: Any) -> None:
    """Delete a cyclonedds entity now (cyclonedds deletes on garbage collection; this does it eagerly, once)."""
    entity.__del__()   # guarded by cyclonedds: the later garbage collection deletes nothing twice


class Participant:
    """One DDS participant on ``domain_id``; topics, writers and readers are made through it and deleted with it
    (:meth:`close`, or the ``with`` block's end)."""

    def __init__(self, domain_id: int, discovery: Discovery = Discovery()) -> None:
        from cyclonedds.core import Policy
        from cyclonedds.domain import DomainParticipant
        from cyclonedds.qos import Qos

        if not 0 <= int(domain_id) <= 232:
            raise DdsError(f"ROS_DOMAIN_ID {domain_id} is out of range: use 0-232 (0-101 are safe on every machine)")
        self.domain_id = int(domain_id)
        self.discovery = discovery
        self.config = _DOMAINS.acquire(self.domain_id, discovery)
        try:
            self.dp = DomainParticipant(self.domain_id, qos=Qos(Policy.Userdata(ENCLAVE_USER_DATA)))
        except Exception:
            _DOMAINS.release(self.domain_id)
            raise
        self._topics: dict = {}
        self._closed = False

    @property
    def gid(self) -> bytes:
        """The participant's GID (what ``ros_discovery_info`` names it by)."""
        return gid(self.dp)

    def topic(self, name: str, dds_type: type, prefix: str = "rt") -> Any:
        """The DDS topic of the ROS topic ``name`` (absolute) with ``dds_type`` (a cyclonedds IdlStruct)."""
        from cyclonedds.topic import Topic

        key = (ros_topic(name, prefix), dds_type)
        if key not in self._topics:
            self._topics[key] = Topic(self.dp, key[0], dds_type)
        return self._topics[key]

    def writer(self, name: str, dds_type: type, qos: Any, type_hash: str | None = None, prefix: str = "rt") -> Any:
        """A DataWriter on the ROS topic ``name`` with the ROS QoS ``qos`` (see :func:`endpoint_qos`)."""
        from cyclonedds.pub import DataWriter

        return DataWriter(self.dp, self.topic(name, dds_type, prefix), endpoint_qos(qos, type_hash))

    def reader(self, name: str, dds_type: type, qos: Any, type_hash: str | None = None, prefix: str = "rt") -> Any:
        """A DataReader on the ROS topic ``name`` with the ROS QoS ``qos`` (see :func:`endpoint_qos`)."""
        from cyclonedds.sub import DataReader

        return DataReader(self.dp, self.topic(name, dds_type, prefix), endpoint_qos(qos, type_hash))

    def close(self) -> None:
        """Delete the participant and everything made through it (peers see its endpoints go); idempotent."""
        if self._closed:
            return
        self._closed = True
        self._topics.clear()
        _delete(self.dp)
        _DOMAINS.release(self.domain_id)

    def __enter__(self) -> Participant:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()
