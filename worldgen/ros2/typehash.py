"""Jazzy's type hashes (RIHS01) of our message classes, and the USER_DATA a DDS reader or writer carries them in.

REP 2011 (since Iron): a type's hash is ``RIHS01_`` and the hex SHA-256 of the canonical JSON of its type
description: ``{"type_description": T, "referenced_type_descriptions": [every type T reaches, sorted by name]}``,
each type ``{"type_name": "pkg/msg/Name", "fields": [...]}``, each field ``{"name": ..., "type": {"type_id": ...,
"capacity": ..., "string_capacity": ..., "nested_type_name": ...}}`` in .msg order, written by ``json.dumps`` with
the separators ``", "`` and ``": "`` (rosidl_generator_type_description's ``calculate_type_hash``; default values
are left out). The type ids are type_description_interfaces/msg/FieldType's. Our table is the message classes of
``worldgen.ros2.msgs`` themselves: their cyclonedds annotations say each field's type.

rmw in Jazzy puts ``typehash=<hash>;`` in the USER_DATA QoS of each topic's readers and writers (a service's
request reader and reply writer carry the Request's and the Response's hash); rclpy's graph shows it as the
endpoint's type hash. Humble reads no hash, and ignores the USER_DATA.
"""

from __future__ import annotations

import hashlib
import json
from functools import lru_cache
from typing import Any, Union

from cyclonedds.idl import IdlStruct
from cyclonedds.idl import types as t

from . import msgs

# type_description_interfaces/msg/FieldType: a primitive's id; arrays add 48, bounded sequences 96, unbounded 144.
FIELD_TYPE_NESTED = 1
FIELD_TYPE_STRING = 17
FIELD_TYPE_BOUNDED_STRING = 21
_PRIMITIVE_IDS = {
    "int8": 2, "uint8": 3, "int16": 4, "uint16": 5, "int32": 6, "uint32": 7, "int64": 8, "uint64": 9,
    "float32": 10, "float64": 11, "bool": 15, "byte": 16,   # ROS's char is uint8 (rosidl_adapter), byte is octet
}
_ARRAY, _BOUNDED_SEQUENCE, _UNBOUNDED_SEQUENCE = 48, 96, 144

TypeRef = Union[str, type]


def _class(ros_type: TypeRef) -> type:
    if isinstance(ros_type, type):
        return ros_type
    try:
        return msgs.TYPES[ros_type]
    except KeyError:
        raise KeyError(f"no message class for {ros_type!r}: worldgen.ros2.msgs.TYPES has "
                       f"{', '.join(sorted(msgs.TYPES))}") from None


def _idl_kind(annotation: Any) -> Any:
    """The cyclonedds marker of an annotation: "int32" for ``types.int32``, an array/sequence/bounded_str object,
    or the annotation itself (``str``, ``bool``, a struct class)."""
    metadata = getattr(annotation, "__metadata__", ())
    return metadata[0] if metadata else annotation


def _element_id(annotation: Any) -> tuple[int, int, str]:
    """(type id, string capacity, nested type name) of a single (non-array) field type."""
    kind = _idl_kind(annotation)
    if isinstance(kind, t.bounded_str):
        return FIELD_TYPE_BOUNDED_STRING, kind.max_length, ""
    if kind is str:
        return FIELD_TYPE_STRING, 0, ""
    if kind is bool:
        return _PRIMITIVE_IDS["bool"], 0, ""
    if isinstance(kind, type) and issubclass(kind, IdlStruct):
        return FIELD_TYPE_NESTED, 0, msgs.ros_type_of(kind)
    if isinstance(kind, str) and kind in _PRIMITIVE_IDS:
        return _PRIMITIVE_IDS[kind], 0, ""
    raise TypeError(f"no ROS 2 field type for the annotation {annotation!r}")


def field_type(annotation: Any) -> dict[str, Any]:
    """A field's ``type_description_interfaces/FieldType`` (less its default value) from its annotation."""
    kind = _idl_kind(annotation)
    offset, capacity = 0, 0
    if isinstance(kind, t.array):
        offset, capacity, annotation = _ARRAY, kind.length, kind.subtype
    elif isinstance(kind, t.sequence):
        offset, capacity = (_BOUNDED_SEQUENCE, kind.max_length) if kind.max_length else (_UNBOUNDED_SEQUENCE, 0)
        annotation = kind.subtype
    type_id, string_capacity, nested = _element_id(annotation)
    return {"type_id": offset + type_id, "capacity": capacity, "string_capacity": string_capacity,
            "nested_type_name": nested}


def _fields(cls: type) -> list[tuple[str, Any]]:
    return [(name, annotation) for name, annotation in cls.__annotations__.items() if not name.startswith("_")]


def _nested_classes(cls: type) -> list[type]:
    """The struct classes the fields of ``cls`` hold (alone, or in an array or sequence)."""
    found = []
    for _, annotation in _fields(cls):
        kind = _idl_kind(annotation)
        if isinstance(kind, (t.array, t.sequence)):
            kind = _idl_kind(kind.subtype)
        if isinstance(kind, type) and issubclass(kind, IdlStruct):
            found.append(kind)
    return found


def individual_description(cls: type) -> dict[str, Any]:
    """One type's description: its ROS name and its fields in order."""
    return {"type_name": msgs.ros_type_of(cls),
            "fields": [{"name": name, "type": field_type(annotation)} for name, annotation in _fields(cls)]}


def type_description(ros_type: TypeRef) -> dict[str, Any]:
    """The type and every type it references (by name, sorted), as REP 2011 hashes them."""
    cls = _class(ros_type)
    referenced: dict[str, dict[str, Any]] = {}
    todo = _nested_classes(cls)
    while todo:
        nested = todo.pop()
        name = msgs.ros_type_of(nested)
        if name not in referenced:
            referenced[name] = individual_description(nested)
            todo.extend(_nested_classes(nested))
    return {"type_description": individual_description(cls),
            "referenced_type_descriptions": [referenced[name] for name in sorted(referenced)]}


@lru_cache(maxsize=None)
def _hash_of(cls: type) -> str:
    text = json.dumps(type_description(cls), ensure_ascii=True, allow_nan=False, indent=None,
                      separators=(", ", ": "), sort_keys=False)
    return "RIHS01_" + hashlib.sha256(text.encode("utf-8")).hexdigest()


def type_hash(ros_type: TypeRef) -> str:
    """``RIHS01_<64 hex>``: Jazzy's hash of a ROS type name (``sensor_msgs/msg/LaserScan``) or message class."""
    return _hash_of(_class(ros_type))


def user_data(ros_type: TypeRef) -> bytes:
    """The USER_DATA QoS value of a reader or writer of that type: ``b"typehash=RIHS01_<hex>;"``."""
    return f"typehash={type_hash(ros_type)};".encode("ascii")
