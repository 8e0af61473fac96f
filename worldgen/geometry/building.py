"""Geometry: a spec's rooms and segments become straight walls, each a set of boxes.

``build_geometry(spec)`` joins corners (no gap, no spike, whatever the angle), writes a wall shared by two rooms
once, and splits a wall around its openings the way the Building Editor does (pieces beside an opening, a lintel
above it, a sill below a window). Everything here is plain numbers; writers turn it into files.

How a plan becomes walls (all distances in metres, along wall centre-lines):

1. Every room edge and segment is an *edge*. Edges on one straight line (within ``EPS``) are projected onto that
   line; edges that overlap, or touch end to end with the same style, merge into one wall. So a wall two rooms
   share is written once, a big room's side stays one wall when a small room shares part of it, and a straight
   line of rooms' sides is one wall, as a person would draw it in the Building Editor.
2. Wall ends that meet are *nodes*. A free end reaches ``thickness/2`` past its point (the editor's way: a wall
   drawn 5 m between centre points is a 5.15 m box). The end of a wall meeting another wall's middle (a
   T-junction) reaches the far face of that wall. Two ends that a room draws as its corner (or, where no room
   does, the two on either side of a gap of 180° or more) reach the point where their outer faces meet
   (``(t/2)·tan(φ/2)`` for a turn of φ), which closes the corner exactly; where that would poke out (a corner
   sharper than 90°) each wall stops where it still lies inside the other, and thin *filler* boxes along the
   outer faces cover the mitre's spike, so the union of all boxes stays within ``JOIN_TOLERANCE`` of the ideal
   mitred band and nothing pokes out of it. Other ends (a Y of three walls, say) stop at the point, which
   already closes it.
3. Openings are placed on their merged wall and split it into pieces; an opening that runs into another wall
   (a corner, a T-junction, a crossing) or overlaps another opening is a SpecError naming its spec line.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from ..core.errors import SpecError
from ..spec.messages import metres as _m   # lengths in messages, written as the spec's own messages write them
from ..spec.model import Material, Obstacle, Opening, Point, RobotPose, Spec, WallStyle

EPS = 1e-3              # two points closer than this are one point; a point this close to a line lies on it
ANG_EPS = 1e-4          # edges whose directions differ less than this (radians) are parallel
JOIN_TOLERANCE = 0.001  # how far the union of a corner's boxes may differ from the ideal mitred band
_TIP = 0.9 * JOIN_TOLERANCE   # filler boxes go this close to a sharp corner's tip
_FILLER_OVERLAP = 1e-5  # each filler reaches this far into its neighbour, so that unions have no slits
_CLEAR = 1e-4           # an opening may touch another wall's box but not cut into it by more than this
MIN_CORNER_DEG = 2.0    # walls meeting at a sharper angle cannot be closed by a sane number of boxes


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
    is the box length of an unsplit wall. A ``filler`` is a thin box that fills the tip of a corner sharper than
    90° (no openings, one piece)."""

    index: int
    start: Point
    end: Point
    thickness: float
    height: float
    material: Material
    pieces: tuple[Piece, ...]
    openings: tuple[PlacedOpening, ...] = ()
    rooms: tuple[str, ...] = ()
    filler: bool = False

    @property
    def length(self) -> float:
        return math.dist(self.start, self.end)

    @property
    def yaw(self) -> float:
        return math.atan2(self.end[1] - self.start[1], self.end[0] - self.start[0])

    def footprint(self) -> tuple[Point, Point, Point, Point]:
        """The four corners of the wall's box seen from above (counter-clockwise from start-right)."""
        return _rectangle(self.start, self.end, self.thickness)


@dataclass(frozen=True)
class Building:
    name: str
    walls: tuple[Wall, ...]
    obstacles: tuple[Obstacle, ...]
    robot: RobotPose | None
    origin: Point          # the bounding-box centre of the walls: the model pose, as the Building Editor writes it
    bounds: tuple[float, float, float, float]   # xmin, ymin, xmax, ymax of everything built


# ------------------------------------------------------------------------------------------------ vectors
def _sub(a: Point, b: Point) -> Point:
    return (a[0] - b[0], a[1] - b[1])


def _add(a: Point, b: Point, k: float = 1.0) -> Point:
    return (a[0] + k * b[0], a[1] + k * b[1])


def _dot(a: Point, b: Point) -> float:
    return a[0] * b[0] + a[1] * b[1]


def _cross(a: Point, b: Point) -> float:
    return a[0] * b[1] - a[1] * b[0]


def _left(u: Point) -> Point:
    return (-u[1], u[0])


def _unit(a: Point, b: Point) -> Point:
    length = math.dist(a, b)
    return ((b[0] - a[0]) / length, (b[1] - a[1]) / length)


def _meet(p: Point, d: Point, q: Point, e: Point) -> tuple[float, float] | None:
    """(λ, μ) with p + λ·d = q + μ·e, or None for parallel lines."""
    den = _cross(d, e)
    if abs(den) < 1e-12:
        return None
    w = _sub(q, p)
    return _cross(w, e) / den, _cross(w, d) / den


def _rectangle(start: Point, end: Point, thickness: float) -> tuple[Point, Point, Point, Point]:
    n = _left(_unit(start, end)) if start != end else (0.0, 1.0)
    h = thickness / 2
    return (_add(start, n, -h), _add(end, n, -h), _add(end, n, h), _add(start, n, h))


# ------------------------------------------------------------------------------------------ working data
@dataclass
class _Edge:
    """A straight wall as the spec draws it: a room's side or a segment."""

    p: Point
    q: Point
    style: WallStyle
    order: int
    label: str
    room: str | None
    line: int | None
    openings: tuple[Opening, ...]
    corners: tuple[tuple[int, int] | None, tuple[int, int] | None] = (None, None)   # (room, vertex) at p and q


@dataclass
class _Hole:
    u0: float
    u1: float
    z0: float
    z1: float
    opening: Opening
    edge: _Edge


@dataclass
class _Run:
    """A merged wall: ``u0..u1`` along the line through ``o`` with direction ``d``; ``e0``/``e1`` how far its box
    reaches past its start/end point."""

    o: Point
    d: Point
    u0: float
    u1: float
    style: WallStyle
    edges: list[_Edge]
    holes: list[_Hole] = field(default_factory=list)
    e0: float = 0.0
    e1: float = 0.0

    def at(self, u: float) -> Point:
        return _add(self.o, self.d, u)

    @property
    def label(self) -> str:
        return self.edges[0].label

    @property
    def half(self) -> float:
        return self.style.thickness / 2


@dataclass
class _End:
    run: int
    side: int          # 0: the run's start, 1: its end
    point: Point
    u: Point           # unit direction from the end into the wall's body
    half: float        # half thickness
    corners: frozenset = frozenset()   # the (room, vertex) corners drawn at this end


@dataclass
class _Filler:
    start: Point
    end: Point
    thickness: float
    height: float
    material: Material
    rooms: tuple[str, ...]


class _Grid:
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


def _bbox(points, pad: float = 0.0) -> tuple[float, float, float, float]:
    xs = [p[0] for p in points]
    ys = [p[1] for p in points]
    return min(xs) - pad, min(ys) - pad, max(xs) + pad, max(ys) + pad


def _fail(spec: Spec, message: str, line: int | None, hint: str | None = None):
    raise SpecError(message, path=spec.source, line=line, hint=hint)


# ------------------------------------------------------------------------------------------------- public
def build_geometry(spec: Spec) -> Building:
    """The walls (boxes), obstacles and robot pose of ``spec``; raises SpecError for what only geometry can tell
    (openings overlapping on a shared wall or running into another wall, shared walls of different thickness)."""
    runs = _merge(_edges(spec), spec)
    for run in runs:
        _place_holes(run, spec)
    fillers = _join(runs, spec)
    walls = [_wall(i, run) for i, run in enumerate(runs)]
    walls += [Wall(len(walls) + i, f.start, f.end, f.thickness, f.height, f.material,
                   (Piece(0.0, math.dist(f.start, f.end), 0.0, f.height),), rooms=f.rooms, filler=True)
              for i, f in enumerate(fillers)]
    _check_clearance(walls, runs, spec)
    if spec.name == "ground_plane" and walls:
        _fail(spec, "the world cannot be named 'ground_plane': its building model would clash with the ground",
              None, "choose another name")
    obstacle_names(spec.obstacles, spec.name, spec=spec)

    wall_points = [c for w in walls for c in w.footprint()]
    if wall_points:
        wx0, wy0, wx1, wy1 = _bbox(wall_points)
        origin = ((wx0 + wx1) / 2, (wy0 + wy1) / 2)
    else:
        origin = (0.0, 0.0)
    everything = wall_points + [c for o in spec.obstacles for c in obstacle_footprint(o)]
    bounds = _bbox(everything) if everything else (0.0, 0.0, 0.0, 0.0)
    return Building(spec.name, tuple(walls), spec.obstacles, spec.robot, origin, bounds)


def obstacle_names(obstacles, building_name: str, *, spec: Spec | None = None) -> list[str]:
    """Each obstacle's model name: its own, or ``obstacle_N`` (N its place in the spec, from 0). Raises
    SpecError when two models of the world would share a name."""
    names = [o.name or f"obstacle_{i}" for i, o in enumerate(obstacles)]
    taken = {building_name: "the building", "ground_plane": "the ground plane"}
    for i, (o, name) in enumerate(zip(obstacles, names)):
        if name in taken:
            what = (f"obstacle name '{name}'" if o.name else
                    f"obstacle {i + 1} has no name, and the one it gets, '{name}',")
            raise SpecError(f"{what} is already used by {taken[name]}", path=spec.source if spec else None,
                            line=o.line, hint="give every obstacle its own name")
        taken[name] = f"the obstacle on line {o.line}" if o.line else "another obstacle"
    return names


def obstacle_footprint(o: Obstacle) -> list[Point]:
    """Points whose bounding box is the obstacle's footprint (a box's corners, a round shape's extremes)."""
    x, y = o.at
    if o.shape == "box" and o.size is not None:
        c, s = math.cos(o.yaw), math.sin(o.yaw)
        hx, hy = o.size[0] / 2, o.size[1] / 2
        return [(x + c * a - s * b, y + s * a + c * b) for a, b in ((-hx, -hy), (hx, -hy), (hx, hy), (-hx, hy))]
    r = o.radius or 0.0
    return [(x - r, y - r), (x + r, y + r)]


# -------------------------------------------------------------------------------------------- 1. merging
def _edges(spec: Spec) -> list[_Edge]:
    edges: list[_Edge] = []
    for r, room in enumerate(spec.rooms):
        vs = room.vertices
        for i, p in enumerate(vs):
            q = vs[(i + 1) % len(vs)]
            label = f"room '{room.name}' wall {i}"
            if math.dist(p, q) <= EPS:
                _fail(spec, f"{label} has no length (vertices {i} and {(i + 1) % len(vs)} coincide)", room.line,
                      "remove the repeated vertex")
            edges.append(_Edge(p, q, room.style, len(edges), label, room.name, room.line,
                               tuple(o for o in room.openings if o.wall == i),
                               ((r, i), (r, (i + 1) % len(vs)))))
        for o in room.openings:
            if not 0 <= o.wall < len(vs):
                _fail(spec, f"room '{room.name}' has no wall {o.wall} (its walls are 0 to {len(vs) - 1})", o.line,
                      "wall i runs from corner i to the next")
    for j, seg in enumerate(spec.segments):
        label = f"segment {j + 1}"   # counted from 1, as the spec's messages count them
        if math.dist(seg.start, seg.end) <= EPS:
            _fail(spec, f"{label} has no length", seg.line, "give it two different end points")
        for o in seg.openings:
            if o.wall != 0:
                _fail(spec, f"{label} has only wall 0", o.line, "a segment is a single wall: wall 0")
        edges.append(_Edge(seg.start, seg.end, seg.style, len(edges), label, None, seg.line, seg.openings))
    return edges


def _direction_key(e: _Edge) -> float:
    theta = math.atan2(e.q[1] - e.p[1], e.q[0] - e.p[0])
    if theta < 0:
        theta += math.pi
    if theta >= math.pi - ANG_EPS:
        theta -= math.pi
    return theta


def _chains(items: list, key, tol: float) -> list[list]:
    """Split items sorted by ``key`` wherever consecutive keys differ by more than ``tol``."""
    groups: list[list] = []
    last = None
    for item in items:
        k = key(item)
        if last is None or k - last > tol:
            groups.append([])
        groups[-1].append(item)
        last = k
    return groups


def _merge(edges: list[_Edge], spec: Spec) -> list[_Run]:
    """Group edges by the straight line they lie on, then merge overlapping or touching stretches."""
    keyed = sorted(((_direction_key(e), e.order, e) for e in edges), key=lambda t: (t[0], t[1]))
    runs: list[_Run] = []
    for same_dir in _chains(keyed, lambda t: t[0], ANG_EPS):
        ref = min(same_dir, key=lambda t: t[1])[2]
        n = _left(_unit(ref.p, ref.q))
        offsets = sorted(((_dot(n, _sub(e.p, ref.p)) + _dot(n, _sub(e.q, ref.p))) / 2, e.order, e)
                         for _, _, e in same_dir)
        for same_line in _chains(offsets, lambda t: t[0], EPS):
            runs += _merge_line([t[2] for t in same_line], spec)
    runs.sort(key=lambda r: r.edges[0].order)
    return runs


def _merge_line(edges: list[_Edge], spec: Spec) -> list[_Run]:
    ref = min(edges, key=lambda e: e.order)
    o, d = ref.p, _unit(ref.p, ref.q)
    spans = []
    for e in edges:
        a, b = _dot(_sub(e.p, o), d), _dot(_sub(e.q, o), d)
        spans.append((min(a, b), max(a, b), e.order, e))
    spans.sort(key=lambda s: (s[0], s[2]))
    runs: list[_Run] = []
    for lo, hi, _, e in spans:
        run = runs[-1] if runs else None
        if run is not None and lo < run.u1 - EPS:           # overlaps: one wall, whatever the materials say
            if (abs(e.style.thickness - run.style.thickness) > 1e-9
                    or abs(e.style.height - run.style.height) > 1e-9):
                _fail(spec, f"{e.label} and {run.label} share a wall but draw it "
                      f"{_m(e.style.thickness)} m thick and {_m(e.style.height)} m high against "
                      f"{_m(run.style.thickness)} m and {_m(run.style.height)} m",
                      e.line, "give both the same wall thickness and height")
        elif run is None or lo > run.u1 + EPS or e.style != run.style:
            runs.append(_Run(o, d, lo, hi, e.style, [e]))
            continue
        run.edges.append(e)
        run.u1 = max(run.u1, hi)
        if e.order < run.edges[0].order:                   # the first edge drawn gives the wall its material
            run.edges.insert(0, run.edges.pop())
            run.style = e.style
    return runs


# ------------------------------------------------------------------------------------------- 2. openings
def _place_holes(run: _Run, spec: Spec) -> None:
    """Map each edge's openings onto the merged wall and refuse overlaps (exact duplicates, as two rooms sharing
    a wall may both list its door, count once)."""
    holes: list[_Hole] = []
    for e in run.edges:
        length = math.dist(e.p, e.q)
        ed = _unit(e.p, e.q)
        for op in e.openings:
            if op.offset < -1e-9 or op.offset + op.width > length + 1e-6:
                _fail(spec, f"the {op.type} at offset {_m(op.offset)} (width {_m(op.width)}) does not fit on "
                      f"{e.label}, which is {_m(length)} m long", op.line,
                      "offset is measured from the wall's first vertex to the opening's near edge")
            top = op.sill + op.height
            if top > run.style.height + 1e-9:
                _fail(spec, f"the {op.type} on {e.label} reaches {_m(top)} m, above the wall's "
                      f"{_m(run.style.height)} m", op.line, "lower its height or sill, or raise the walls")
            a = _dot(_sub(_add(e.p, ed, op.offset), run.o), run.d)
            b = _dot(_sub(_add(e.p, ed, op.offset + op.width), run.o), run.d)
            holes.append(_Hole(min(a, b), max(a, b), op.sill, top, op, e))
    holes.sort(key=lambda h: (h.u0, h.u1, h.edge.order))
    kept: list[_Hole] = []
    for h in holes:
        prev = max(kept, key=lambda k: k.u1) if kept else None
        if prev is not None and h.u0 < prev.u1 - 1e-6:
            same = (h.opening.type == prev.opening.type and abs(h.u0 - prev.u0) < 1e-6
                    and abs(h.u1 - prev.u1) < 1e-6 and abs(h.z0 - prev.z0) < 1e-6 and abs(h.z1 - prev.z1) < 1e-6)
            if same:
                continue
            where = f"line {prev.opening.line}" if prev.opening.line else prev.edge.label
            _fail(spec, f"the {h.opening.type} on {h.edge.label} overlaps the {prev.opening.type} on "
                  f"{prev.edge.label} ({where}): they are on the same wall", h.opening.line,
                  "move one of them along the wall, or list a shared wall's door in one room only")
        kept.append(h)
    run.holes = kept


# ---------------------------------------------------------------------------------------------- 3. joins
def _join(runs: list[_Run], spec: Spec) -> list[_Filler]:
    """Set every run's end extensions from what meets it there; return the filler boxes of sharp corners."""
    ends: list[_End] = []
    for k, r in enumerate(runs):
        drawn: tuple[set, set] = (set(), set())
        for e in r.edges:
            for point, corner in zip((e.p, e.q), e.corners):
                u = _dot(_sub(point, r.o), r.d)
                for side, at in ((0, r.u0), (1, r.u1)):
                    if corner is not None and abs(u - at) <= EPS:
                        drawn[side].add(corner)
        ends.append(_End(k, 0, r.at(r.u0), r.d, r.half, frozenset(drawn[0])))
        ends.append(_End(k, 1, r.at(r.u1), (-r.d[0], -r.d[1]), r.half, frozenset(drawn[1])))

    # cluster end points closer than EPS (union-find over a fine grid)
    parent = list(range(len(ends)))

    def root(i: int) -> int:
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    cell = 4 * EPS
    buckets: dict[tuple[int, int], list[int]] = {}
    for i, e in enumerate(ends):
        bx, by = math.floor(e.point[0] / cell), math.floor(e.point[1] / cell)
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for j in buckets.get((bx + dx, by + dy), ()):
                    if math.dist(ends[j].point, e.point) <= EPS:
                        parent[root(i)] = root(j)
        buckets.setdefault((bx, by), []).append(i)
    nodes: dict[int, list[_End]] = {}
    for i, e in enumerate(ends):
        nodes.setdefault(root(i), []).append(e)

    extent = _bbox([e.point for e in ends]) if ends else (0.0, 0.0, 1.0, 1.0)
    grid = _Grid(max(1.0, (extent[2] - extent[0] + extent[3] - extent[1]) / 128))
    for k, r in enumerate(runs):
        grid.add(k, _bbox([r.at(r.u0), r.at(r.u1)], EPS))

    fillers: list[_Filler] = []
    for node_ends in sorted(nodes.values(), key=lambda es: (es[0].run, es[0].side)):
        o = node_ends[0].point
        mine = {e.run for e in node_ends}
        through = []
        for k in grid.near((o[0] - EPS, o[1] - EPS, o[0] + EPS, o[1] + EPS)):
            r = runs[k]
            if k in mine:
                continue
            u = _dot(_sub(o, r.o), r.d)
            if abs(_cross(r.d, _sub(o, r.o))) <= EPS and r.u0 + EPS < u < r.u1 - EPS:
                through.append(r)
        fillers += _join_node(node_ends, through, runs, spec)
    return fillers


def _set(runs: list[_Run], end: _End, e: float) -> None:
    """Let the box reach at least ``e`` past this end (an end may close two corners; the longer reach wins)."""
    run = runs[end.run]
    if end.side == 0:
        run.e0 = max(run.e0, e)
    else:
        run.e1 = max(run.e1, e)


def _stem(end: _End, walls: list[_Run]) -> float:
    """How far a wall end reaches past the walls it meets at an angle (a T-junction, or a wall ending in a
    corner): as far as possible, up to the far face, while both corners of its end stay inside those walls."""
    reaches = {0.0}
    for wall in walls:
        sin_t = abs(_cross(end.u, wall.d))
        cos_t = abs(_dot(end.u, wall.d))
        if sin_t >= 0.05:
            reaches.add(max(0.0, (wall.half - end.half * cos_t) / sin_t))
    n = _left(end.u)
    for reach in sorted(reaches, reverse=True):
        tip = _add(end.point, end.u, -reach)
        if all(any(_in_box(wall, _add(tip, n, side * end.half)) for wall in walls) for side in (-1, 1)):
            return reach
    return 0.0


def _in_box(run: _Run, p: Point) -> bool:
    """Whether p lies in the run's box as extended so far (to within a micrometre)."""
    rel = _sub(p, run.o)
    u = _dot(rel, run.d)
    return (run.u0 - run.e0 - 1e-6 <= u <= run.u1 + run.e1 + 1e-6
            and abs(_cross(run.d, rel)) <= run.half + 1e-6)


def _angle(u: Point) -> float:
    a = math.atan2(u[1], u[0])
    return a + 2 * math.pi if a < 0 else a


def _join_node(ends: list[_End], through: list[_Run], runs: list[_Run], spec: Spec) -> list[_Filler]:
    """Set the reach of every wall end meeting at one point.

    * Corners: two ends that a room draws as its corner (consecutive sides) are mitred. At a point on no other
      wall and without such a room corner, the two ends on either side of a gap of 180° or more are (two
      segments, or a room side and a segment, meeting end to end).
    * An end on another wall's middle (a T-junction, or a room corner on a wall) also reaches into that wall,
      up to its far face; an end beside a corner reaches into the corner's walls as far as it stays inside them.
    * An end alone is free: it reaches half its thickness.
    * Anything else ends at the point. That is enough: where no gap is 180° or more (a Y), every gap's facing
      faces meet on both walls' bodies, so the polygon around the point is the union of triangles (point, gap
      before wall k, gap after wall k), each inside wall k's band.
    """
    if len(ends) == 1 and not through:
        _set(runs, ends[0], ends[0].half)
        return []
    ends = sorted(ends, key=lambda e: (_angle(e.u), e.run, e.side))
    pairs = [(a, b) for i, a in enumerate(ends) for b in ends[i + 1:] if a.corners & b.corners]
    if not pairs and not through:
        gaps = [(_angle(ends[(i + 1) % len(ends)].u) - _angle(ends[i].u)) % (2 * math.pi) for i in range(len(ends))]
        widest = max(range(len(ends)), key=lambda i: gaps[i])
        if gaps[widest] >= math.pi - ANG_EPS:
            pairs = [(ends[widest], ends[(widest + 1) % len(ends)])]
    fillers: list[_Filler] = []
    for a, b in pairs:
        outside_from_a = (_angle(b.u) - _angle(a.u)) % (2 * math.pi) >= math.pi
        fillers += _corner(a, b, runs, spec) if outside_from_a else _corner(b, a, runs, spec)
    paired = [e for pair in pairs for e in pair]
    for end in ends:
        if through:
            _set(runs, end, _stem(end, through))
        elif end not in paired:
            _set(runs, end, _stem(end, [runs[e.run] for e in paired]) if paired else 0.0)
    return fillers


def _corner(left: _End, right: _End, runs: list[_Run], spec: Spec) -> list[_Filler]:
    """Two walls meeting at a corner; the outer side is the reflex gap going counter-clockwise from ``left`` to
    ``right``. Each box reaches the mitre point of the outer faces, or stops where it would poke out of the
    other wall and leaves the mitre's tip to filler boxes."""
    o = left.point
    inner = _angle(left.u) - _angle(right.u)
    inner = inner % (2 * math.pi)                    # the corner's inside angle, from right ccw to left
    if abs(inner - math.pi) < ANG_EPS:               # straight on: walls of different style meeting end to end
        _set(runs, left, 0.0)
        _set(runs, right, 0.0)
        return []
    if inner < math.radians(MIN_CORNER_DEG):
        r = runs[left.run].edges[0]
        _fail(spec, f"{r.label} and {runs[right.run].label} meet at {math.degrees(inner):.2f}°, too sharp a corner "
              f"to build from boxes", r.line, f"make the angle at least {MIN_CORNER_DEG:g}°")
    nl, nr = _left(left.u), _left(right.u)
    # outer faces: left's left side, right's right side
    out_l = _add(o, nl, left.half)
    out_r = _add(o, nr, -right.half)
    lam, mu = _meet(out_l, left.u, out_r, right.u)
    m = _add(out_l, left.u, lam)
    mitre_l, mitre_r = -lam, -mu
    # where each box's inner end corner would leave the other wall: its inner face meets the other's outer face
    safe_l = -_meet(_add(o, nl, -left.half), left.u, out_r, right.u)[0]
    safe_r = -_meet(_add(o, nr, right.half), right.u, out_l, left.u)[0]
    e_l, e_r = min(mitre_l, safe_l), min(mitre_r, safe_r)
    _set(runs, left, e_l)
    _set(runs, right, e_r)
    fillers: list[_Filler] = []
    for end, mitre, e, inward in ((left, mitre_l, e_l, (-nl[0], -nl[1])), (right, mitre_r, e_r, nr)):
        run = runs[end.run]
        rooms = tuple(dict.fromkeys(x.room for x in run.edges if x.room))
        for start, stop, width in _spike_strips(m, end.u, inward, inner, mitre - e):
            fillers.append(_Filler(start, stop, width, run.style.height, run.style.material, rooms))
    return fillers


def _spike_strips(m: Point, f: Point, g: Point, alpha: float, rho: float) -> list[tuple[Point, Point, float]]:
    """Boxes filling one half of a sharp corner's mitre tip.

    The tip is the wedge of angle ``alpha`` at the mitre point ``m`` between the two walls' outer faces; this
    face runs from ``m`` in direction ``f`` and ``g`` points from it into its wall. The wall's own box covers the
    face from ``rho`` on. Strip k lies along the face from ``r_k`` to ``r_(k-1)``, ``r_k·tan(alpha)`` wide, so its
    inner corner nearest the tip sits exactly on the other wall's outer face (nothing pokes out) while it covers
    this face's half of the wedge (the half nearer this face than the bisector) over its stretch, since that half
    is at most ``r_(k-1)·tan(alpha/2)`` wide there. Hence r shrinks by ``q = tan(alpha)/tan(alpha/2)`` (about 2)
    per strip, and the strips stop once the uncovered tip is shorter than ``_TIP``.
    """
    if rho <= _TIP:
        return []
    q = math.tan(alpha) / math.tan(alpha / 2)
    strips = []
    reach = rho + _FILLER_OVERLAP
    r = rho / q
    while True:
        w = r * math.tan(alpha)
        base = _add(m, g, w / 2)
        strips.append((_add(base, f, reach), _add(base, f, r), w))
        if r <= _TIP:
            return strips
        reach = r + _FILLER_OVERLAP
        r /= q


# ----------------------------------------------------------------------------------------------- 4. walls
def _wall(index: int, run: _Run) -> Wall:
    start = run.at(run.u0 - run.e0)
    end = run.at(run.u1 + run.e1)
    length = run.u1 - run.u0 + run.e0 + run.e1
    height = run.style.height
    shift = run.e0 - run.u0
    openings = tuple(PlacedOpening(h.opening.type, h.u0 + shift, h.u1 + shift, h.z0, h.z1) for h in run.holes)
    rooms = tuple(dict.fromkeys(e.room for e in sorted(run.edges, key=lambda e: e.order) if e.room))
    return Wall(index, start, end, run.style.thickness, height, run.style.material,
                split_pieces(length, height, openings), openings, rooms)


def split_pieces(length: float, height: float, openings) -> tuple[Piece, ...]:
    """The boxes of a wall ``length`` long and ``height`` high around its openings (sorted along the wall, not
    overlapping): full-height pieces between them, a sill under each window, a lintel over each opening that
    is lower than the wall. Pieces shorter or lower than 0.1 mm are dropped (an opening as long and as high as
    the whole wall leaves none)."""
    pieces: list[Piece] = []
    s = 0.0
    for op in openings:
        if op.s0 - s > 1e-4:
            pieces.append(Piece(s, op.s0, 0.0, height))
        if op.z0 > 1e-4:
            pieces.append(Piece(op.s0, op.s1, 0.0, op.z0))
        if height - op.z1 > 1e-4:
            pieces.append(Piece(op.s0, op.s1, op.z1, height))
        s = max(s, op.s1)
    if length - s > 1e-4:
        pieces.append(Piece(s, length, 0.0, height))
    return tuple(pieces)


def _check_clearance(walls: list[Wall], runs: list[_Run], spec: Spec) -> None:
    """An opening must not run into another wall's box (a corner, a T-junction, a crossing)."""
    if not any(w.openings for w in walls):
        return
    extent = _bbox([c for w in walls for c in w.footprint()])
    grid = _Grid(max(1.0, (extent[2] - extent[0] + extent[3] - extent[1]) / 128))
    for w in walls:
        grid.add(w.index, _bbox(w.footprint()))
    for w, run in zip(walls, runs):
        d = _unit(w.start, w.end)
        for op, hole in zip(w.openings, run.holes):
            a = _add(w.start, d, op.s0 + _CLEAR)
            b = _add(w.start, d, op.s1 - _CLEAR)
            rect = _rectangle(a, b, w.thickness - 2 * _CLEAR)
            for k in grid.near(_bbox(rect)):
                other = walls[k]
                if k != w.index and _overlap(rect, other.footprint()):
                    what = runs[k].label if k < len(runs) else "a corner filler"
                    _fail(spec, f"the {op.type} on {hole.edge.label} runs into {what}", hole.opening.line,
                          "move the opening along its wall so that it clears the walls meeting it")


def _overlap(a, b) -> bool:
    """Whether two convex polygons (corner lists) overlap with positive area (separating axis test)."""
    for poly in (a, b):
        for i, p in enumerate(poly):
            q = poly[(i + 1) % len(poly)]
            axis = _left(_sub(q, p))
            pa = [_dot(axis, v) for v in a]
            pb = [_dot(axis, v) for v in b]
            if max(pa) <= min(pb) or max(pb) <= min(pa):
                return False
    return True
