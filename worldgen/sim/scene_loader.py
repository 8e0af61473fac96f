"""A :class:`~worldgen.core.scene.Scene` → static pybullet bodies, and contact points back → shape labels.

Boxes, cylinders and spheres go into compound bodies of at most 16 children (pybullet silently drops the
children of ``createCollisionShapeArray`` beyond 16), meshes become static concave triangle meshes (split when
they have more vertices than pybullet takes in one shape; a triangle soup becomes its convex hull, see
:func:`soup_hull`), planes become infinite ``GEOM_PLANE`` bodies.
pybullet does not say which child of a compound a contact touched, so :meth:`SceneBodies.label` finds the child
nearest to the contact point.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import pybullet as pb

from ..core.scene import Scene, Shape

COMPOUND_LIMIT = 16            # children per createCollisionShapeArray that pybullet keeps
MESH_FACES_PER_SHAPE = 30_000  # ≤ 90,000 vertices per shape; pybullet refuses somewhere above 100,000
MAX_OVERLAP = 1000             # triangle boxes over an average point of a mesh's box: more is a soup (soup_hull)
# Collision filter bits. Bullet pairs two objects when each one's group meets the other's mask; a ray (whose
# group is bit 0) hits objects whose group meets the ray's mask and whose mask has bit 0. So static scene bodies
# never pair with each other; they, bodies that move under physics (spawned models) and every robot pair with
# each robot; robot i (group ROBOT_GROUP << i) pairs with every other robot; rays cast with mask SCENE_GROUP see
# only the scene, and robot i's LiDAR (ray_mask(i)) sees the scene, moving bodies and the other robots.
RAY_GROUP, SCENE_GROUP, ROBOT_GROUP = 0b001, 0b010, 0b100
MAX_ROBOTS = 16
ALL_ROBOTS = sum(ROBOT_GROUP << i for i in range(MAX_ROBOTS))
DYNAMIC_GROUP = ROBOT_GROUP << MAX_ROBOTS
SCENE_MASK = RAY_GROUP | ALL_ROBOTS | DYNAMIC_GROUP
DYNAMIC_MASK = RAY_GROUP | SCENE_GROUP | ALL_ROBOTS | DYNAMIC_GROUP


def robot_group(slot: int) -> int:
    """The collision group of robot ``slot`` (0 … MAX_ROBOTS − 1)."""
    if not 0 <= slot < MAX_ROBOTS:
        raise ValueError(f"at most {MAX_ROBOTS} robots in one simulation")
    return ROBOT_GROUP << slot


def robot_mask(slot: int) -> int:
    """What robot ``slot`` collides with (and that other robots' LiDARs see it)."""
    return RAY_GROUP | SCENE_GROUP | DYNAMIC_GROUP | (ALL_ROBOTS & ~robot_group(slot))


def ray_mask(slot: int) -> int:
    """What robot ``slot``'s LiDAR sees: everything but that robot."""
    return SCENE_GROUP | DYNAMIC_GROUP | (ALL_ROBOTS & ~robot_group(slot))
SURFACE_FRICTION = 1.0         # Gazebo's default μ for surfaces without a <surface> block


@dataclass
class SceneBodies:
    """What :func:`load_scene` made: body id → the shapes it holds (in child order), and the plane bodies."""

    shapes: dict[int, list[Shape]] = field(default_factory=dict)
    planes: set[int] = field(default_factory=set)
    children: dict[int, Children] = field(default_factory=dict, repr=False)   # body → its shapes as arrays

    @property
    def obstacle_bodies(self) -> list[int]:
        return sorted(b for b in self.shapes if b not in self.planes)

    def shape_at(self, body: int, point) -> Shape | None:
        """The shape of ``body`` that a contact at world ``point`` touched (the nearest child)."""
        shapes = self.shapes.get(body)
        if not shapes:
            return None
        if len(shapes) == 1:
            return shapes[0]
        children = self.children.get(body)
        if children is None or not children.current(shapes):
            children = self.children[body] = Children(shapes)
        return shapes[int(np.argmin(children.distances(point)))]

    def label(self, body: int, point) -> str:
        shape = self.shape_at(body, point)
        return (shape.label or shape.kind) if shape is not None else f"body {body}"


def load_scene(client: int, scene: Scene, add_ground: bool = True) -> SceneBodies:
    """Create static bodies for every shape of ``scene`` in pybullet client ``client``.

    A ground plane at z = 0 is added when the scene has no plane and ``add_ground`` (Gazebo worlds include
    ``model://ground_plane``, which a reader may not have expanded). Every body gets μ = 1.0 and the scene's
    collision group.
    """
    bodies = SceneBodies()
    planes = [s for s in scene.shapes if s.kind == "plane"]
    if not planes and add_ground:
        planes = [Shape(kind="plane", position=(0.0, 0.0, 0.0), normal=(0.0, 0.0, 1.0), model="ground_plane",
                        name="added")]
    for shape in planes:
        sid = pb.createCollisionShape(pb.GEOM_PLANE, planeNormal=list(shape.normal or (0.0, 0.0, 1.0)),
                                      physicsClientId=client)
        body = _static_body(client, sid, shape.position, shape.orientation)
        bodies.shapes[body] = [shape]
        bodies.planes.add(body)
    bodies.shapes.update(primitive_bodies(client, scene.shapes))
    for shape in scene.shapes:
        if shape.kind == "mesh" and shape.vertices is not None and shape.faces is not None:
            hull = soup_hull(np.asarray(shape.vertices, float), np.asarray(shape.faces, int))
            if hull is not None:   # a triangle soup: its convex hull, as the geometric checks take its sections
                sid = pb.createCollisionShape(pb.GEOM_MESH, vertices=hull.tolist(), physicsClientId=client)
                bodies.shapes[_static_body(client, sid, shape.position, shape.orientation)] = [shape]
                continue
            for vertices, faces in _mesh_pieces(np.asarray(shape.vertices, float), np.asarray(shape.faces, int)):
                sid = pb.createCollisionShape(pb.GEOM_MESH, vertices=vertices.tolist(),
                                              indices=faces.reshape(-1).tolist(),
                                              flags=pb.GEOM_FORCE_CONCAVE_TRIMESH, physicsClientId=client)
                bodies.shapes[_static_body(client, sid, shape.position, shape.orientation)] = [shape]
    return bodies


def primitive_bodies(client: int, shapes) -> dict[int, list[Shape]]:
    """The boxes, cylinders and spheres among ``shapes`` as static compound bodies (at most
    :data:`COMPOUND_LIMIT` children each, grouped by floor cell; base at the world origin): body → its shapes."""
    made = {}
    primitives = sorted((s for s in shapes if s.kind in GEOM and _usable(s)), key=_cell)
    for start in range(0, len(primitives), COMPOUND_LIMIT):
        chunk = primitives[start:start + COMPOUND_LIMIT]
        sid = pb.createCollisionShapeArray(
            shapeTypes=[GEOM[s.kind] for s in chunk],
            halfExtents=[[v / 2 for v in s.size] if s.kind == "box" else [0.0, 0.0, 0.0] for s in chunk],
            radii=[float(s.radius or 0.0) for s in chunk],
            lengths=[float(s.length or 0.0) for s in chunk],
            collisionFramePositions=[list(s.position) for s in chunk],
            collisionFrameOrientations=[list(s.orientation) for s in chunk],
            physicsClientId=client)
        made[_static_body(client, sid, (0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0))] = chunk
    return made


GEOM = {"box": pb.GEOM_BOX, "cylinder": pb.GEOM_CYLINDER, "sphere": pb.GEOM_SPHERE}
CELL = 2.0   # m: primitives are grouped by floor cell, so each compound is compact and the robot meets few


def _cell(shape: Shape) -> tuple[int, int]:
    return math.floor(shape.position[0] / CELL), math.floor(shape.position[1] / CELL)


def _usable(shape: Shape) -> bool:
    """Shapes with the sizes their kind needs, all positive (a reader reports the others)."""
    if shape.kind == "box":
        return shape.size is not None and all(v > 0 for v in shape.size)
    if shape.kind == "cylinder":
        return bool(shape.radius and shape.radius > 0 and shape.length and shape.length > 0)
    return bool(shape.radius and shape.radius > 0)


def _static_body(client: int, sid: int, position, orientation) -> int:
    body = pb.createMultiBody(baseMass=0, baseCollisionShapeIndex=sid, basePosition=list(position),
                              baseOrientation=list(orientation), physicsClientId=client)
    pb.changeDynamics(body, -1, lateralFriction=SURFACE_FRICTION, physicsClientId=client)
    pb.setCollisionFilterGroupMask(body, -1, SCENE_GROUP, SCENE_MASK, physicsClientId=client)
    return body


def soup_hull(vertices: np.ndarray, faces: np.ndarray) -> np.ndarray | None:
    """The convex hull's corners of a triangle soup, None for a surface. A soup's triangles, large and crossing
    one another, overlap everywhere, so Bullet's ray test meets thousands of them for each beam (a 100 000-triangle
    soup: 1 s per 360-beam scan); the overlap measured is how many triangles' boxes cover an average point of the
    mesh's box (each side at least 1 % of the mesh's largest), over :data:`MAX_OVERLAP` making a soup."""
    if len(faces) < MAX_OVERLAP:
        return None
    corners = vertices[faces[(faces >= 0).all(axis=1) & (faces < len(vertices)).all(axis=1)]]
    if len(corners) == 0:
        return None
    extent = vertices.max(axis=0) - vertices.min(axis=0)
    least = max(float(extent.max()) * 0.01, 1e-9)
    boxes = np.maximum(corners.max(axis=1) - corners.min(axis=1), least)
    overlap = float(np.prod(boxes, axis=1).sum() / np.prod(np.maximum(extent, least)))
    if overlap <= MAX_OVERLAP:
        return None
    from scipy.spatial import ConvexHull

    points = corners.reshape(-1, 3)
    try:
        return points[ConvexHull(points).vertices]
    except Exception:   # Qhull refuses a flat or degenerate set (QhullError, named differently across scipy): its box
        low, high = points.min(axis=0), points.max(axis=0)
        return np.array([[x, y, z] for x in (low[0], high[0]) for y in (low[1], high[1]) for z in (low[2], high[2])])


def _mesh_pieces(vertices: np.ndarray, faces: np.ndarray):
    """Split a triangle mesh into pieces of at most MESH_FACES_PER_SHAPE faces, each with its own vertices."""
    faces = faces[(faces >= 0).all(axis=1) & (faces < len(vertices)).all(axis=1)]
    for start in range(0, len(faces), MESH_FACES_PER_SHAPE):
        chunk = faces[start:start + MESH_FACES_PER_SHAPE]
        used, local = np.unique(chunk.reshape(-1), return_inverse=True)
        yield vertices[used], local.reshape(-1, 3)


def _rotation(orientation) -> list:
    x, y, z, w = orientation
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]


class Children:
    """A body's shapes as arrays, to measure a point's distance to all of them at once (a robot rubbing along a
    grid of small cells makes thousands of contacts a second, each with a compound of up to 16 children)."""

    def __init__(self, shapes: list[Shape]):
        self.shapes = shapes
        self.poses = [(s.position, s.orientation) for s in shapes]
        self.centres = np.array([s.position for s in shapes], float).reshape(-1, 3)
        self.rotations = np.array([_rotation(s.orientation) for s in shapes], float).reshape(-1, 3, 3)
        self.box = np.array([s.kind == "box" and s.size is not None for s in shapes], bool)
        self.half = np.array([s.size if b else (0.0, 0.0, 0.0) for s, b in zip(shapes, self.box)], float) / 2
        self.cylinder = np.array([s.kind == "cylinder" and bool(s.radius and s.length) for s in shapes], bool)
        self.sphere = np.array([s.kind == "sphere" and bool(s.radius) for s in shapes], bool)
        self.radius = np.array([s.radius or 0.0 for s in shapes], float)
        self.half_length = np.array([(s.length or 0.0) / 2 for s in shapes], float)

    def current(self, shapes: list[Shape]) -> bool:
        """Whether these arrays are still ``shapes`` where they are now (a moved model's shapes get new poses)."""
        return shapes is self.shapes and all(s.position is p and s.orientation is o
                                             for s, (p, o) in zip(shapes, self.poses))

    def distances(self, point) -> np.ndarray:
        """Signed distance from world ``point`` to the surface of each box, cylinder and sphere (negative inside);
        of any other kind, to its origin."""
        local = np.einsum("nji,nj->ni", self.rotations, np.asarray(point, float) - self.centres)
        out = np.linalg.norm(local, axis=1)
        if self.box.any():
            out[self.box] = _rounded(np.abs(local[self.box]) - self.half[self.box])
        if self.cylinder.any():
            near = local[self.cylinder]
            out[self.cylinder] = _rounded(np.stack([np.hypot(near[:, 0], near[:, 1]) - self.radius[self.cylinder],
                                                    np.abs(near[:, 2]) - self.half_length[self.cylinder]], axis=1))
        out[self.sphere] -= self.radius[self.sphere]
        return out


def _rounded(q: np.ndarray) -> np.ndarray:
    """The signed distance of each row's point, given as its excess ``q`` over each half-extent of a convex
    shape (outside: the length of the positive part; inside: minus the smallest margin)."""
    return np.linalg.norm(np.maximum(q, 0.0), axis=1) + np.minimum(q.max(axis=1), 0.0)
