"""Scene shapes → triangles to draw: each kind of :class:`~worldgen.core.scene.Shape` as an array of triangle
corners (``(3·T) × 3``, three rows per triangle) with a normal per corner, in the shape's own frame.

Boxes and meshes have flat faces (a normal per face); cylinders (along their local z, as in SDF) have smooth sides
of :data:`SEGMENTS` facets and flat caps; spheres are smooth latitude-longitude meshes; a plane is a square of its
``size`` (Gazebo's ground plane: 100 × 100 m) through its origin, perpendicular to its normal. Winding is not
relied on: the renderer lights both sides of a face.
"""

from __future__ import annotations

import numpy as np

from ..core import poses
from ..core.scene import Shape

SEGMENTS = 32            # facets around a cylinder (a 0.2 m radius one is within 1 mm of round)
SPHERE_RINGS = 12        # latitude bands of a sphere (and twice as many longitude segments)
PLANE_SIZE = 100.0       # m: Gazebo's ground_plane visual is 100 × 100 m


def box(size) -> tuple[np.ndarray, np.ndarray]:
    """The 12 triangles of a box of full ``size`` (x, y, z) centred on the origin."""
    half = np.asarray(size, float) / 2
    corners, normals = [], []
    for axis in range(3):
        u, v = (axis + 1) % 3, (axis + 2) % 3
        for sign in (-1.0, 1.0):
            quad = np.zeros((4, 3))
            quad[:, axis] = sign
            quad[:, u] = (-1, 1, 1, -1)
            quad[:, v] = (-1, -1, 1, 1)
            corners.append(quad[[0, 1, 2, 0, 2, 3]] * half)
            n = np.zeros(3)
            n[axis] = sign
            normals.append(np.tile(n, (6, 1)))
    return np.vstack(corners), np.vstack(normals)


def cylinder(radius: float, length: float, segments: int = SEGMENTS) -> tuple[np.ndarray, np.ndarray]:
    """A cylinder of ``radius`` along z from −length/2 to length/2: ``segments`` side quads and two fans."""
    a = np.linspace(0.0, 2 * np.pi, segments + 1)
    ring = np.stack([np.cos(a), np.sin(a), np.zeros_like(a)], axis=1)
    h = length / 2
    p0, p1 = ring[:-1], ring[1:]
    bottom = np.array([0.0, 0.0, -h])
    top = np.array([0.0, 0.0, h])
    side = np.stack([p0 * radius + bottom, p1 * radius + bottom, p1 * radius + top,
                     p0 * radius + bottom, p1 * radius + top, p0 * radius + top], axis=1).reshape(-1, 3)
    side_n = np.stack([p0, p1, p1, p0, p1, p0], axis=1).reshape(-1, 3)
    centre = np.zeros_like(p0)
    cap_top = np.stack([centre + top, p0 * radius + top, p1 * radius + top], axis=1).reshape(-1, 3)
    cap_bottom = np.stack([centre + bottom, p1 * radius + bottom, p0 * radius + bottom], axis=1).reshape(-1, 3)
    n_top = np.tile([0.0, 0.0, 1.0], (len(cap_top), 1))
    return np.vstack([side, cap_top, cap_bottom]), np.vstack([side_n, n_top, -n_top])


def sphere(radius: float, rings: int = SPHERE_RINGS) -> tuple[np.ndarray, np.ndarray]:
    """A latitude-longitude sphere of ``radius``: ``rings`` bands of ``2·rings`` quads, normals radial."""
    theta = np.linspace(0.0, np.pi, rings + 1)
    phi = np.linspace(0.0, 2 * np.pi, 2 * rings + 1)
    t, p = np.meshgrid(theta, phi, indexing="ij")
    unit = np.stack([np.sin(t) * np.cos(p), np.sin(t) * np.sin(p), np.cos(t)], axis=-1)
    a, b = unit[:-1, :-1], unit[:-1, 1:]
    c, d = unit[1:, 1:], unit[1:, :-1]
    n = np.stack([a, b, c, a, c, d], axis=2).reshape(-1, 3)
    return n * radius, n


def mesh(vertices, faces) -> tuple[np.ndarray, np.ndarray]:
    """A triangle mesh's faces (indices out of range dropped), each with its own flat normal."""
    v = np.asarray(vertices, float).reshape(-1, 3)
    f = np.asarray(faces, int).reshape(-1, 3)
    f = f[(f >= 0).all(axis=1) & (f < len(v)).all(axis=1)]
    tri = v[f]
    n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    length = np.linalg.norm(n, axis=1, keepdims=True)
    n = np.where(length > 0, n / np.where(length > 0, length, 1.0), [0.0, 0.0, 1.0])
    return tri.reshape(-1, 3), np.repeat(n, 3, axis=0)


def plane(normal=(0.0, 0.0, 1.0), size=(PLANE_SIZE, PLANE_SIZE)) -> tuple[np.ndarray, np.ndarray]:
    """A square ``size`` through the origin, perpendicular to ``normal``."""
    n = np.asarray(normal, float)
    n = n / (np.linalg.norm(n) or 1.0)
    helper = np.array([1.0, 0.0, 0.0]) if abs(n[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    u = np.cross(n, helper)
    u /= np.linalg.norm(u)
    v = np.cross(n, u)
    su, sv = size[0] / 2, size[1] / 2
    quad = np.array([-su * u - sv * v, su * u - sv * v, su * u + sv * v, -su * u + sv * v])
    return quad[[0, 1, 2, 0, 2, 3]], np.tile(n, (6, 1))


def shape_triangles(shape: Shape) -> tuple[np.ndarray, np.ndarray] | None:
    """A shape's triangles and normals in its own frame; None for a shape without the sizes its kind needs."""
    if shape.kind == "box" and shape.size is not None and all(s > 0 for s in shape.size):
        return box(shape.size)
    if shape.kind == "cylinder" and (shape.radius or 0) > 0 and (shape.length or 0) > 0:
        return cylinder(shape.radius, shape.length)
    if shape.kind == "sphere" and (shape.radius or 0) > 0:
        return sphere(shape.radius)
    if shape.kind == "mesh" and shape.vertices is not None and shape.faces is not None:
        found = mesh(shape.vertices, shape.faces)
        return found if len(found[0]) else None
    if shape.kind == "plane":
        size = shape.size[:2] if shape.size is not None and all(s > 0 for s in shape.size[:2]) else None
        return plane(shape.normal or (0.0, 0.0, 1.0), size or (PLANE_SIZE, PLANE_SIZE))
    return None


def shape_matrix(shape: Shape) -> np.ndarray:
    """The 4 × 4 pose of a shape's frame (in whatever frame its ``position``/``orientation`` are given)."""
    return poses.transform(shape.position, poses.quat_matrix(*shape.orientation))


def placed(shapes, frame: np.ndarray | None = None, default_color=(0.7, 0.7, 0.7, 1.0)
           ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``shapes`` as one triangle soup: corners, normals and RGB colours (N × 3 each), every shape at its pose
    and then at ``frame`` (4 × 4; None: as given). A shape without a colour gets ``default_color``; a fully
    transparent one (alpha 0) is left out."""
    corners, normals, colors = [], [], []
    outer = np.eye(4) if frame is None else np.asarray(frame, float)
    for shape in shapes:
        color = shape.color if shape.color is not None else default_color
        if len(color) > 3 and color[3] <= 0:
            continue
        found = shape_triangles(shape)
        if found is None:
            continue
        t = outer @ shape_matrix(shape)
        p, n = found
        corners.append(p @ t[:3, :3].T + t[:3, 3])
        normals.append(n @ t[:3, :3].T)
        colors.append(np.tile(np.asarray(color[:3], float), (len(p), 1)))
    if not corners:
        empty = np.zeros((0, 3))
        return empty, empty, empty
    return np.vstack(corners), np.vstack(normals), np.vstack(colors)
