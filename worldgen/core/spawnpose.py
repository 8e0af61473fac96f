"""The robot's spawn pose as worldgen passes it around, and the one reader of ``--spawn`` values."""

from __future__ import annotations

import math
from typing import Tuple

from .errors import InputError

Pose = Tuple[float, float, float, float]   # x, y, z, yaw
SPAWN_FORMS = "X,Y[,YAW]"
MAX_SPAWN_DISTANCE = 1e6   # m: as far from the origin as worldgen places anything (1000 km)
_HINT = ("write --spawn X,Y or X,Y,YAW in metres and radians (the robot stands on the floor), "
         "e.g. --spawn -5.5,-1.0,1.57")


def parse_spawn(text: str) -> tuple[float, float, float]:
    """A ``--spawn`` value → (x, y, yaw): ``X,Y[,YAW]`` in metres and radians, the same in every command (the
    robot stands on the floor, so there is no z). InputError (with the form to write) for anything else: not
    two or three numbers, a number that is not finite, X or Y past 1000 km, or a yaw beyond ±2π (probably
    degrees)."""
    parts = [p.strip() for p in str(text).split(",")]
    try:
        values = [float(p) for p in parts]
    except ValueError:
        raise InputError(f"bad --spawn value {text!r}: {SPAWN_FORMS} must be numbers", hint=_HINT) from None
    if len(values) not in (2, 3):
        extra = ", and there is no Z" if len(values) == 4 else ""
        raise InputError(f"bad --spawn value {text!r}: {len(values)} numbers, not 2 or 3{extra}", hint=_HINT)
    if not all(math.isfinite(v) for v in values):
        raise InputError(f"bad --spawn value {text!r}: every number must be finite", hint=_HINT)
    if max(abs(values[0]), abs(values[1])) > MAX_SPAWN_DISTANCE:
        raise InputError(f"bad --spawn value {text!r}: X and Y must be within {MAX_SPAWN_DISTANCE / 1000:g} km of the "
                         "origin", hint=_HINT)
    yaw = values[2] if len(values) == 3 else 0.0
    if abs(yaw) > 2 * math.pi:
        raise InputError(f"bad --spawn yaw {format(yaw, 'g')}: more than 2π, so probably degrees",
                         hint=f"write the yaw in radians, e.g. {format(math.radians(yaw), '.4g')} for "
                              f"{format(yaw, 'g')}°")
    return (values[0], values[1], yaw)


def floor_pose(spawn: tuple[float, float, float]) -> Pose:
    """(x, y, yaw) → the (x, y, z, yaw) a launch file writes: z 0, on the floor."""
    return (spawn[0], spawn[1], 0.0, spawn[2])


def plan_pose(pose) -> tuple[float, float, float] | None:
    """A launch file's pose (x, y, z, yaw; missing values 0) → (x, y, yaw); None stays None."""
    if pose is None:
        return None
    values = list(pose) + [0.0] * (4 - len(pose))
    return (float(values[0]), float(values[1]), float(values[3]))
