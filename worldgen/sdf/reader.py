"""The world reader: a Gazebo world or model file, as people really save them, becomes a :class:`~worldgen.core.scene.Scene`.

``read_world(path)`` places every ``<collision>`` in the world frame the way Gazebo does: model ∘ nested model ∘ link ∘
collision poses (``relative_to`` included), the first ``<state>`` applied (state poses are world-frame),
``<include>`` resolved through the model path, meshes loaded with trimesh; and every ``<visual>`` the same way, with
its material's colour, into ``scene.visuals`` (what a camera sees: :mod:`.visuals`). A file that is not XML at all
raises :class:`~worldgen.core.errors.WorldFileError` with its line; everything else the reader notices becomes a
:class:`~worldgen.core.findings.Finding` in ``scene.findings``, so one odd element never hides the rest of the world.

Finding ids: ``sdf-version``, ``structure``, ``pose``, ``include``, ``mesh``, ``geometry``, ``sizes``, ``names``,
``static``, ``collision``, ``state``.

The read, top-down: :func:`read_world` parses the file and starts a :class:`~.context.ReadContext`; the root's
scope is read into a model tree (:mod:`.models`: models, links, collisions, with poses through the frame graph of
:mod:`.frames`; shapes and meshes in :mod:`.shapes`; visuals in :mod:`.visuals`; ``<include>`` in :mod:`.includes`);
the first ``<state>`` moves it (:mod:`.state`); :mod:`.emit` places every collision and visual in the world frame
as a scene shape, and says which visual-only links are not floor markings.
"""

from __future__ import annotations

from pathlib import Path

from lxml import etree

from ..core.errors import WorldFileError
from ..core.inputs import read_capped
from ..core.scene import Scene
from .context import ReadContext, SdfFile, describe_file, parse_sdf
from .emit import emit_models
from .models import read_scope
from .resolve import model_sdf_file
from .shapes import report_missing_meshes
from .state import apply_state_block
from .values import children


def read_world(path, *, model_paths=(), apply_state=True) -> Scene:
    """Read a ``.world``/``.sdf``/``model.sdf`` file (or a model folder holding ``model.config``) into a Scene.

    ``model_paths`` are searched before ``GAZEBO_MODEL_PATH``/``SDF_PATH``/ROS packages for ``model://`` URIs.
    ``apply_state=False`` ignores the file's ``<state>`` block (poses as written in the models).
    Raises WorldFileError when the file is missing, empty, not XML, or not SDF at all.
    """
    path = Path(path)
    if path.is_dir():
        sdf_file, _ = model_sdf_file(path)
        if sdf_file is None:
            raise WorldFileError("is a folder without model.config or model.sdf", path=path,
                                 hint="pass a .world file or a model folder")
        path = sdf_file
    try:
        data = read_capped(path, what="world file")
    except FileNotFoundError:
        raise WorldFileError("no such file", path=path, hint="check the path and the file name") from None
    except OSError as err:
        raise WorldFileError(f"cannot be read: {err.strerror}", path=path, hint="check its permissions") from None
    return _read(ReadContext.start(path, model_paths), parse_sdf(data, path), apply_state)


def read_world_text(text: str, *, source: str | Path | None = None, model_paths=(), apply_state=True) -> Scene:
    """Read SDF text; ``source`` (a path, maybe fictitious) names it in findings and anchors relative paths."""
    label = Path(source) if source is not None else Path("<string>")
    return _read(ReadContext.start(label, model_paths), parse_sdf(text.encode("utf-8"), label),
                 apply_state)


def _read(ctx: ReadContext, root, apply_state: bool) -> Scene:
    """The whole read: the root's contents into the model tree, <state> applied, the shapes placed."""
    f = describe_file(ctx, root, ctx.source)
    scene = Scene(source=ctx.source if ctx.source.name != "<string>" else None,
                  sdf_version=root.get("version"))
    world_el, models, state_el = _root_contents(ctx, root, f)
    if world_el is not None:
        scene.world_name = world_el.get("name")
        if f.version >= (1, 5):
            for physics in children(world_el, "physics"):
                if physics.find("gravity") is not None:
                    ctx.note("structure", "warning", f"<gravity> inside <physics> is SDF 1.4 syntax; SDF "
                             f"{root.get('version')} ignores it there (Gazebo uses the world's own <gravity>, "
                             "default 0 0 -9.8)", f.where(physics.find("gravity")),
                             "move <gravity> out of <physics> to be a child of <world>")
    if state_el is not None:
        if apply_state:
            apply_state_block(ctx, state_el, models, f)
        else:
            ctx.note("state", "info", "the file has a <state> block; not applied (poses as the models "
                     "give them)", f.where(state_el))
    emit_models(ctx, models, scene)
    report_missing_meshes(ctx)
    scene.findings = ctx.findings
    return scene


def _root_contents(ctx: ReadContext, root, f: SdfFile):
    """(world element or None, top-level models, first <state> or None) for any accepted root form."""
    tag = root.tag
    if tag == "robot":
        raise WorldFileError("this is a URDF robot description, not an SDF world", path=f.path,
                             hint="pass the .world file the launch file loads")
    if tag == "launch":
        raise WorldFileError("this is a roslaunch file, not an SDF world", path=f.path,
                             hint="pass the .world file it names in its world_name argument")
    if tag in ("world", "model"):
        ctx.note("structure", "warning", f"the root element is <{tag}> without the <sdf> wrapper",
                 f.where(root), f"wrap it: <sdf version='1.6'><{tag} …>…</{tag}></sdf>")
        holder = etree.Element("sdf")
        holder.append(root)
        root = holder
    elif tag != "sdf":
        raise WorldFileError(f"the root element is <{tag}>, not <sdf>", path=f.path,
                             hint="a Gazebo world starts with <sdf version='1.6'><world name='default'>")
    worlds = children(root, "world")
    if len(worlds) > 1:
        ctx.note("structure", "warning", f"{len(worlds)} <world> elements; only the first is read",
                 f.where(worlds[1]), "keep one <world> per file")
    if worlds:
        world = worlds[0]
        states = children(world, "state")
        if len(states) > 1:
            ctx.note("state", "info", f"{len(states)} <state> blocks; Gazebo applies the first, so does the "
                     "reader", f.where(states[1]))
        return world, read_scope(ctx, world, f, None, "the world", static=False), (states[0] if states else None)
    models = children(root, "model")
    if not models:
        ctx.note("structure", "warning", "the file holds no <world> and no <model>, so no geometry",
                 f.where(root), "a world file needs <sdf><world name='default'>…</world></sdf>")
    return None, read_scope(ctx, root, f, None, "the file", static=False), None
