"""The model tree placed in the world frame: every collision becomes a scene :class:`~worldgen.core.scene.Shape`
(model ∘ nested model ∘ link ∘ collision, or the world-frame poses ``<state>`` gave)."""

from __future__ import annotations

from typing import List

import numpy as np

from ..core import poses
from ..core.scene import Scene, Shape
from .context import ReadContext
from .tree import Model


def emit_models(ctx: ReadContext, models: List[Model], scene: Scene) -> None:
    """Each top-level model's name and shapes into ``scene``; a finding for a non-static model with shapes."""
    for model in models:
        scene.models.append(model.name)
        world = model.world if model.world is not None else model.pose
        scene.model_poses[model.name] = (float(world[0, 3]), float(world[1, 3]), float(world[2, 3]),
                                         *poses.matrix_quat(world[:3, :3]))
        before = len(scene.shapes)
        emit_model(model, poses.IDENTITY, model.name, scene.shapes)
        if not model.static and len(scene.shapes) > before:
            ctx.note("static", "info", f"model '{model.name}' is not static; Gazebo would let the robot push it",
                     model.where, "add <static>1</static> to the model if it is meant to stay put")


def emit_model(model: Model, parent: np.ndarray, label: str, out: List[Shape]) -> None:
    """The shapes of ``model`` (placed in ``parent``'s frame) and of its nested models, labelled ``a::b``."""
    world = model.world if model.world is not None else parent @ model.pose
    for link in model.links:
        link_world = link.world if link.world is not None else world @ link.pose
        for c in link.collisions:
            t = link_world @ c.pose
            out.append(Shape(position=(float(t[0, 3]), float(t[1, 3]), float(t[2, 3])),
                             orientation=poses.matrix_quat(t[:3, :3]), model=label, link=link.name,
                             name=c.name, static=model.static, **c.shape))
    for sub in model.models:
        emit_model(sub, world, f"{label}::{sub.name}", out)
