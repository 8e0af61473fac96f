"""Where a TurtleBot3 may spawn in a scene.

The spawn point of a world file is chosen inside its room: walls and obstacles are sliced in the robot's height
band (:data:`SLICE_Z`), the free areas the walls close are found (the room holding the building's centre first),
and the centre of the largest circle inside it is taken. An explicit spawn inside a wall, closer to one than the
robot's radius (:data:`ROBOT_RADIUS`), or outside the room is refused.

Heavy modules (shapely, the SDF reader) are imported when first used.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Sequence

from ..core.errors import InputError
from ..core.spawnpose import Pose
from ..core.numbers import format_number
from .disc_space import obstacle_union
from .slices import footprints_between

# Radius of the disc that holds each robot's footprint around base_footprint: the farthest corner of the ROBOTIS
# navigation footprint (burger x -0.105…0.041, y ±0.105; waffle and waffle_pi x -0.205…0.077, y ±0.155). Both
# hold the robot's collision shapes (the burger's base box reaches 0.124 m, the waffle's 0.238 m), so a robot
# spawned this far from a wall can turn in place there.
ROBOT_RADIUS = {"burger": math.hypot(0.105, 0.105), "waffle": math.hypot(0.205, 0.155),
                "waffle_pi": math.hypot(0.205, 0.155)}
# The height band a TurtleBot3 occupies, where walls and obstacles are sliced: above a floor slab (Gazebo's
# asphalt_plane is a 0.1 m box half sunk into the ground; the validator counts slabs up to 0.1 m as floor) and up
# to the top of a burger (0.192 m) with some room.
SLICE_Z = (0.11, 0.3)


def robot_radius(model: str) -> float:
    """:data:`ROBOT_RADIUS` of a model name; a burger's for anything else (``env``, a description file)."""
    return ROBOT_RADIUS.get(model, ROBOT_RADIUS["burger"])


@dataclass(frozen=True)
class Rooms:
    """The free floor of a world in the robot's height band.

    ``free`` are the connected free areas (walls and obstacles cut out), largest first; ``closed`` says which of
    them the walls close (the free area does not reach the outside, as for the validator's ``enclosed`` check);
    ``centre`` is the centre of the walls' bounding box (the building's origin, as the Building Editor writes
    it; None when nothing stands in the band); ``blocked`` is the walls' and obstacles' footprint; ``radius``
    the robot's.
    """

    free: tuple             # shapely Polygons
    closed: tuple[bool, ...]
    centre: tuple[float, float] | None
    blocked: object         # shapely geometry
    radius: float

    def fits(self, region) -> bool:
        """Whether a robot of :attr:`radius` fits somewhere in ``region`` (one of :attr:`free`). A region whose
        bounds are narrower than the robot either way holds no disc of it (a noisy grid's thousands of pockets
        are told so without shrinking each)."""
        x0, y0, x1, y1 = region.bounds
        if min(x1 - x0, y1 - y0) < 2 * self.radius:
            return False
        return not region.buffer(-self.radius, quad_segs=8).is_empty

    def rooms(self) -> list:
        """The closed free areas the robot fits in, largest first."""
        return [p for p, c in zip(self.free, self.closed) if c and self.fits(p)]


def world_rooms(scene, radius: float = ROBOT_RADIUS["burger"]) -> Rooms:
    """Slice ``scene`` (a :class:`worldgen.core.scene.Scene`) in the robot's height band (:data:`SLICE_Z`) and find
    its free areas and which of them are closed rooms."""
    import shapely

    prints = footprints_between(scene, *SLICE_Z)
    if not prints:
        return Rooms((), (), None, shapely.Polygon(), radius)
    blocked = obstacle_union(prints)
    xmin, ymin, xmax, ymax = blocked.bounds
    margin = 2 * radius + 1.0
    frame = shapely.box(xmin - margin, ymin - margin, xmax + margin, ymax + margin)
    parts = sorted(_polygons(frame.difference(blocked)), key=lambda p: (-p.area, p.bounds))
    closed = tuple(p.exterior.distance(frame.exterior) > 1e-6 for p in parts)
    return Rooms(tuple(parts), closed, ((xmin + xmax) / 2, (ymin + ymax) / 2), blocked, radius)


def deepest_point(rooms: Rooms) -> tuple[float, float] | None:
    """The centre of the largest circle inside the room holding the building's centre (else inside the largest
    room), rounded to the centimetre. A world without a closed room: the same inside the walls' bounding box,
    else the free point nearest the centre. None when nothing stands in the robot's band."""
    import shapely
    from shapely.ops import nearest_points, polylabel

    if rooms.centre is None:
        return None
    centre = shapely.Point(rooms.centre)
    candidates = rooms.rooms()
    if not candidates:
        inside = shapely.box(*rooms.blocked.bounds)
        candidates = [p for p in sorted(_polygons(shapely.union_all(list(rooms.free)).intersection(inside)),
                                        key=lambda p: (-p.area, p.bounds)) if rooms.fits(p)]
    if candidates:
        region = next((p for p in candidates if p.covers(centre)), candidates[0])
        point = polylabel(region, tolerance=0.002)
    else:   # no room and no space inside the walls' bounds: the free point nearest the centre (1 cm to spare)
        region = shapely.union_all(list(rooms.free)).buffer(-(rooms.radius + 0.01), quad_segs=8)
        if region.is_empty:
            return None
        point = nearest_points(centre, region)[1]
    rounded = shapely.Point(round(point.x, 2), round(point.y, 2))
    if rooms.blocked.distance(rounded) >= rooms.radius and region.covers(rounded):
        point = rounded
    return (point.x + 0.0, point.y + 0.0)


def room_points(rooms: Rooms, most: int | None = None, regions: list | None = None) -> list[tuple[float, float]]:
    """The deepest free point (centre of the largest inscribed circle, to the centimetre where that still
    fits) of every closed room the robot fits in (of the ``most`` largest), largest room first; [] when the world
    has none. ``regions``: ``rooms.rooms()``, when known."""
    import shapely
    from shapely.ops import polylabel

    points = []
    for region in (rooms.rooms() if regions is None else regions)[:most]:
        point = polylabel(region, tolerance=0.002)
        x, y = round(point.x, 2) + 0.0, round(point.y, 2) + 0.0
        rounded = shapely.Point(x, y)
        if not (rooms.blocked.distance(rounded) >= rooms.radius and region.covers(rounded)):
            x, y = point.x + 0.0, point.y + 0.0
        points.append((x, y))
    return points


def spawn_problem(rooms: Rooms, x: float, y: float) -> str | None:
    """Why a robot cannot spawn at (x, y) — inside a wall or obstacle, closer to one than its radius, outside
    every closed room of a world that has one — or None when it can."""
    import shapely

    if rooms.centre is None:
        return None
    point = shapely.Point(x, y)
    if rooms.blocked.covers(point):
        return "it is inside a wall or an obstacle"
    rooms_here = rooms.rooms()
    if rooms_here and not any(p.covers(point) for p in rooms_here):
        return "it is outside the room" if len(rooms_here) == 1 else "it is outside every room of the world"
    clearance = rooms.blocked.distance(point)
    if clearance < rooms.radius:
        return (f"it is {clearance:.2f} m from a wall or obstacle, and the robot reaches {rooms.radius:.3f} m "
                "from its centre")
    return None


def spawn_in_scene(scene, model: str = "env", spawn: Sequence[float] | None = None, **how) -> Pose:
    """:func:`checked_spawn` for a :class:`worldgen.core.scene.Scene` and a robot model (``how``: its keywords)."""
    return checked_spawn(world_rooms(scene, robot_radius(model)), spawn, **how)


def checked_spawn(rooms: Rooms, spawn: Sequence[float] | None, *, source: str | Path | None = None,
                  what: str = "--spawn",
                  hint: str = "choose a free point inside the room (or leave --spawn out to get one)") -> Pose:
    """``spawn`` (x, y[, z[, yaw]]) as a full pose when the robot may spawn there (InputError naming ``what``,
    with ``hint``, otherwise), or, when None, the :func:`deepest_point` (InputError when the robot fits
    nowhere)."""
    if spawn is not None:
        pose = tuple(float(v) for v in spawn) + (0.0,) * (4 - len(spawn))
        problem = spawn_problem(rooms, pose[0], pose[1])
        if problem:
            raise InputError(f"{what} ({format_number(pose[0])}, {format_number(pose[1])}) is no place for the "
                             f"robot: {problem}", path=source, hint=hint)
        return pose
    point = deepest_point(rooms)
    if point is None:
        if rooms.centre is None:   # nothing stands in the robot's way: anywhere will do
            return (0.0, 0.0, 0.0, 0.0)
        raise InputError("the robot fits nowhere in this world", path=source, hint="pass --spawn X,Y")
    return (point[0], point[1], 0.0, 0.0)


def _polygons(geometry) -> list:
    if geometry.is_empty:
        return []
    if geometry.geom_type == "Polygon":
        return [geometry]
    return [g for g in getattr(geometry, "geoms", []) if g.geom_type == "Polygon" and not g.is_empty]

