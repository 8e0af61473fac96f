"""A session's world as its robots' cameras see it: what to draw, where it is now, and the picture
(:class:`CameraScene`; the drawing itself is :mod:`.camera`'s).

Drawn, each in its own colour (a shape without one in Gazebo's grey, 0.7):

- the scene's visual shapes (``Scene.visuals``: walls, obstacles, floor markings), each model's at the model's
  current pose (moved by set_model_state, or moving under physics); a scene with no visuals at all is drawn from
  its collision shapes, grey;
- the ground: the world's ground plane, or the one the session added (drawn a little behind what lies on it);
- models spawned while it runs (their visuals, else their collision shapes) and the movers (a walking person);
- every other robot, from its URDF's visuals (:mod:`worldgen.robots.visuals`) at its links' current poses. A
  camera never draws its own robot.

Meshes are made once, when a model, mover or robot is first seen, and released when it is gone; each picture
then costs one draw call per model, link and mover. The OpenGL context is made when the first picture is asked
for (:meth:`CameraScene.open` makes it earlier, to fail early when it cannot be made).
"""

from __future__ import annotations

import numpy as np

from ..core import poses
from ..robots.cameras import CameraParams
from ..robots.visuals import link_visuals
from . import triangles
from .camera import Renderer, intrinsics
from .models import owners


def sensor_pose(robot, camera: CameraParams) -> np.ndarray:
    """The world pose (4 × 4) of ``camera``'s sensor frame on ``robot``: its link's frame, then the sensor's
    ``<pose>`` in it."""
    position, orientation = robot.link_pose(camera.link)
    link = poses.transform(position, poses.quat_matrix(*orientation))
    return link @ poses.pose_matrix(*camera.pose)


class CameraScene:
    """The drawable state of one :class:`~.session.Session` (see the module docstring)."""

    def __init__(self, session):
        self.session = session
        self.renderer: Renderer | None = None
        self.fixed: list = []                                  # (mesh, behind): world shapes in no model
        self.models: dict[str, tuple[object, list]] = {}       # name → (Model, [(mesh, behind)])
        self.movers: dict[int, tuple[object, object]] = {}     # body → (Shape, mesh)
        self.robots: dict[int, tuple[object, list]] = {}       # id(robot) → (Robot, [(link, mesh)])

    def open(self) -> None:
        """Make the OpenGL context and the world's meshes (InputError when no context can be made)."""
        if self.renderer is not None:
            return
        self.renderer = Renderer()
        scene, bodies = self.session.scene, self.session.bodies
        shapes = scene.visuals or scene.shapes
        models = self.session.models.models
        in_models = {id(s) for s in shapes if any(owner in models for owner in owners(s.model))}
        loose = [s for s in shapes if id(s) not in in_models]
        if not any(s.kind == "plane" for s in shapes):   # no ground to see: the collision planes (the added one)
            loose += [s for body in sorted(bodies.planes) for s in bodies.shapes[body]]
        self.fixed = self._meshes(loose)

    def _meshes(self, shapes) -> list:
        """``shapes`` as at most two meshes: the solids, and the planes (drawn a little behind): (mesh, behind)."""
        found = []
        for group, behind in (([s for s in shapes if s.kind != "plane"], False),
                              ([s for s in shapes if s.kind == "plane"], True)):
            mesh = self.renderer.mesh(*triangles.placed(group))
            if mesh is not None:
                found.append((mesh, behind))
        return found

    def image(self, robot, camera: CameraParams) -> np.ndarray:
        """What ``camera`` on ``robot`` sees now: height × width × 3 uint8 RGB, row 0 at the top."""
        self.open()
        self._sync()
        client = self.session.client
        draws = [(mesh, poses.IDENTITY, behind) for mesh, behind in self.fixed]
        for model, meshes in self.models.values():
            if meshes:
                frame = model.world_frame(client)
                draws += [(mesh, frame, behind) for mesh, behind in meshes]
        draws += [(mesh, triangles.shape_matrix(shape), False) for shape, mesh in self.movers.values()
                  if mesh is not None]
        for other, links in self.robots.values():
            if other is not robot:
                draws += [(mesh, _link_matrix(other, link), False) for link, mesh in links]
        k = intrinsics(camera.fx, camera.fx, camera.cx, camera.cy)
        return self.renderer.render(k, camera.width, camera.height, camera.near, camera.far,
                                    sensor_pose(robot, camera), draws)

    # -- keeping up with what is in the world ----------------------------------------------------------------

    def _sync(self) -> None:
        session, renderer = self.session, self.renderer
        models = session.models.models
        for name in [n for n, (m, _) in self.models.items() if models.get(n) is not m]:
            for mesh, _ in self.models.pop(name)[1]:
                _release(mesh)
        for name, model in models.items():
            if name not in self.models:
                self.models[name] = (model, self._meshes(_model_shapes(model)))
        for body in [b for b in self.movers if b not in session.movers]:
            _release(self.movers.pop(body)[1])
        for body, shape in session.movers.items():
            if body not in self.movers:
                self.movers[body] = (shape, renderer.mesh(*triangles.placed([_at_origin(shape)])))
        alive = {id(r): r for r in session.robots}
        for key in [k for k, (r, _) in self.robots.items() if alive.get(k) is not r]:
            for _, mesh in self.robots.pop(key)[1]:
                _release(mesh)
        for key, robot in alive.items():
            if key not in self.robots:
                self.robots[key] = (robot, _robot_meshes(renderer, robot))

    def close(self) -> None:
        if self.renderer is None:
            return
        meshes = [m for m, _ in self.fixed] + [m for _, ms in self.models.values() for m, _ in ms]
        meshes += [m for _, m in self.movers.values()] + [m for _, ms in self.robots.values() for _, m in ms]
        for mesh in meshes:
            _release(mesh)
        self.fixed, self.models, self.movers, self.robots = [], {}, {}, {}
        self.renderer.close()
        self.renderer = None


def _model_shapes(model) -> list:
    """A model's visuals (else its collision shapes, grey), placed in the model frame."""
    parts = model.visuals if model.visuals is not None else model.shapes
    shapes = []
    for shape, local in parts:
        moved = _at_origin(shape)
        moved.position = tuple(float(v) for v in local[:3, 3])
        moved.orientation = poses.matrix_quat(local[:3, :3])
        shapes.append(moved)
    return shapes


def _at_origin(shape):
    import dataclasses

    return dataclasses.replace(shape, position=(0.0, 0.0, 0.0), orientation=(0.0, 0.0, 0.0, 1.0))


def _robot_meshes(renderer: Renderer, robot) -> list:
    by_link: dict[str, list] = {}
    for shape in link_visuals(robot.urdf, robot.source):
        if shape.link in robot.link_index:
            by_link.setdefault(shape.link, []).append(shape)
    found = []
    for link, shapes in by_link.items():
        mesh = renderer.mesh(*triangles.placed(shapes))
        if mesh is not None:
            found.append((link, mesh))
    return found


def _link_matrix(robot, link: str) -> np.ndarray:
    position, orientation = robot.link_pose(link)
    return poses.transform(position, poses.quat_matrix(*orientation))


def _release(mesh) -> None:
    if mesh is not None:
        mesh.release()
