"""``<include>``: its URI resolved through the model path, the included model file parsed and read (as a model
of the including scope), Gazebo's stock ground plane stood in for, include cycles cut. An online (Gazebo Fuel)
model, as Gazebo Sim worlds include them, is never downloaded: a warning names it (Fuel's stock "Ground Plane" and
"Sun", which ROBOTIS's Gazebo Sim worlds include, are stood in for as the stock ``ground_plane`` and ``sun`` are).

The included ``<model>`` is read by the function the caller passes (:func:`worldgen.sdf.models.read_model`), so
that reading a model and including one do not import each other.
"""

from __future__ import annotations

from typing import Callable, Optional, Tuple

import numpy as np

from ..core.errors import WorldFileError
from ..core.inputs import read_capped
from .context import ReadContext, SdfFile, describe_file, parse_sdf
from .frames import Frames
from .resolve import STOCK_MODELS, Resolved, fuel_model, model_sdf_file, uri_fix
from .tree import Model, ground_plane
from .values import children, read_bool, read_pose

INCLUDE_CHILDREN = {"uri", "name", "pose", "static", "plugin", "placement_frame"}
MAX_INCLUDE_DEPTH = 16   # includes inside included models, nested
MAX_INCLUDES = 5000      # model files included in one world read, counting every copy at every depth

# read_model(ctx, model_element, file, parent_static, frames, name=..., static=...) -> Model
ReadModel = Callable[..., Model]


def read_include(ctx: ReadContext, el, f: SdfFile, parent_static: bool, frames: Frames,
                 read_model: ReadModel) -> Optional[Tuple[Model, np.ndarray, Optional[str]]]:
    """An ``<include>``: (model, pose in parent, relative_to) or None when it adds no geometry."""
    where = f.where(el)
    uri = (el.findtext("uri") or "").strip()
    for child in children(el):
        if child.tag not in INCLUDE_CHILDREN:
            ctx.note("structure", "info", f"<{child.tag}> inside <include> is not part of SDF; Gazebo "
                     "ignores it", f.where(child), "remove it, or change the included model itself")
    if not uri:
        ctx.note("include", "warning", "<include> without a <uri>; skipped", where,
                 "add <uri>model://NAME</uri>")
        return None
    name_override = (el.findtext("name") or "").strip() or None
    static_override = read_bool(ctx, el.find("static"), f, None)
    resolved = ctx.resolver.resolve(uri, f.dir, want_dir=True)
    stock = resolved.model_name if resolved.model_name in STOCK_MODELS else None
    if resolved.path is None:
        fuel = fuel_model(uri) if resolved.remote else None
        named = f"the Fuel model '{fuel[1]}' ({fuel[0]})" if fuel else None
        if stock == "ground_plane":
            ctx.note("include", "info", f"{named}: Gazebo's stock ground plane, never downloaded; stood in for by a "
                     "plane at z = 0" if named else f"{uri}: Gazebo's stock ground plane, stood in for by a plane "
                     "at z = 0", where)
            return (ground_plane(name_override or "ground_plane", where), *read_pose(ctx, el, f))
        if stock == "sun":
            if named:
                ctx.note("include", "info", f"{named}: Gazebo's stock sun, a light with nothing to collide with "
                         "(never downloaded)", where)
            return None
        if resolved.remote:
            ctx.note("include", "warning", f"{named or uri} is an online model, never downloaded here: its "
                     "geometry is missing (not counted as walls)" + (f" ({uri})" if named else ""), where,
                     "download it (gz fuel download -u URL), put its folder on --model-path DIR (or "
                     "GZ_SIM_RESOURCE_PATH) and include it as model://NAME" if named else
                     "download it and put its folder on GAZEBO_MODEL_PATH, or pass --model-path DIR")
        else:
            ctx.note("include", "warning", f"cannot find included model {uri}: {resolved.reason}; its "
                     "geometry is missing (not counted as walls)", where, uri_fix(uri, resolved))
        return None
    model = load_included(ctx, resolved, where, parent_static, name_override, static_override, frames, read_model)
    if model is None:
        return None
    if el.find("pose") is None:   # the include's pose replaces the model's own; without one, that stands
        return model, model.pose, None
    return (model, *read_pose(ctx, el, f))


def _count_include(ctx: ReadContext, uri: str, where: str) -> None:
    """Refuse (WorldFileError) an include nested deeper than MAX_INCLUDE_DEPTH or past MAX_INCLUDES in all:
    a world whose includes fan out (each model including several others) grows exponentially."""
    ctx.include_count += 1
    if len(ctx.include_stack) >= MAX_INCLUDE_DEPTH:
        raise WorldFileError(f"{where}: {uri} is nested more than {MAX_INCLUDE_DEPTH} includes deep, the most "
                             "worldgen follows", path=None,
                             hint="include the innermost models from an outer file (see Limits in the README)")
    if ctx.include_count > MAX_INCLUDES:
        raise WorldFileError(f"{where}: the world includes more than {MAX_INCLUDES} models (counting the includes "
                             "inside included models), the most worldgen reads", path=None,
                             hint="include fewer copies, or merge repeated models into one model file (see "
                                  "Limits in the README)")


def load_included(ctx: ReadContext, resolved: Resolved, where: str, parent_static: bool, name: Optional[str],
                  static: Optional[bool], frames: Frames, read_model: ReadModel) -> Optional[Model]:
    """Parse the model file ``resolved`` points at (a model folder's SDF file) and read its ``<model>``, with
    its own pose; None (with a finding) for a folder without SDF, an include cycle, a file that cannot be read,
    or a file holding no model."""
    path = resolved.path
    assert path is not None
    if path.is_dir():
        sdf_file, note = model_sdf_file(path)
        if note:
            ctx.note("include", "info", f"{resolved.uri}: {note}", where)
        if sdf_file is None:
            ctx.note("include", "warning", f"{resolved.uri} resolves to {path}, which has no SDF file",
                     where, "give the model folder a model.config and a model.sdf")
            return None
        path = sdf_file
    if path in ctx.include_stack:
        ctx.note("include", "error", f"{resolved.uri} includes itself (directly or through other models)", where,
                 "break the include cycle")
        return None
    _count_include(ctx, resolved.uri, where)
    if path not in ctx.parsed:   # a model included many times is parsed once
        try:
            ctx.parsed[path] = parse_sdf(read_capped(path, what="model file"), path)
        except (WorldFileError, OSError) as err:
            ctx.parsed[path] = err
    root = ctx.parsed[path]
    if isinstance(root, Exception):
        ctx.note("include", "error", f"included model {resolved.uri} cannot be read: {root}", where,
                 "fix the included file")
        return None
    inc = describe_file(ctx, root, path)
    model_el = root if root.tag == "model" else root.find("model")
    if model_el is None and root.find("light") is not None:
        return None  # a light model (Gazebo's sun): nothing to collide with
    if model_el is None:
        kind = "a world, not a model" if root.find("world") is not None else "no <model>"
        ctx.note("include", "warning", f"{resolved.uri} ({path}) holds {kind}; nothing included", where,
                 "include a model folder (model.config + model.sdf)")
        return None
    ctx.include_stack.append(path)
    try:
        frames.scope = f"model '{name or model_el.get('name')}'"
        model = read_model(ctx, model_el, inc, parent_static, frames, name=name, static=static)
    finally:
        ctx.include_stack.pop()
    model.pose, _ = read_pose(ctx, model_el, inc)
    return model
