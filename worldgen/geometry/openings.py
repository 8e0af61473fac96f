"""Openings on a merged wall: each spec opening is placed on its run, once runs are merged (overlaps
refused; see :func:`worldgen.geometry.building.build_geometry`), and a built wall is split into boxes around
its openings the way the Building Editor does it (pieces beside an opening, a lintel above it, a sill below a
window)."""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..spec.messages import metres   # lengths in messages, written as the spec's own messages write them
from ..spec.model import Spec
from .runs import Hole, Run, fail
from .vectors import add, dot, sub, unit


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


def place_holes(run: Run, spec: Spec) -> None:
    """Map each edge's openings onto the merged wall and refuse overlaps (exact duplicates, as two rooms sharing
    a wall may both list its door, count once)."""
    holes: list[Hole] = []
    for e in run.edges:
        length = math.dist(e.p, e.q)
        ed = unit(e.p, e.q)
        for op in e.openings:
            if op.offset < -1e-9 or op.offset + op.width > length + 1e-6:
                fail(spec, f"the {op.type} at offset {metres(op.offset)} (width {metres(op.width)}) does not fit on "
                     f"{e.label}, which is {metres(length)} m long", op.line,
                     "offset is measured from the wall's first vertex to the opening's near edge")
            top = op.sill + op.height
            if top > run.style.height + 1e-9:
                fail(spec, f"the {op.type} on {e.label} reaches {metres(top)} m, above the wall's "
                     f"{metres(run.style.height)} m", op.line, "lower its height or sill, or raise the walls")
            a = dot(sub(add(e.p, ed, op.offset), run.o), run.d)
            b = dot(sub(add(e.p, ed, op.offset + op.width), run.o), run.d)
            holes.append(Hole(min(a, b), max(a, b), op.sill, top, op, e))
    holes.sort(key=lambda h: (h.u0, h.u1, h.edge.order))
    kept: list[Hole] = []
    for h in holes:
        prev = max(kept, key=lambda k: k.u1) if kept else None
        if prev is not None and h.u0 < prev.u1 - 1e-6:
            same = (h.opening.type == prev.opening.type and abs(h.u0 - prev.u0) < 1e-6
                    and abs(h.u1 - prev.u1) < 1e-6 and abs(h.z0 - prev.z0) < 1e-6 and abs(h.z1 - prev.z1) < 1e-6)
            if same:
                continue
            where = f"line {prev.opening.line}" if prev.opening.line else prev.edge.label
            fail(spec, f"the {h.opening.type} on {h.edge.label} overlaps the {prev.opening.type} on "
                 f"{prev.edge.label} ({where}): they are on the same wall", h.opening.line,
                 "move one of them along the wall, or list a shared wall's door in one room only")
        kept.append(h)
    run.holes = kept


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
