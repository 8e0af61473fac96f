"""Findings about a world built from a spec, in the spec's own words.

The SDF writer names each wall's collision ``Wall_N_Collision[_i]`` in a link ``Wall_N`` of the model named after
the spec (:mod:`worldgen.sdf.writer`), N being the index of the geometry's merged wall
(:func:`worldgen.geometry.building.build_geometry`). A merged wall is the union of the spec's room sides and
segments that lie on its line and overlap it, so each N maps back to those: ``room 'kitchen', wall 2 (from
(2.5,-2) to (6,-2))``, a shared wall naming every room that draws it. :func:`rename_findings` rewrites the scene's
labels in findings' messages and places with those names, and a floor marking's link (``floor_markings/track``)
with the spec's line or patch (``line 'track'``, at its line in the spec).
"""

from __future__ import annotations

import math
import re
from dataclasses import replace
from typing import Dict, List

from ..core.findings import Finding
from ..spec.model import MARKINGS_MODEL
from ..geometry.building import build_geometry

ON_LINE = 1e-3   # m: a spec side this close to a wall's centre-line lies on it


def _num(value: float) -> str:
    text = f"{value:.3f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def _pt(p) -> str:
    return f"({_num(p[0])},{_num(p[1])})"


def _spec_sides(spec) -> list[tuple[str, tuple, tuple]]:
    """Every side the spec draws: (its name, from, to)."""
    sides = []
    for room in spec.rooms:
        vs = room.vertices
        for i, p in enumerate(vs):
            q = vs[(i + 1) % len(vs)]
            sides.append((f"room '{room.name}', wall {i} (from {_pt(p)} to {_pt(q)})", p, q))
    for j, seg in enumerate(spec.segments):
        sides.append((f"segment {j + 1} (from {_pt(seg.start)} to {_pt(seg.end)})", seg.start, seg.end))
    return sides


def _on_wall(wall, p, q) -> bool:
    """Whether the side p–q lies on the wall's centre-line and overlaps it by more than a join does."""
    (ax, ay), (bx, by) = wall.start, wall.end
    length = math.hypot(bx - ax, by - ay)
    if length < 1e-9:
        return False
    ux, uy = (bx - ax) / length, (by - ay) / length
    for x, y in (p, q):
        if abs((x - ax) * uy - (y - ay) * ux) > ON_LINE:
            return False
    s0, s1 = sorted(((p[0] - ax) * ux + (p[1] - ay) * uy, (q[0] - ax) * ux + (q[1] - ay) * uy))
    return min(s1, length) - max(s0, 0.0) > min(wall.thickness, (s1 - s0) / 2)


def wall_sides(spec, building=None) -> Dict[int, list]:
    """Each built wall's index → the spec's sides on it, as (name, from, to); a corner filler → [(its name, None,
    None)]. ``building`` is the spec's geometry when already built."""
    import shapely

    building = building if building is not None else build_geometry(spec)
    sides = _spec_sides(spec)
    tree = shapely.STRtree([shapely.LineString([p, q]) for _, p, q in sides])
    straight = [w for w in building.walls if not w.filler]
    zones = shapely.buffer(shapely.linestrings([[w.start, w.end] for w in straight]), 2 * ON_LINE, quad_segs=1) \
        if straight else []
    near: Dict[int, list] = {}
    for k, i in zip(*tree.query(zones)) if len(zones) else ():   # every wall's nearby sides in one query
        near.setdefault(int(k), []).append(int(i))
    found: Dict[int, list] = {}
    for k, wall in enumerate(straight):
        on = [sides[i] for i in sorted(near.get(k, ())) if _on_wall(wall, sides[i][1], sides[i][2])]
        if on:
            found[wall.index] = on
    for wall in building.walls:
        if wall.filler:
            rooms = " and ".join(f"'{r}'" for r in wall.rooms)
            found[wall.index] = [(f"the filler at a sharp corner of room {rooms}" if rooms else "a corner filler",
                                  None, None)]
    return dict(sorted(found.items()))


def _along(p, q, point) -> float:
    """How far ``point`` lies from the segment p–q."""
    (ax, ay), (bx, by) = p, q
    dx, dy = bx - ax, by - ay
    length2 = dx * dx + dy * dy
    t = 0.0 if length2 == 0 else max(0.0, min(1.0, ((point[0] - ax) * dx + (point[1] - ay) * dy) / length2))
    return math.hypot(point[0] - ax - t * dx, point[1] - ay - t * dy)


def side_name(sides: list, point=None) -> str:
    """The name of a wall drawn by ``sides``: the sides at ``point`` when given (a wall two rooms share names
    both, "shared with"), else every side of the straight wall."""
    if point is not None and sides[0][1] is not None:
        distances = [_along(p, q, point) for _, p, q in sides]
        nearest = min(distances)
        at = [side for side, d in zip(sides, distances) if d <= nearest + 0.05]
        return at[0][0] + "".join(f", shared with {n}" for n, _, _ in at[1:])
    if len(sides) == 1:
        return sides[0][0]
    return "the straight wall of " + " and ".join(n for n, _, _ in sides)


_MARKING = re.compile(rf"(?:floor marking )?({MARKINGS_MODEL}/\w+)")


def marking_labels(spec) -> Dict[str, tuple]:
    """Each floor marking's SDF label (``floor_markings/track``) → what the spec calls it (``line 'track'``; an
    unnamed one by the name the world gives it, ``patch_1``) and where it is (``spec.yaml:12``)."""
    from ..spec.markings import marking_names

    found = {}
    line_names, patch_names = marking_names(spec.lines, spec.patches)
    for kind, names, items in (("line", line_names, spec.lines), ("patch", patch_names, spec.patches)):
        for name, item in zip(names, items):
            called = f"{kind} '{item.name}'" if item.name else name   # line_1: as the world names it
            where = f"{spec.source}:{item.line}" if spec.source and item.line else (spec.source or called)
            found[f"{MARKINGS_MODEL}/{name}"] = (called, where)
    return found


_POINT = re.compile(r"\((-?\d+(?:\.\d+)?), (-?\d+(?:\.\d+)?)\)")


def rename_findings(findings: List[Finding], spec, near=None, sides=None) -> List[Finding]:
    """``findings`` with the building's ``NAME/Wall_N/Wall_N_Collision[_i]`` labels replaced by the spec's names
    of those walls (the sides at the first point the finding names, else at ``near`` — the spawn, where the
    robot touches things — when a straight wall runs along several); a gap "between" two pieces of one wall is
    "in" that wall. ``sides``: :func:`wall_sides` when already known."""
    if sides is None:
        try:
            sides = wall_sides(spec)
        except Exception:   # a spec that does not build has no walls to name (its own error says why)
            return findings
    marks = marking_labels(spec)
    if not sides and not marks:
        return findings
    label = re.escape(spec.name) + r"/Wall_(\d+)/Wall_\d+_Collision(?:_\d+)?"
    pair = re.compile(rf"between ({label}) and ({label})")
    single = re.compile(label)

    def renamed(f: Finding) -> Finding:
        spot = _POINT.search(f.message) or (_POINT.search(f.where) if f.where else None)
        point = (float(spot.group(1)), float(spot.group(2))) if spot else near

        def name_of(index: str, whole: str) -> str:
            return side_name(sides[int(index)], point) if int(index) in sides else whole

        def one(match) -> str:
            return name_of(match.group(1), match.group(0))

        def both(match) -> str:
            a, b = name_of(match.group(2), match.group(1)), name_of(match.group(4), match.group(3))
            return f"in {a}" if a == b else f"between {a} and {b}"

        def text(value):
            if value is None:
                return None
            value = single.sub(one, pair.sub(both, value))
            return _MARKING.sub(lambda m: marks[m.group(1)][0] if m.group(1) in marks else m.group(0), value)

        if f.where in marks:   # a marking's place is its line in the spec
            return replace(f, message=text(f.message), where=marks[f.where][1])
        return replace(f, message=text(f.message), where=text(f.where))

    return [renamed(f) for f in findings]
