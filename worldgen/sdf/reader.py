"""The world reader: a Gazebo world or model file, as people really save them, becomes a :class:`~worldgen.core.scene.Scene`.

``read_world(path)`` places every ``<collision>`` in the world frame the way Gazebo does: model ∘ nested model ∘ link ∘
collision poses (``relative_to`` included), the first ``<state>`` applied (state poses are world-frame),
``<include>`` resolved through the model path, meshes loaded with trimesh. A file that is not XML at all raises
:class:`~worldgen.core.errors.WorldFileError` with its line; everything else the reader notices becomes a
:class:`~worldgen.core.findings.Finding` in ``scene.findings``, so one odd element never hides the rest of the world.

Finding ids: ``sdf-version``, ``structure``, ``pose``, ``include``, ``mesh``, ``geometry``, ``sizes``, ``names``,
``static``, ``collision``, ``state``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from lxml import etree

from ..core.errors import WorldFileError
from ..core.findings import Finding, Severity
from ..core.safexml import parse_bytes
from ..core.scene import Scene, Shape
from ..core import poses
from .meshes import MeshCache
from .resolve import STOCK_MODELS, Resolved, Resolver, model_sdf_file

KNOWN_VERSIONS = ("1.4", "1.5", "1.6", "1.7", "1.8", "1.9")
_INCLUDE_CHILDREN = {"uri", "name", "pose", "static", "plugin", "placement_frame"}
_MAX_INCLUDE_DEPTH = 16
_MODEL_PATH_FIX = ("put the folder that holds it on GAZEBO_MODEL_PATH (or pass --model-path DIR to worldgen)")


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
        data = path.read_bytes()
    except FileNotFoundError:
        raise WorldFileError("no such file", path=path, hint="check the path and the file name") from None
    except OSError as err:
        raise WorldFileError(f"cannot be read: {err.strerror}", path=path, hint="check its permissions") from None
    return _Reader(path, model_paths).read(_parse(data, path), apply_state)


def read_world_text(text: str, *, source: str | Path | None = None, model_paths=(), apply_state=True) -> Scene:
    """Read SDF text; ``source`` (a path, maybe fictitious) names it in findings and anchors relative paths."""
    label = Path(source) if source is not None else Path("<string>")
    return _Reader(label, model_paths).read(_parse(text.encode("utf-8"), label), apply_state)


def _parse(data: bytes, path: Path) -> etree._Element:
    return parse_bytes(data, path, empty_hint="a Gazebo world starts with <sdf version='1.6'>")


# ----------------------------------------------------------------------------------------------------------------
# The model tree the reader builds before it places anything (so that <state> can override poses first).

@dataclass
class _Collision:
    name: str
    pose: np.ndarray  # in the link frame
    shape: dict       # Shape keyword arguments for the geometry (kind, size, radius, …)


@dataclass
class _Link:
    name: str
    pose: np.ndarray  # in the model frame
    collisions: list[_Collision] = field(default_factory=list)
    world: np.ndarray | None = None  # from <state>: world frame


@dataclass
class _Model:
    name: str
    pose: np.ndarray  # in the parent frame (world or parent model)
    static: bool
    where: str
    links: list[_Link] = field(default_factory=list)
    models: list[_Model] = field(default_factory=list)
    world: np.ndarray | None = None  # from <state>: world frame


@dataclass(frozen=True)
class _File:
    """One SDF file being read: its path (for findings and relative URIs) and SDF version."""

    path: Path
    version: tuple[int, int]

    @property
    def dir(self) -> Path:
        return self.path.parent

    def where(self, el) -> str:
        return f"{self.path}:{el.sourceline}" if getattr(el, "sourceline", None) else str(self.path)


def _children(el, tag: str | None = None):
    """Element children (no comments or processing instructions), optionally of one tag."""
    return [c for c in el.iterchildren(tag=etree.Element) if tag is None or c.tag == tag]


class _Frames:
    """The named frames of one scope (a model, or the world) and their poses in the scope's frame.

    Every pose-bearing child (link, nested model or include, joint, frame) is an entry, placed on first use and
    cached, so ``relative_to`` may name a sibling declared later. Names are looked up to their first entry (a
    duplicate name is reported elsewhere) but each entry keeps its own pose. Unknown names and cycles fall back to
    the scope frame with a warning.
    """

    def __init__(self, reader: _Reader, scope: str):
        self.reader, self.scope = reader, scope
        self.entries: list[tuple[str, np.ndarray, str | None, str]] = []   # name, pose, relative_to, where
        self.first: dict[str, int] = {}
        self.children: dict[str, _Frames] = {}
        self.placed: dict[int, np.ndarray] = {}

    def add(self, name: str, pose: np.ndarray, relative_to: str | None, where: str) -> int:
        """Record an entry; returns its index for :meth:`place`."""
        self.entries.append((name, pose, relative_to, where))
        self.first.setdefault(name, len(self.entries) - 1)
        return len(self.entries) - 1

    def resolve(self, name: str, stack: tuple[str, ...] = ()) -> np.ndarray | None:
        """The pose of the frame called ``name`` (``a::b`` for one inside nested model ``a``), or None."""
        if name in ("__model__", "world", ""):
            return poses.IDENTITY
        if "::" in name:
            head, rest = name.split("::", 1)
            base, sub = self.resolve(head, stack), self.children.get(head)
            inner = sub.resolve(rest) if sub is not None else None
            return None if base is None or inner is None else base @ inner
        index = self.first.get(name)
        return None if index is None or name in stack else self.place(index, stack)

    def place(self, index: int, stack: tuple[str, ...] = ()) -> np.ndarray:
        """Entry ``index``'s pose in the scope frame, its ``relative_to`` resolved."""
        if index not in self.placed:
            name, pose, relative_to, where = self.entries[index]
            base = poses.IDENTITY
            if relative_to:
                found = self.resolve(relative_to, stack + (name,))
                if found is None:
                    why = "a cycle" if relative_to in stack + (name,) else "no frame of that name"
                    self.reader.note("pose", "warning", f"'{name}' in {self.scope} has relative_to='{relative_to}', "
                                     f"{why} in that scope; treated as relative to its parent", where,
                                     "name a sibling link, model, joint or frame, or drop relative_to")
                else:
                    base = found
            self.placed[index] = base @ pose
        return self.placed[index]


class _Reader:
    """One read of one world: findings, the model-path resolver and the mesh cache live here."""

    def __init__(self, source: Path, model_paths):
        self.source = source
        self.findings: list[Finding] = []
        self.resolver = Resolver(model_paths, world_file=source if source.name != "<string>" else None)
        self.meshes = MeshCache()
        self.include_stack: list[Path] = []
        self.missing_meshes: dict[str, list] = {}  # uri -> [reason, fix, where, labels]

    def note(self, check: str, severity: Severity, message: str, where: str | None = None,
             fix: str | None = None) -> None:
        self.findings.append(Finding(check, severity, message, where, fix))

    # -- files and roots ------------------------------------------------------------------------------------
    def read(self, root, apply_state: bool) -> Scene:
        f = self._file(root, self.source)
        scene = Scene(source=self.source if self.source.name != "<string>" else None,
                      sdf_version=root.get("version"))
        world_el, models, state_el = self._root_contents(root, f)
        if world_el is not None:
            scene.world_name = world_el.get("name")
            if f.version >= (1, 5):
                for physics in _children(world_el, "physics"):
                    if physics.find("gravity") is not None:
                        self.note("structure", "warning", f"<gravity> inside <physics> is SDF 1.4 syntax; SDF "
                                  f"{root.get('version')} ignores it there (Gazebo uses the world's own <gravity>, "
                                  "default 0 0 -9.8)", f.where(physics.find("gravity")),
                                  "move <gravity> out of <physics> to be a child of <world>")
        if state_el is not None:
            if apply_state:
                self._apply_state(state_el, models, f)
            else:
                self.note("state", "info", "the file has a <state> block; not applied (poses as the models "
                          "give them)", f.where(state_el))
        self._emit_all(models, scene)
        self._report_missing_meshes()
        scene.findings = self.findings
        return scene

    def _file(self, root, path: Path) -> _File:
        """Check the root's SDF version (a finding when odd) and describe the file."""
        text = root.get("version") if root.tag == "sdf" else None
        if root.tag == "sdf" and text is None:
            self.note("sdf-version", "warning", "<sdf> has no version attribute; read as SDF 1.6",
                      f"{path}:{root.sourceline}", "write <sdf version='1.6'> (Gazebo 9/11)")
        elif text is not None and text.strip() not in KNOWN_VERSIONS:
            self.note("sdf-version", "warning", f"SDF version '{text}' is not one the reader knows "
                      f"({KNOWN_VERSIONS[0]}–{KNOWN_VERSIONS[-1]}); read as the nearest known one",
                      f"{path}:{root.sourceline}", "use version 1.6 for Gazebo 9/11 (ROS Melodic/Noetic)")
        try:
            major, minor = (int(p) for p in (text or "1.6").strip().split(".")[:2])
        except ValueError:
            major, minor = 1, 6
        return _File(path, (major, minor))

    def _root_contents(self, root, f: _File):
        """(world element or None, top-level models, first <state> or None) for any accepted root form."""
        tag = root.tag
        if tag == "robot":
            raise WorldFileError("this is a URDF robot description, not an SDF world", path=f.path,
                                 hint="pass the .world file the launch file loads")
        if tag == "launch":
            raise WorldFileError("this is a roslaunch file, not an SDF world", path=f.path,
                                 hint="pass the .world file it names in its world_name argument")
        if tag in ("world", "model"):
            self.note("structure", "warning", f"the root element is <{tag}> without the <sdf> wrapper",
                      f.where(root), f"wrap it: <sdf version='1.6'><{tag} …>…</{tag}></sdf>")
            holder = etree.Element("sdf")
            holder.append(root)
            root = holder
        elif tag != "sdf":
            raise WorldFileError(f"the root element is <{tag}>, not <sdf>", path=f.path,
                                 hint="a Gazebo world starts with <sdf version='1.6'><world name='default'>")
        worlds = _children(root, "world")
        if len(worlds) > 1:
            self.note("structure", "warning", f"{len(worlds)} <world> elements; only the first is read",
                      f.where(worlds[1]), "keep one <world> per file")
        if worlds:
            world = worlds[0]
            states = _children(world, "state")
            if len(states) > 1:
                self.note("state", "info", f"{len(states)} <state> blocks; Gazebo applies the first, so does the "
                          "reader", f.where(states[1]))
            return world, self._scope(world, f, None, "the world", static=False), (states[0] if states else None)
        models = _children(root, "model")
        if not models:
            self.note("structure", "warning", "the file holds no <world> and no <model>, so no geometry",
                      f.where(root), "a world file needs <sdf><world name='default'>…</world></sdf>")
        return None, self._scope(root, f, None, "the file", static=False), None

    # -- scopes: the world, or a model's body ------------------------------------------------------------------
    def _scope(self, el, f: _File, model: _Model | None, label: str, static: bool,
               frames: _Frames | None = None) -> list[_Model]:
        """Read the links, nested models and includes directly under ``el``; returns the nested models.

        ``model`` receives the links (None at world level). Poses are resolved through the scope's frames.
        """
        frames = frames or _Frames(self, label)
        nested: list[tuple[_Model, int]] = []                  # with their frame entries
        links: list[tuple[_Link, etree._Element, int]] = []
        for child in _children(el):
            tag = child.tag
            if tag == "model":
                sub_frames = _Frames(self, f"model '{child.get('name')}'")
                sub = self._model(child, f, static, sub_frames)
                pose, rel = self._pose(child, f)
                nested.append((sub, frames.add(sub.name, pose, rel, f.where(child))))
                frames.children.setdefault(sub.name, sub_frames)
            elif tag == "include":
                sub_frames = _Frames(self, "an included model")
                found = self._include(child, f, static, sub_frames)
                if found is not None:
                    sub, pose, rel = found
                    nested.append((sub, frames.add(sub.name, pose, rel, f.where(child))))
                    frames.children.setdefault(sub.name, sub_frames)
            elif tag == "link" and model is not None:
                pose, rel = self._pose(child, f)
                link = _Link(child.get("name") or "link", pose)
                links.append((link, child, frames.add(link.name, pose, rel, f.where(child))))
            elif tag == "joint" and model is not None:
                pose, rel = self._pose(child, f)
                frames.add(child.get("name") or "", pose, rel or child.findtext("child", "").strip() or None,
                           f.where(child))
            elif tag == "frame":
                pose, rel = self._pose(child, f)
                frames.add(child.get("name") or "", pose, rel or child.get("attached_to") or None, f.where(child))
            elif tag == "population":
                self._population(child, f)
            elif tag == "actor":
                self.note("structure", "info", f"actor '{child.get('name')}' ignored (animated; not an obstacle "
                          "the reader can place)", f.where(child))
        self._check_unique([m.name for m, _ in nested], f"models in {label}", f.where(el))
        if model is not None:
            self._check_unique([link.name for link, _, _ in links], f"links in model '{model.name}'", f.where(el))
        for sub, entry in nested:
            sub.pose = frames.place(entry)
        for link, link_el, entry in links:
            link.pose = frames.place(entry)
            self._link(link, link_el, f, model, frames)
            model.links.append(link)
        return [m for m, _ in nested]

    def _model(self, el, f: _File, parent_static: bool, frames: _Frames, *, name: str | None = None,
               static: bool | None = None) -> _Model:
        """A ``<model>`` element and everything in it (its own pose is set by the parent scope)."""
        name = name or el.get("name") or "model"
        own_static = self._bool(el.find("static"), f, False) if static is None else static
        model = _Model(name, poses.IDENTITY, parent_static or own_static, f.where(el))
        model.models = self._scope(el, f, model, f"model '{name}'", model.static, frames)
        return model

    def _link(self, link: _Link, el, f: _File, model: _Model, frames: _Frames) -> None:
        collisions = _children(el, "collision")
        self._check_unique([c.get("name") or "" for c in collisions],
                           f"collisions in {model.name}/{link.name}", f.where(el))
        for c in collisions:
            name = c.get("name") or "collision"
            pose, rel = self._pose(c, f)
            if rel and rel != link.name:
                frame = frames.resolve(rel)
                if frame is None:
                    self.note("pose", "warning", f"collision {model.name}/{link.name}/{name} has relative_to="
                              f"'{rel}', no frame of that name; treated as relative to its link", f.where(c))
                else:
                    pose = poses.inverse(link.pose) @ frame @ pose
            label = f"{model.name}/{link.name}/{name}"
            geometry = c.find("geometry")
            if geometry is None:
                self.note("structure", "warning", f"collision {label} has no <geometry>; skipped", f.where(c),
                          "give it a <geometry> (box, cylinder, sphere or mesh)")
                continue
            shape = self._geometry(geometry, f, label)
            if shape is not None:
                link.collisions.append(_Collision(name, pose, shape))
        visuals = _children(el, "visual")
        if visuals and not collisions:
            heights = [self._visual_height(v) for v in visuals]
            tall = any(h is None or h >= 0.05 for h in heights)
            self.note("collision", "warning" if tall else "info",
                      f"link {model.name}/{link.name} has a <visual> but no <collision>: Gazebo lets the robot "
                      "drive through it and the LiDAR does not see it", f.where(el),
                      "add a <collision> with the same geometry as the visual" if tall else None)

    @staticmethod
    def _visual_height(visual) -> float | None:
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

    # -- includes ----------------------------------------------------------------------------------------------
    def _include(self, el, f: _File, parent_static: bool, frames: _Frames):
        """An ``<include>``: (model, pose in parent, relative_to) or None when it adds no geometry."""
        where = f.where(el)
        uri = (el.findtext("uri") or "").strip()
        for child in _children(el):
            if child.tag not in _INCLUDE_CHILDREN:
                self.note("structure", "info", f"<{child.tag}> inside <include> is not part of SDF; Gazebo "
                          "ignores it", f.where(child), "remove it, or change the included model itself")
        if not uri:
            self.note("include", "warning", "<include> without a <uri>; skipped", where,
                      "add <uri>model://NAME</uri>")
            return None
        name_override = (el.findtext("name") or "").strip() or None
        static_override = self._bool(el.find("static"), f, None)
        resolved = self.resolver.resolve(uri, f.dir, want_dir=True)
        stock = resolved.model_name if resolved.model_name in STOCK_MODELS else None
        if resolved.path is None:
            if stock == "ground_plane":
                self.note("include", "info", f"{uri}: Gazebo's stock ground plane, stood in for by a plane at "
                          "z = 0", where)
                return (_ground_plane(name_override or "ground_plane", where), *self._pose(el, f))
            if stock == "sun":
                return None
            if resolved.remote:
                self.note("include", "warning", f"{uri} is an online (Fuel) model; it is never downloaded, so its "
                          "geometry is missing", where,
                          "download it and put its folder on GAZEBO_MODEL_PATH, or pass --model-path DIR")
            else:
                self.note("include", "warning", f"cannot find included model {uri}: {resolved.reason}; its "
                          "geometry is missing (not counted as walls)", where, _uri_fix(uri, resolved))
            return None
        model = self._load_included(resolved, where, parent_static, name_override, static_override, frames)
        if model is None:
            return None
        if el.find("pose") is None:   # the include's pose replaces the model's own; without one, that stands
            return model, model.pose, None
        return (model, *self._pose(el, f))

    def _load_included(self, resolved: Resolved, where: str, parent_static: bool, name: str | None,
                       static: bool | None, frames: _Frames) -> _Model | None:
        path = resolved.path
        assert path is not None
        if path.is_dir():
            sdf_file, note = model_sdf_file(path)
            if note:
                self.note("include", "info", f"{resolved.uri}: {note}", where)
            if sdf_file is None:
                self.note("include", "warning", f"{resolved.uri} resolves to {path}, which has no SDF file",
                          where, "give the model folder a model.config and a model.sdf")
                return None
            path = sdf_file
        if path in self.include_stack or len(self.include_stack) >= _MAX_INCLUDE_DEPTH:
            why = ("includes itself (directly or through other models)" if path in self.include_stack else
                   f"is nested more than {_MAX_INCLUDE_DEPTH} includes deep")
            self.note("include", "error", f"{resolved.uri} {why}", where, "break the include cycle")
            return None
        try:
            root = _parse(path.read_bytes(), path)
        except (WorldFileError, OSError) as err:
            self.note("include", "error", f"included model {resolved.uri} cannot be read: {err}", where,
                      "fix the included file")
            return None
        inc = self._file(root, path)
        model_el = root if root.tag == "model" else root.find("model")
        if model_el is None and root.find("light") is not None:
            return None  # a light model (Gazebo's sun): nothing to collide with
        if model_el is None:
            kind = "a world, not a model" if root.find("world") is not None else "no <model>"
            self.note("include", "warning", f"{resolved.uri} ({path}) holds {kind}; nothing included", where,
                      "include a model folder (model.config + model.sdf)")
            return None
        self.include_stack.append(path)
        try:
            frames.scope = f"model '{name or model_el.get('name')}'"
            model = self._model(model_el, inc, parent_static, frames, name=name, static=static)
        finally:
            self.include_stack.pop()
        model.pose, _ = self._pose(model_el, inc)
        return model

    def _population(self, el, f: _File) -> None:
        inner = el.find("model")
        count = (el.findtext("model_count") or "?").strip()
        what = f"model '{inner.get('name')}'" if inner is not None else "a model"
        self.note("structure", "warning", f"<population> '{el.get('name')}' ({count} copies of {what}) is not "
                  "expanded: Gazebo scatters those models at run time, so they are not in the scene", f.where(el),
                  "place the copies as ordinary <model>s if the robot must avoid them")

    # -- geometry ----------------------------------------------------------------------------------------------
    def _geometry(self, geometry, f: _File, label: str) -> dict | None:
        """Shape keyword arguments for one ``<geometry>``; None (with a finding when it matters) when unusable."""
        kinds = _children(geometry)
        if not kinds:
            self.note("structure", "warning", f"collision {label} has an empty <geometry>; skipped",
                      f.where(geometry), "put a <box>, <cylinder>, <sphere> or <mesh> in it")
            return None
        g = kinds[0]
        where = f.where(g)
        if g.tag == "box":
            size = self._floats(g.findtext("size"), 3, (1.0, 1.0, 1.0), f, g, f"box size of {label}")
            if min(size) <= 0:
                return self._bad_size(f"box {label} has size {_fmt(size)}: every side must be positive", where)
            return {"kind": "box", "size": size}
        if g.tag == "cylinder":
            radius = self._floats(g.findtext("radius"), 1, (1.0,), f, g, f"cylinder radius of {label}")[0]
            length = self._floats(g.findtext("length"), 1, (1.0,), f, g, f"cylinder length of {label}")[0]
            if radius <= 0 or length <= 0:
                return self._bad_size(f"cylinder {label} has radius {radius:g} and length {length:g}: both must be "
                                      "positive", where)
            return {"kind": "cylinder", "radius": radius, "length": length}
        if g.tag == "sphere":
            radius = self._floats(g.findtext("radius"), 1, (1.0,), f, g, f"sphere radius of {label}")[0]
            if radius <= 0:
                return self._bad_size(f"sphere {label} has radius {radius:g}: it must be positive", where)
            return {"kind": "sphere", "radius": radius}
        if g.tag == "plane":
            normal = np.array(self._floats(g.findtext("normal"), 3, (0.0, 0.0, 1.0), f, g, f"normal of {label}"))
            norm = float(np.linalg.norm(normal))
            if norm == 0:
                return self._bad_size(f"plane {label} has a zero normal", where)
            return {"kind": "plane", "normal": tuple(float(v) for v in normal / norm)}
        if g.tag == "mesh":
            return self._mesh(g, f, label)
        if g.tag == "empty":
            return None
        self.note("geometry", "warning", f"collision {label} uses <{g.tag}> geometry, which the reader does not "
                  "support; skipped", where, "use box, cylinder, sphere or mesh geometry for obstacles")
        return None

    def _bad_size(self, message: str, where: str) -> None:
        self.note("sizes", "error", message + "; the shape is skipped", where,
                  "give the shape a real size (metres, greater than zero)")
        return None

    def _mesh(self, g, f: _File, label: str) -> dict | None:
        uri = (g.findtext("uri") or "").strip()
        if not uri:
            self.note("mesh", "warning", f"mesh of {label} has no <uri>; skipped", f.where(g),
                      "add <uri>model://MODEL/meshes/FILE</uri>")
            return None
        scale = self._floats(g.findtext("scale"), 3, (1.0, 1.0, 1.0), f, g, f"mesh scale of {label}")
        if min(scale) <= 0:
            return self._bad_size(f"mesh {label} has scale {_fmt(scale)}: every factor must be positive",
                                  f.where(g))
        if g.find("submesh") is not None:
            self.note("mesh", "info", f"mesh {label} names a <submesh>; the whole mesh is used", f.where(g))
        resolved = self.resolver.resolve(uri, f.dir, want_dir=False)
        if resolved.path is None:
            entry = self.missing_meshes.setdefault(uri, [resolved.reason, _uri_fix(uri, resolved), f.where(g), []])
            entry[3].append(label)
            return None
        try:
            vertices, faces = self.meshes.load(resolved.path, scale)
        except ValueError as err:
            self.note("mesh", "warning", f"mesh {resolved.path} of {label} {err}; skipped", f.where(g),
                      "re-export the mesh as .dae, .stl or .obj")
            return None
        return {"kind": "mesh", "vertices": vertices, "faces": faces}

    def _report_missing_meshes(self) -> None:
        for uri, (reason, fix, where, labels) in self.missing_meshes.items():
            shown = ", ".join(labels[:3]) + (f" and {len(labels) - 3} more" if len(labels) > 3 else "")
            self.note("mesh", "warning", f"mesh {uri} not found ({reason}); {len(labels)} collision"
                      f"{'s' if len(labels) > 1 else ''} skipped: {shown}", where, fix)

    # -- state -------------------------------------------------------------------------------------------------
    def _apply_state(self, state, models: list[_Model], f: _File) -> None:
        """Apply Gazebo's first ``<state>``: model and link poses there are world-frame and win."""
        moved: list[str] = []
        by_name = {m.name: m for m in models}
        for child in _children(state):
            if child.tag == "model":
                self._state_model(child, by_name, f, moved)
            elif child.tag in ("insertions", "deletions"):
                self.note("state", "warning", f"<state> has <{child.tag}>, which the reader does not apply",
                          f.where(child), "save the world again from Gazebo without them")
        if moved:
            shown = ", ".join(moved[:4]) + (f" and {len(moved) - 4} more" if len(moved) > 4 else "")
            self.note("state", "info", f"<state> moves {len(moved)} model{'s' if len(moved) > 1 else ''} away from "
                      f"{'their' if len(moved) > 1 else 'its'} <pose> ({shown}); Gazebo applies the first <state>, "
                      "so the reader places them there", f.where(state))

    def _state_model(self, el, models: dict[str, _Model], f: _File, moved: list[str] | None) -> None:
        """One state ``<model>`` (``moved`` collects how far top-level models move; None for nested ones)."""
        name = el.get("name") or ""
        model = models.get(name)
        if model is None:
            self.note("state", "info", f"<state> names model '{name}', which the world does not have; ignored",
                      f.where(el))
            return
        if el.find("pose") is not None:
            model.world, _ = self._pose(el, f)
            if moved is not None:
                shift = float(np.linalg.norm(model.world[:2, 3] - model.pose[:2, 3]))
                turn = abs(math.remainder(poses.yaw_of(model.world) - poses.yaw_of(model.pose), 2 * math.pi))
                turned = turn >= math.radians(2)
                if shift >= 0.05 or turned:
                    moved.append(f"'{name}' {shift:.2f} m" + (f", {math.degrees(turn):.0f}°" if turned else ""))
        scale = self._floats(el.findtext("scale"), 3, (1.0, 1.0, 1.0), f, el, f"state scale of '{name}'")
        if any(abs(s - 1.0) > 1e-9 for s in scale):
            self.note("state", "info", f"<state> scales model '{name}' by {_fmt(scale)}; the reader keeps its "
                      "unscaled geometry", f.where(el))
        links = {link.name: link for link in model.links}
        for link_el in _children(el, "link"):
            link = links.get(link_el.get("name") or "")
            if link is None:
                self.note("state", "info", f"<state> names link '{link_el.get('name')}' that model '{name}' does "
                          "not have; ignored", f.where(link_el))
            elif link_el.find("pose") is not None:
                link.world, _ = self._pose(link_el, f)
        nested = {m.name: m for m in model.models}
        for sub in _children(el, "model"):
            self._state_model(sub, nested, f, None)

    # -- placing shapes ----------------------------------------------------------------------------------------
    def _emit_all(self, models: list[_Model], scene: Scene) -> None:
        for model in models:
            scene.models.append(model.name)
            before = len(scene.shapes)
            self._emit(model, poses.IDENTITY, model.name, scene.shapes)
            if not model.static and len(scene.shapes) > before:
                self.note("static", "info", f"model '{model.name}' is not static; Gazebo would let the robot push it",
                          model.where, "add <static>1</static> to the model if it is meant to stay put")

    def _emit(self, model: _Model, parent: np.ndarray, label: str, out: list[Shape]) -> None:
        world = model.world if model.world is not None else parent @ model.pose
        for link in model.links:
            link_world = link.world if link.world is not None else world @ link.pose
            for c in link.collisions:
                t = link_world @ c.pose
                out.append(Shape(position=(float(t[0, 3]), float(t[1, 3]), float(t[2, 3])),
                                 orientation=poses.matrix_quat(t[:3, :3]), model=label, link=link.name,
                                 name=c.name, static=model.static, **c.shape))
        for sub in model.models:
            self._emit(sub, world, f"{label}::{sub.name}", out)

    # -- small parsers -----------------------------------------------------------------------------------------
    def _pose(self, owner, f: _File) -> tuple[np.ndarray, str | None]:
        """The ``<pose>`` child of ``owner`` as a matrix, and the frame it is relative to (None: the parent)."""
        el = owner.find("pose")
        if el is None:
            return poses.IDENTITY, None
        relative_to = (el.get("relative_to") or el.get("frame") or "").strip() or None
        quat = el.get("rotation_format", "euler_rpy") == "quat_xyzw"
        count = 7 if quat else 6
        values = self._floats(el.text, count, (0.0,) * count, f, el, "pose")
        if quat:
            return poses.transform(values[:3], poses.quat_matrix(*values[3:])), relative_to
        if (el.get("degrees") or "").strip().lower() in ("true", "1"):
            values = values[:3] + tuple(math.radians(v) for v in values[3:])
        return poses.pose_matrix(*values), relative_to

    def _floats(self, text, count: int, default: tuple, f: _File, el, what: str) -> tuple:
        if text is None or not text.strip():
            return default
        parts = text.split()
        try:
            values = tuple(float(p) for p in parts)
        except ValueError:
            values = ()
        if len(values) != count or not all(math.isfinite(v) for v in values):
            self.note("structure", "warning", f"{what} '{' '.join(parts)}' is not {count} number"
                      f"{'s' if count > 1 else ''}; used {_fmt(default)}", f.where(el),
                      f"write {count} plain numbers separated by spaces")
            return default
        return values

    def _bool(self, el, f: _File, default):
        if el is None:
            return default
        text = (el.text or "").strip().lower()
        if text in ("1", "true"):
            return True
        if text in ("0", "false"):
            return False
        self.note("structure", "warning", f"<{el.tag}> '{el.text}' is not a boolean; used {default}", f.where(el),
                  f"write <{el.tag}>1</{el.tag}> or <{el.tag}>0</{el.tag}>")
        return default

    def _check_unique(self, names: list[str], what: str, where: str) -> None:
        seen, dupes = set(), []
        for name in names:
            if name in seen and name not in dupes:
                dupes.append(name)
            seen.add(name)
        if dupes:
            self.note("names", "warning", f"duplicate {what}: {', '.join(dupes)}; Gazebo refuses or renames them",
                      where, "give each one a unique name")


def _ground_plane(name: str, where: str) -> _Model:
    """A stand-in for Gazebo's stock ground_plane model: a static plane through z = 0."""
    link = _Link("link", poses.IDENTITY, [_Collision("collision", poses.IDENTITY,
                                                      {"kind": "plane", "normal": (0.0, 0.0, 1.0)})])
    return _Model(name, poses.IDENTITY, True, where, links=[link])


def _uri_fix(uri: str, resolved: Resolved) -> str:
    """How to make an unresolved model or mesh URI resolvable."""
    if uri.startswith(("model://", "package://")) and not uri.startswith("model:///"):
        return _MODEL_PATH_FIX
    if resolved.remote:
        return "download it and refer to it with a model:// URI"
    return ("the path points at a folder on the author's machine: copy the model folder somewhere on "
            "GAZEBO_MODEL_PATH (or --model-path DIR) and refer to it as model://NAME")


def _fmt(values) -> str:
    return " ".join(f"{v:g}" for v in values)
