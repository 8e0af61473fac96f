"""Joining wall ends where they meet (for :func:`worldgen.geometry.building.build_geometry`): how far each
run's box reaches past its end points, so that corners close with no gap and no spike, and the thin filler boxes
that cover the tip of a corner sharper than 90°. See :mod:`worldgen.geometry.building` for the rules."""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..spec.model import Material, Point, Spec
from .runs import ANG_EPS, EPS, Run, fail
from .vectors import CellGrid, add, bbox, cross, dot, left_normal, meet, sub

JOIN_TOLERANCE = 0.001  # how far the union of a corner's boxes may differ from the ideal mitred band
_TIP = 0.9 * JOIN_TOLERANCE   # filler boxes go this close to a sharp corner's tip
_FILLER_OVERLAP = 1e-5  # each filler reaches this far into its neighbour, so that unions have no slits
MIN_CORNER_DEG = 2.0    # walls meeting at a sharper angle cannot be closed by a sane number of boxes


@dataclass
class _End:
    run: int
    side: int          # 0: the run's start, 1: its end
    point: Point
    u: Point           # unit direction from the end into the wall's body
    half: float        # half thickness
    corners: frozenset = frozenset()   # the (room, vertex) corners drawn at this end


@dataclass
class Filler:
    start: Point
    end: Point
    thickness: float
    height: float
    material: Material
    rooms: tuple[str, ...]


def join_corners(runs: list[Run], spec: Spec) -> list[Filler]:
    """Set every run's end extensions from what meets it there; return the filler boxes of sharp corners."""
    ends: list[_End] = []
    for k, r in enumerate(runs):
        drawn: tuple[set, set] = (set(), set())
        for e in r.edges:
            for point, corner in zip((e.p, e.q), e.corners):
                u = dot(sub(point, r.o), r.d)
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

    extent = bbox([e.point for e in ends]) if ends else (0.0, 0.0, 1.0, 1.0)
    grid = CellGrid(max(1.0, (extent[2] - extent[0] + extent[3] - extent[1]) / 128))
    for k, r in enumerate(runs):
        grid.add(k, bbox([r.at(r.u0), r.at(r.u1)], EPS))

    fillers: list[Filler] = []
    for node_ends in sorted(nodes.values(), key=lambda es: (es[0].run, es[0].side)):
        o = node_ends[0].point
        mine = {e.run for e in node_ends}
        through = []
        for k in grid.near((o[0] - EPS, o[1] - EPS, o[0] + EPS, o[1] + EPS)):
            r = runs[k]
            if k in mine:
                continue
            u = dot(sub(o, r.o), r.d)
            if abs(cross(r.d, sub(o, r.o))) <= EPS and r.u0 + EPS < u < r.u1 - EPS:
                through.append(r)
        fillers += _join_node(node_ends, through, runs, spec)
    return fillers


def _set(runs: list[Run], end: _End, e: float) -> None:
    """Let the box reach at least ``e`` past this end (an end may close two corners; the longer reach wins)."""
    run = runs[end.run]
    if end.side == 0:
        run.e0 = max(run.e0, e)
    else:
        run.e1 = max(run.e1, e)


def _stem(end: _End, walls: list[Run]) -> float:
    """How far a wall end reaches past the walls it meets at an angle (a T-junction, or a wall ending in a
    corner): as far as possible, up to the far face, while both corners of its end stay inside those walls."""
    reaches = {0.0}
    for wall in walls:
        sin_t = abs(cross(end.u, wall.d))
        cos_t = abs(dot(end.u, wall.d))
        if sin_t >= 0.05:
            reaches.add(max(0.0, (wall.half - end.half * cos_t) / sin_t))
    n = left_normal(end.u)
    for reach in sorted(reaches, reverse=True):
        tip = add(end.point, end.u, -reach)
        if all(any(_in_box(wall, add(tip, n, side * end.half)) for wall in walls) for side in (-1, 1)):
            return reach
    return 0.0


def _in_box(run: Run, p: Point) -> bool:
    """Whether p lies in the run's box as extended so far (to within a micrometre)."""
    rel = sub(p, run.o)
    u = dot(rel, run.d)
    return (run.u0 - run.e0 - 1e-6 <= u <= run.u1 + run.e1 + 1e-6
            and abs(cross(run.d, rel)) <= run.half + 1e-6)


def _angle(u: Point) -> float:
    a = math.atan2(u[1], u[0])
    return a + 2 * math.pi if a < 0 else a


def _join_node(ends: list[_End], through: list[Run], runs: list[Run], spec: Spec) -> list[Filler]:
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
    fillers: list[Filler] = []
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


def _corner(left: _End, right: _End, runs: list[Run], spec: Spec) -> list[Filler]:
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
        fail(spec, f"{r.label} and {runs[right.run].label} meet at {math.degrees(inner):.2f}°, too sharp a corner "
             f"to build from boxes", r.line, f"make the angle at least {MIN_CORNER_DEG:g}°")
    nl, nr = left_normal(left.u), left_normal(right.u)
    # outer faces: left's left side, right's right side
    out_l = add(o, nl, left.half)
    out_r = add(o, nr, -right.half)
    lam, mu = meet(out_l, left.u, out_r, right.u)
    m = add(out_l, left.u, lam)
    mitre_l, mitre_r = -lam, -mu
    # where each box's inner end corner would leave the other wall: its inner face meets the other's outer face
    safe_l = -meet(add(o, nl, -left.half), left.u, out_r, right.u)[0]
    safe_r = -meet(add(o, nr, right.half), right.u, out_l, left.u)[0]
    e_l, e_r = min(mitre_l, safe_l), min(mitre_r, safe_r)
    _set(runs, left, e_l)
    _set(runs, right, e_r)
    fillers: list[Filler] = []
    for end, mitre, e, inward in ((left, mitre_l, e_l, (-nl[0], -nl[1])), (right, mitre_r, e_r, nr)):
        run = runs[end.run]
        rooms = tuple(dict.fromkeys(x.room for x in run.edges if x.room))
        for start, stop, width in _spike_strips(m, end.u, inward, inner, mitre - e):
            fillers.append(Filler(start, stop, width, run.style.height, run.style.material, rooms))
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
        base = add(m, g, w / 2)
        strips.append((add(base, f, reach), add(base, f, r), w))
        if r <= _TIP:
            return strips
        reach = r + _FILLER_OVERLAP
        r /= q
