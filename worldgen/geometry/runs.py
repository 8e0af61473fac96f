"""Merging a spec's walls into straight runs: every room side and segment is an *edge*; edges on one straight line
that overlap, or touch end to end with the same style, become one *run* (a wall written once). The first step of
:func:`worldgen.geometry.building.build_geometry`; the working data the later steps share (edges, runs, the holes
openings cut) is defined here."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from ..core.errors import SpecError
from ..spec.messages import metres   # lengths in messages, written as the spec's own messages write them
from ..spec.model import Opening, Point, Spec, WallStyle
from .vectors import add, dot, left_normal, sub, unit

EPS = 1e-3              # two points closer than this are one point; a point this close to a line lies on it
ANG_EPS = 1e-4          # edges whose directions differ less than this (radians) are parallel


# ------------------------------------------------------------------------------------------ working data
@dataclass
class Edge:
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
class Hole:
    u0: float
    u1: float
    z0: float
    z1: float
    opening: Opening
    edge: Edge


@dataclass
class Run:
    """A merged wall: ``u0..u1`` along the line through ``o`` with direction ``d``; ``e0``/``e1`` how far its box
    reaches past its start/end point."""

    o: Point
    d: Point
    u0: float
    u1: float
    style: WallStyle
    edges: list[Edge]
    holes: list[Hole] = field(default_factory=list)
    e0: float = 0.0
    e1: float = 0.0

    def at(self, u: float) -> Point:
        return add(self.o, self.d, u)

    @property
    def label(self) -> str:
        return self.edges[0].label

    @property
    def half(self) -> float:
        return self.style.thickness / 2


def fail(spec: Spec, message: str, line: int | None, hint: str | None = None):
    """Raise the SpecError that names the spec's file and ``line``: what only the geometry can tell."""
    raise SpecError(message, path=spec.source, line=line, hint=hint)


# ------------------------------------------------------------------------------------------------ merging
def spec_edges(spec: Spec) -> list[Edge]:
    edges: list[Edge] = []
    for r, room in enumerate(spec.rooms):
        vs = room.vertices
        for i, p in enumerate(vs):
            q = vs[(i + 1) % len(vs)]
            label = f"room '{room.name}' wall {i}"
            if math.dist(p, q) <= EPS:
                fail(spec, f"{label} has no length (vertices {i} and {(i + 1) % len(vs)} coincide)", room.line,
                     "remove the repeated vertex")
            edges.append(Edge(p, q, room.style, len(edges), label, room.name, room.line,
                              tuple(o for o in room.openings if o.wall == i),
                              ((r, i), (r, (i + 1) % len(vs)))))
        for o in room.openings:
            if not 0 <= o.wall < len(vs):
                fail(spec, f"room '{room.name}' has no wall {o.wall} (its walls are 0 to {len(vs) - 1})", o.line,
                     "wall i runs from corner i to the next")
    for j, seg in enumerate(spec.segments):
        label = f"segment {j + 1}"   # counted from 1, as the spec's messages count them
        if math.dist(seg.start, seg.end) <= EPS:
            fail(spec, f"{label} has no length", seg.line, "give it two different end points")
        for o in seg.openings:
            if o.wall != 0:
                fail(spec, f"{label} has only wall 0", o.line, "a segment is a single wall: wall 0")
        edges.append(Edge(seg.start, seg.end, seg.style, len(edges), label, None, seg.line, seg.openings))
    return edges


def _direction_key(e: Edge) -> float:
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


def merge_edges(edges: list[Edge], spec: Spec) -> list[Run]:
    """Group edges by the straight line they lie on, then merge overlapping or touching stretches."""
    keyed = sorted(((_direction_key(e), e.order, e) for e in edges), key=lambda t: (t[0], t[1]))
    runs: list[Run] = []
    for same_dir in _chains(keyed, lambda t: t[0], ANG_EPS):
        ref = min(same_dir, key=lambda t: t[1])[2]
        n = left_normal(unit(ref.p, ref.q))
        offsets = sorted(((dot(n, sub(e.p, ref.p)) + dot(n, sub(e.q, ref.p))) / 2, e.order, e)
                         for _, _, e in same_dir)
        for same_line in _chains(offsets, lambda t: t[0], EPS):
            runs += _merge_line([t[2] for t in same_line], spec)
    runs.sort(key=lambda r: r.edges[0].order)
    return runs


def _merge_line(edges: list[Edge], spec: Spec) -> list[Run]:
    ref = min(edges, key=lambda e: e.order)
    o, d = ref.p, unit(ref.p, ref.q)
    spans = []
    for e in edges:
        a, b = dot(sub(e.p, o), d), dot(sub(e.q, o), d)
        spans.append((min(a, b), max(a, b), e.order, e))
    spans.sort(key=lambda s: (s[0], s[2]))
    runs: list[Run] = []
    for lo, hi, _, e in spans:
        run = runs[-1] if runs else None
        if run is not None and lo < run.u1 - EPS:           # overlaps: one wall, whatever the materials say
            if (abs(e.style.thickness - run.style.thickness) > 1e-9
                    or abs(e.style.height - run.style.height) > 1e-9):
                fail(spec, f"{e.label} and {run.label} share a wall but draw it "
                     f"{metres(e.style.thickness)} m thick and {metres(e.style.height)} m high against "
                     f"{metres(run.style.thickness)} m and {metres(run.style.height)} m",
                     e.line, "give both the same wall thickness and height")
        elif run is None or lo > run.u1 + EPS or e.style != run.style:
            runs.append(Run(o, d, lo, hi, e.style, [e]))
            continue
        run.edges.append(e)
        run.u1 = max(run.u1, hi)
        if e.order < run.edges[0].order:                   # the first edge drawn gives the wall its material
            run.edges.insert(0, run.edges.pop())
            run.style = e.style
    return runs
