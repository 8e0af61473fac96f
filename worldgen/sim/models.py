"""The models of a running world as Gazebo lists them (``/gazebo/model_states``): the world file's top-level models
and the ones spawned since, each with a pose that can be read and set, and that can be deleted.

A model also keeps its visual shapes (what a camera draws, :mod:`.camera_scene`) with their poses in the model
frame: a world model's from the scene's ``visuals``, a spawned one's from its SDF; ``None`` when the source had no
visuals at all (the camera then draws the collision shapes).

A world model's shapes start out in the session's shared static compounds (:func:`.scene_loader.load_scene`);
the first time it is moved it gets bodies of its own. Each body of a model keeps its pose relative to the model
frame, so moving the model is one reset per body. A spawned model that is not static moves under physics (one
compound body whose frame is the model's, with its mass); a static one stays where it is put.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Dict, List, Optional, Tuple

import numpy as np
import pybullet as pb

from ..core import poses
from ..core.scene import Scene, Shape
from .scene_loader import (DYNAMIC_GROUP, DYNAMIC_MASK, GEOM, SCENE_GROUP, SCENE_MASK, SURFACE_FRICTION, SceneBodies,
    primitive_bodies)

Pose7 = Tuple[float, float, float, float, float, float, float]   # x y z qx qy qz qw


def matrix_of(pose: Pose7) -> np.ndarray:
    return poses.transform(pose[:3], poses.quat_matrix(*pose[3:]))


def pose_of(t: np.ndarray) -> Pose7:
    return (float(t[0, 3]), float(t[1, 3]), float(t[2, 3]), *poses.matrix_quat(t[:3, :3]))


def owners(name: str) -> List[str]:
    """The models a shape of model ``name`` is part of: ``name`` itself and each model it is nested in (each part
    of it before a ``::``)."""
    found, at = [name], name.find("::")
    while at >= 0:
        found.append(name[:at])
        at = name.find("::", at + 1)
    return found


def by_model(shapes, names) -> Dict[str, list]:
    """``shapes`` grouped by which of the model ``names`` they belong to, in one pass (a world of thousands of
    models would otherwise compare every shape with every model)."""
    groups: Dict[str, list] = {name: [] for name in names}
    for shape in shapes:
        for owner in owners(shape.model):
            if owner in groups:
                groups[owner].append(shape)
    return groups


def _shape_matrix(shape: Shape) -> np.ndarray:
    return poses.transform(shape.position, poses.quat_matrix(*shape.orientation))


@dataclass
class Model:
    """One model: its shapes with their poses in the model frame, its bodies with theirs, and where it started."""

    name: str
    static: bool
    frame: np.ndarray                                   # the model's world pose (static models)
    initial: np.ndarray
    shapes: List[Tuple[Shape, np.ndarray]] = field(default_factory=list)   # shape, pose in the model frame
    bodies: List[Tuple[int, np.ndarray]] = field(default_factory=list)     # body, base pose in the model frame
    spawned: bool = False
    own: bool = False                                   # has bodies of its own (else shares the scene's)
    visuals: Optional[List[Tuple[Shape, np.ndarray]]] = None   # visual, pose in the model frame (None: unknown)

    def world_frame(self, client: int) -> np.ndarray:
        """Where the model is now: its frame, or, moving under physics, its body's pose back to the model frame."""
        if self.static or not self.own or not self.bodies:
            return self.frame
        body, base = self.bodies[0]
        position, orientation = pb.getBasePositionAndOrientation(body, physicsClientId=client)
        return matrix_of((*position, *orientation)) @ poses.inverse(base)


class WorldModels:
    """Every model of a session's world by name (see the module docstring)."""

    def __init__(self, client: int, bodies: SceneBodies, scene: Scene):
        self.client, self.bodies = client, bodies
        self.models: Dict[str, Model] = {}
        shapes, seen = by_model(scene.shapes, scene.models), by_model(scene.visuals, scene.models)
        for name in scene.models:
            frame = matrix_of(scene.model_poses[name]) if name in scene.model_poses else np.eye(4)
            inverse = poses.inverse(frame)
            mine = shapes[name]
            visuals = [(v, inverse @ _shape_matrix(v)) for v in seen[name]]
            self.models[name] = Model(name, all(s.static for s in mine), frame, frame.copy(),
                                      [(s, inverse @ _shape_matrix(s)) for s in mine],
                                      visuals=visuals if scene.visuals else None)
        planes = [s for s in scene.shapes if s.kind == "plane"]
        if planes and not any(planes[0] in [s for s, _ in m.shapes] for m in self.models.values()):
            self.models.setdefault("ground_plane", Model("ground_plane", True, np.eye(4), np.eye(4)))

    def names(self) -> List[str]:
        return list(self.models)

    def get(self, name: str) -> Optional[Model]:
        return self.models.get(name)

    # -- reading ---------------------------------------------------------------------------------------------

    def pose(self, name: str) -> Pose7:
        return pose_of(self.models[name].world_frame(self.client))

    def twist(self, name: str) -> Tuple[Tuple[float, float, float], Tuple[float, float, float]]:
        model = self.models[name]
        if not model.static and model.own:
            lin, ang = pb.getBaseVelocity(model.bodies[0][0], physicsClientId=self.client)
            return tuple(lin), tuple(ang)
        return (0.0, 0.0, 0.0), (0.0, 0.0, 0.0)

    # -- changing --------------------------------------------------------------------------------------------

    def spawn(self, name: str, shapes: List[Shape], frame: np.ndarray, static: bool, mass: float = 1.0,
              visuals: Optional[List[Shape]] = None) -> Model:
        """A new model ``name`` whose ``shapes`` (and ``visuals``: None when its source had none) are given in its
        own frame, placed at ``frame`` (world)."""
        model = Model(name, static, frame.copy(), frame.copy(), [(s, _shape_matrix(s)) for s in shapes],
                      spawned=True, own=True,
                      visuals=None if visuals is None else [(v, _shape_matrix(v)) for v in visuals])
        for shape, local in model.shapes:
            world = frame @ local
            shape.position = tuple(float(v) for v in world[:3, 3])
            shape.orientation = poses.matrix_quat(world[:3, :3])
        if static:
            self._static_bodies(model)
        else:
            self._dynamic_body(model, mass)
        self.models[name] = model
        return model

    def set_pose(self, name: str, frame: np.ndarray, linear=(0.0, 0.0, 0.0), angular=(0.0, 0.0, 0.0)) -> None:
        """Model ``name`` at world pose ``frame`` (with that twist when it moves under physics)."""
        model = self.models[name]
        if not model.own:
            self._detach(model)
        model.frame = frame.copy()
        for body, base in model.bodies:
            t = frame @ base
            pb.resetBasePositionAndOrientation(body, t[:3, 3].tolist(), list(poses.matrix_quat(t[:3, :3])),
                                               physicsClientId=self.client)
            if not model.static:
                pb.resetBaseVelocity(body, list(linear), list(angular), physicsClientId=self.client)
        for shape, local in model.shapes:
            world = frame @ local
            shape.position = tuple(float(v) for v in world[:3, 3])
            shape.orientation = poses.matrix_quat(world[:3, :3])

    def delete(self, name: str) -> None:
        model = self.models.pop(name)
        if not model.own:
            self._detach(model)
        for body, _ in model.bodies:
            pb.removeBody(body, physicsClientId=self.client)
            self.bodies.shapes.pop(body, None)
            self.bodies.planes.discard(body)

    def reset(self) -> None:
        """Every model back at the pose it started at (Gazebo's reset_world; spawned models stay)."""
        for name, model in self.models.items():
            if model.own or not np.allclose(model.frame, model.initial):
                self.set_pose(name, model.initial)

    # -- bodies ----------------------------------------------------------------------------------------------

    def _detach(self, model: Model) -> None:
        """Give a world model bodies of its own: the shared compounds holding its shapes are rebuilt without them."""
        mine = {id(s) for s, _ in model.shapes}
        inverse = poses.inverse(model.frame)
        for body in [b for b, shapes in self.bodies.shapes.items() if any(id(s) in mine for s in shapes)]:
            shapes = self.bodies.shapes[body]
            if all(id(s) in mine for s in shapes):   # a mesh or plane body of this model alone: keep it
                position, orientation = pb.getBasePositionAndOrientation(body, physicsClientId=self.client)
                model.bodies.append((body, inverse @ matrix_of((*position, *orientation))))
                continue
            pb.removeBody(body, physicsClientId=self.client)
            del self.bodies.shapes[body]
            others = [s for s in shapes if id(s) not in mine]
            self.bodies.shapes.update(primitive_bodies(self.client, others))
            for new_body, new_shapes in primitive_bodies(self.client, [s for s in shapes if id(s) in mine]).items():
                self.bodies.shapes[new_body] = new_shapes
                model.bodies.append((new_body, inverse))   # children at world poses, base at the origin
        model.own = True

    def _static_bodies(self, model: Model) -> None:
        inverse = poses.inverse(model.frame)
        shapes = [s for s, _ in model.shapes if s.kind in GEOM]
        for body, chunk in primitive_bodies(self.client, shapes).items():
            self.bodies.shapes[body] = chunk
            model.bodies.append((body, inverse))
        for shape, local in model.shapes:
            if shape.kind == "mesh" and shape.vertices is not None and shape.faces is not None:
                sid = pb.createCollisionShape(pb.GEOM_MESH, vertices=np.asarray(shape.vertices, float).tolist(),
                                              indices=np.asarray(shape.faces, int).reshape(-1).tolist(),
                                              flags=pb.GEOM_FORCE_CONCAVE_TRIMESH, physicsClientId=self.client)
                body = _body(self.client, sid, 0.0, model.frame @ local)
                self.bodies.shapes[body] = [shape]
                model.bodies.append((body, local))

    def _dynamic_body(self, model: Model, mass: float) -> None:
        """One body in the model frame with the model's mass: a compound of its primitives, or, when it has a
        mesh, the convex hull of all its geometry (Bullet moves only convex meshes)."""
        parts = [(s, local) for s, local in model.shapes if s.kind in GEOM or (s.kind == "mesh" and s.vertices is not None)]
        if not parts:
            return
        if any(s.kind == "mesh" for s, _ in parts):
            points = np.vstack([_points(s) @ local[:3, :3].T + local[:3, 3] for s, local in parts])
            sid = pb.createCollisionShape(pb.GEOM_MESH, vertices=points.tolist(), physicsClientId=self.client)
        else:
            sid = pb.createCollisionShapeArray(
                shapeTypes=[GEOM[s.kind] for s, _ in parts],
                halfExtents=[[v / 2 for v in s.size] if s.kind == "box" else [0.0, 0.0, 0.0] for s, _ in parts],
                radii=[float(s.radius or 0.0) for s, _ in parts], lengths=[float(s.length or 0.0) for s, _ in parts],
                collisionFramePositions=[local[:3, 3].tolist() for _, local in parts],
                collisionFrameOrientations=[list(poses.matrix_quat(local[:3, :3])) for _, local in parts],
                physicsClientId=self.client)
        body = _body(self.client, sid, mass, model.frame)
        pb.setCollisionFilterGroupMask(body, -1, DYNAMIC_GROUP, DYNAMIC_MASK, physicsClientId=self.client)
        self.bodies.shapes[body] = [s for s, _ in parts]
        model.bodies.append((body, np.eye(4)))


def _points(shape: Shape) -> np.ndarray:
    """Points of a shape in its own frame whose convex hull is (about) the shape."""
    if shape.kind == "mesh":
        return np.asarray(shape.vertices, float)
    if shape.kind == "box":
        half = np.asarray(shape.size, float) / 2
        return np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]) * half
    angles = np.linspace(0, 2 * np.pi, 24, endpoint=False)
    r = float(shape.radius or 0.0)
    if shape.kind == "cylinder":
        h = float(shape.length or 0.0) / 2
        ring = np.stack([r * np.cos(angles), r * np.sin(angles)], axis=1)
        return np.vstack([np.hstack([ring, np.full((24, 1), z)]) for z in (-h, h)])
    ring = np.stack([r * np.cos(angles), r * np.sin(angles), np.zeros(24)], axis=1)
    return np.vstack([ring, [[0, 0, r], [0, 0, -r]], ring[:, [0, 2, 1]], ring[:, [2, 0, 1]]])


def _body(client: int, sid: int, mass: float, frame: np.ndarray) -> int:
    body = pb.createMultiBody(baseMass=mass, baseCollisionShapeIndex=sid, basePosition=frame[:3, 3].tolist(),
                              baseOrientation=list(poses.matrix_quat(frame[:3, :3])), physicsClientId=client)
    pb.changeDynamics(body, -1, lateralFriction=SURFACE_FRICTION, physicsClientId=client)
    pb.setCollisionFilterGroupMask(body, -1, SCENE_GROUP, SCENE_MASK, physicsClientId=client)
    return body
