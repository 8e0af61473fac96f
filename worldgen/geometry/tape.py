"""A line of tape laid on the floor as boxes and discs: a thin box along each segment, a disc as wide as the tape
at each joint. The discs round every corner, so the pieces together cover the polyline grown by half the width
(round joins, flat ends) with no gap at any angle, and a loop has none where it closes.

Plain numbers, no shapely: the writer (:mod:`worldgen.sdf.writer`) turns the pieces into ``<visual>`` boxes and
cylinders; the tests compare their union with shapely's buffer of the polyline.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import List, Sequence, Tuple

Point = Tuple[float, float]

LAYER = 0.00001        # m: each marking lies this much above the one before, so overlapping ones never flicker
THICKNESS = 0.001      # m: how thick a marking is (its top is what a camera sees)


@dataclass(frozen=True)
class Strip:
    """The box along one segment: its centre, length and heading (the tape's width across it)."""

    center: Point
    length: float
    yaw: float


def tape_pieces(points: Sequence[Point], closed: bool) -> Tuple[List[Strip], List[Point]]:
    """The strips along the segments of the polyline ``points`` (the last point joined to the first when
    ``closed``) and the joints where a disc goes: every point of a loop, the inner points of an open line (its
    ends stay square, as tape is cut)."""
    count = len(points) if closed else len(points) - 1
    strips = []
    for i in range(count):
        (ax, ay), (bx, by) = points[i], points[(i + 1) % len(points)]
        strips.append(Strip(((ax + bx) / 2, (ay + by) / 2), math.hypot(bx - ax, by - ay), math.atan2(by - ay, bx - ax)))
    joints = list(points) if closed else list(points[1:-1])
    return strips, joints


def layer_bottom(index: int) -> float:
    """The height of the bottom of marking ``index`` (patches first, then lines, in spec order)."""
    return index * LAYER
