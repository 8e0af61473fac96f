"""A triangle mesh cut by a horizontal plane: the segments where it crosses the plane, made into a footprint.

Triangles that share an edge share its vertex indices once repeated vertices are merged (:func:`merged_mesh`),
so the segments of a surface's section meet end to end and outline its walls. A closed surface's section is
filled by the even-odd rule; an open one blocks only along its surface. A triangle soup (random triangles
crossing one another) has a section whose pieces cross each other some K² times: past the limits here it is
taken as its convex hull instead, and the footprint carries a note saying so.
"""

from __future__ import annotations

MAX_SECTION_SEGMENTS = 50_000   # segments in one mesh's section at one height
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


def merged_mesh(vertices, faces):
    """Vertices (rounded to 1 nm) made unique and faces renumbered, so that triangles sharing an edge share
    its vertex indices even when the file repeated the vertices per triangle."""
    import numpy as np

    v = np.round(np.asarray(vertices, dtype=float).reshape(-1, 3), 9)
    f = np.asarray(faces, dtype=np.int64).reshape(-1, 3)
    if len(v) == 0:
        return v, f
    unique, index = np.unique(v, axis=0, return_inverse=True)
    return unique, index.reshape(-1)[f]


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


def mesh_footprint(world, vertices, faces, z: float, sliver: float):
    """A mesh's section at height ``z`` (``world``: its vertices in the world frame; ``vertices``: as loaded, for
    the closed-surface test) and a note, or (None, None) when the plane misses it.

    The section is the solid faces of the section (even-odd rule) plus every cut segment as a strip ``sliver``
    wide, so that a mesh that is not closed still blocks where it has surface. A section that is a tangle rather
    than a surface's outline (over :data:`MAX_SECTION_SEGMENTS` segments, or over :data:`MAX_CROSSINGS` segments
    crossing one another: a triangle soup) would cost time and memory growing with the square of its size; it is
    taken as its convex hull, solid, and the note says so."""
    import shapely

    if world[:, 2].min() > z or world[:, 2].max() < z:
        return None, None
    segments = mesh_section_segments(world, faces, z)
    if len(segments) == 0:
        return None, None
    lines = shapely.multilinestrings(segments)
    why = tangled(segments)
    if why:
        hull = shapely.MultiPoint(segments.reshape(-1, 2)).convex_hull.buffer(sliver, quad_segs=1)
        return hull, f"its section at {z:.3f} m is {why}; taken as the convex hull of that section (solid)"
    strips = lines.buffer(sliver, quad_segs=1)
    if not _closed_surface(faces, vertices):
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
    met = 0
    for start in range(0, k, 64):
        met += len(tree.query(lines[start:start + 64], predicate="intersects")[0])
        if met > allowed:
            return f"a tangle of segments crossing one another (more than {MAX_CROSSINGS} crossings: a " \
                   "triangle soup, not a surface)"
    return None


def _closed_surface(faces, vertices) -> bool:
    """True when every edge of the mesh is shared by exactly two triangles (after merging repeated vertices),
    so that its sections bound solid material; a loose sheet only blocks along its surface."""
    import numpy as np

    key = (id(faces), id(vertices))
    known = _CLOSED.get(key)   # one lookup: validate's worker threads share the cache
    if known is not None and known[0] is faces and known[1] is vertices:
        return known[2]
    _, f = merged_mesh(vertices, faces)
    edges = np.sort(np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]]), axis=1)
    _, counts = np.unique(edges, axis=0, return_counts=True)
    closed = bool(len(counts)) and bool((counts == 2).all())
    if len(_CLOSED) >= 16:
        _CLOSED.clear()
    _CLOSED[key] = (faces, vertices, closed)   # the arrays kept, so that their ids stay theirs
    return closed


_CLOSED: dict = {}   # (id(faces), id(vertices)) -> (faces, vertices, closed): one mesh is sliced at several heights


def _probe(polygon) -> tuple[float, float]:
    p = polygon.representative_point()
    return p.x, p.y
