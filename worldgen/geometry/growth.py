"""Footprints united and grown by a radius, in time near linear in their number.

GEOS buffers a many-part geometry by noding every offset curve against every other, and unites many polygons
level by level, copying every disjoint part at every level: both grow much faster than the number of parts (10 000
boxes 0.2 m apart: seconds per radius, gigabytes at the radii where the grown boxes overlap). Here each part is
grown on its own (the Minkowski sum of a union is the union of the parts' sums, so the result is the same region),
the grown parts are sorted into clusters of parts that meet (scipy's connected components of the pairs an STRtree
finds), and only the parts of one cluster are united with each other. A part that touches nothing is taken as it
is.

Plain numbers in, plain numbers out: numpy, scipy and shapely, imported when first used.
"""

from __future__ import annotations

SMALL = 200   # up to this many parts, GEOS's own union and buffer are fast enough: used as they are
DENSE = 2.0   # parts whose envelopes add up to this many times their common envelope are united in one go


def cluster_labels(geometries):
    """A label per geometry, shared by the geometries that meet, directly or through others."""
    import numpy as np
    import shapely
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    n = len(geometries)
    a, b = shapely.STRtree(geometries).query(geometries, predicate="intersects")
    graph = coo_matrix((np.ones(len(a), dtype=np.int8), (a, b)), shape=(n, n))
    return connected_components(graph, directed=False)[1]   # numbered in order of each cluster's first part


def unite(geometries):
    """The union of ``geometries`` (valid shapely polygons, any overlap), as one geometry; empty for none."""
    import numpy as np
    import shapely

    geometries = np.asarray([g for g in geometries if g is not None and not g.is_empty], dtype=object)
    if len(geometries) == 0:
        return shapely.Polygon()
    if len(geometries) == 1:
        return geometries[0]
    bounds = shapely.bounds(geometries)
    covered = np.prod(bounds[:, 2:] - bounds[:, :2], axis=1).sum()
    x0, y0 = bounds[:, :2].min(axis=0)
    x1, y1 = bounds[:, 2:].max(axis=0)
    if covered > DENSE * (x1 - x0) * (y1 - y0):   # they overlap a lot: one union, which GEOS does well then
        return shapely.union_all(geometries)
    label = cluster_labels(geometries)
    alone = np.bincount(label)[label] == 1
    merged = [shapely.union_all(geometries[label == k]) for k in np.unique(label[~alone])]
    pieces = shapely.get_parts(np.concatenate([geometries[alone], np.asarray(merged, dtype=object)]))
    pieces = pieces[(shapely.get_type_id(pieces) == 3) & ~shapely.is_empty(pieces)]
    return pieces[0] if len(pieces) == 1 else shapely.MultiPolygon(list(pieces))


def grown(geometry, r: float, quad_segs: int):
    """``geometry`` (a polygon or a union of disjoint polygons) grown by ``r`` (its Minkowski sum with a disc,
    arcs of ``quad_segs`` segments per quarter), as :func:`unite` unites the grown parts."""
    import shapely

    if r <= 0 or geometry.is_empty:
        return geometry
    parts = shapely.get_parts(geometry)
    if len(parts) <= SMALL:
        return geometry.buffer(r, quad_segs=quad_segs)
    return unite(shapely.buffer(parts, r, quad_segs=quad_segs))
