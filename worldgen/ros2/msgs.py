"""The ROS 2 messages the simulated robot, its camera and its clock speak, as DDS types of PyPI's cyclonedds.

Each class is a cyclonedds IDL struct whose DDS type name is the one ROS 2's rosidl gives the message
(``sensor_msgs/msg/LaserScan`` is ``sensor_msgs::msg::dds_::LaserScan_``), with the fields of ROS 2 Jazzy's
``.msg`` definitions in their order and with their types, so a sample serialized here is byte for byte what an rclpy
node sends and receives. ``TYPES`` maps each ROS type name to its class; ``to_cdr`` / ``from_cdr`` are the bytes of a
sample as ROS 2 puts them on the wire (XCDR1, little endian, behind the 4-byte encapsulation header ``00 01 00 00``);
``stamp`` makes a ``builtin_interfaces/Time`` from float seconds as rclpy does.

Mapping of the ``.msg`` types: ``float32/64``, ``(u)int8..64`` the same-named cyclonedds types, ``string`` is ``str``,
``string<=N`` a bounded string, ``bool`` is ``bool``, ``T[N]`` an array, ``T[]`` a sequence, ``char`` is ``uint8``
(as rosidl maps it). An empty message carries rosidl's one ``uint8 structure_needs_at_least_one_member``.
Samples take Python values: lists (or tuples, or ``array.array``) for number sequences, not numpy arrays (cyclonedds
tests a sequence's truth value); a ``uint8[]`` field (``Image.data``, ``CompressedImage.data``) takes any flat
bytes-like object (``bytes``, ``bytearray``, a 1-D ``memoryview``; a numpy image as ``img.tobytes()``) and reads back
as ``bytes``.

Messages have no key fields: every ROS 2 topic is keyless. ``rmw_dds_common``'s discovery types are Jazzy's (a
16-byte Gid); Humble's Gid is 24 bytes under the same DDS type name, so Humble's are the ``Humble*`` classes (see
``DISCOVERY``). Nothing here imports outside cyclonedds (Python 3.10+, the ``ros2`` extra).
"""

# No ``from __future__ import annotations`` here, unlike the rest of worldgen: cyclonedds reads these annotations at
# run time, and it resolves a string annotation only when it is a bare name (``sequence[float32]`` would fail).

import dataclasses
from dataclasses import field
from typing import Callable, Dict, Tuple, Type, TypeVar, Union

from cyclonedds.idl import Endianness, IdlStruct
from cyclonedds.idl import types as t
from cyclonedds.idl._machinery import BytesMachine   # see _octets

NS_PER_S = 1_000_000_000
_INT32 = (-2**31, 2**31 - 1)

TYPES: Dict[str, Type[IdlStruct]] = {}   # ROS type name ("sensor_msgs/msg/LaserScan") -> class
Msg = TypeVar("Msg", bound=IdlStruct)


def dds_type_name(ros_type: str) -> str:
    """``sensor_msgs/msg/LaserScan`` -> ``sensor_msgs::msg::dds_::LaserScan_`` (rosidl's DDS name of a type)."""
    package, kind, name = ros_type.split("/")
    return f"{package}::{kind}::dds_::{name}_"


def ros_type_name(dds_type: str) -> str:
    """``sensor_msgs::msg::dds_::LaserScan_`` -> ``sensor_msgs/msg/LaserScan``; the inverse of ``dds_type_name``."""
    parts = dds_type.split("::")
    if len(parts) != 4 or parts[2] != "dds_" or not parts[3].endswith("_"):
        raise ValueError(f"not a ROS 2 DDS type name: {dds_type!r} (expected pkg::msg::dds_::Name_)")
    return f"{parts[0]}/{parts[1]}/{parts[3][:-1]}"


def ros_type_of(cls: Type[IdlStruct]) -> str:
    """The ROS type name of one of our message classes."""
    return ros_type_name(cls.__idl_typename__)


def _message(cls: Type[Msg]) -> Type[Msg]:
    """A dataclass, registered in TYPES under the ROS name its DDS type name stands for."""
    cls = dataclasses.dataclass(cls)
    TYPES.setdefault(ros_type_of(cls), cls)
    return cls


def _octets(cls: Type[Msg], *names: str) -> Type[Msg]:
    """Serialize the ``uint8[]`` fields ``names`` of ``cls`` from and to ``bytes`` in one copy.

    cyclonedds packs a ``sequence[uint8]`` element by element (about 60 ms for a 640x480 rgb8 image) and refuses a
    ``bytes`` annotation when it builds a topic's XTypes type object. So the annotation stays ``sequence[uint8]`` (the
    type object says what rosidl's does) and the two (de)serializers of those fields become cyclonedds' own octet
    string machine, whose wire form is the same (uint32 count, then the octets) in XCDR1 and XCDR2.
    cyclonedds is pinned exactly in the ``ros2`` extra; tests/test_ros2_msgs.py checks the bytes against rosbags.
    """
    idl = cls.__idl__
    idl.populate()
    for machine in (idl.v1_machine, idl.v2_machine):
        for name in names:
            if name not in machine.members_machines:
                raise TypeError(f"{cls.__name__} has no field {name!r} to serialize as octets")
            machine.members_machines[name] = BytesMachine()
    return cls


def _zeros(n: int) -> Callable[[], list]:
    return lambda: [0.0] * n


# ---- builtin_interfaces, std_msgs (rcl_interfaces, common_interfaces)

@_message
class Time(IdlStruct, typename=dds_type_name("builtin_interfaces/msg/Time")):
    sec: t.int32 = 0
    nanosec: t.uint32 = 0


@_message
class Duration(IdlStruct, typename=dds_type_name("builtin_interfaces/msg/Duration")):
    sec: t.int32 = 0
    nanosec: t.uint32 = 0


@_message
class Header(IdlStruct, typename=dds_type_name("std_msgs/msg/Header")):
    stamp: Time = field(default_factory=Time)
    frame_id: str = ""


@_message
class String(IdlStruct, typename=dds_type_name("std_msgs/msg/String")):
    data: str = ""


@_message
class Empty(IdlStruct, typename=dds_type_name("std_msgs/msg/Empty")):
    structure_needs_at_least_one_member: t.uint8 = 0


# ---- geometry_msgs

@_message
class Vector3(IdlStruct, typename=dds_type_name("geometry_msgs/msg/Vector3")):
    x: t.float64 = 0.0
    y: t.float64 = 0.0
    z: t.float64 = 0.0


@_message
class Point(IdlStruct, typename=dds_type_name("geometry_msgs/msg/Point")):
    x: t.float64 = 0.0
    y: t.float64 = 0.0
    z: t.float64 = 0.0


@_message
class Quaternion(IdlStruct, typename=dds_type_name("geometry_msgs/msg/Quaternion")):
    x: t.float64 = 0.0
    y: t.float64 = 0.0
    z: t.float64 = 0.0
    w: t.float64 = 1.0   # the .msg's default, as rclpy's Quaternion()


@_message
class Pose(IdlStruct, typename=dds_type_name("geometry_msgs/msg/Pose")):
    position: Point = field(default_factory=Point)
    orientation: Quaternion = field(default_factory=Quaternion)


@_message
class PoseWithCovariance(IdlStruct, typename=dds_type_name("geometry_msgs/msg/PoseWithCovariance")):
    pose: Pose = field(default_factory=Pose)
    covariance: t.array[t.float64, 36] = field(default_factory=_zeros(36))


@_message
class Twist(IdlStruct, typename=dds_type_name("geometry_msgs/msg/Twist")):
    linear: Vector3 = field(default_factory=Vector3)
    angular: Vector3 = field(default_factory=Vector3)


@_message
class TwistStamped(IdlStruct, typename=dds_type_name("geometry_msgs/msg/TwistStamped")):
    header: Header = field(default_factory=Header)
    twist: Twist = field(default_factory=Twist)


@_message
class TwistWithCovariance(IdlStruct, typename=dds_type_name("geometry_msgs/msg/TwistWithCovariance")):
    twist: Twist = field(default_factory=Twist)
    covariance: t.array[t.float64, 36] = field(default_factory=_zeros(36))


@_message
class Transform(IdlStruct, typename=dds_type_name("geometry_msgs/msg/Transform")):
    translation: Vector3 = field(default_factory=Vector3)
    rotation: Quaternion = field(default_factory=Quaternion)


@_message
class TransformStamped(IdlStruct, typename=dds_type_name("geometry_msgs/msg/TransformStamped")):
    header: Header = field(default_factory=Header)
    child_frame_id: str = ""
    transform: Transform = field(default_factory=Transform)


# ---- sensor_msgs

@_message
class LaserScan(IdlStruct, typename=dds_type_name("sensor_msgs/msg/LaserScan")):
    header: Header = field(default_factory=Header)
    angle_min: t.float32 = 0.0
    angle_max: t.float32 = 0.0
    angle_increment: t.float32 = 0.0
    time_increment: t.float32 = 0.0
    scan_time: t.float32 = 0.0
    range_min: t.float32 = 0.0
    range_max: t.float32 = 0.0
    ranges: t.sequence[t.float32] = field(default_factory=list)
    intensities: t.sequence[t.float32] = field(default_factory=list)


@_message
class Imu(IdlStruct, typename=dds_type_name("sensor_msgs/msg/Imu")):
    header: Header = field(default_factory=Header)
    orientation: Quaternion = field(default_factory=Quaternion)
    orientation_covariance: t.array[t.float64, 9] = field(default_factory=_zeros(9))
    angular_velocity: Vector3 = field(default_factory=Vector3)
    angular_velocity_covariance: t.array[t.float64, 9] = field(default_factory=_zeros(9))
    linear_acceleration: Vector3 = field(default_factory=Vector3)
    linear_acceleration_covariance: t.array[t.float64, 9] = field(default_factory=_zeros(9))


@_message
class JointState(IdlStruct, typename=dds_type_name("sensor_msgs/msg/JointState")):
    header: Header = field(default_factory=Header)
    name: t.sequence[str] = field(default_factory=list)
    position: t.sequence[t.float64] = field(default_factory=list)
    velocity: t.sequence[t.float64] = field(default_factory=list)
    effort: t.sequence[t.float64] = field(default_factory=list)


@_message
class Image(IdlStruct, typename=dds_type_name("sensor_msgs/msg/Image")):
    header: Header = field(default_factory=Header)
    height: t.uint32 = 0
    width: t.uint32 = 0
    encoding: str = ""
    is_bigendian: t.uint8 = 0
    step: t.uint32 = 0
    data: t.sequence[t.uint8] = b""   # bytes-like in, bytes out (see _octets)


_octets(Image, "data")


@_message
class RegionOfInterest(IdlStruct, typename=dds_type_name("sensor_msgs/msg/RegionOfInterest")):
    x_offset: t.uint32 = 0
    y_offset: t.uint32 = 0
    height: t.uint32 = 0
    width: t.uint32 = 0
    do_rectify: bool = False


@_message
class CameraInfo(IdlStruct, typename=dds_type_name("sensor_msgs/msg/CameraInfo")):
    header: Header = field(default_factory=Header)
    height: t.uint32 = 0
    width: t.uint32 = 0
    distortion_model: str = ""
    d: t.sequence[t.float64] = field(default_factory=list)
    k: t.array[t.float64, 9] = field(default_factory=_zeros(9))
    r: t.array[t.float64, 9] = field(default_factory=_zeros(9))
    p: t.array[t.float64, 12] = field(default_factory=_zeros(12))
    binning_x: t.uint32 = 0
    binning_y: t.uint32 = 0
    roi: RegionOfInterest = field(default_factory=RegionOfInterest)


@_message
class CompressedImage(IdlStruct, typename=dds_type_name("sensor_msgs/msg/CompressedImage")):
    header: Header = field(default_factory=Header)
    format: str = ""
    data: t.sequence[t.uint8] = b""   # bytes-like in, bytes out (see _octets)


_octets(CompressedImage, "data")


# ---- nav_msgs, tf2_msgs, rosgraph_msgs, std_srvs

@_message
class Odometry(IdlStruct, typename=dds_type_name("nav_msgs/msg/Odometry")):
    header: Header = field(default_factory=Header)
    child_frame_id: str = ""
    pose: PoseWithCovariance = field(default_factory=PoseWithCovariance)
    twist: TwistWithCovariance = field(default_factory=TwistWithCovariance)


@_message
class TFMessage(IdlStruct, typename=dds_type_name("tf2_msgs/msg/TFMessage")):
    transforms: t.sequence[TransformStamped] = field(default_factory=list)


@_message
class Clock(IdlStruct, typename=dds_type_name("rosgraph_msgs/msg/Clock")):
    clock: Time = field(default_factory=Time)


@_message
class EmptyRequest(IdlStruct, typename=dds_type_name("std_srvs/srv/Empty_Request")):
    structure_needs_at_least_one_member: t.uint8 = 0


@_message
class EmptyResponse(IdlStruct, typename=dds_type_name("std_srvs/srv/Empty_Response")):
    structure_needs_at_least_one_member: t.uint8 = 0


# ---- rmw_dds_common: what every ROS 2 participant publishes on the DDS topic ``ros_discovery_info`` (its nodes
# and their endpoints). A Gid is an entity's 16-byte DDS GUID; Jazzy's .msg says char[16], rosidl makes it uint8.

@_message
class Gid(IdlStruct, typename=dds_type_name("rmw_dds_common/msg/Gid")):
    data: t.array[t.uint8, 16] = bytes(16)


@_message
class NodeEntitiesInfo(IdlStruct, typename=dds_type_name("rmw_dds_common/msg/NodeEntitiesInfo")):
    node_namespace: t.bounded_str[256] = ""
    node_name: t.bounded_str[256] = ""
    reader_gid_seq: t.sequence[Gid] = field(default_factory=list)
    writer_gid_seq: t.sequence[Gid] = field(default_factory=list)


@_message
class ParticipantEntitiesInfo(IdlStruct, typename=dds_type_name("rmw_dds_common/msg/ParticipantEntitiesInfo")):
    gid: Gid = field(default_factory=Gid)
    node_entities_info_seq: t.sequence[NodeEntitiesInfo] = field(default_factory=list)


# Humble's: the same names, a 24-byte Gid (the 16-byte GUID, then zeros). Not in TYPES (its names are Jazzy's).

@dataclasses.dataclass
class HumbleGid(IdlStruct, typename=dds_type_name("rmw_dds_common/msg/Gid")):
    data: t.array[t.uint8, 24] = bytes(24)


@dataclasses.dataclass
class HumbleNodeEntitiesInfo(IdlStruct, typename=dds_type_name("rmw_dds_common/msg/NodeEntitiesInfo")):
    node_namespace: t.bounded_str[256] = ""
    node_name: t.bounded_str[256] = ""
    reader_gid_seq: t.sequence[HumbleGid] = field(default_factory=list)
    writer_gid_seq: t.sequence[HumbleGid] = field(default_factory=list)


@dataclasses.dataclass
class HumbleParticipantEntitiesInfo(IdlStruct, typename=dds_type_name("rmw_dds_common/msg/ParticipantEntitiesInfo")):
    gid: HumbleGid = field(default_factory=HumbleGid)
    node_entities_info_seq: t.sequence[HumbleNodeEntitiesInfo] = field(default_factory=list)


# Per ROS distribution: (Gid, NodeEntitiesInfo, ParticipantEntitiesInfo) and the Gid's size in bytes.
DISCOVERY: Dict[str, Tuple[type, type, type, int]] = {
    "jazzy": (Gid, NodeEntitiesInfo, ParticipantEntitiesInfo, 16),
    "humble": (HumbleGid, HumbleNodeEntitiesInfo, HumbleParticipantEntitiesInfo, 24),
}


# ---- the wire form, and stamps

def to_cdr(message: IdlStruct) -> bytes:
    """The sample as ROS 2 sends it: the encapsulation header ``00 01 00 00`` (CDR, little endian), then XCDR1.

    A DataWriter does this itself when its QoS has ``DataRepresentation(use_cdrv0_representation=True)``
    (cyclonedds then pads the sample to a multiple of 4 bytes, as DDS does)."""
    return message.serialize(use_version_2=False, endianness=Endianness.Little)


def from_cdr(cls: Type[Msg], data: Union[bytes, bytearray, memoryview]) -> Msg:
    """A sample of ``cls`` from its serialized bytes; the header says the representation and byte order."""
    return cls.deserialize(bytes(data))


def split_nanoseconds(nanoseconds: int) -> Tuple[int, int]:
    """(sec, nanosec) with nanosec in [0, 1e9): floor division, as rclpy's ``Time.to_msg`` and ``Duration.to_msg``."""
    sec, nanosec = divmod(int(nanoseconds), NS_PER_S)
    if not _INT32[0] <= sec <= _INT32[1]:
        raise ValueError(f"{nanoseconds} ns is outside builtin_interfaces' int32 seconds")
    return sec, nanosec


def _nanoseconds(seconds: float) -> int:
    # rclpy: ``int(seconds * S_TO_NS)``, a float product truncated toward zero (rclpy/time.py, duration.py)
    if seconds != seconds or seconds in (float("inf"), float("-inf")):
        raise ValueError(f"a time must be a finite number of seconds, not {seconds}")
    return int(seconds * NS_PER_S)


def stamp(seconds: float) -> Time:
    """``builtin_interfaces/Time`` for float seconds, the values rclpy's ``Time(seconds=s).to_msg()`` gives
    (a negative time, which rclpy refuses, floors: -0.25 s is sec -1, nanosec 750000000)."""
    return Time(*split_nanoseconds(_nanoseconds(seconds)))


def stamp_ns(nanoseconds: int) -> Time:
    """``builtin_interfaces/Time`` for integer nanoseconds (exact; a simulated clock counted in ns)."""
    return Time(*split_nanoseconds(nanoseconds))


def duration(seconds: float) -> Duration:
    """``builtin_interfaces/Duration`` for float seconds, as rclpy's ``Duration(seconds=s).to_msg()``."""
    return Duration(*split_nanoseconds(_nanoseconds(seconds)))


def seconds(time: Union[Time, Duration]) -> float:
    """Float seconds of a Time or Duration."""
    return time.sec + time.nanosec / NS_PER_S
