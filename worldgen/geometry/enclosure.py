"""Is the robot's spawn point inside a closed room, and if not, where is the way out?

The scene is sliced by a horizontal plane at the robot's LiDAR height into 2-D footprints (boxes exactly at any
orientation, cylinders and spheres as circles, meshes by their triangle/plane section), which are united with a
0.5 mm buffer so that sub-millimetre slivers between walls count as closed. The spawn is enclosed when its
free-space component does not reach the outside (a frame well beyond everything).

When it does reach the outside, the ways out are measured with discs: a disc of radius ``r`` passes an opening
exactly when the opening is wider than ``2·r``, whatever the walls' thickness. Where a disc's centre can be is
the free space shrunk by ``r``; the smallest ``r`` at which no outside disc can cover the spawn any more is half
the widest way out. Just below that radius the spawn's side and the outside are joined by a thin channel of
centre space, the neck: the nearest wall points on either side of it are the gap's ends, their midpoint is where
the gap is and their distance its width. Where no disc of that radius fits round the spawn at all (a corridor open
at its end, a room missing a wall), the neck is where the channel of slightly smaller discs that reach the spawn
opens into the outside: the corridor's end, between the walls' ends, however far away. A neck that is itself a long
corridor (the spawn at the bend of an open L) is named at its open end too. A spawn in a corner, which only small
discs reach whatever the room's way out, is searched from the nearest point deeper in the room instead. When the
far side of a neck is itself a region closed at a larger scale (the space behind a free-standing partition, say),
the search follows that region's way out instead, which is the door a person would name. The gap is then closed
with a thin bar and the search repeats, listing further ways out, widest first.

Plain numbers in, plain numbers out: no pybullet here, only numpy and shapely (imported when first used).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..core.scene import Scene
from .disc_space import MANY_SHAPES, MAX_GAP, WIDTH_TOLERANCE, Space, components, obstacle_union, reaches_outside
from .slices import SLIVER, Footprint, footprints

MARGIN = 1.0           # the "outside" frame lies this far beyond the scene and the spawn
MAX_SEARCH = 200.0     # … but never wider than this (m): beyond it the walls do not surround the spawn
MAX_GAP_ROUNDS = 6     # gaps listed at most (then: "there may be more")


@dataclass(frozen=True)
class Gap:
    """A way out: ``centre`` and ``ends`` in world coordinates (m), ``width`` the distance between the ends,
    ``between`` the labels of the shapes on either side."""

    centre: tuple[float, float]
    width: float
    ends: tuple[tuple[float, float], tuple[float, float]]
    between: tuple[str, ...] = ()

    def to_dict(self) -> dict:
        return {"centre": [round(c, 3) for c in self.centre], "width": round(self.width, 3),
                "ends": [[round(c, 3) for c in e] for e in self.ends], "between": list(self.between)}


@dataclass(frozen=True)
class Enclosure:
    """What the slice says about the spawn point.

    ``enclosed`` is None when the spawn is inside a shape or within :data:`SLIVER` of one (``inside`` names the
    nearest). ``has_walls`` is False when nothing at all is cut by the slicing plane. ``region_area``/
    ``region_bounds`` describe the free region around the spawn when it is enclosed. ``nearest`` is the distance
    from the spawn to the nearest footprint. ``rooms`` are the bounds (xmin, ymin, xmax, ymax) of closed regions
    elsewhere, nearest first, when the spawn is not enclosed (where it probably should have been).
    """

    spawn: tuple[float, float]
    height: float
    enclosed: bool | None
    inside: str | None = None
    gaps: tuple[Gap, ...] = ()
    has_walls: bool = True
    region_area: float | None = None
    region_bounds: tuple[float, float, float, float] | None = None
    nearest: float | None = None
    rooms: tuple[tuple[float, float, float, float], ...] = ()
    more: bool = False      # the search stopped after MAX_GAP_ROUNDS gaps: there may be more
    notes: tuple[str, ...] = ()   # what was simplified on the way (a tangled mesh, a search cut short), why


def _frame(obstacles, spawn, margin: float):
    import shapely

    xs, ys = [spawn[0]], [spawn[1]]
    if not obstacles.is_empty:
        x0, y0, x1, y1 = obstacles.bounds
        xs += [x0, x1]
        ys += [y0, y1]
    return shapely.box(min(xs) - margin, min(ys) - margin, max(xs) + margin, max(ys) + margin)


@dataclass
class _Way:
    gap: Gap
    plug: object                 # a thin bar across the gap that closes it
    beyond: tuple | None         # a point just past the gap, on the outside
    real: bool                   # the point it was found for lies in a region a disc of that size can be in


def _neck(space: Space, point: tuple[float, float], lo: float, hi: float, prints: list[Footprint]
          ) -> _Way | None:
    """The narrowest place between ``point`` and the outside. At radius ``hi`` the point is cut off, at ``lo``
    it is not: the neck is the bit of disc-centre space that exists at ``lo`` and joins the point's side to the
    outside, but is gone at ``hi``. Its ends are the nearest wall points on either side of it. A neck that is a
    long corridor is named where it opens into the outside (:func:`_corridor_end`); when no disc of radius ``hi``
    fits on the point's side at all (the point is in such a corridor, or in a room missing a wall), where the
    channel of smaller discs that reach the point does (:func:`_mouth`)."""
    import shapely
    from shapely.ops import nearest_points

    outside = space.at(hi)[1]
    if outside is None:
        return None
    here = shapely.Point(point)
    side = _side(space, here, hi)
    if side:
        side = shapely.union_all(side)
        a, x = nearest_points(side, outside)
        found = _channel(space.at(lo)[0], side, outside, hi - lo, 2 * hi)
        neck = found[0] if found is not None else ((a.x + x.x) / 2, (a.y + x.y) / 2)
    else:   # no disc of that size fits on the point's side at all (a corridor, a room missing a whole wall)
        found = None
        a, x = _mouth(space, here, lo, hi, outside)
        neck = (x.x, x.y) if a.equals(here) else ((a.x + x.x) / 2, (a.y + x.y) / 2)
    ends = _gap_ends(space.obstacles, neck, (x.x - a.x, x.y - a.y), space.limit)
    if ends is None and not side:   # near a wide opening, reached by a disc far bigger than it, resting across it
        ends = _resting(space.obstacles, x, here, 2 * (hi - lo) + RESTING_SLACK * hi)
    if ends is None:
        return None
    if found is not None and found[1] is not None:   # a long passage: a corridor's open end?
        way = _corridor_end(space, ends, found[1], prints)
        if way is not None:
            return way
    return _way(space, ends, prints, a, x, bool(side))


def _corridor_end(space: Space, ends, mouth, prints: list[Footprint]) -> _Way | None:
    """The way out at the end of a long passage where it opens into the outside (``mouth``: the points either side
    of that end), when the passage is a corridor: the same two walls either side at its middle (``ends``) and at
    that end. Otherwise None (a passage among many shapes, say, whose middle names the way out)."""
    a, x = mouth
    there = _gap_ends(space.obstacles, ((a.x + x.x) / 2, (a.y + x.y) / 2), (x.x - a.x, x.y - a.y), space.limit)
    if there is None:
        return None
    walls = _gap_between(*ends, prints).between
    if len(walls) != 2 or set(_gap_between(*there, prints).between) != set(walls):
        return None
    return _way(space, there, prints, a, x, True)


def _way(space: Space, ends, prints: list[Footprint], a, x, real: bool) -> _Way:
    """The way out between the wall points ``ends``, crossed from ``a`` (the point's side) to ``x`` (outside)."""
    import shapely

    e1, e2 = ends
    gap = _gap_between(e1, e2, prints)
    plug = shapely.LineString([e1, e2]).buffer(2 * SLIVER, quad_segs=1)
    return _Way(gap, plug, _beyond(space, gap, (x.x - a.x, x.y - a.y)), real)


RESTING_SLACK = 0.006   # the grown walls' arcs (8 segments a quarter) lie up to 0.5 % of the radius inside the disc


def _resting(obstacles, centre, here, slack: float):
    """The wall points a disc centred at ``centre`` rests on across an opening, seen from ``here`` on the other
    side: the nearest wall point, and the nearest one of another wall piece the disc touches (within ``slack`` of
    its radius) such that the line between them separates ``here`` from ``centre``. None when there is none.

    Near a wide opening (a missing wall) the discs that still reach the point are far bigger than the opening and
    rest on its two ends from outside: the half-plane search of :func:`_gap_ends` sees both ends on one side."""
    import shapely
    from shapely.ops import nearest_points

    reach = obstacles.distance(centre) + slack
    pieces = sorted(components(obstacles.intersection(centre.buffer(reach, quad_segs=16))),
                    key=lambda p: p.distance(centre))
    if len(pieces) < 2:
        return None
    path = shapely.LineString([here, centre])
    e1 = nearest_points(pieces[0], centre)[0]
    for piece in pieces[1:]:
        e2 = nearest_points(piece, centre)[0]
        if shapely.LineString([e1, e2]).intersects(path):
            return (e1.x, e1.y), (e2.x, e2.y)
    return None


def _side(space: Space, here, r: float) -> list:
    """The parts of disc-centre space at radius ``r``, other than the outside, whose discs cover ``here``."""
    import numpy as np
    import shapely

    parts, outside = space.at(r)
    with np.errstate(over="ignore", invalid="ignore"):   # all at once (thousands of pockets), quietly as one by one
        near = shapely.distance(parts, here) <= r + 1e-9 if parts else []
    return [c for c, covers in zip(parts, near) if covers and c is not outside]


def _mouth(space: Space, here, lo: float, hi: float, outside):
    """Where the point's way out is when no disc of radius ``hi`` fits on its side at all: the discs a little
    smaller that reach it come down a channel (a corridor, a room missing a wall) too narrow for the larger ones,
    and the way out is where that channel opens into the outside (the corridor's open end), however far from the
    point. As (the channel's end, the nearest outside point to it); when no such channel is found, (the point,
    the nearest outside point to it). The nearest outside point alone may lie across a wall (beside a long
    corridor): it names no way out."""
    import shapely
    from shapely.ops import nearest_points

    r = max(0.0, lo - (hi - lo))   # the channel a little wider than at ``lo``, so that it is surely there
    reached = space.at(r)[1]
    if reached is not None:
        rest = reached.difference(outside.buffer(hi - r + 1e-6, quad_segs=4))
        channel = [p for p in components(rest) if p.distance(here) <= r + 1e-9]
        if channel:
            a, x = nearest_points(shapely.union_all(channel), outside)
            return a, x
    return here, nearest_points(here, outside)[1]


LONG_PASSAGE = 1.0   # m: a passage longer than this and than it is wide is a corridor, named at its open end
CORRIDOR_VERTICES = 5000   # … unless its outline has more vertices than this (a network round many shapes)


def _channel(parts_lo, side, outside, d: float, width: float):
    """Where the disc-centre space at the smaller radius joins ``side`` to ``outside`` (both taken at the
    larger radius, ``d`` more): the pieces of it farther than ``d`` from both that touch both. The middle of the
    longest such piece (a door, a crack through a wall), and, when that piece is a long passage (longer than
    :data:`LONG_PASSAGE` and than ``width``, the gap's), the points either side of where it opens into the
    outside (on its side, outside), else None. None when there is no such piece."""
    import shapely

    grown_side, grown_out = side.buffer(d + 1e-6, quad_segs=4), outside.buffer(d + 1e-6, quad_segs=4)
    rest = shapely.union_all(parts_lo).difference(shapely.union_all([grown_side, grown_out]))
    bridges = [p for p in components(rest)
               if p.distance(grown_side) < 1e-5 and p.distance(grown_out) < 1e-5]
    if not bridges:
        return None
    best = max(bridges, key=lambda p: (p.length, p.area))
    c = best.representative_point()
    return (c.x, c.y), (_opening(best, grown_out, outside, width) if best.length / 2 > max(LONG_PASSAGE, width)
                        else None)


def _opening(passage, grown_out, outside, width: float):
    """Where a long ``passage`` opens into the outside (it touches ``grown_out``, the outside grown a little, there):
    (a point of its end, the nearest outside point to it), when it opens in one place only (within ``width``);
    else None (a network of passages round many shapes: one with holes, or too intricate to be a corridor)."""
    import numpy as np
    import shapely
    from shapely.ops import nearest_points

    if len(passage.interiors) or len(passage.exterior.coords) > CORRIDOR_VERTICES:
        return None
    points = shapely.points(shapely.get_coordinates(passage))
    shapely.prepare(grown_out)
    touching = points[shapely.intersects(grown_out, shapely.buffer(points, 1e-5, quad_segs=1))]
    if len(touching) == 0 or np.ptp(shapely.get_coordinates(touching), axis=0).max() > width:
        return None
    return nearest_points(touching[0], outside)


def _gap_ends(obstacles, neck, outward, limit: float = MAX_GAP):
    """The wall point nearest the neck, and the nearest one on the other side of the neck from it."""
    import shapely
    from shapely.ops import nearest_points

    n = shapely.Point(neck)
    e1 = nearest_points(obstacles, n)[0]
    ux, uy = e1.x - n.x, e1.y - n.y
    length = math.hypot(ux, uy)
    if length < 1e-9:   # the neck touches a wall: look across, perpendicular to the way out
        ux, uy, length = -outward[1], outward[0], math.hypot(*outward)
        if length < 1e-9:
            return None
    ux, uy = ux / length, uy / length
    far = 4 * limit   # the half-plane beyond the neck, away from e1
    px, py = -uy, ux
    half = shapely.Polygon([(n.x - ux * 1e-6 + px * far, n.y - uy * 1e-6 + py * far),
                            (n.x - ux * 1e-6 - px * far, n.y - uy * 1e-6 - py * far),
                            (n.x - ux * far - px * far, n.y - uy * far - py * far),
                            (n.x - ux * far + px * far, n.y - uy * far + py * far)])
    other = obstacles.intersection(half)
    if other.is_empty:
        return None
    e2 = nearest_points(other, n)[0]
    return (e1.x, e1.y), (e2.x, e2.y)


def _beyond(space: Space, gap: Gap, outward, step: float = 0.05):
    """A free point ``step`` m past the gap, on its outside."""
    import shapely

    (ax, ay), (bx, by) = gap.ends
    length = math.hypot(bx - ax, by - ay)
    if length < 1e-9:
        return None
    nx, ny = -(by - ay) / length, (bx - ax) / length
    if nx * outward[0] + ny * outward[1] < 0:
        nx, ny = -nx, -ny
    q = (gap.centre[0] + step * nx, gap.centre[1] + step * ny)
    return None if space.obstacles.covers(shapely.Point(q)) else q


MAX_DEPTH = 3   # how far the search follows a way out into further enclosed regions


MAX_ANCHOR = 4   # how many times the search may move deeper into the room from a point in a corner


def _anchored(space: Space, point) -> tuple:
    """The point the way out is searched from, and the radii that cut it off (see :meth:`Space.critical_radius`).

    A point near a corner is cut off at the radius of the discs that still fit into the corner, whatever the
    room's way out: no disc of the larger radius fits on its side at all. The search then moves to the centre of
    the nearest disc a little smaller that covers it (farther from the walls, in the same room), as long as that
    one is cut off only at a clearly larger radius. Along a corridor too narrow for the larger discs that radius
    is the same, and the point stays (its way out is the corridor's end: :func:`_mouth`)."""
    import shapely
    from shapely.ops import nearest_points

    bounds = space.critical_radius(point)
    for _ in range(MAX_ANCHOR):
        if bounds is None or not bounds[1]:
            break
        lo, hi = bounds
        here = shapely.Point(point)
        if _side(space, here, hi):
            break
        reached = space.at(max(0.0, lo - (hi - lo)))[1]
        if reached is None:
            break
        c = nearest_points(reached, here)[0]
        deeper = space.critical_radius((c.x, c.y))
        if deeper is None or deeper[1] <= hi + WIDTH_TOLERANCE:
            break
        point, bounds = (c.x, c.y), deeper
    return point, bounds


def _way_out(space: Space, point, prints: list[Footprint], depth: int = 0, max_depth: int = MAX_DEPTH
             ) -> _Way | None:
    """The widest way out from ``point``, or None when nothing encloses it at any scale up to the space's limit.

    The narrowest cut between the point and the outside may lie inside the building (beside a free-standing
    partition, say). When the far side of that cut is itself a region closed at a larger scale (a disc of that
    size fits in it and cannot get out), the search closes the cut and follows that region's way out instead:
    the door a person would name."""
    point, bounds = _anchored(space, point)
    if bounds is None or not bounds[1]:
        return None
    way = _neck(space, point, *bounds, prints)
    if way is None:
        return None
    if depth < max_depth and way.beyond is not None:
        further = _way_out(space.plugged(way.plug), way.beyond, prints, depth + 1, max_depth)
        if further is not None and further.real:
            return further
    return way


def _gap_between(e1, e2, prints: list[Footprint]) -> Gap:
    import shapely

    e1, e2 = sorted([(round(e1[0], 6), round(e1[1], 6)), (round(e2[0], 6), round(e2[1], 6))])
    between = []
    geometries = [f.geometry for f in prints]
    for end in (e1, e2):
        k, d = _nearest(geometries, shapely.Point(end))
        if k is not None and prints[k].label not in between and d < 0.01:
            between.append(prints[k].label)
    # the ends lie on the footprints grown by SLIVER: the opening itself is that much wider on each side
    return Gap(centre=((e1[0] + e2[0]) / 2, (e1[1] + e2[1]) / 2), width=math.dist(e1, e2) + 2 * SLIVER,
               ends=(e1, e2), between=tuple(between))


def _nearest(geometries: list, point) -> tuple:
    """(the index of the first of ``geometries`` nearest ``point``, its distance), or (None, None) for none: the
    distances all at once (10 000 footprints), the first of equal ones as ``min`` takes it."""
    import numpy as np
    import shapely

    if not geometries:
        return None, None
    with np.errstate(over="ignore", invalid="ignore"):   # quietly, as one by one
        distances = shapely.distance(geometries, point)
    if np.isnan(distances).any():   # no order among them: as min over them one by one
        k = min(range(len(geometries)), key=lambda i: geometries[i].distance(point))
        return k, geometries[k].distance(point)
    k = int(distances.argmin())
    return k, float(distances[k])


def passage_width(prints: list[Footprint], gap: Gap) -> float:
    """How wide the way through ``gap`` is among other footprints (the robot's body, say, rather than the
    LiDAR plane): 0 when they block its middle, else the distance between their nearest points either side."""
    import shapely

    if not prints:
        return math.inf
    obstacles = obstacle_union(prints)
    if obstacles.covers(shapely.Point(gap.centre)):
        return 0.0
    (ax, ay), (bx, by) = gap.ends
    ends = _gap_ends(obstacles, gap.centre, (-(by - ay), bx - ax), max(MAX_GAP, gap.width * 2))
    return math.dist(*ends) + 2 * SLIVER if ends is not None else math.inf


def analyse(prints: list[Footprint], spawn: tuple[float, float], height: float) -> Enclosure:
    """Decide whether ``spawn`` is enclosed by ``prints`` (footprints cut at ``height``) and find the gaps."""
    import numpy as np
    import shapely

    spawn = (float(spawn[0]), float(spawn[1]))
    point = shapely.Point(spawn)
    if not prints:
        return Enclosure(spawn, height, enclosed=False, has_walls=False)
    with np.errstate(over="ignore"):   # a spawn 1000 km out: inf, as one by one
        distances = shapely.distance([p.geometry for p in prints], point)
    closest = int(distances.argmin())   # the first of the nearest, as min over (distance, index)
    nearest = float(distances[closest])
    obstacles = obstacle_union(prints)
    if obstacles.covers(point):   # in a shape, or within SLIVER of one (a gap that thin counts as closed)
        return Enclosure(spawn, height, enclosed=None, inside=prints[closest].label, nearest=nearest)
    limit = search_limit(obstacles, spawn)
    frame = _frame(obstacles, spawn, MARGIN + limit)
    space = Space(obstacles, frame, limit=limit)
    if space.cut_off(spawn, 0.0):
        region = next(c for c in space.at(0.0)[0] if c.covers(point))
        return Enclosure(spawn, height, enclosed=True, region_area=region.area,
                         region_bounds=tuple(region.bounds), nearest=nearest)
    rooms = _closed_regions(space.at(0.0)[0], frame, point)
    gaps: list[Gap] = []
    more = True
    many = len(prints) > MANY_SHAPES   # then only the widest way out, followed one region further
    for _ in range(1 if many else MAX_GAP_ROUNDS):   # name the widest way out, close it, look again
        way = _way_out(space, spawn, prints, max_depth=1 if many else MAX_DEPTH)
        if way is None or any(math.dist(way.gap.centre, g.centre) < 0.01 for g in gaps):
            more = False
            break
        gaps.append(way.gap)
        space = space.plugged(way.plug)
        if space.cut_off(spawn, 0.0):
            more = False
            break
    return Enclosure(spawn, height, enclosed=False, gaps=tuple(gaps), nearest=nearest, rooms=rooms, more=more)


ROOM_MIN_AREA = 0.25   # m²: closed pockets smaller than this (inside a pillar, between joined walls) are no rooms


def _closed_regions(parts, frame, point) -> tuple[tuple[float, float, float, float], ...]:
    rooms = [c for c in parts if not reaches_outside(c, frame) and c.area >= ROOM_MIN_AREA]
    rooms.sort(key=lambda c: (c.distance(point), c.bounds))
    return tuple(tuple(round(v, 4) for v in c.bounds) for c in rooms)


def enclosure(scene: Scene, spawn: tuple[float, float], height: float) -> Enclosure:
    """:func:`analyse` of the scene cut at ``height``, with the notes of any footprint simplified on the way. The
    footprints are cut once per scene and height (:mod:`.scene_memo`), and united once (:func:`obstacle_union`):
    a world checked from each of its rooms."""
    from dataclasses import replace

    prints = footprints(scene, height)
    notes = tuple(f"mesh {p.label}: {p.note}" for p in prints if p.note)
    if len(prints) > MANY_SHAPES:
        notes += (f"{len(prints)} shapes stand at the slicing height, more than {MANY_SHAPES}: only the widest way "
                  f"out is searched (not up to {MAX_GAP_ROUNDS}), to keep the check fast",)
    return replace(analyse(prints, spawn, height), notes=notes)


def search_limit(obstacles, spawn) -> float:
    """The widest opening searched for: :data:`MAX_GAP`, or the extent of the walls and the spawn together
    (an open corridor end or a missing wall can be as wide as the building), at most :data:`MAX_SEARCH`."""
    x0, y0, x1, y1 = obstacles.bounds
    x0, x1 = min(x0, spawn[0]), max(x1, spawn[0])
    y0, y1 = min(y0, spawn[1]), max(y1, spawn[1])
    return min(MAX_SEARCH, max(MAX_GAP, math.hypot(x1 - x0, y1 - y0)))
