"""Plane vectors as (x, y) tuples, and the few shapes the building's geometry is made of: a wall's rectangle, a
bounding box, an overlap test of convex polygons, and a grid of cells for near-neighbour queries. Plain numbers,
nothing imported."""

from __future__ import annotations

import math
from typing import Tuple

Point = Tuple[float, float]


def sub(a: Point, b: Point) -> Point:
    return (a[0] - b[0], a[1] - b[1])


def add(a: Point, b: Point, k: float = 1.0) -> Point:
    return (a[0] + k * b[0], a[1] + k * b[1])


def dot(a: Point, b: Point) -> float:
    return a[0] * b[0] + a[1] * b[1]


def cross(a: Point, b: Point) -> float:
    return a[0] * b[1] - a[1] * b[0]


def left_normal(u: Point) -> Point:
    return (-u[1], u[0])


def unit(a: Point, b: Point) -> Point:
    length = math.dist(a, b)
    return ((b[0] - a[0]) / length, (b[1] - a[1]) / length)


def meet(p: Point, d: Point, q: Point, e: Point) -> tuple[float, float] | None:
    """(λ, μ) with p + λ·d = q + μ·e, or None for parallel lines."""
    den = cross(d, e)
    if abs(den) < 1e-12:
        return None
    w = sub(q, p)
    return cross(w, e) / den, cross(w, d) / den


def rectangle(start: Point, end: Point, thickness: float) -> tuple[Point, Point, Point, Point]:
    n = left_normal(unit(start, end)) if start != end else (0.0, 1.0)
    h = thickness / 2
    return (add(start, n, -h), add(end, n, -h), add(end, n, h), add(start, n, h))


def bbox(points, pad: float = 0.0) -> tuple[float, float, float, float]:
    xs = [p[0] for p in points]
    ys = [p[1] for p in points]
    return min(xs) - pad, min(ys) - pad, max(xs) + pad, max(ys) + pad


def overlap(a, b) -> bool:
    """Whether two convex polygons (corner lists) overlap with positive area (separating axis test)."""
    for poly in (a, b):
        for i, p in enumerate(poly):
            q = poly[(i + 1) % len(poly)]
            axis = left_normal(sub(q, p))
            pa = [dot(axis, v) for v in a]
            pb = [dot(axis, v) for v in b]
            if max(pa) <= min(pb) or max(pb) <= min(pa):
                return False
    return True


class CellGrid:
    """A uniform grid of cells holding items by their bounding boxes, for near-neighbour queries."""

    def __init__(self, cell: float):
        self.cell = cell
        self.cells: dict[tuple[int, int], list[int]] = {}

    def _keys(self, box: tuple[float, float, float, float]):
        c = self.cell
        for i in range(math.floor(box[0] / c), math.floor(box[2] / c) + 1):
            for j in range(math.floor(box[1] / c), math.floor(box[3] / c) + 1):
                yield i, j

    def add(self, item: int, box: tuple[float, float, float, float]) -> None:
        for key in self._keys(box):
            self.cells.setdefault(key, []).append(item)

    def near(self, box: tuple[float, float, float, float]) -> list[int]:
        found: set[int] = set()
        for key in self._keys(box):
            found.update(self.cells.get(key, ()))
        return sorted(found)
