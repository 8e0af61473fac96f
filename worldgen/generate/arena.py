"""``arena``: one closed room whose outline is not convex, for wall following and for stopping at a wall from any side.

``right``: the footprint is a grid of square cells ``min_width`` across; cells are taken away from its edge one at a
time (each time only if the rest stays one piece, without a hole and without two cells meeting only at a corner), so
the outline stays one simple right-angled polygon and no part of the floor is narrower than a cell. The outline's
convex hull is at least :data:`NOTCH` per cent larger than the floor, so the room is never a rectangle nor one with
a token notch: when the carving leaves less (one corner cell of a large grid), the room is the grid less a corner
block a third of each side across. ``free``: a polygon of 6 to 10 corners round the footprint's
centre, each at a random angle and distance (a star-shaped polygon never crosses itself), kept when it has a corner
pointing in (by 15° at least), no corner sharper than :data:`MIN_ANGLE`, no wall shorter than :data:`MIN_EDGE` and
no two walls that do not meet closer than ``min_width``; otherwise drawn again (a right-angled L after :data:`TRIES`
draws). The robot starts at a random place at least its turning clearance from every wall, facing a wall 1 to 3.3 m
ahead (another place is drawn, a few times, until one has such a wall).
"""

from __future__ import annotations

import bisect
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
NOTCH = 3   # %: a right-angled outline's convex hull is at least this much larger than its floor
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

RING = ((0, 1), (1, 1), (1, 0), (1, -1), (0, -1), (-1, -1), (-1, 0), (-1, 1))   # round a cell, N first


class _Carving:
    """A grid of cells being carved from its edge, kept valid: one piece (four-connected), no hole, no two cells
    meeting only at a corner. Each removal is judged from the cell's eight neighbours (for such a set, taking a
    cell away keeps it one piece exactly when its neighbours left form one run round it), so carving is linear in
    the cells taken, however large the grid."""

    def __init__(self, cols: int, rows: int):
        self.cells = {(i, j) for i in range(cols) for j in range(rows)}
        self.edge = sorted(c for c in self.cells if self._on_edge(c))   # a random choice indexes this order
        self._edge = set(self.edge)
        self.col_count, self.row_count = [rows] * cols, [cols] * rows
        self.box = [0, cols - 1, 0, rows - 1]   # the cells' bounds: first and last column, first and last row

    def _on_edge(self, c: Cell) -> bool:
        return any((c[0] + di, c[1] + dj) not in self.cells for di, dj in RING[::2])

    def removable(self, c: Cell) -> bool:
        """Whether the rest after taking the edge cell ``c`` away is still valid, at least three cells and not a
        rectangle."""
        if len(self.cells) <= 3:
            return False
        here = [(c[0] + di, c[1] + dj) in self.cells for di, dj in RING]
        # the neighbours left form one run round it (so two of them never meet only at a corner either: an edge
        # cell has a side open, and a corner between two sides that are not would be a second gap in the ring)
        if sum(here[k] and not here[k - 1] for k in range(8)) != 1:
            return False
        i0, i1, j0, j1 = self.box
        i, j = c
        i0 += i == i0 and self.col_count[i] == 1
        i1 -= i == i1 and self.col_count[i] == 1
        j0 += j == j0 and self.row_count[j] == 1
        j1 -= j == j1 and self.row_count[j] == 1
        return len(self.cells) - 1 != (i1 - i0 + 1) * (j1 - j0 + 1)

    def remove(self, c: Cell) -> None:
        self.cells.discard(c)
        self.edge.pop(bisect.bisect_left(self.edge, c))
        self._edge.discard(c)
        for di, dj in RING[::2]:
            n = (c[0] + di, c[1] + dj)
            if n in self.cells and n not in self._edge:
                bisect.insort(self.edge, n)
                self._edge.add(n)
        i, j = c
        self.col_count[i] -= 1
        self.row_count[j] -= 1
        box = self.box
        while self.col_count[box[0]] == 0:
            box[0] += 1
        while self.col_count[box[1]] == 0:
            box[1] -= 1
        while self.row_count[box[2]] == 0:
            box[2] += 1
        while self.row_count[box[3]] == 0:
            box[3] -= 1

    def notched(self) -> bool:
        """Whether the cells' convex hull is at least :data:`NOTCH` larger than they are (exact: in whole
        half-cells, from the edge cells' corners)."""
        corners = {(i + a, j + b) for i, j in self.edge for a in (0, 1) for b in (0, 1)}
        return 100 * _hull_area2(sorted(corners)) >= 2 * (100 + NOTCH) * len(self.cells)


def _hull_area2(points: List[Cell]) -> int:
    """Twice the area of the convex hull of integer points sorted by x then y (Andrew's monotone chain)."""
    def half(seq):
        chain: List[Cell] = []
        for p in seq:
            while len(chain) >= 2 and ((chain[-1][0] - chain[-2][0]) * (p[1] - chain[-2][1]) -
                                       (chain[-1][1] - chain[-2][1]) * (p[0] - chain[-2][0])) <= 0:
                chain.pop()
            chain.append(p)
        return chain[:-1]
    ring = half(points) + half(points[::-1])
    return sum(ring[k - 1][0] * ring[k][1] - ring[k][0] * ring[k - 1][1] for k in range(len(ring)))


def _carve(cols: int, rows: int, rng: Rng) -> Set[Cell]:
    carving = _Carving(cols, rows)
    goal = rng.between(1, max(1, int(cols * rows * 0.4)))
    for _ in range(4 * goal):
        if len(carving.cells) <= cols * rows - goal:
            break
        cell = rng.choice(carving.edge)
        if carving.removable(cell):
            carving.remove(cell)
    if carving.notched():
        return carving.cells
    # too little taken away (a rectangle is convex, one corner cell of a large grid hardly less so): the grid
    # less a corner block a third of each side across, an L whose hull is at least 1/18 larger
    a, b = -(-cols // 3), -(-rows // 3)
    x = rng.choice([0, cols - a])
    y = rng.choice([0, rows - b])
    return {(i, j) for i in range(cols) for j in range(rows) if not (x <= i < x + a and y <= j < y + b)}


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
