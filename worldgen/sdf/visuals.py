"""A link's ``<visual>``: what a camera sees of it. Its geometry is read like a collision's (quietly: see
:func:`~.shapes.read_geometry`), its colour from its ``<material>`` (:func:`material_color`)."""

from __future__ import annotations

import math
from typing import Optional, Tuple

import numpy as np

from ..core.materials import script_color
from .context import ReadContext, SdfFile
from .shapes import read_geometry
from .tree import Visual

RGBA = Tuple[float, float, float, float]


def read_visual(ctx: ReadContext, el, f: SdfFile, label: str, pose: np.ndarray,
                shape: Optional[dict] = None) -> Optional[Visual]:
    """The ``<visual>`` ``el`` (its pose in the link frame already resolved; its ``shape`` too when a collision
    beside it has the same geometry), or None when its geometry cannot be drawn (none, an empty or unsupported
    one, a mesh that cannot be found)."""
    if shape is None:
        geometry = el.find("geometry")
        shape = read_geometry(ctx, geometry, f, label, visual=True) if geometry is not None else None
    if shape is None:
        return None
    color = material_color(el.find("material"))
    transparency = _number(el.findtext("transparency"))
    if color is not None and transparency is not None and 0 < transparency <= 1:
        color = color[:3] + (color[3] * (1 - transparency),)
    return Visual(el.get("name") or "visual", pose, shape, color)


def material_color(material) -> Optional[RGBA]:
    """The colour a camera sees of a ``<material>``: its ``<diffuse>`` (the lit colour, which Gazebo lets override
    the script's); else the colour of a stock ``<script>`` name (``Gazebo/Wood``: :mod:`worldgen.core.materials`);
    else its ``<ambient>``; else None. The script comes before ``<ambient>`` because the Building Editor writes
    ``<ambient>1 1 1 1</ambient>`` beside every script it saves, and such walls look wooden or grey, not white."""
    if material is None:
        return None
    diffuse = _rgba(material.findtext("diffuse"))
    if diffuse is not None:
        return diffuse
    stock = script_color(material.findtext("script/name"))
    if stock is not None:
        return stock
    return _rgba(material.findtext("ambient"))


def _rgba(text) -> Optional[RGBA]:
    """``r g b [a]`` from 0 to 1 (values outside are clipped), or None when the text is not 3 or 4 numbers."""
    if text is None:
        return None
    try:
        parts = [float(p) for p in text.split()]
    except ValueError:
        return None
    if len(parts) not in (3, 4) or not all(math.isfinite(p) for p in parts):
        return None
    parts = [min(1.0, max(0.0, p)) for p in parts] + [1.0] * (4 - len(parts))
    return (parts[0], parts[1], parts[2], parts[3])


def _number(text) -> Optional[float]:
    try:
        value = float(text)
    except (TypeError, ValueError):
        return None
    return value if math.isfinite(value) else None
