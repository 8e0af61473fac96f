"""Plane geometry for the generators, in plain Python: axis-aligned rectangles, convex outlines and circles,
their overlaps and distances, and how far a ray travels before it meets a wall.

No shapely or numpy here: the generators make a world in a few milliseconds and the same bytes everywhere, so
they use only arithmetic whose rounding IEEE 754 fixes (see :mod:`.trig`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Iterable, List, Sequence, Tuple

from .trig import sin_cos

Point = Tuple[float, float]
INF = float("inf")


@dataclass(frozen=True)
class Rect:
    """An axis-aligned rectangle, x0 < x1, y0 < y1."""

    x0: float
    y0: float
    x1: float
    y1: float

    @property
    def width(self) -> float:
        return self.x1 - self.x0

    @property
    def height(self) -> float:
        return self.y1 - self.y0

    @property
    def centre(self) -> Point:
        return ((self.x0 + self.x1) / 2, (self.y0 + self.y1) / 2)

    @property
    def area(self) -> float:
        return self.width * self.height

    def shrunk(self, d: float) -> "Rect":
        return Rect(self.x0 + d, self.y0 + d, self.x1 - d, self.y1 - d)

    def overlaps(self, other: "Rect") -> bool:
        """Whether they share area (touching along an edge does not count)."""
        return self.x0 < other.x1 and other.x0 < self.x1 and self.y0 < other.y1 and other.y0 < self.y1

    def corners(self) -> List[Point]:
        return [(self.x0, self.y0), (self.x1, self.y0), (self.x1, self.y1), (self.x0, self.y1)]

    def gap(self, other: "Rect") -> float:
        """The distance between the two (0 when they touch or overlap)."""
        dx = max(other.x0 - self.x1, self.x0 - other.x1, 0.0)
        dy = max(other.y0 - self.y1, self.y0 - other.y1, 0.0)
        return math.sqrt(dx * dx + dy * dy)


def box_outline(centre: Point, size: Tuple[float, float], yaw: float) -> List[Point]:
    """The corners of a ``size`` box turned by ``yaw`` about ``centre``, counter-clockwise."""
    s, c = sin_cos(yaw)
    hx, hy = size[0] / 2, size[1] / 2
    return [(centre[0] + c * x - s * y, centre[1] + s * x + c * y)
            for x, y in ((-hx, -hy), (hx, -hy), (hx, hy), (-hx, hy))]


def dist(a: Point, b: Point) -> float:
    """The distance between two points (:func:`math.dist` has changed its rounding between Python versions)."""
    dx, dy = a[0] - b[0], a[1] - b[1]
    return math.sqrt(dx * dx + dy * dy)


def point_segment(p: Point, a: Point, b: Point) -> float:
    """The distance from ``p`` to the segment a–b."""
    dx, dy = b[0] - a[0], b[1] - a[1]
    length2 = dx * dx + dy * dy
    t = 0.0 if length2 == 0 else max(0.0, min(1.0, ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / length2))
    ex, ey = a[0] + t * dx - p[0], a[1] + t * dy - p[1]
    return math.sqrt(ex * ex + ey * ey)


def _edges(polygon: Sequence[Point]):
    return [(polygon[i], polygon[(i + 1) % len(polygon)]) for i in range(len(polygon))]


def inside_convex(p: Point, polygon: Sequence[Point]) -> bool:
    """Whether ``p`` is inside (or on) a counter-clockwise convex polygon."""
    return all((b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]) >= 0 for a, b in _edges(polygon))


def _separation(a: Sequence[Point], b: Sequence[Point]) -> float:
    """The widest gap an edge of either convex polygon (counter-clockwise) leaves between them along its normal:
    a lower bound of their distance, and their distance when a face of one is what is nearest the other; at most
    0 when they overlap (the separating axis test)."""
    best = -INF
    for poly, other in ((a, b), (b, a)):
        for p, q in _edges(poly):
            nx, ny = q[1] - p[1], p[0] - q[0]   # outward normal of a counter-clockwise edge
            length = math.sqrt(nx * nx + ny * ny)
            best = max(best, min((v[0] - p[0]) * nx + (v[1] - p[1]) * ny for v in other) / length)
    return best


def convex_distance(a: Sequence[Point], b: Sequence[Point]) -> float:
    """The distance between two counter-clockwise convex polygons (0 when they overlap)."""
    if _separation(a, b) <= 0:
        return 0.0
    return min(min(point_segment(p, *e) for p in a for e in _edges(b)),
               min(point_segment(p, *e) for p in b for e in _edges(a)))


def convex_apart(a: Sequence[Point], b: Sequence[Point], gap: float) -> bool:
    """Whether two counter-clockwise convex polygons are at least ``gap`` apart."""
    return _separation(a, b) >= gap or convex_distance(a, b) >= gap


def convex_circle_distance(polygon: Sequence[Point], centre: Point, radius: float) -> float:
    """The distance between a counter-clockwise convex polygon and a disc (0 when they overlap)."""
    if inside_convex(centre, polygon):
        return 0.0
    return max(0.0, min(point_segment(centre, *e) for e in _edges(polygon)) - radius)


def ray_hit(origin: Point, direction: Point, segments: Iterable[Tuple[Point, Point]]) -> float:
    """How far a ray from ``origin`` along the unit vector ``direction`` goes before it meets one of
    ``segments`` (INF when it meets none)."""
    best = INF
    ox, oy = origin
    dx, dy = direction
    for (ax, ay), (bx, by) in segments:
        ex, ey = bx - ax, by - ay
        denom = dx * ey - dy * ex
        if abs(denom) < 1e-12:
            continue
        t = ((ax - ox) * ey - (ay - oy) * ex) / denom
        u = ((ax - ox) * dy - (ay - oy) * dx) / denom
        if t > 1e-9 and -1e-9 <= u <= 1 + 1e-9:
            best = min(best, t)
    return best


def band_hit(origin: Point, heading: float, half_width: float, segments: Sequence[Tuple[Point, Point]],
             rays: int = 3) -> Tuple[float, float]:
    """How far rays across a band ``2·half_width`` wide, sent from ``origin`` along ``heading``, travel before
    ``segments`` stop them: (the shortest, the longest). A wall square across the band stops them all alike; a
    doorway or a corner in the band lets some go on."""
    s, c = sin_cos(heading)
    hits = []
    for k in range(rays):
        off = -half_width + 2 * half_width * k / (rays - 1)
        start = (origin[0] - s * off, origin[1] + c * off)
        hits.append(ray_hit(start, (c, s), segments))
    return min(hits), max(hits)


def facing(origin: Point, headings: Sequence[float], half_width: float, segments: Sequence[Tuple[Point, Point]],
           near: float, far: float, rng) -> Tuple[float, bool]:
    """A heading from ``headings`` with a wall square across the band ahead (within 0.2 m over the band), between
    ``near`` and ``far`` away: the first such in a random order, and True. When none has: one whose nearest wall
    is in that range, else the one whose nearest wall is closest to halfway between, and False."""
    reach = []
    for yaw in rng.shuffled(headings):
        lo, hi = band_hit(origin, yaw, half_width, segments)
        if near <= lo and hi <= far and hi - lo <= 0.2:
            return yaw, True
        reach.append((yaw, lo))
    middle = (near + far) / 2
    return min(reach, key=lambda item: (not near <= item[1] <= far, abs(item[1] - middle), item[0]))[0], False


def polygon_area(polygon: Sequence[Point]) -> float:
    """The signed area (positive counter-clockwise)."""
    return sum(a[0] * b[1] - b[0] * a[1] for a, b in _edges(polygon)) / 2


def min_edge_distance(polygon: Sequence[Point], p: Point) -> float:
    """The distance from ``p`` to the nearest edge of ``polygon``."""
    return min(point_segment(p, *e) for e in _edges(polygon))


def inside_polygon(p: Point, polygon: Sequence[Point]) -> bool:
    """Whether ``p`` is inside a simple polygon (even-odd rule)."""
    x, y = p
    inside = False
    for (ax, ay), (bx, by) in _edges(polygon):
        if (ay > y) != (by > y) and x < ax + (y - ay) * (bx - ax) / (by - ay):
            inside = not inside
    return inside


def edges_of(polygon: Sequence[Point]) -> List[Tuple[Point, Point]]:
    return _edges(polygon)
