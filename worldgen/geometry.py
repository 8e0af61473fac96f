"""Geometry: a spec's rooms and segments become straight walls, each a set of boxes.

``build_geometry(spec)`` joins corners (no gap, no spike, whatever the angle), writes a wall shared by two rooms
once, and splits a wall around its openings the way the Building Editor does (pieces beside an opening, a lintel
above it, a sill below a window). Everything here is plain numbers; writers turn it into files.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from .spec import Material, Obstacle, Point, RobotPose


@dataclass(frozen=True)
class Piece:
    """One box of a wall, in the wall's own frame: ``s0..s1`` along the wall from its start point, ``z0..z1`` up.
    Its thickness is the wall's."""

    s0: float
    s1: float
    z0: float
    z1: float


@dataclass(frozen=True)
class PlacedOpening:
    """An opening on a built wall: ``s0..s1`` along the wall from its start point, ``z0..z1`` up."""

    type: str
    s0: float
    s1: float
    z0: float
    z1: float


@dataclass(frozen=True)
class Wall:
    """A straight wall. ``start``/``end`` are the ends of its boxes' centre-line (joins included), so its length
    is the box length of an unsplit wall."""

    index: int
    start: Point
    end: Point
    thickness: float
    height: float
    material: Material
    pieces: tuple[Piece, ...]
    openings: tuple[PlacedOpening, ...] = ()
    rooms: tuple[str, ...] = ()

    @property
    def length(self) -> float:
        return math.dist(self.start, self.end)

    @property
    def yaw(self) -> float:
        return math.atan2(self.end[1] - self.start[1], self.end[0] - self.start[0])


@dataclass(frozen=True)
class Building:
    name: str
    walls: tuple[Wall, ...]
    obstacles: tuple[Obstacle, ...]
    robot: RobotPose | None
    origin: Point          # the bounding-box centre of the walls: the model pose, as the Building Editor writes it
    bounds: tuple[float, float, float, float]   # xmin, ymin, xmax, ymax of everything built
