"""The robot's spawn pose as worldgen passes it around, and the one reader of ``--spawn`` values."""

from __future__ import annotations

import math
from typing import Tuple

from .errors import InputError

Pose = Tuple[float, float, float, float]   # x, y, z, yaw
_SPAWN_HINTS = {   # --spawn forms → how to write them (see parse_spawn)
    True: "write --spawn X,Y or X,Y,Z or X,Y,Z,YAW in metres and radians, e.g. --spawn 1.0,-0.5,0,1.57",
    False: "write --spawn X,Y or X,Y,YAW in metres and radians, e.g. --spawn -5.5,-1.0,1.57",
}


def parse_spawn(text: str, z: bool = False) -> tuple[float, ...]:
    """A ``--spawn`` value (metres, radians) → pose; InputError (with the forms to write) for anything else.

    ``z`` (``worldgen launch``, which writes a launch file's pose): ``X,Y[,Z[,YAW]]`` → (x, y, z, yaw).
    Otherwise (validate, drive, preview: the robot stands on the floor): ``X,Y[,YAW]`` → (x, y, yaw); a launch
    file's ``X,Y,Z,YAW`` is taken too, its Z dropped.
    """
    parts = [p.strip() for p in text.split(",")]
    try:
        values = [float(p) for p in parts]
    except ValueError:
        values = []
    if len(values) not in (2, 3, 4) or not all(math.isfinite(v) for v in values):
        raise InputError(f"bad --spawn value {text!r}", hint=_SPAWN_HINTS[z])
    if z:
        values += [0.0] * (4 - len(values))
        return (values[0], values[1], values[2], values[3])
    if len(values) == 4:
        values = [values[0], values[1], values[3]]
    return (values[0], values[1], values[2] if len(values) == 3 else 0.0)
