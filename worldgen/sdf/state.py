"""Gazebo's ``<state>`` block applied to the model tree: model and link poses there are world-frame and win."""

from __future__ import annotations

import math
from typing import Dict, List, Optional

import numpy as np

from ..core import poses
from ..core.numbers import format_numbers
from .context import ReadContext, SdfFile
from .tree import Model
from .values import children, read_floats, read_pose


def apply_state_block(ctx: ReadContext, state, models: List[Model], f: SdfFile) -> None:
    """Apply Gazebo's first ``<state>``: model and link poses there are world-frame and win."""
    moved: List[str] = []
    by_name = {m.name: m for m in models}
    for child in children(state):
        if child.tag == "model":
            _state_model(ctx, child, by_name, f, moved)
        elif child.tag in ("insertions", "deletions"):
            ctx.note("state", "warning", f"<state> has <{child.tag}>, which the reader does not apply",
                     f.where(child), "save the world again from Gazebo without them")
    if moved:
        shown = ", ".join(moved[:4]) + (f" and {len(moved) - 4} more" if len(moved) > 4 else "")
        ctx.note("state", "info", f"<state> moves {len(moved)} model{'s' if len(moved) > 1 else ''} away from "
                 f"{'their' if len(moved) > 1 else 'its'} <pose> ({shown}); Gazebo applies the first <state>, "
                 "so the reader places them there", f.where(state))


def _state_model(ctx: ReadContext, el, models: Dict[str, Model], f: SdfFile, moved: Optional[List[str]]) -> None:
    """One state ``<model>`` (``moved`` collects how far top-level models move; None for nested ones)."""
    name = el.get("name") or ""
    model = models.get(name)
    if model is None:
        ctx.note("state", "info", f"<state> names model '{name}', which the world does not have; ignored",
                 f.where(el))
        return
    if el.find("pose") is not None:
        model.world, _ = read_pose(ctx, el, f)
        if moved is not None:
            shift = float(np.linalg.norm(model.world[:2, 3] - model.pose[:2, 3]))
            turn = abs(math.remainder(poses.yaw_of(model.world) - poses.yaw_of(model.pose), 2 * math.pi))
            turned = turn >= math.radians(2)
            if shift >= 0.05 or turned:
                moved.append(f"'{name}' {shift:.2f} m" + (f", {math.degrees(turn):.0f}°" if turned else ""))
    scale = read_floats(ctx, el.findtext("scale"), 3, (1.0, 1.0, 1.0), f, el, f"state scale of '{name}'")
    if any(abs(s - 1.0) > 1e-9 for s in scale):
        ctx.note("state", "info", f"<state> scales model '{name}' by {format_numbers(scale, None)}; the reader "
                 "keeps its unscaled geometry", f.where(el))
    links = {link.name: link for link in model.links}
    for link_el in children(el, "link"):
        link = links.get(link_el.get("name") or "")
        if link is None:
            ctx.note("state", "info", f"<state> names link '{link_el.get('name')}' that model '{name}' does "
                     "not have; ignored", f.where(link_el))
        elif link_el.find("pose") is not None:
            link.world, _ = read_pose(ctx, link_el, f)
    nested = {m.name: m for m in model.models}
    for sub in children(el, "model"):
        _state_model(ctx, sub, nested, f, None)
