"""Furniture along a room's walls that never cuts a way through the room.

Each side of the room's floor gets a band (at most :data:`MAX_BAND` deep) where furniture may stand; what is left
in the middle is the *core*, at least two turning clearances across, so the robot can turn anywhere on it and
pass between anything on opposite sides. A band is kept shallower than the distance from its wall to any door
in the sides beside it, so every door opens straight onto the core, and a *door zone* in front of each door
(the door's width plus 0.1 m either side, as deep as its band) stays empty. The core and the door zones are free
and overlap, so every door of the room is reachable from every other and from a spawn on the core, whatever
stands in the bands: that is the "every room reachable" of ``generate rooms``, by construction.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import List, Sequence, Tuple

from ..spec.model import Material, Obstacle
from .rng import Rng
from .shapes import Rect

MAX_BAND = 0.9        # m: the deepest band (a sofa or a single bed along a wall)
ZONE_SIDE = 0.1       # m: a door zone is this much wider than its door on each side
WALL_GAP = 0.02       # m: furniture stands this far off its wall
TRIES = 8             # placements tried per piece


@dataclass(frozen=True)
class Piece:
    """A kind of furniture: ``along`` its wall, ``depth`` away from it, ``height``; a cylinder when ``round``."""

    name: str
    along: float
    depth: float
    height: float
    material: str = "Gazebo/Wood"
    round: bool = False


CATALOGUE = (
    Piece("sofa", 1.8, 0.85, 0.8, "Gazebo/Grey"), Piece("bed", 1.9, 0.9, 0.5, "Gazebo/White"),
    Piece("desk", 1.2, 0.6, 0.75), Piece("table", 1.2, 0.8, 0.75), Piece("shelf", 0.9, 0.35, 1.8),
    Piece("wardrobe", 1.0, 0.6, 2.0), Piece("cabinet", 0.8, 0.45, 0.9),
    Piece("plant", 0.4, 0.4, 0.9, "Gazebo/Green", round=True), Piece("bin", 0.3, 0.3, 0.5, "Gazebo/Grey", round=True),
)

# The sides of a room's floor, as a rect's walls are numbered: 0 bottom (y0), 1 right (x1), 2 top (y1), 3 left (x0).
SIDES = (0, 1, 2, 3)


@dataclass(frozen=True)
class DoorSpan:
    """A door on side ``side`` of a room's floor, from ``start`` to ``end`` along that side's axis (x for sides 0
    and 2, y for 1 and 3), in world coordinates."""

    side: int
    start: float
    end: float


def bands(floor: Rect, doors: Sequence[DoorSpan], core_min: float) -> Tuple[float, float, float, float]:
    """How deep each side's band may be: at most :data:`MAX_BAND`, leaving ``core_min`` across the middle, and
    short of every door in the two sides beside it (by the door zone's margin)."""
    depth = []
    for side in SIDES:
        across = floor.height if side in (0, 2) else floor.width
        d = min(MAX_BAND, (across - core_min) / 2)
        for door in doors:
            if door.side in (side, (side + 2) % 4):
                continue
            # distance from this side's wall to the door's near edge, along the door's side
            if side == 0:
                reach = door.start - floor.y0
            elif side == 2:
                reach = floor.y1 - door.end
            elif side == 3:
                reach = door.start - floor.x0
            else:
                reach = floor.x1 - door.end
            d = min(d, reach - ZONE_SIDE)
        depth.append(max(0.0, round(d, 3)))
    return tuple(depth)


def core(floor: Rect, depth: Sequence[float]) -> Rect:
    return Rect(floor.x0 + depth[3], floor.y0 + depth[0], floor.x1 - depth[1], floor.y1 - depth[2])


def door_zones(floor: Rect, doors: Sequence[DoorSpan], depth: Sequence[float]) -> List[Rect]:
    zones = []
    for door in doors:
        a, b = door.start - ZONE_SIDE, door.end + ZONE_SIDE
        d = depth[door.side] + 0.01
        zones.append({0: Rect(a, floor.y0, b, floor.y0 + d), 2: Rect(a, floor.y1 - d, b, floor.y1),
                      3: Rect(floor.x0, a, floor.x0 + d, b), 1: Rect(floor.x1 - d, a, floor.x1, b)}[door.side])
    return zones


def _footprint(floor: Rect, side: int, piece: Piece, at: float) -> Rect:
    """The piece against side ``side``, starting ``at`` along it (world coordinate)."""
    g, along, deep = WALL_GAP, piece.along, piece.depth
    if side == 0:
        return Rect(at, floor.y0 + g, at + along, floor.y0 + g + deep)
    if side == 2:
        return Rect(at, floor.y1 - g - deep, at + along, floor.y1 - g)
    if side == 3:
        return Rect(floor.x0 + g, at, floor.x0 + g + deep, at + along)
    return Rect(floor.x1 - g - deep, at, floor.x1 - g, at + along)


def furnish(room: str, floor: Rect, doors: Sequence[DoorSpan], core_min: float, count: int, rng: Rng
            ) -> Tuple[List[Obstacle], Rect]:
    """Up to ``count`` pieces along the walls of the room whose free floor (wall faces) is ``floor``, and the core
    they leave free."""
    depth = bands(floor, doors, core_min)
    zones = door_zones(floor, doors, depth)
    placed: List[Rect] = []
    obstacles: List[Obstacle] = []
    used: dict = {}
    for _ in range(count):
        for _ in range(TRIES):
            piece, side = rng.choice(CATALOGUE), rng.choice(SIDES)
            if piece.depth + WALL_GAP > depth[side]:
                continue
            low, high = (floor.x0, floor.x1) if side in (0, 2) else (floor.y0, floor.y1)
            at = rng.step(low + WALL_GAP, high - WALL_GAP - piece.along, 0.01)
            if at + piece.along > high - WALL_GAP + 1e-9:
                continue
            box = _rounded(_footprint(floor, side, piece, at))
            if any(box.overlaps(other) for other in placed + zones):
                continue
            placed.append(box)
            used[piece.name] = used.get(piece.name, 0) + 1
            obstacles.append(_obstacle(f"{room}_{piece.name}_{used[piece.name]}", piece, box, side))
            break
    return obstacles, core(floor, depth)


def _rounded(r: Rect) -> Rect:
    return Rect(round(r.x0, 3), round(r.y0, 3), round(r.x1, 3), round(r.y1, 3))


def _obstacle(name: str, piece: Piece, box: Rect, side: int) -> Obstacle:
    centre = (round(box.centre[0], 3), round(box.centre[1], 3))
    material = Material(piece.material)
    if piece.round:
        return Obstacle("cylinder", centre, radius=round(piece.along / 2, 3), height=piece.height,
                        material=material, name=name)
    size = (piece.along, piece.depth) if side in (0, 2) else (piece.depth, piece.along)
    return Obstacle("box", centre, size=(size[0], size[1], piece.height), material=material, name=name)
