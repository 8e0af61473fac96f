"""``rooms``: an apartment. The footprint is split into rooms (and a corridor along its length), the rooms are
joined by doors at least the robot's width plus a margin, furniture stands along their walls, and windows sit in
the outer walls.

Layout: a corridor (when asked for and when the footprint is wide enough) runs the length of the footprint; the
parts beside it, or the whole footprint, are split again and again across their longer side (a guillotine cut at a
random place, every room at least :func:`min_room` on each side) until there are as many rooms as asked. Every
cut leaves rooms at least twice a door's span long on both sides of it, so two neighbours across any cut share
enough wall for a door, and the rooms on each side are joined among themselves: every room can be joined to every
other. Doors: each room beside the corridor opens onto it; the rest are joined in a random spanning tree over the
walls rooms share (Kruskal's, in a seeded order), and each wall left over gets a door with the chance ``loops``.
Furniture: :mod:`.furniture` (along the walls, never between a door and the middle of its room). The robot starts
in the middle of a random room, facing a wall or a piece of furniture 1 to 3.3 m ahead with nothing in between.
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import Dict, List, Optional, Tuple

from ..spec.model import Material, Obstacle, Opening, RobotPose, Room, Spec, WallStyle
from .furniture import DoorSpan, furnish
from .options import RoomsOptions
from .rng import Rng
from .robot import RobotSpace
from .shapes import Rect, facing
from .trig import HALF_PI, PI

THICKNESS = 0.15
GRAIN = 0.05            # m: room corners lie on this grid
DOOR_SLACK = 0.1        # m: a door keeps this far from the walls at either end of the wall it is in
AREA_PER_ROOM = 14.0    # m²: the rooms' number when none is asked for
WINDOW_CHANCE = 0.6
WINDOW_WIDTHS = (0.8, 1.0, 1.2)
AHEAD = (1.0, 3.3)      # m: how far the robot's first wall ahead may be (the LiDAR reaches 3.5 m)
HEADINGS = (0.0, HALF_PI, PI, -HALF_PI)


def _snap(value: float) -> float:
    return round(round(value / GRAIN) * GRAIN, 3)


def door_width(options: RoomsOptions, space: RobotSpace) -> float:
    return options.door if options.door is not None else round(max(0.9, space.passage), 3)


def min_room(door: float) -> float:
    """The shortest side a room may have: two door spans (door, wall and slack), so rooms across a cut always share
    enough wall for a door."""
    return _snap(math.ceil(2 * (door + THICKNESS + 2 * DOOR_SLACK) / GRAIN - 1e-9) * GRAIN)


def resolve(options: RoomsOptions, space: RobotSpace) -> RoomsOptions:
    from ..core.errors import InputError

    door = door_width(options, space)
    if door < space.passage:
        raise InputError(f"--door {door:g} is too narrow for the {space.model}, which is {space.width:g} m wide",
                         hint=f"give --door at least {space.passage:g} (its width and 0.2 m), or leave it out")
    w, h = (_snap(v) for v in options.size)
    side = min_room(door)
    if min(w, h) < side:
        raise InputError(f"--size {w:g}x{h:g} is too small for a room with a {door:g} m door",
                         hint=f"make both sides at least {side:g} m")
    rooms = options.rooms if options.rooms is not None else max(2, min(16, round(w * h / AREA_PER_ROOM)))
    return replace(options, size=(w, h), door=door, rooms=rooms)


def _corridor(foot: Rect, options: RoomsOptions, side: float, width: float, rng: Rng
              ) -> Tuple[Optional[Rect], List[Rect]]:
    """The corridor along the footprint's longer side, and the parts beside it (the footprint when no corridor
    fits or none is asked for)."""
    if not options.corridor or options.rooms < 3:
        return None, [foot]
    along_x = foot.width >= foot.height
    across = foot.height if along_x else foot.width
    lo0 = foot.y0 if along_x else foot.x0
    if across >= 2 * side + width:
        start = rng.step(lo0 + side, lo0 + across - side - width, GRAIN)
    elif across >= side + width:
        start = rng.choice((lo0, _snap(lo0 + across - width)))
    else:
        return None, [foot]
    end = _snap(start + width)
    if along_x:
        hall = Rect(foot.x0, start, foot.x1, end)
        parts = [Rect(foot.x0, foot.y0, foot.x1, start), Rect(foot.x0, end, foot.x1, foot.y1)]
    else:
        hall = Rect(start, foot.y0, end, foot.y1)
        parts = [Rect(foot.x0, foot.y0, start, foot.y1), Rect(end, foot.y0, foot.x1, foot.y1)]
    return hall, [p for p in parts if p.width > 1e-6 and p.height > 1e-6]


def _split(parts: List[Rect], count: int, side: float, rng: Rng) -> List[Rect]:
    """Cut the largest part that can be cut across its longer side until there are ``count`` parts."""
    parts = list(parts)
    while len(parts) < count:
        order = sorted(range(len(parts)), key=lambda i: (-parts[i].area, i))
        for i in order:
            r = parts[i]
            vertical = r.width >= r.height
            length = r.width if vertical else r.height
            if length < 2 * side - 1e-9:
                continue
            lo = r.x0 if vertical else r.y0
            cut = rng.step(lo + side, lo + length - side, GRAIN)
            a, b = ((Rect(r.x0, r.y0, cut, r.y1), Rect(cut, r.y0, r.x1, r.y1)) if vertical else
                    (Rect(r.x0, r.y0, r.x1, cut), Rect(r.x0, cut, r.x1, r.y1)))
            parts[i:i + 1] = [a, b]
            break
        else:
            break
    return parts


def _shared(a: Rect, b: Rect) -> Optional[Tuple[int, float, float]]:
    """The wall ``a`` and ``b`` share: (side of ``a`` it is on, start, end along it), or None."""
    for side, same in ((1, abs(a.x1 - b.x0) < 1e-6), (3, abs(a.x0 - b.x1) < 1e-6)):
        if same:
            lo, hi = max(a.y0, b.y0), min(a.y1, b.y1)
            if hi > lo + 1e-6:
                return side, lo, hi
    for side, same in ((2, abs(a.y1 - b.y0) < 1e-6), (0, abs(a.y0 - b.y1) < 1e-6)):
        if same:
            lo, hi = max(a.x0, b.x0), min(a.x1, b.x1)
            if hi > lo + 1e-6:
                return side, lo, hi
    return None


def _doors(rects: List[Rect], hall: Optional[int], door: float, loops: float, rng: Rng
           ) -> List[Tuple[int, int, int, float]]:
    """The doors: (room, neighbour, side of the room, start along it)."""
    need = door + THICKNESS + 2 * DOOR_SLACK
    pairs = [(i, j, s) for i in range(len(rects)) for j in range(i + 1, len(rects))
             for s in (_shared(rects[i], rects[j]),) if s is not None and s[2] - s[1] >= need - 1e-9]
    group = list(range(len(rects)))

    def root(i: int) -> int:
        while group[i] != i:
            group[i] = group[group[i]]
            i = group[i]
        return i

    chosen = []
    first = [p for p in pairs if hall in (p[0], p[1])]
    for i, j, shared in first + rng.shuffled([p for p in pairs if hall not in (p[0], p[1])]):
        joined = root(i) == root(j)
        if joined and not rng.chance(loops):
            continue
        group[root(i)] = root(j)
        side, lo, hi = shared
        start = rng.step(lo + THICKNESS / 2 + DOOR_SLACK, hi - THICKNESS / 2 - DOOR_SLACK - door, 0.01)
        chosen.append((i, j, side, start))
    return chosen


def _opening_offset(r: Rect, side: int, start: float, width: float) -> float:
    """A rect room's wall ``side`` runs counter-clockwise from its corner ``side``: the offset of an opening
    spanning ``start`` … ``start + width`` along the world axis."""
    return round({0: start - r.x0, 1: start - r.y0, 2: r.x1 - start - width, 3: r.y1 - start - width}[side], 3)


def _windows(r: Rect, foot: Rect, rng: Rng) -> List[Tuple[int, float, float]]:
    """Windows in the room's outer walls: (side, start along it, width)."""
    found = []
    for side, outer in ((0, r.y0 == foot.y0), (1, r.x1 == foot.x1), (2, r.y1 == foot.y1), (3, r.x0 == foot.x0)):
        lo, hi = (r.x0, r.x1) if side in (0, 2) else (r.y0, r.y1)
        room_for = hi - lo - THICKNESS - 2 * DOOR_SLACK
        width = rng.choice(WINDOW_WIDTHS)
        if outer and rng.chance(WINDOW_CHANCE) and room_for >= width:
            start = rng.step(lo + THICKNESS / 2 + DOOR_SLACK, hi - THICKNESS / 2 - DOOR_SLACK - width, 0.01)
            found.append((side, start, width))
    return found


def _names(rects: List[Rect], hall: Optional[int]) -> List[str]:
    order = sorted((i for i in range(len(rects)) if i != hall), key=lambda i: (-rects[i].area, i))
    names: Dict[int, str] = {} if hall is None else {hall: "hall"}
    bedrooms = small = 0
    for rank, i in enumerate(order):
        if rank == 0:
            names[i] = "living"
        elif rank == 1 and rects[i].area >= 6:
            names[i] = "kitchen"
        elif rects[i].area < 6:
            small += 1
            names[i] = "bath" if small == 1 else f"storage_{small - 1}"
        else:
            bedrooms += 1
            names[i] = f"bedroom_{bedrooms}"
    return [names[i] for i in range(len(rects))]


def make(name: str, options: RoomsOptions, space: RobotSpace, rng: Rng) -> Tuple[Spec, str]:
    w, h = options.size
    foot = Rect(_snap(-w / 2), _snap(-h / 2), _snap(-w / 2) + w, _snap(-h / 2) + h)
    foot = Rect(*(round(v, 3) for v in (foot.x0, foot.y0, foot.x1, foot.y1)))
    door, side = options.door, min_room(options.door)
    width = max(1.2, _snap(math.ceil((2 * space.clearance + THICKNESS + 0.2) / GRAIN) * GRAIN))
    hall, parts = _corridor(foot, options, side, width, rng)
    rects = ([hall] if hall else []) + _split(parts, options.rooms - (1 if hall else 0), side, rng)
    hall_index = 0 if hall else None
    names = _names(rects, hall_index)
    doors = _doors(rects, hall_index, door, options.loops, rng)
    style = WallStyle(THICKNESS, options.wall_height, Material())
    spans: Dict[int, List[DoorSpan]] = {i: [] for i in range(len(rects))}
    openings: Dict[int, List[Opening]] = {i: [] for i in range(len(rects))}
    door_height = min(2.0, options.wall_height)
    for i, j, s, start in doors:
        openings[i].append(Opening("door", s, _opening_offset(rects[i], s, start, door), door, door_height))
        spans[i].append(DoorSpan(s, start, round(start + door, 3)))
        spans[j].append(DoorSpan((s + 2) % 4, start, round(start + door, 3)))
    if options.windows and options.wall_height >= 1.4:
        for i, r in enumerate(rects):
            for s, start, ww in _windows(r, foot, rng):
                openings[i].append(Opening("window", s, _opening_offset(r, s, start, ww), ww, 0.8, 0.5))
    obstacles: List[Obstacle] = []
    cores = []
    for i, r in enumerate(rects):
        floor = r.shrunk(THICKNESS / 2)
        pieces, core = furnish(names[i], floor, spans[i], 2 * space.clearance, options.furniture, rng)
        obstacles += pieces
        cores.append(core)
    rooms = tuple(Room(names[i], tuple(r.corners()), style,
                       tuple(sorted(openings[i], key=lambda o: (o.wall, o.offset)))) for i, r in enumerate(rects))
    start_room = rng.choice([i for i in range(len(rects)) if i != hall_index] or [0])
    robot = _spawn(rects[start_room], cores[start_room], spans[start_room], obstacles, space, options.robot, rng)
    spec = Spec(name=name, style=style, rooms=rooms, obstacles=tuple(obstacles), robot=robot)
    corridor = " and a corridor" if hall else ""
    rooms_ = _count(len(rects) - (1 if hall else 0), "room")
    return spec, (f"a {w:g} x {h:g} m flat of {rooms_}{corridor}, {_count(len(doors), 'door')} {door:g} m wide, "
                  f"{_count(len(obstacles), 'piece')} of furniture; the robot starts in room '{names[start_room]}'")


def shortfall(spec: Spec, options: RoomsOptions) -> Optional[str]:
    """What the flat lacks of what was asked (None: nothing): fewer rooms than ``--rooms``, when no room was left
    that could be cut again with both its parts at least :func:`min_room` a side."""
    if len(spec.rooms) >= options.rooms:
        return None
    w, h = options.size
    return (f"{len(spec.rooms)} rooms, not the {options.rooms} asked: no room of the {w:g} x {h:g} m flat could be "
            f"cut again with both parts at least {min_room(options.door):g} m a side (two door spans); give a larger "
            f"--size or fewer --rooms")


def _count(n: int, what: str) -> str:
    return f"{n} {what}{'' if n == 1 else 's'}"


def _faces(r: Rect, spans: List[DoorSpan], obstacles: List[Obstacle]):
    """The room's wall faces (doorways left out) and its furniture's sides, as segments, for the heading."""
    floor = r.shrunk(THICKNESS / 2)
    segments = []
    for side, (a, b) in enumerate(((floor.x0, floor.x1), (floor.y0, floor.y1), (floor.x0, floor.x1),
                                   (floor.y0, floor.y1))):
        cuts = sorted((d.start, d.end) for d in spans if d.side == side)
        points, at = [], a
        for s, e in cuts:
            points.append((at, s))
            at = e
        points.append((at, b))
        for s, e in points:
            if e <= s:
                continue
            segments.append({0: ((s, floor.y0), (e, floor.y0)), 2: ((s, floor.y1), (e, floor.y1)),
                             1: ((floor.x1, s), (floor.x1, e)), 3: ((floor.x0, s), (floor.x0, e))}[side])
    for o in obstacles:
        hx, hy = ((o.size[0] / 2, o.size[1] / 2) if o.shape == "box" else (o.radius, o.radius))
        box = Rect(o.at[0] - hx, o.at[1] - hy, o.at[0] + hx, o.at[1] + hy)
        if box.overlaps(floor):
            c = box.corners()
            segments += [(c[k], c[(k + 1) % 4]) for k in range(4)]
    return segments


def _spawn(r: Rect, core: Rect, spans: List[DoorSpan], obstacles: List[Obstacle], space: RobotSpace, model: str,
           rng: Rng) -> RobotPose:
    centre = (round(core.centre[0], 2), round(core.centre[1], 2))
    yaw, _ = facing(centre, HEADINGS, space.width / 2 + 0.05, _faces(r, spans, obstacles), *AHEAD, rng)
    return RobotPose(model, centre, round(yaw, 4))
