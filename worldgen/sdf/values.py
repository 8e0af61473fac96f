"""The small SDF value parsers: element children, ``<pose>`` (euler or quaternion, ``relative_to``), lists of
numbers, booleans, and the duplicate-name check. A value that does not parse becomes a finding and its default."""

from __future__ import annotations

import math
from typing import Optional, Tuple

import numpy as np
from lxml import etree

from ..core import poses
from ..core.numbers import format_numbers
from .context import ReadContext, SdfFile


def children(el, tag: str | None = None):
    """Element children (no comments or processing instructions), optionally of one tag."""
    return [c for c in el.iterchildren(tag=etree.Element) if tag is None or c.tag == tag]


def read_pose(ctx: ReadContext, owner, f: SdfFile) -> Tuple[np.ndarray, Optional[str]]:
    """The ``<pose>`` child of ``owner`` as a matrix, and the frame it is relative to (None: the parent)."""
    el = owner.find("pose")
    if el is None:
        return poses.IDENTITY, None
    relative_to = (el.get("relative_to") or el.get("frame") or "").strip() or None
    quat = el.get("rotation_format", "euler_rpy") == "quat_xyzw"
    degrees = (el.get("degrees") or "").strip().lower() in ("true", "1")
    key = (el.text, quat, degrees)
    known = ctx.pose_texts.get(key)   # a pose written many times (each wall's collision and visual) is read once
    if known is not None:
        return known, relative_to
    count = 7 if quat else 6
    noted = len(ctx.findings)
    values = read_floats(ctx, el.text, count, (0.0,) * count, f, el, "pose")
    if quat:
        matrix = poses.transform(values[:3], poses.quat_matrix(*values[3:]))
    else:
        if degrees:
            values = values[:3] + tuple(math.radians(v) for v in values[3:])
        matrix = poses.pose_matrix(*values)
    if len(ctx.findings) == noted:   # a pose that does not parse is said every time
        matrix.setflags(write=False)
        ctx.pose_texts[key] = matrix
    return matrix, relative_to


def read_floats(ctx: ReadContext, text, count: int, default: tuple, f: SdfFile, el, what: str) -> tuple:
    """``count`` numbers from ``text``; ``default`` when it is empty, or (with a finding) when it does not parse."""
    if text is None or not text.strip():
        return default
    parts = text.split()
    try:
        values = tuple(float(p) for p in parts)
    except ValueError:
        values = ()
    if len(values) != count or not all(math.isfinite(v) for v in values):
        ctx.note("structure", "warning", f"{what} '{' '.join(parts)}' is not {count} number"
                 f"{'s' if count > 1 else ''}; used {format_numbers(default, None)}", f.where(el),
                 f"write {count} plain numbers separated by spaces")
        return default
    return values


def read_bool(ctx: ReadContext, el, f: SdfFile, default):
    """The boolean in element ``el`` (1/0/true/false); ``default`` when ``el`` is None or (with a finding) odd."""
    if el is None:
        return default
    text = (el.text or "").strip().lower()
    if text in ("1", "true"):
        return True
    if text in ("0", "false"):
        return False
    ctx.note("structure", "warning", f"<{el.tag}> '{el.text}' is not a boolean; used {default}", f.where(el),
             f"write <{el.tag}>1</{el.tag}> or <{el.tag}>0</{el.tag}>")
    return default


def check_unique(ctx: ReadContext, names: list[str], what: str, where: str) -> None:
    """A finding naming every name that occurs more than once among ``names``."""
    seen, dupes = set(), []
    for name in names:
        if name in seen and name not in dupes:
            dupes.append(name)
        seen.add(name)
    if dupes:
        ctx.note("names", "warning", f"duplicate {what}: {', '.join(dupes)}; Gazebo refuses or renames them",
                 where, "give each one a unique name")
