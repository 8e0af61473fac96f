"""Reading a spec's walls: its wall style (``walls:``), its rooms (a ``rect`` or a ``polygon`` of corners) and
segments, and the openings cut into them. Every check names the file and line of the value to change; what only the
geometry can tell (walls that rooms share, openings that run into another wall) is checked by
:mod:`worldgen.geometry.building`.
"""

from __future__ import annotations

import math

from . import values
from .messages import describe, describe_sized, metres
from .model import (DOOR_HEIGHT, DOOR_WIDTH, EPS, LIMIT, MIN_SIZE, OPENING_KEYS, OPENING_TYPES, RECT_KEYS, ROOM_KEYS,
                    SEGMENT_KEYS, WALL_KEYS, WINDOW_HEIGHT, WINDOW_SILL, WINDOW_WIDTH, Opening, Point, Room, Segment,
                    WallStyle)
from .nodes import Node
from .values import Source


def read_style(src: Source, node: Node, what: str, base: WallStyle) -> WallStyle:
    if node.value is None:
        return base
    keys = values.mapping(src, node, what, WALL_KEYS)
    return WallStyle(
        thickness=values.length(src, keys["thickness"], f"{what} thickness") if "thickness" in keys else base.thickness,
        height=values.length(src, keys["height"], f"{what} height") if "height" in keys else base.height,
        material=values.material(src, keys["material"], f"{what} material") if "material" in keys else base.material,
    )


def read_room(src: Source, node: Node, index: int, base: WallStyle) -> Room:
    keys = values.mapping(src, node, f"room {index + 1}", ROOM_KEYS, required=("name",))
    name = values.name(src, keys["name"], "room name")
    what = f"room '{name}'"
    if ("rect" in keys) == ("polygon" in keys):
        src.fail(f"{what} needs exactly one of 'rect' or 'polygon'", node.line,
                 hint="e.g. rect: {center: [0, 0], size: [5, 5]} or polygon: [[0, 0], [5, 0], [5, 5], [0, 5]]")
    style = read_style(src, keys["walls"], f"walls of {what}", base) if "walls" in keys else base
    if "rect" in keys:
        vertices = read_rect(src, keys["rect"], what, style)
    else:
        vertices = read_polygon(src, keys["polygon"], what)
    lengths = [math.dist(vertices[i], vertices[(i + 1) % len(vertices)]) for i in range(len(vertices))]
    openings = read_openings(src, keys.get("openings"), what, lengths, style, on_segment=False)
    return Room(name=name, vertices=vertices, style=style, openings=openings, line=node.line)


def read_rect(src: Source, node: Node, what: str, style: WallStyle) -> tuple[Point, ...]:
    keys = values.mapping(src, node, f"rect of {what}", RECT_KEYS, required=RECT_KEYS)
    cx, cy = values.point(src, keys["center"], f"center of {what}")
    size = keys["size"]
    if not isinstance(size.value, list) or len(size.value) != 2:
        src.fail(f"size of {what} must be [width, depth] in metres, not {describe_sized(size.value)}", size.line,
                 hint="e.g. size: [5, 4]")
    w = values.length(src, size.value[0], f"width (x size) of {what}")
    d = values.length(src, size.value[1], f"depth (y size) of {what}")
    for extent, axis, v in ((w, "x", size.value[0]), (d, "y", size.value[1])):
        if extent <= style.thickness + EPS:
            src.fail(f"{what} is {metres(extent)} m along {axis}: not more than its walls' thickness "
                     f"{metres(style.thickness)} m, so it has no floor", v.line,
                     hint="sizes are between the walls' centre-lines; make the room larger")
    if max(abs(cx) + w / 2, abs(cy) + d / 2) > LIMIT:
        src.fail(f"{what} reaches farther than {LIMIT:g} m from the origin", node.line,
                 hint="coordinates are in metres")
    x0, x1, y0, y1 = (round(v, 9) for v in (cx - w / 2, cx + w / 2, cy - d / 2, cy + d / 2))
    return ((x0, y0), (x1, y0), (x1, y1), (x0, y1))


def read_polygon(src: Source, node: Node, what: str) -> tuple[Point, ...]:
    items = node.value
    if not isinstance(items, list):
        src.fail(f"polygon of {what} must be a list of points [[x, y], …], not {describe(items)}",
                 node.line, hint="e.g. polygon: [[0, 0], [4, 0], [4, 3], [0, 3]]")
    points = [values.point(src, p, f"corner {i} of {what}") for i, p in enumerate(items)]
    if len(points) >= 4 and math.dist(points[0], points[-1]) < MIN_SIZE:
        points.pop()   # the first point repeated at the end closes the ring: the same polygon
    if len(points) < 3:
        src.fail(f"the polygon of {what} has {len(points)} point{'s' if len(points) != 1 else ''}; "
                 "a room needs at least 3", node.line,
                 hint="list the corners of the room in order, e.g. [[0, 0], [4, 0], [4, 3], [0, 3]]")
    for j in range(len(points)):
        for i in range(j):
            gap = math.dist(points[i], points[j])
            if gap < MIN_SIZE:   # closer than 1 mm: one point, for the geometry too
                near = f" to within {metres(gap * 1000)} mm" if gap else ""
                src.fail(f"corner {j} of {what} repeats corner {i} ({metres(points[i][0])}, {metres(points[i][1])})"
                         f"{near}", items[j].line,
                         hint="remove it: list each corner once; only the first may be repeated at the end")
    crossing = _crossing_walls(points)
    if crossing:
        i, j = crossing
        src.fail(f"walls {i} and {j} of {what} cross or overlap", items[j].line,
                 hint="list the corners in order around the room, either direction; "
                      "wall i runs from corner i to corner i+1, counting from 0")
    area = sum(points[i][0] * points[(i + 1) % len(points)][1] - points[(i + 1) % len(points)][0] * points[i][1]
               for i in range(len(points))) / 2
    if abs(area) < 1e-6:
        src.fail(f"the points of the polygon of {what} lie on one line: it has no floor", node.line,
                 hint="list the corners of the room in order around it")
    return tuple(points)


def read_openings(src: Source, node: Node | None, owner: str, lengths: list[float], style: WallStyle, *,
                  on_segment: bool) -> tuple[Opening, ...]:
    openings = [read_opening(src, n, i, owner, lengths, style, on_segment)
                for i, n in enumerate(values.listing(src, node, f"openings of {owner}"))]
    ordered = sorted(enumerate(openings), key=lambda io: (io[1].wall, io[1].offset))
    for (i, a), (j, b) in zip(ordered, ordered[1:]):
        if a.wall == b.wall and b.offset < a.offset + a.width + EPS:
            first, second = sorted((i, j))
            src.fail(f"openings {first + 1} and {second + 1} of {owner} overlap or touch on wall {a.wall} "
                     f"({metres(a.offset)}–{metres(a.offset + a.width)} m and "
                     f"{metres(b.offset)}–{metres(b.offset + b.width)} m along it)", openings[second].line,
                     hint="change the offset of one, or make them one wider opening")
    return tuple(openings)


def read_opening(src: Source, node: Node, index: int, owner: str, lengths: list[float], style: WallStyle,
                 on_segment: bool) -> Opening:
    label = f"opening {index + 1} of {owner}"
    keys = values.mapping(src, node, label, OPENING_KEYS, required=("type",) if on_segment else ("type", "wall"))
    kind = values.text(src, keys["type"], f"type of {label}", OPENING_TYPES)
    what = f"{kind} {index + 1} of {owner}"
    wall = 0
    if "wall" in keys:
        wnode = keys["wall"]
        if isinstance(wnode.value, bool) or not isinstance(wnode.value, int):
            src.fail(f"wall of {what} must be a wall number, not {describe(wnode.value)}", wnode.line,
                     hint="walls are numbered from 0: wall i runs from point i to point i+1")
        wall = wnode.value
        if not 0 <= wall < len(lengths):
            hint = ("a segment is a single wall: write wall: 0 or leave it out" if on_segment else
                    f"use wall 0 to {len(lengths) - 1}: wall i runs from corner i to the next; a rect's "
                    "wall 0 is the bottom (min y) one, then counter-clockwise")
            src.fail(f"{what} is on wall {wall}, but {owner} has {len(lengths)} "
                     f"wall{'s' if len(lengths) > 1 else ''}", wnode.line, hint=hint)
    length, t, top = lengths[wall], style.thickness, style.height
    where = f"wall {wall}"

    def line(key: str) -> int:
        return keys[key].line if key in keys else node.line

    width = values.length(src, keys["width"], f"width of {what}") if "width" in keys else (
        DOOR_WIDTH if kind == "door" else WINDOW_WIDTH)
    if kind == "door":
        height = values.length(src, keys["height"], f"height of {what}") if "height" in keys else min(DOOR_HEIGHT, top)
        sill = values.distance(src, keys["sill"], f"sill of {what}") if "sill" in keys else 0.0
        if sill > 0:
            src.fail(f"{what} has a sill of {metres(sill)} m, but a door starts at the floor", keys["sill"].line,
                     hint="remove the sill, or make it type: window")
    else:
        height = values.length(src, keys["height"], f"height of {what}") if "height" in keys else WINDOW_HEIGHT
        sill = values.distance(src, keys["sill"], f"sill of {what}") if "sill" in keys else WINDOW_SILL

    room_for = length - t
    if room_for <= EPS:
        src.fail(f"{what} is on {where}, which is {metres(length)} m long: no longer than the walls are thick "
                 f"({metres(t)} m), so it has no room for an opening", node.line,
                 hint="put the opening on a longer wall, or remove it")
    if width > room_for + EPS:
        src.fail(f"{what} is {metres(width)} m wide, but {where} has only {metres(room_for)} m between its "
                 f"corners ({metres(length)} m long, less {metres(t)} m of wall thickness)", line("width"),
                 hint=f"make the width at most {metres(room_for)}, or put it on a longer wall")
    offset = values.distance(src, keys["offset"], f"offset of {what}") if "offset" in keys else (length - width) / 2
    lo, hi = t / 2, length - t / 2 - width
    span = f"use an offset from {metres(lo)} to {metres(hi)} m, or leave offset out to centre the {kind}"
    if offset < lo - EPS:
        src.fail(f"{what} starts {metres(offset)} m along {where}: inside the corner, which takes the first "
                 f"{metres(lo)} m (half the wall thickness)", line("offset"), hint=span)
    if offset + width > length - lo + EPS:
        src.fail(f"{what} ends {metres(offset + width)} m along {where}, which is {metres(length)} m long: inside the "
                 f"corner, which takes the last {metres(lo)} m (half the wall thickness)", line("offset"), hint=span)
    if kind == "door" and height > top + EPS:
        src.fail(f"{what} is {metres(height)} m tall, but the walls of {owner} are {metres(top)} m", line("height"),
                 hint=f"make the door at most {metres(top)} m tall, or raise the walls with walls: {{height: …}}")
    if kind == "window" and sill + height > top + EPS:
        src.fail(f"{what} reaches {metres(sill + height)} m up (sill {metres(sill)} + height {metres(height)}), "
                 f"above the {metres(top)} m walls of {owner}", line("height" if "height" in keys else "sill"),
                 hint=f"make sill + height at most {metres(top)} m")
    return Opening(type=kind, wall=wall, offset=round(offset, 9), width=width, height=height, sill=sill,
                   line=node.line)


def read_segment(src: Source, node: Node, index: int, base: WallStyle) -> Segment:
    what = f"segment {index + 1}"
    keys = values.mapping(src, node, what, SEGMENT_KEYS, required=("from", "to"))
    start = values.point(src, keys["from"], f"'from' of {what}")
    end = values.point(src, keys["to"], f"'to' of {what}")
    length = math.dist(start, end)
    if length < MIN_SIZE:
        src.fail(f"{what} starts and ends at the same point", keys["to"].line,
                 hint="give 'from' and 'to' two different points")
    style = read_style(src, keys["walls"], f"walls of {what}", base) if "walls" in keys else base
    openings = read_openings(src, keys.get("openings"), what, [length], style, on_segment=True)
    return Segment(start=start, end=end, style=style, openings=openings, line=node.line)


def _crossing_walls(points: list[Point]) -> tuple[int, int] | None:
    """The first pair of walls (edges) of a closed polygon that cross, touch or fold back, or None."""
    n = len(points)
    edges = [(points[i], points[(i + 1) % n]) for i in range(n)]
    for i in range(n):
        a, b = edges[i]
        for j in range(i + 1, n):
            c, d = edges[j]
            if j == i + 1 or (i == 0 and j == n - 1):
                shared, p, q = (b, a, d) if j == i + 1 else (a, b, c)
                u, v = (p[0] - shared[0], p[1] - shared[1]), (q[0] - shared[0], q[1] - shared[1])
                if abs(u[0] * v[1] - u[1] * v[0]) <= 1e-9 * math.hypot(*u) * math.hypot(*v) and \
                        u[0] * v[0] + u[1] * v[1] > 0:
                    return (i, j)   # the two walls fold back over each other
            elif _segments_meet(a, b, c, d):
                return (i, j)
    return None


def _segments_meet(a: Point, b: Point, c: Point, d: Point) -> bool:
    def orient(p, q, r):
        value = (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])
        return 0 if abs(value) <= 1e-9 else (1 if value > 0 else -1)

    def within(p, q, r):   # q on segment p–r, given the three are collinear
        return min(p[0], r[0]) - 1e-9 <= q[0] <= max(p[0], r[0]) + 1e-9 and \
            min(p[1], r[1]) - 1e-9 <= q[1] <= max(p[1], r[1]) + 1e-9

    o1, o2, o3, o4 = orient(a, b, c), orient(a, b, d), orient(c, d, a), orient(c, d, b)
    if o1 != o2 and o3 != o4 and 0 not in (o1, o2, o3, o4):
        return True
    return (o1 == 0 and within(a, c, b)) or (o2 == 0 and within(a, d, b)) or \
        (o3 == 0 and within(c, a, d)) or (o4 == 0 and within(c, b, d))
