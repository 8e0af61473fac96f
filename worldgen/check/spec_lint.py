"""The ``spec`` check: what a spec draws that builds but is probably a mistake.

* Rooms that overlap (their centre-line polygons share floor, not just a wall): the walls of one run through
  the other, which the student rarely means.
* Obstacles that stand in a wall: the obstacle's footprint cuts into a built wall's box.

Both are warnings naming the spec's rooms, walls and obstacles (:mod:`worldgen.check.spec_names`) and where.
"""

from __future__ import annotations

from typing import List

from ..core.findings import Finding
from ..geometry.building import build_geometry, obstacle_names
from .spec_names import side_name, wall_sides

MIN_OVERLAP = 0.01   # m²: shared floor smaller than this is a wall two rooms share, not an overlap


def _xy(p) -> str:
    return f"({p.x + 0.0:.2f}, {p.y + 0.0:.2f})".replace("-0.00", "0.00")


def _obstacle_shape(o):
    import shapely
    from shapely import affinity

    if o.shape == "box" and o.size is not None:
        box = shapely.box(-o.size[0] / 2, -o.size[1] / 2, o.size[0] / 2, o.size[1] / 2)
        return affinity.translate(affinity.rotate(box, o.yaw, origin=(0, 0), use_radians=True), *o.at)
    return shapely.Point(o.at).buffer(o.radius or 0.0, quad_segs=16)


def _overlapping_rooms(spec) -> List[Finding]:
    """A warning per pair of rooms that share floor, in the order of the spec's rooms (an STRtree finds the pairs
    whose polygons meet: a spec of thousands of rooms is not compared pair by pair)."""
    import shapely

    findings: List[Finding] = []
    polygons = [(room.name, shapely.Polygon(room.vertices)) for room in spec.rooms]
    valid = [i for i, (_, p) in enumerate(polygons) if p.is_valid]
    if len(valid) < 2:
        return findings
    tree = shapely.STRtree([polygons[i][1] for i in valid])
    near, other = tree.query([polygons[i][1] for i in valid], predicate="intersects")
    for i, j in sorted({(valid[a], valid[b]) for a, b in zip(near, other) if valid[a] < valid[b]}):
        (a_name, a), (b_name, b) = polygons[i], polygons[j]
        shared = a.intersection(b)
        if shared.area > MIN_OVERLAP:
            findings.append(Finding(
                "spec", "warning",
                f"rooms '{a_name}' and '{b_name}' overlap: they share {shared.area:.2f} m² of floor around "
                f"{_xy(shared.representative_point())}, so the walls of one run through the other",
                where=spec.source, fix="move the rooms so that they only share a wall (a side drawn along the "
                                       "same line), or join them into one polygon"))
    return findings


def lint_spec(spec, building=None, sides=None) -> List[Finding]:
    """The ``spec`` check's findings for ``spec`` (none when it does not build: its own error says why);
    ``building`` and ``sides`` (:func:`worldgen.check.spec_names.wall_sides`) when already known."""
    import shapely

    try:
        building = building if building is not None else build_geometry(spec)
        sides = sides if sides is not None else wall_sides(spec, building)
    except Exception:
        return []
    findings = _overlapping_rooms(spec)
    walls = list(building.walls)
    boxes = [shapely.Polygon(w.footprint()) for w in walls]
    tree = shapely.STRtree(boxes)   # only the walls whose box meets an obstacle's are cut with it
    for o, name in zip(spec.obstacles, obstacle_names(spec.obstacles, spec.name)):
        shape = _obstacle_shape(o)
        hit = []
        for k in sorted(tree.query(shape, predicate="intersects")):
            cut = shape.intersection(boxes[k])
            if cut.area > 1e-4:
                hit.append((walls[k], cut))
        for wall, cut in hit[:3]:
            spot = cut.representative_point()
            what = side_name(sides[wall.index], (spot.x, spot.y)) if wall.index in sides else f"wall {wall.index}"
            findings.append(Finding(
                "spec", "warning",
                f"obstacle '{name}' stands in {what}: {cut.area:.3f} m² of it is inside the wall, around "
                f"{_xy(cut.representative_point())}",
                where=f"{spec.source}:{o.line}" if spec.source and o.line else spec.source,
                fix="move the obstacle clear of the wall, or make it smaller"))
    return findings
