"""The model tree placed in the world frame: every collision becomes a scene
:class:`~worldgen.core.scene.Shape` (model ∘ nested model ∘ link ∘ collision, or the world-frame poses ``<state>``
gave), and so does every visual, with its colour, in ``scene.visuals``."""

from __future__ import annotations

import functools
import math
from typing import List

import numpy as np

from ..core import poses
from ..core.numbers import format_numbers
from ..core.scene import Scene, Shape
from ..geometry.markings import is_floor_marking
from .context import ReadContext
from .shapes import MAX_SIZE
from .tree import Link, Model

MAX_COORDINATE = MAX_SIZE   # m from the origin: a shape placed farther (1000 km) is a typo, and pybullet and GEOS
#                             crash (SIGSEGV) on coordinates near the float limits, so it is skipped with a finding


def emit_models(ctx: ReadContext, models: List[Model], scene: Scene) -> None:
    """Each top-level model's name and shapes into ``scene``; a finding for a non-static model with shapes."""
    for model in models:
        scene.models.append(model.name)
        world = model.world if model.world is not None else model.pose
        scene.model_poses[model.name] = (float(world[0, 3]), float(world[1, 3]), float(world[2, 3]),
                                         *_quaternion(world[:3, :3]))
        before = len(scene.shapes)
        far: list = []
        emit_model(ctx, model, poses.IDENTITY, model.name, scene, far)
        if far:
            ctx.note("pose", "warning", f"model '{model.name}' places {len(far)} shape{'s' if len(far) > 1 else ''} "
                     f"at {format_numbers(far[0], None)}, farther than {MAX_COORDINATE / 1000:g} km from the origin (or not a "
                     "number); skipped", model.where, "check the model's <pose> and its links': metres, x y z")
        if not model.static and len(scene.shapes) > before:
            ctx.note("static", "info", f"model '{model.name}' is not static; Gazebo would let the robot push it",
                     model.where, "add <static>1</static> to the model if it is meant to stay put")


def emit_model(ctx: ReadContext, model: Model, parent: np.ndarray, label: str, scene: Scene, far: list) -> None:
    """The shapes and visuals of ``model`` (placed in ``parent``'s frame) and of its nested models, labelled
    ``a::b``; the position of each shape placed beyond :data:`MAX_COORDINATE` goes to ``far`` instead."""
    world = model.world if model.world is not None else parent @ model.pose
    for link in model.links:
        link_world = link.world if link.world is not None else world @ link.pose
        placed: dict = {}   # a visual often shares its collision's pose: placed once
        for c in link.collisions:
            position, orientation = _place(link_world, c.pose, placed)
            if _beyond(position, far):
                continue
            scene.shapes.append(Shape(position=position, orientation=orientation, model=label, link=link.name,
                                      name=c.name, static=model.static, **c.shape))
        visuals = []
        for v in link.visuals:
            position, orientation = _place(link_world, v.pose, placed)
            if _beyond(position, far):
                continue
            visuals.append(Shape(position=position, orientation=orientation, model=label, link=link.name,
                                 name=v.name, static=model.static, color=v.color, **v.shape))
        scene.visuals += visuals
        if link.bare is not None:
            _bare_link(ctx, link, label, visuals)
    for sub in model.models:
        emit_model(ctx, sub, world, f"{label}::{sub.name}", scene, far)


def _beyond(position, far: list) -> bool:
    """Whether ``position`` is no number or farther than MAX_COORDINATE from the origin (then noted in ``far``)."""
    if all(math.isfinite(c) and abs(c) <= MAX_COORDINATE for c in position):
        return False
    far.append(position)
    return True


def _place(link_world: np.ndarray, pose: np.ndarray, placed: dict) -> tuple:
    """The world position and orientation of a pose in the link's frame (``placed`` caches them by pose object)."""
    if id(pose) not in placed:
        t = link_world @ pose
        placed[id(pose)] = ((float(t[0, 3]), float(t[1, 3]), float(t[2, 3])), _quaternion(t[:3, :3]))
    return placed[id(pose)]


QUATERNIONS_KEPT = 1024


def _quaternion(rotation: np.ndarray) -> tuple:
    """:func:`~worldgen.core.poses.matrix_quat` of ``rotation``, remembered by its bytes (the last
    :data:`QUATERNIONS_KEPT`): the models of a big world share a few rotations (10 000 posts: one, twice each)."""
    return _quaternion_of(rotation.tobytes(), rotation.dtype.str)


@functools.lru_cache(maxsize=QUATERNIONS_KEPT)
def _quaternion_of(data: bytes, dtype: str) -> tuple:
    return poses.matrix_quat(np.frombuffer(data, dtype=dtype).reshape(3, 3))


def _bare_link(ctx: ReadContext, link: Link, label: str, visuals: List[Shape]) -> None:
    """A link with visuals and no collision: nothing to say when every visual is a marking lying on the floor
    (tape, a painted patch: meant to be driven over); else Gazebo lets the robot through it, which a wall-like
    visual (5 cm or taller) makes a warning and a low one an info."""
    if visuals and not link.unread and all(is_floor_marking(v) for v in visuals):
        return
    ctx.note("collision", "warning" if link.tall else "info",
             f"link {label}/{link.name} has a <visual> but no <collision>: Gazebo lets the robot drive through it "
             "and the LiDAR does not see it", link.bare,
             "add a <collision> with the same geometry as the visual" if link.tall else None)
