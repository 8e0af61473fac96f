"""The robot interface's message values (:mod:`worldgen.interface`: nested dicts in ROS 2's field names, times as
float seconds) as the DDS samples of :mod:`.msgs`, and a velocity command back as (v, ω)."""

from __future__ import annotations

import dataclasses
from typing import Any, Dict, Type

from . import msgs

TIMES = ("stamp", "clock")
ELEMENTS = {"transforms": msgs.TransformStamped}   # the sequences of messages among the robot's fields
_FIELDS: Dict[type, Dict[str, Any]] = {}


def _fields(cls: type) -> Dict[str, Any]:
    found = _FIELDS.get(cls)
    if found is None:
        found = _FIELDS[cls] = {f.name: f.type for f in dataclasses.fields(cls)}
    return found


def build(cls: Type[Any], values: dict) -> Any:
    """A ``cls`` sample holding ``values`` (numpy arrays become lists, as cyclonedds wants them)."""
    fields = _fields(cls)
    kwargs = {}
    for key, value in values.items():
        if key in TIMES:
            kwargs[key] = msgs.stamp(value)
        elif isinstance(value, dict):
            kwargs[key] = build(fields[key], value)
        elif key in ELEMENTS and isinstance(value, list):
            kwargs[key] = [build(ELEMENTS[key], v) for v in value]
        elif hasattr(value, "tolist") and not isinstance(value, (bytes, bytearray)):
            kwargs[key] = value.tolist() if getattr(value, "ndim", 1) else value.item()
        else:
            kwargs[key] = value
    return cls(**kwargs)


def velocity(sample: Any) -> tuple:
    """(linear x, angular z) of a Twist or a TwistStamped."""
    twist = getattr(sample, "twist", sample)
    return twist.linear.x, twist.angular.z
