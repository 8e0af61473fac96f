"""Floor markings in a scene: visual-only geometry lying on the floor (tape, painted patches) that the robot drives
over and the LiDAR never sees, but a camera does.

A visual is *flat on the floor* (:func:`is_floor_marking`) when it is not a plane and lies between
:data:`FLOOR_BELOW` below the ground and :data:`MARKING_TOP` above it. A *marking* (:func:`floor_markings`) is a
link with no collision whose visuals all are: one spec line or patch (:mod:`worldgen.sdf.writer` writes a link
per line and patch in the model ``floor_markings``), or a marking someone drew in a world of their own.

Nothing here imports shapely at import time: the reader calls :func:`is_floor_marking` on every read.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Dict, List, Optional, Tuple

from ..core.boxes import box_corners
from ..core.scene import Scene, Shape

MARKING_TOP = 0.01     # m: a visual whose top is no higher than this lies on the floor (a 1 mm tape, stacked)
FLOOR_BELOW = 0.01     # m: nor whose bottom sinks deeper than this under it
ROUND_SIDES = 32       # sides of a disc's outline


def z_range(shape: Shape) -> Optional[Tuple[float, float]]:
    """The lowest and highest world z of a shape; None for planes and shapes without a size."""
    import numpy as np

    from ..core.poses import quat_matrix

    cz = shape.position[2]
    if shape.kind == "box" and shape.size is not None:
        z = (np.asarray(box_corners(shape.size)) @ quat_matrix(*shape.orientation).T)[:, 2]
        return cz + float(z.min()), cz + float(z.max())
    if shape.kind == "cylinder" and shape.radius and shape.length:
        axis_z = quat_matrix(*shape.orientation)[2, 2]
        half = abs(axis_z) * shape.length / 2 + math.sqrt(max(0.0, 1 - axis_z ** 2)) * shape.radius
        return cz - half, cz + half
    if shape.kind == "sphere" and shape.radius:
        return cz - shape.radius, cz + shape.radius
    if shape.kind == "mesh" and shape.vertices is not None and len(shape.vertices):
        z = (np.asarray(shape.vertices, float) @ quat_matrix(*shape.orientation).T)[:, 2]
        return cz + float(z.min()), cz + float(z.max())
    return None


def is_floor_marking(shape: Shape) -> bool:
    """Whether ``shape`` lies flat on the floor (see the module docstring)."""
    found = z_range(shape)
    return found is not None and found[0] >= -FLOOR_BELOW and 0.0 <= found[1] <= MARKING_TOP


@dataclass
class Marking:
    """One floor marking: a link's visuals, all flat on the floor. ``width`` is how wide it is in metres: the
    widest of its pieces' narrow sides (a line's segments may be shorter than the tape is wide, its joint discs
    are as wide as the tape), so a tape line is as wide as its tape."""

    model: str
    link: str
    shapes: List[Shape]
    width: float

    @property
    def label(self) -> str:
        return f"{self.model}/{self.link}"

    @property
    def colors(self) -> List[Optional[Tuple[float, float, float, float]]]:
        """Its pieces' colours, each once, in order (None for a piece whose colour the world does not say)."""
        return list(dict.fromkeys(s.color for s in self.shapes))

    @property
    def top(self) -> float:
        return max(z_range(s)[1] for s in self.shapes)


def floor_markings(scene: Scene) -> List[Marking]:
    """The scene's floor markings, in scene order: each link that has visuals and no collision shape, all of
    whose visuals are flat on the floor."""
    solid = {(s.model, s.link) for s in scene.shapes}
    links: Dict[Tuple[str, str], List[Shape]] = {}
    for v in scene.visuals:
        if (v.model, v.link) not in solid:
            links.setdefault((v.model, v.link), []).append(v)
    return [Marking(model, link, shapes, max(piece_width(s) for s in shapes))
            for (model, link), shapes in links.items() if all(is_floor_marking(s) for s in shapes)]


def piece_width(shape: Shape) -> float:
    """How wide one flat piece is seen from above: a box's narrower horizontal side, a disc's diameter, a lying
    cylinder's narrower extent, a mesh's footprint's mean width (twice its area over its perimeter: a strip's
    width)."""
    from ..core.poses import quat_matrix

    rotation = quat_matrix(*shape.orientation)
    if shape.kind == "box":
        up = max(range(3), key=lambda k: abs(rotation[2, k]))
        return min(v for k, v in enumerate(shape.size) if k != up)
    if shape.kind == "cylinder":
        return 2 * shape.radius if abs(rotation[2, 2]) > 0.9 else min(2 * shape.radius, shape.length)
    if shape.kind == "sphere":
        return 2 * shape.radius
    outline = footprint(shape)
    return 2 * outline.area / outline.length if outline.length > 0 else 0.0


def footprint(shape: Shape):
    """A flat piece's outline seen from above (shapely, world x/y): the convex hull of its corners (a disc's
    outline points), or for a mesh the union of its triangles."""
    import numpy as np
    import shapely

    from ..core.poses import quat_matrix

    rotation = quat_matrix(*shape.orientation)
    if shape.kind == "mesh":
        points = np.asarray(shape.vertices, float) @ rotation.T + np.asarray(shape.position)
        triangles = shapely.polygons(points[np.asarray(shape.faces)][:, :, :2])
        return shapely.union_all(triangles[shapely.area(triangles) > 0]).buffer(0)
    if shape.kind == "box":
        local = np.asarray(box_corners(shape.size))
    else:
        radius = shape.radius
        half = shape.length / 2 if shape.kind == "cylinder" else 0.0
        a = np.linspace(0, 2 * math.pi, ROUND_SIDES, endpoint=False)
        ring = np.column_stack([radius * np.cos(a), radius * np.sin(a)])
        local = np.vstack([np.column_stack([ring, np.full(len(a), z)]) for z in (-half, half)])
    points = local @ rotation.T + np.asarray(shape.position)
    return shapely.MultiPoint(points[:, :2]).convex_hull
