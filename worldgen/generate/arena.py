"""``arena``: one closed room whose outline is not convex, for wall following and for stopping at a wall from any side.

``right``: the footprint is a grid of square cells ``min_width`` across; cells are taken away from its edge one at a
time (each time only if the rest stays one piece, without a hole and without two cells meeting only at a corner), so
the outline stays one simple right-angled polygon and no part of the floor is narrower than a cell. At least one
cell goes, so the room is never a plain rectangle. ``free``: a polygon of 6 to 10 corners round the footprint's
centre, each at a random angle and distance (a star-shaped polygon never crosses itself), kept when it has a corner
pointing in (by 15° at least), no corner sharper than :data:`MIN_ANGLE`, no wall shorter than :data:`MIN_EDGE` and
no two walls that do not meet closer than ``min_width``; otherwise drawn again (a right-angled L after :data:`TRIES`
draws). The robot starts at a random place at least its turning clearance from every wall, facing a wall 1 to 3.3 m
ahead (another place is drawn, a few times, until one has such a wall).
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import List, Sequence, Set, Tuple

from ..spec.model import Material, RobotPose, Room, Spec, WallStyle
from .options import ArenaOptions
from .rng import Rng
from .robot import RobotSpace
from .shapes import Point, dist, edges_of, facing, inside_polygon, min_edge_distance, point_segment, polygon_area
from .trig import PI, TAU, sin_cos

THICKNESS = 0.15
GRAIN = 0.05
MIN_ANGLE = 60.0 * PI / 180   # the sharpest corner of a free outline
MIN_EDGE = 0.8                # m: the shortest wall of a free outline
MIN_REFLEX = 195.0 * PI / 180  # a free outline has a corner pointing in at least this much
SHARP_COS = sin_cos(PI - MIN_ANGLE)[1]
REFLEX_COS = sin_cos(MIN_REFLEX - PI)[1]
TRIES = 200
AHEAD = (1.0, 3.3)
SPAWN_TRIES = 12
Cell = Tuple[int, int]


def resolve(options: ArenaOptions, space: RobotSpace) -> ArenaOptions:
    from ..core.errors import InputError

    width = round(math.ceil(options.min_width / GRAIN - 1e-9) * GRAIN, 3)
    least = round(math.ceil((THICKNESS + 2 * space.clearance) / GRAIN - 1e-9) * GRAIN, 3)
    if width < least:
        raise InputError(f"--min-width {width:g} leaves the {space.model} no room to turn",
                         hint=f"give --min-width at least {least:g}")
    w, h = (round(round(v / GRAIN) * GRAIN, 3) for v in options.size)
    if min(w, h) < 2 * width:
        raise InputError(f"--size {w:g}x{h:g} is too small for an outline with a corner pointing in",
                         hint=f"make both sides at least twice --min-width ({2 * width:g} m)")
    return replace(options, size=(w, h), min_width=width)


# ------------------------------------------------------------------------------------------------ right-angled

def _pinched(cells: Set[Cell], cols: int, rows: int) -> bool:
    """Whether two cells meet only at a corner anywhere (the outline would touch itself there)."""
    for i in range(-1, cols):
        for j in range(-1, rows):
            a, b, c, d = (i, j) in cells, (i + 1, j) in cells, (i, j + 1) in cells, (i + 1, j + 1) in cells
            if (a and d and not b and not c) or (b and c and not a and not d):
                return True
    return False


def _connected(cells: Set[Cell]) -> bool:
    start = min(cells)
    seen, todo = {start}, [start]
    while todo:
        i, j = todo.pop()
        for n in ((i + 1, j), (i - 1, j), (i, j + 1), (i, j - 1)):
            if n in cells and n not in seen:
                seen.add(n)
                todo.append(n)
    return len(seen) == len(cells)


def _carve(cols: int, rows: int, rng: Rng) -> Set[Cell]:
    cells = {(i, j) for i in range(cols) for j in range(rows)}
    goal = rng.between(1, max(1, int(cols * rows * 0.4)))
    for _ in range(4 * goal):
        if len(cells) <= cols * rows - goal:
            break
        edge = sorted(c for c in cells
                      if any(n not in cells for n in ((c[0] + 1, c[1]), (c[0] - 1, c[1]), (c[0], c[1] + 1),
                                                       (c[0], c[1] - 1))))
        cell = rng.choice(edge)
        rest = cells - {cell}
        if len(rest) >= 3 and _connected(rest) and not _pinched(rest, cols, rows) and not _rectangle(rest):
            cells = rest
    if _rectangle(cells):   # nothing taken away: a corner goes (a rectangle is convex)
        cells = cells - {rng.choice([(0, 0), (cols - 1, 0), (0, rows - 1), (cols - 1, rows - 1)])}
    return cells


def _rectangle(cells: Set[Cell]) -> bool:
    """Whether the cells fill their bounding rectangle (a whole row or column carved away leaves one)."""
    cols = {i for i, _ in cells}
    rows = {j for _, j in cells}
    return len(cells) == (max(cols) - min(cols) + 1) * (max(rows) - min(rows) + 1)


def _outline(cells: Set[Cell]) -> List[Tuple[int, int]]:
    """The cells' outline as grid corners, counter-clockwise, without corners on straight runs."""
    edges = {}
    for i, j in cells:
        for a, b, n in (((i, j), (i + 1, j), (i, j - 1)), ((i + 1, j), (i + 1, j + 1), (i + 1, j)),
                        ((i + 1, j + 1), (i, j + 1), (i, j + 1)), ((i, j + 1), (i, j), (i - 1, j))):
            if n not in cells:
                edges[a] = b
    start = min(edges)
    ring, at = [start], edges[start]
    while at != start:
        ring.append(at)
        at = edges[at]
    corners = []
    for k, p in enumerate(ring):
        a, b = ring[k - 1], ring[(k + 1) % len(ring)]
        if (p[0] - a[0]) * (b[1] - p[1]) - (p[1] - a[1]) * (b[0] - p[0]) != 0:
            corners.append(p)
    return corners


def _right(options: ArenaOptions, rng: Rng) -> Tuple[List[Point], List[Point]]:
    s = options.min_width
    cols, rows = int(options.size[0] / s + 1e-9), int(options.size[1] / s + 1e-9)
    cells = _carve(cols, rows, rng)
    x0, y0 = -cols * s / 2, -rows * s / 2
    polygon = [(round(x0 + i * s, 3), round(y0 + j * s, 3)) for i, j in _outline(cells)]
    centres = [(round(x0 + (i + 0.5) * s, 3), round(y0 + (j + 0.5) * s, 3)) for i, j in sorted(cells)]
    return polygon, centres


# ------------------------------------------------------------------------------------------------ free

def _turn(a: Point, p: Point, b: Point) -> Tuple[float, float]:
    """How a counter-clockwise outline turns at ``p``: (the sine and the cosine of the turn), positive sine to the
    left (a corner pointing out), negative to the right (a corner pointing in)."""
    ux, uy, vx, vy = p[0] - a[0], p[1] - a[1], b[0] - p[0], b[1] - p[1]
    norm = math.sqrt((ux * ux + uy * uy) * (vx * vx + vy * vy))
    return (ux * vy - uy * vx) / norm, (ux * vx + uy * vy) / norm


def _segments_apart(e: Tuple[Point, Point], f: Tuple[Point, Point]) -> float:
    return min(point_segment(e[0], *f), point_segment(e[1], *f), point_segment(f[0], *e), point_segment(f[1], *e))


def _good(polygon: Sequence[Point], width: float) -> bool:
    n = len(polygon)
    turns = [_turn(polygon[k - 1], polygon[k], polygon[(k + 1) % n]) for k in range(n)]
    # a corner sharper than MIN_ANGLE turns by more than π − MIN_ANGLE; one pointing in by MIN_REFLEX − π turns
    # to the right at least that much
    if any(sine > 0 and cosine < SHARP_COS for sine, cosine in turns) or \
            not any(sine < 0 and cosine <= REFLEX_COS for sine, cosine in turns):
        return False
    edges = edges_of(polygon)
    if min(dist(*e) for e in edges) < MIN_EDGE:
        return False
    return all(_segments_apart(edges[i], edges[j]) >= width
               for i in range(n) for j in range(i + 2, n) if not (i == 0 and j == n - 1))


def _free(options: ArenaOptions, rng: Rng) -> Tuple[List[Point], List[Point]]:
    w, h = options.size
    for _ in range(TRIES):
        n = rng.between(6, 10)
        polygon = []
        for k in range(n):
            s, c = sin_cos((k + rng.uniform(-0.3, 0.3)) * TAU / n)
            r = rng.uniform(0.55, 1.0)
            polygon.append((round(c * r * w / 2, 2), round(s * r * h / 2, 2)))
        if polygon_area(polygon) > 0 and _good(polygon, options.min_width):
            return polygon, []
    half_w, half_h = round(w / 2, 3), round(h / 2, 3)
    # an L: the footprint less its top-right quarter
    polygon = [(-half_w, -half_h), (half_w, -half_h), (half_w, 0.0), (0.0, 0.0), (0.0, half_h), (-half_w, half_h)]
    return polygon, []


def _free_spot(polygon: Sequence[Point], room_for: float, rng: Rng) -> Point:
    """A random point of the floor at least ``room_for`` from every wall's centre-line (the deepest of a 0.25 m
    grid when 200 draws find none)."""
    xs, ys = [p[0] for p in polygon], [p[1] for p in polygon]
    for _ in range(200):
        p = (round(rng.uniform(min(xs), max(xs)), 2), round(rng.uniform(min(ys), max(ys)), 2))
        if inside_polygon(p, polygon) and min_edge_distance(polygon, p) >= room_for:
            return p
    grid = [(round(min(xs) + i * 0.25, 2), round(min(ys) + j * 0.25, 2))
            for i in range(int((max(xs) - min(xs)) / 0.25) + 1) for j in range(int((max(ys) - min(ys)) / 0.25) + 1)]
    return max((p for p in grid if inside_polygon(p, polygon)), key=lambda p: (min_edge_distance(polygon, p), p))


# ------------------------------------------------------------------------------------------------ the arena

def make(name: str, options: ArenaOptions, space: RobotSpace, rng: Rng) -> Tuple[Spec, str]:
    polygon, candidates = (_right if options.outline == "right" else _free)(options, rng)
    room_for = space.clearance + THICKNESS / 2 + 0.05
    faces = _faces(polygon)
    headings = ((0.0, PI / 2, PI, -PI / 2) if options.outline == "right" else
                tuple(k * PI / 4 for k in range(-3, 5)))
    for _ in range(SPAWN_TRIES):   # a place with a wall square ahead at a distance worth driving
        # the cells' centres of a right-angled arena are each half a cell from the walls
        spawn = rng.choice(candidates) if candidates else _free_spot(polygon, room_for, rng)
        yaw, square = facing(spawn, headings, space.width / 2 + 0.05, faces, *AHEAD, rng)
        if square:
            break
    style = WallStyle(THICKNESS, options.wall_height, Material())
    spec = Spec(name=name, style=style, rooms=(Room("arena", tuple(polygon), style),),
                robot=RobotPose(options.robot, spawn, round(yaw, 4)))
    area = polygon_area(polygon)
    shape = "right-angled" if options.outline == "right" else "free"
    return spec, (f"a {shape} arena of {len(polygon)} walls and {area:.1f} m², nowhere narrower than "
                  f"{options.min_width:g} m")


def _faces(polygon: Sequence[Point]) -> List[Tuple[Point, Point]]:
    """The walls' centre-lines, each moved half a thickness into the room (near enough to its face for the
    heading; a corner's faces meet a little off the centre-lines')."""
    out = []
    for a, b in edges_of(polygon):
        length = dist(a, b)
        nx, ny = -(b[1] - a[1]) / length, (b[0] - a[0]) / length   # inward for a counter-clockwise polygon
        d = THICKNESS / 2
        out.append(((a[0] + nx * d, a[1] + ny * d), (b[0] + nx * d, b[1] + ny * d)))
    return out
