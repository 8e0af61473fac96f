"""The robot interface's message values (:mod:`worldgen.interface`: nested dicts, times as float seconds) as rospy
messages: ROS 1 spells a few fields otherwise (CameraInfo's ``D``, ``K``, ``R``, ``P``) and times as
``rospy.Time``."""

from __future__ import annotations

UPPER = {"d": "D", "k": "K", "r": "R", "p": "P"}   # sensor_msgs/CameraInfo's ROS 1 names
TIMES = ("stamp", "clock")
_SLOTS: dict = {}   # message class → {field: type}: the same for every message of a class


def ros1_type(name: str) -> str:
    """``sensor_msgs/msg/LaserScan`` → ``sensor_msgs/LaserScan``."""
    return name.replace("/msg/", "/")


def message_class(name: str):
    """The rospy class of a ROS type name (either spelling)."""
    package, _, msg = ros1_type(name).partition("/")
    module = __import__(f"{package}.msg", fromlist=[msg])
    return getattr(module, msg)


def ros_time(rospy, seconds: float):
    """``rospy.Time`` of simulated ``seconds``, to the nearest nanosecond (``Time.from_sec`` truncates: 1.2 s would
    be 1.199999999 s, short of a ``rospy.Rate`` deadline at 1.2 s, which then waits for the next clock)."""
    return rospy.Time(0, round(seconds * 1e9))


def fill(msg, values: dict, rospy):
    """Set ``values`` on the rospy message ``msg`` (nested messages filled in place; lists of dicts become lists
    of the field's element type); returns ``msg``."""
    slots = _SLOTS.get(type(msg))
    if slots is None:
        slots = _SLOTS[type(msg)] = dict(zip(msg.__slots__, msg._slot_types))
    for key, value in values.items():
        name = UPPER.get(key, key) if key not in slots else key
        if isinstance(value, dict):
            fill(getattr(msg, name), value, rospy)
        elif name in TIMES:
            setattr(msg, name, ros_time(rospy, value))
        elif isinstance(value, list) and value and isinstance(value[0], dict):
            element = message_class(slots[name].rstrip("[]"))
            setattr(msg, name, [fill(element(), v, rospy) for v in value])
        else:
            setattr(msg, name, value)
    return msg
