"""A triangle mesh cut by a horizontal plane: the segments where it crosses the plane, made into a footprint.

Triangles that share an edge share its vertex indices once repeated vertices are merged, so the segments of a
surface's section meet end to end and outline its walls: each edge's crossing is computed once, in one direction,
so both triangles beside it get the same point to the last bit. A closed surface's section is filled by the
even-odd rule; an open one blocks only along its surface. A triangle soup (random triangles crossing one another)
has a section whose pieces cross each other some K² times: past the limits here it is taken as its convex hull
instead, and the footprint carries a note saying so.

Whether a surface is closed is trimesh's (``merge_vertices`` then ``is_watertight``: 1.5 s for a 1.3 M-triangle
sphere where our own numpy took 5.4 s), found once per shape and kept on it (:attr:`Shape.closed`). The section
itself stays ours: trimesh's ``intersections.mesh_plane`` is as fast (59 ms against 64 ms at 1.3 M triangles)
but works each triangle's edges in the triangle's own order, so neighbours' segment ends differ in the last bits
and no ring closes (a closed sphere's section fills nothing); and it takes a vertex within 1e-8 of the plane as
on it, where worldgen takes it as just above (``benchmarks/bench_mesh_section.py`` measures both).
"""

from __future__ import annotations

MAX_SECTION_SEGMENTS = 10_000   # segments in one mesh's section at one height
MAX_CROSSINGS = 5_000           # pairs of those segments that cross (a surface's outline has none)


def mesh_section_segments(vertices, faces, z: float):
    """The segments (K × 2 × 2, x/y) where a triangle mesh (world vertices) crosses the plane at height ``z``."""
    import numpy as np

    v = np.round(np.asarray(vertices, dtype=float).reshape(-1, 3), 9)
    f = np.asarray(faces, dtype=np.int64).reshape(-1, 3)
    if len(v) == 0 or len(f) == 0:
        return np.zeros((0, 2, 2))
    d = v[:, 2] - z
    d[d == 0] = 1e-12            # a vertex exactly on the plane counts as just above it
    above = d[f] > 0
    f = f[above.any(axis=1) & ~above.all(axis=1)]
    if len(f) == 0:
        return np.zeros((0, 2, 2))
    if len(f) > MAX_SECTION_SEGMENTS:   # a tangle (see tangled): its hull needs the points, not exact joins
        return _loose_segments(v[:, :2], d, f)
    # Only the crossing triangles' vertices are merged: np.unique sorts them by their coordinates as it would
    # sort them all, so every edge is taken in the same direction as when the whole mesh is merged.
    used, inverse = np.unique(f, return_inverse=True)
    v, merged = np.unique(v[used], axis=0, return_inverse=True)
    f = merged.reshape(-1)[inverse.reshape(-1)].reshape(-1, 3)
    d = v[:, 2] - z
    d[d == 0] = 1e-12
    ring = np.roll(f, -1, axis=1)               # the three edges of each crossing triangle, each edge always
    a, b = np.minimum(f, ring), np.maximum(f, ring)   # taken in the same direction so neighbours agree exactly
    da, db = d[a], d[b]
    crossing = (da > 0) != (db > 0)
    t = np.where(crossing, da / np.where(crossing, da - db, 1.0), 0.0)
    points = v[a][:, :, :2] + (v[b][:, :, :2] - v[a][:, :, :2]) * t[:, :, None]
    order = np.argsort(~crossing, axis=1, kind="stable")[:, :2]   # the two crossing edges of each triangle
    return np.take_along_axis(points, order[:, :, None], axis=1)


def _loose_segments(xy, d, f):
    """The section's segments of the crossing triangles ``f`` without merging their vertices: each triangle's
    two crossing edges, interpolated in the triangle's own order (enough for a convex hull, in linear time)."""
    import numpy as np

    ring = np.roll(f, -1, axis=1)
    da, db = d[f], d[ring]
    crossing = (da > 0) != (db > 0)
    t = np.where(crossing, da / np.where(crossing, da - db, 1.0), 0.0)
    points = xy[f] + (xy[ring] - xy[f]) * t[:, :, None]
    order = np.argsort(~crossing, axis=1, kind="stable")[:, :2]
    return np.take_along_axis(points, order[:, :, None], axis=1)


def _inside_by_parity(point, segments) -> bool:
    """Even-odd rule against loose segments: works for closed sections even when the loops are not merged."""
    x1, y1 = segments[:, 0, 0], segments[:, 0, 1]
    x2, y2 = segments[:, 1, 0], segments[:, 1, 1]
    px, py = point
    straddle = (y1 > py) != (y2 > py)
    with_y = (y2 - y1)
    safe = with_y != 0
    xs = x1 + (py - y1) * (x2 - x1) / (with_y + ~safe)
    return bool((straddle & safe & (px < xs)).sum() % 2)


def mesh_footprint(shape, world, z: float, sliver: float):
    """A mesh shape's section at height ``z`` (``world``: its vertices in the world frame) and a note, or
    (None, None) when the plane misses it.

    The section is the solid faces of the section (even-odd rule) plus every cut segment as a strip ``sliver``
    wide, so that a mesh that is not closed still blocks where it has surface. A section that is a tangle rather
    than a surface's outline (over :data:`MAX_SECTION_SEGMENTS` segments, or over :data:`MAX_CROSSINGS` segments
    crossing one another: a triangle soup) would cost time and memory growing with the square of its size; it is
    taken as its convex hull, solid, and the note says so."""
    import shapely

    if world[:, 2].min() > z or world[:, 2].max() < z:
        return None, None
    segments = mesh_section_segments(world, shape.faces, z)
    if len(segments) == 0:
        return None, None
    lines = shapely.multilinestrings(segments)
    why = tangled(segments)
    if why:
        hull = shapely.MultiPoint(segments.reshape(-1, 2)).convex_hull.buffer(sliver, quad_segs=1)
        return hull, f"its section at {z:.3f} m is {why}; taken as the convex hull of that section (solid)"
    strips = lines.buffer(sliver, quad_segs=1)
    if not closed_surface(shape):
        return strips, None
    noded = shapely.get_parts(shapely.union_all(lines))
    polygons = shapely.get_parts(shapely.polygonize(noded))
    solid = [p for p in polygons if p.area > 0 and _inside_by_parity(_probe(p), segments)]
    return (shapely.union_all([strips, *solid]) if solid else strips), None


def tangled(segments) -> str | None:
    """Why the section ``segments`` (K × 2 × 2) is too tangled to unite exactly, or None: more than
    :data:`MAX_SECTION_SEGMENTS` of them, or more than :data:`MAX_CROSSINGS` pairs that meet other than at the
    ends they share with their neighbours. Pairs are counted in chunks, stopping as soon as there are too many."""
    import shapely

    k = len(segments)
    if k > MAX_SECTION_SEGMENTS:
        return f"{k} segments (more than {MAX_SECTION_SEGMENTS})"
    lines = shapely.linestrings(segments)
    tree = shapely.STRtree(lines)
    allowed = 3 * k + 2 * MAX_CROSSINGS   # itself, two neighbours each way, and the crossings allowed
    tangle = f"a tangle of segments crossing one another (more than {MAX_CROSSINGS} crossings: a triangle soup, " \
             "not a surface)"
    # A sample first, spread evenly over the section: in a soup each segment meets hundreds, so 64 of them
    # tell in one query what the full count would find after many (each query costs as much as the lines met).
    sample = lines[:: max(1, k // 64)][:64]
    if len(sample) < k and len(tree.query(sample, predicate="intersects")[0]) * (k / len(sample)) > 4 * allowed:
        return tangle
    met = 0
    step = 8
    start = 0
    while start < k:
        met += len(tree.query(lines[start:start + step], predicate="intersects")[0])
        if met > allowed:
            return tangle
        start += step
        step = min(step * 2, 512)
    return None


def closed_surface(shape) -> bool:
    """True when every edge of ``shape``'s mesh is shared by exactly two triangles once vertices within 1 nm are
    merged, so that its sections bound solid material (a loose sheet only blocks along its surface). Found once
    and kept on the shape: a mesh is sliced at several heights."""
    if shape.closed is None:
        shape.closed = watertight(shape.vertices, shape.faces)
    return shape.closed


def watertight(vertices, faces) -> bool:
    """Whether a triangle mesh is closed: trimesh's test, on a copy whose vertices are merged at 1 nm."""
    import numpy as np
    import trimesh

    mesh = trimesh.Trimesh(np.asarray(vertices, dtype=float).reshape(-1, 3),
                           np.asarray(faces, dtype=np.int64).reshape(-1, 3), process=False)
    if len(mesh.faces) == 0:
        return False
    mesh.merge_vertices(digits_vertex=9)
    return bool(mesh.is_watertight)


def _probe(polygon) -> tuple[float, float]:
    p = polygon.representative_point()
    return p.x, p.y
