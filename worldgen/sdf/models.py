"""Reading a scope (the world, or a model's body) into the model tree: nested models, includes, links and their
collisions, with every pose resolved through the scope's :class:`~.frames.Frames`."""

from __future__ import annotations

from typing import List, Optional, Tuple

from lxml import etree

from ..core import poses
from .context import ReadContext, SdfFile
from .frames import Frames
from .includes import read_include
from .shapes import read_geometry
from .tree import Collision, Link, Model
from .visuals import read_visual
from .values import check_unique, children, read_bool, read_pose


def read_scope(ctx: ReadContext, el, f: SdfFile, model: Optional[Model], label: str, static: bool,
               frames: Optional[Frames] = None) -> List[Model]:
    """Read the links, nested models and includes directly under ``el``; returns the nested models.

    ``model`` receives the links (None at world level). Poses are resolved through the scope's frames.
    """
    frames = frames or Frames(ctx, label)
    nested: List[Tuple[Model, int]] = []                  # with their frame entries
    links: List[Tuple[Link, etree._Element, int]] = []
    for child in children(el):
        tag = child.tag
        if tag == "model":
            sub_frames = Frames(ctx, f"model '{child.get('name')}'")
            sub = read_model(ctx, child, f, static, sub_frames)
            pose, rel = read_pose(ctx, child, f)
            nested.append((sub, frames.add(sub.name, pose, rel, f.where(child))))
            frames.children.setdefault(sub.name, sub_frames)
        elif tag == "include":
            sub_frames = Frames(ctx, "an included model")
            found = read_include(ctx, child, f, static, sub_frames, read_model)
            if found is not None:
                sub, pose, rel = found
                nested.append((sub, frames.add(sub.name, pose, rel, f.where(child))))
                frames.children.setdefault(sub.name, sub_frames)
        elif tag == "link" and model is not None:
            pose, rel = read_pose(ctx, child, f)
            link = Link(child.get("name") or "link", pose)
            links.append((link, child, frames.add(link.name, pose, rel, f.where(child))))
        elif tag == "joint" and model is not None:
            pose, rel = read_pose(ctx, child, f)
            frames.add(child.get("name") or "", pose, rel or child.findtext("child", "").strip() or None,
                       f.where(child))
        elif tag == "frame":
            pose, rel = read_pose(ctx, child, f)
            frames.add(child.get("name") or "", pose, rel or child.get("attached_to") or None, f.where(child))
        elif tag == "population":
            _population(ctx, child, f)
        elif tag == "actor":
            ctx.note("structure", "info", f"actor '{child.get('name')}' ignored (animated; not an obstacle "
                     "the reader can place)", f.where(child))
    check_unique(ctx, [m.name for m, _ in nested], f"models in {label}", f.where(el))
    if model is not None:
        check_unique(ctx, [link.name for link, _, _ in links], f"links in model '{model.name}'", f.where(el))
    for sub, entry in nested:
        sub.pose = frames.place(entry)
    for link, link_el, entry in links:
        link.pose = frames.place(entry)
        read_link(ctx, link, link_el, f, model, frames)
        model.links.append(link)
    return [m for m, _ in nested]


def read_model(ctx: ReadContext, el, f: SdfFile, parent_static: bool, frames: Frames, *,
               name: Optional[str] = None, static: Optional[bool] = None) -> Model:
    """A ``<model>`` element and everything in it (its own pose is set by the parent scope)."""
    name = name or el.get("name") or "model"
    own_static = read_bool(ctx, el.find("static"), f, False) if static is None else static
    model = Model(name, poses.IDENTITY, parent_static or own_static, f.where(el))
    model.models = read_scope(ctx, el, f, model, f"model '{name}'", model.static, frames)
    return model


def read_link(ctx: ReadContext, link: Link, el, f: SdfFile, model: Model, frames: Frames) -> None:
    """The collisions and visuals of ``<link>`` ``el`` into ``link`` (its pose already placed). A link that shows
    visuals but has nothing to collide with is marked ``bare``: the emitter, which knows where it ends up, says so
    unless it is a marking lying on the floor."""
    collisions = children(el, "collision")
    check_unique(ctx, [c.get("name") or "" for c in collisions],
                 f"collisions in {model.name}/{link.name}", f.where(el))
    visuals = children(el, "visual")
    read: dict = {}   # (pose, geometry) as written → (pose, shape) read: a visual drawn like a collision reuses it
    for c in collisions:
        name = c.get("name") or "collision"
        label = f"{model.name}/{link.name}/{name}"
        pose = _pose_in_link(ctx, c, f, link, frames, f"collision {label}")
        geometry = c.find("geometry")
        if geometry is None:
            ctx.note("structure", "warning", f"collision {label} has no <geometry>; skipped", f.where(c),
                     "give it a <geometry> (box, cylinder, sphere or mesh)")
            continue
        shape = read_geometry(ctx, geometry, f, label)
        if shape is not None:
            link.collisions.append(Collision(name, pose, shape))
            written = _as_written(c, geometry) if visuals else None   # only a visual looks it up
            if written is not None:
                read.setdefault(written, (pose, shape))
    for v in visuals:
        label = f"{model.name}/{link.name}/{v.get('name') or 'visual'}"
        written = _as_written(v, v.find("geometry")) if read else None
        same = read.get(written) if written is not None else None
        if same is not None:
            visual = read_visual(ctx, v, f, label, *same)
        else:
            visual = read_visual(ctx, v, f, label, _pose_in_link(ctx, v, f, link, frames, f"visual {label}"))
        if visual is not None:
            link.visuals.append(visual)
        else:
            link.unread += 1
    if visuals and not collisions:
        link.bare = f.where(el)
        link.tall = any(h is None or h >= 0.05 for h in (visual_height(v) for v in visuals))


def _as_written(el, geometry) -> tuple | None:
    """A collision's or visual's pose and plain geometry (box, cylinder, sphere) as written, to compare; None for
    anything else."""
    g = geometry[0] if geometry is not None and len(geometry) else None
    if g is None or g.tag not in ("box", "cylinder", "sphere"):
        return None
    pose = el.find("pose")
    return ((pose.text, tuple(sorted(pose.attrib.items()))) if pose is not None else None, g.tag,
            tuple((part.tag, part.text) for part in g))


def _pose_in_link(ctx: ReadContext, el, f: SdfFile, link: Link, frames: Frames, what: str):
    """The pose of a collision or visual ``el`` in its link's frame (``relative_to`` another frame resolved)."""
    pose, rel = read_pose(ctx, el, f)
    if rel and rel != link.name:
        frame = frames.resolve(rel)
        if frame is None:
            ctx.note("pose", "warning", f"{what} has relative_to='{rel}', no frame of that name; treated as "
                     "relative to its link", f.where(el))
        else:
            pose = poses.inverse(link.pose) @ frame @ pose
    return pose


def visual_height(visual) -> Optional[float]:
    """How tall a visual is (None when unknown: a mesh, or numbers that do not parse)."""
    try:
        box = visual.findtext("geometry/box/size")
        if box is not None:
            return float(box.split()[2])
        length = visual.findtext("geometry/cylinder/length")
        if length is not None:
            return float(length)
        radius = visual.findtext("geometry/sphere/radius")
        return 2 * float(radius) if radius is not None else None
    except (ValueError, IndexError):
        return None


def _population(ctx: ReadContext, el, f: SdfFile) -> None:
    inner = el.find("model")
    count = (el.findtext("model_count") or "?").strip()
    what = f"model '{inner.get('name')}'" if inner is not None else "a model"
    ctx.note("structure", "warning", f"<population> '{el.get('name')}' ({count} copies of {what}) is not "
             "expanded: Gazebo scatters those models at run time, so they are not in the scene", f.where(el),
             "place the copies as ordinary <model>s if the robot must avoid them")
