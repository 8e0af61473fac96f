"""A scene sliced at a height: each shape's section as a plane footprint (shapely), the footprints over a height
band, the top of a shape and the floor under a point. :mod:`.enclosure` finds rooms and gaps in these footprints.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..core.boxes import box_corners
from ..core.scene import Scene, Shape
from .mesh_section import mesh_footprint
from .scene_memo import remembered

SLIVER = 0.0005        # every footprint grows by this much: gaps under 1 mm are closed
CIRCLE_SEGMENTS = 16   # per quarter circle, for cylinders and spheres
PRISM_SIDES = 48       # tilted cylinders are sliced as prisms with this many sides
FAST_BOXES = 200       # scenes with more shapes slice upright boxes as their rectangles (the same regions)


@dataclass(frozen=True)
class Footprint:
    """One shape's section at the slicing height, with where it came from."""

    label: str
    geometry: object   # shapely geometry (Polygon / MultiPolygon)
    note: str | None = None   # how the section was simplified (a mesh too tangled to cut exactly), if it was


def _to_world(shape: Shape, local) -> "np.ndarray":
    import numpy as np

    from ..core.poses import quat_matrix

    return np.asarray(local, dtype=float) @ quat_matrix(*shape.orientation).T + np.asarray(shape.position)


def _convex_section(points, z: float):
    """Section of the convex hull of ``points`` (N × 3, world) by the plane at height ``z``.

    The section of a convex hull is the convex hull of where the segments between its points cross the plane,
    so this is exact for boxes at any orientation and for prisms.
    """
    import numpy as np
    import shapely

    d = points[:, 2] - z
    if d.min() > 0 or d.max() < 0:
        return None
    i, j = np.triu_indices(len(points), k=1)
    crossing = d[i] * d[j] < 0
    t = d[i][crossing] / (d[i][crossing] - d[j][crossing])
    hits = points[i][crossing] + (points[j][crossing] - points[i][crossing]) * t[:, None]
    on_plane = points[np.abs(d) < 1e-12]
    xy = np.vstack([hits[:, :2], on_plane[:, :2]])
    if len(xy) < 3:
        return None
    hull = shapely.MultiPoint(xy).convex_hull
    return hull if hull.geom_type == "Polygon" and hull.area > 0 else None


def _box_section(shape: Shape, z: float, fast: bool = False, upright=None):
    """A box's section: the convex section; or, ``fast``, when one of its axes stands upright (most walls), its
    rectangle between bottom and top (the same region, without the general computation; ``upright``: that, when
    known)."""
    upright = upright if upright is not None else (_upright_box(shape) if fast else None)
    if upright is not None and upright[0] < z < upright[1]:
        return upright[2]
    if upright is not None and not upright[0] <= z <= upright[1]:
        return None
    return _convex_section(_to_world(shape, box_corners(shape.size)), z)


def _upright_box(shape: Shape):
    """(bottom, top, rectangle seen from above) of a box one of whose axes stands upright, else None."""
    import shapely

    from ..core.poses import quat_matrix

    rotation = quat_matrix(*shape.orientation)
    for k in range(3):
        if abs(rotation[2, k]) > 1 - 1e-12:
            break
    else:
        return None
    i, j = (a for a in range(3) if a != k)
    hi, hj, hk = shape.size[i] / 2, shape.size[j] / 2, shape.size[k] / 2
    ux, uy, vx, vy = rotation[0, i] * hi, rotation[1, i] * hi, rotation[0, j] * hj, rotation[1, j] * hj
    if ux * vy - uy * vx == 0:
        return None
    x, y, z = shape.position
    ring = [(x + ux + vx, y + uy + vy), (x - ux + vx, y - uy + vy), (x - ux - vx, y - uy - vy),
            (x + ux - vx, y + uy - vy)]
    polygon = shapely.Polygon(ring if ux * vy - uy * vx > 0 else ring[::-1])
    return z - hk, z + hk, polygon


def _cylinder_section(shape: Shape, z: float):
    import numpy as np
    import shapely

    from ..core.poses import quat_matrix

    r, half = shape.radius, shape.length / 2
    axis = quat_matrix(*shape.orientation)[:, 2]
    cx, cy, cz = shape.position
    if abs(axis[2]) > 1 - 1e-6:   # upright: an exact circle
        if abs(z - cz) > half:
            return None
        return shapely.Point(cx, cy).buffer(r, quad_segs=CIRCLE_SEGMENTS)
    a = np.linspace(0, 2 * math.pi, PRISM_SIDES, endpoint=False)
    ring = np.column_stack([r * np.cos(a), r * np.sin(a)])
    local = np.vstack([np.column_stack([ring, np.full(len(a), -half)]),
                       np.column_stack([ring, np.full(len(a), half)])])
    return _convex_section(_to_world(shape, local), z)


def _sphere_section(shape: Shape, z: float):
    import shapely

    d = z - shape.position[2]
    if abs(d) >= shape.radius:
        return None
    return shapely.Point(shape.position[:2]).buffer(math.sqrt(shape.radius ** 2 - d * d), quad_segs=CIRCLE_SEGMENTS)


def _mesh_section(shape: Shape, z: float):
    """A mesh's section (see :mod:`.mesh_section`), with a note when it had to be simplified."""
    if shape.vertices is None or shape.faces is None:
        return None, None
    return mesh_footprint(shape, _to_world(shape, shape.vertices), z, SLIVER)


def section(shape: Shape, z: float, fast: bool = False, upright=None):
    """The 2-D footprint (shapely geometry, world x/y) of ``shape`` cut by the plane at height ``z``, or None
    (``upright``: a box's :func:`_upright_box`, when known)."""
    if shape.kind == "box" and shape.size is not None:
        return _box_section(shape, z, fast, upright)
    if shape.kind == "cylinder" and shape.radius and shape.length:
        return _cylinder_section(shape, z)
    if shape.kind == "sphere" and shape.radius:
        return _sphere_section(shape, z)
    if shape.kind == "mesh":
        return _mesh_section(shape, z)[0]
    return None   # ground planes and degenerate shapes


def footprints(scene: Scene, z: float) -> list[Footprint]:
    """Every shape of ``scene`` cut at height ``z``, in scene order (shapes the plane misses are left out); cut
    once per scene and height (:mod:`.scene_memo`)."""
    return list(remembered(scene, ("footprints", z), lambda: _footprints(scene, z)))


def _uprights(scene: Scene, shapes: list[Shape]) -> list:
    """:func:`_upright_box` of each of ``shapes`` (the scene's obstacles; None for all but boxes), once per scene:
    the cut at the LiDAR's height and the robot's bands share them."""
    return remembered(scene, "upright boxes", lambda: [
        _upright_box(s) if s.kind == "box" and s.size is not None else None for s in shapes])


def _footprints(scene: Scene, z: float) -> list[Footprint]:
    out = []
    shapes = scene.obstacles()
    fast = len(shapes) > FAST_BOXES
    uprights = _uprights(scene, shapes) if fast else [None] * len(shapes)
    for shape, upright in zip(shapes, uprights):
        geometry, note = (_mesh_section(shape, z) if shape.kind == "mesh" else
                          (section(shape, z, fast, upright), None))
        if geometry is not None and not geometry.is_empty:
            out.append(Footprint(shape.label, geometry, note))
    return out


def footprints_between(scene: Scene, z0: float, z1: float, steps: int = 4, also: tuple[float, ...] = ()
                       ) -> list[Footprint]:
    """Footprints of everything between heights ``z0`` and ``z1``: sections at ``steps`` heights (and at the
    heights in ``also``), united per shape. Used for the robot's body, which spans a height range rather than
    a single plane. Computed once per scene and heights (:mod:`.scene_memo`)."""
    return list(remembered(scene, ("between", z0, z1, steps, tuple(also)),
                           lambda: _footprints_between(scene, z0, z1, steps, also)))


def _footprints_between(scene: Scene, z0: float, z1: float, steps: int, also: tuple[float, ...]) -> list[Footprint]:
    import shapely

    heights = sorted({z0 + (z1 - z0) * i / (steps - 1) for i in range(steps)} | set(also))
    out = []
    shapes = scene.obstacles()
    fast = len(shapes) > FAST_BOXES
    for shape, upright in zip(shapes, _uprights(scene, shapes) if fast else [None] * len(shapes)):
        if upright is not None and any(upright[0] < z < upright[1] for z in heights):
            out.append(Footprint(shape.label, upright[2]))   # its sections at the other heights: the same, or none
            continue
        parts = [g for g in (section(shape, z) for z in heights) if g is not None and not g.is_empty]
        if parts:   # an upright shape's sections are all alike: no union needed
            same = all(p.equals_exact(parts[0], 0.0) for p in parts[1:])
            out.append(Footprint(shape.label, parts[0] if same else shapely.union_all(parts)))
    return out


def shape_top(shape: Shape) -> float | None:
    """The highest point of a shape (world z), or None for planes and degenerate shapes."""
    import numpy as np

    from ..core.poses import quat_matrix

    if shape.kind == "box" and shape.size is not None:
        return float(_to_world(shape, box_corners(shape.size))[:, 2].max())
    if shape.kind == "cylinder" and shape.radius and shape.length:
        axis = quat_matrix(*shape.orientation)[:, 2]
        tilt = math.sqrt(max(0.0, 1 - axis[2] ** 2))
        return shape.position[2] + abs(axis[2]) * shape.length / 2 + tilt * shape.radius
    if shape.kind == "sphere" and shape.radius:
        return shape.position[2] + shape.radius
    if shape.kind == "mesh" and shape.vertices is not None and len(shape.vertices):
        return float(_to_world(shape, np.asarray(shape.vertices, float))[:, 2].max())
    return None


def ground_under(scene: Scene, xy: tuple[float, float], max_step: float) -> tuple[float, str | None]:
    """The floor height under ``xy``: the top of the highest shape no taller than ``max_step`` whose top face
    lies under the point (a floor slab such as Gazebo's asphalt_plane), else 0; and that shape's label. The slabs
    are found once per scene (:mod:`.scene_memo`)."""
    import shapely

    point = shapely.Point(xy)
    best, label = 0.0, None
    for top, name, cut in remembered(scene, ("slabs", max_step), lambda: _slabs(scene, max_step)):
        if best < top and cut.covers(point):
            best, label = top, name
    return best, label


def _slabs(scene: Scene, max_step: float) -> list:
    """(top, label, top face) of every shape whose top is above 0 and at most ``max_step``, in scene order."""
    found = []
    for shape in scene.obstacles():
        top = shape_top(shape)
        if top is None or not 0.0 < top <= max_step:
            continue
        cut = section(shape, top - 0.001)
        if cut is not None:
            found.append((top, shape.label, cut))
    return found


# ------------------------------------------------------------------------------------------------- enclosure
