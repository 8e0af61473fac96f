"""One ``<geometry>`` becomes Shape keyword arguments: box, cylinder, sphere, plane, or a mesh loaded with trimesh
(through the read's mesh cache). Meshes that cannot be found are reported once per URI, at the end of the read."""

from __future__ import annotations

from typing import Optional

import numpy as np

from ..core.numbers import format_numbers
from .context import ReadContext, SdfFile
from .meshes import DECIMATE, MAX_WORLD_TRIANGLES
from .resolve import uri_fix
from .values import children, read_floats


def read_geometry(ctx: ReadContext, geometry, f: SdfFile, label: str, visual: bool = False) -> Optional[dict]:
    """Shape keyword arguments for one ``<geometry>``; None (with a finding when it matters) when unusable.

    A ``visual``'s geometry is read the same way, quietly: what is wrong with it is not in the robot's way, so
    only a mesh that cannot be found or loaded is said (once per URI, as an info, by :func:`report_missing_meshes`);
    a plane keeps its ``<size>`` (x, y, 0)."""
    if visual:
        ctx = _Quiet(ctx)
    kinds = children(geometry)
    if not kinds:
        ctx.note("structure", "warning", f"collision {label} has an empty <geometry>; skipped",
                 f.where(geometry), "put a <box>, <cylinder>, <sphere> or <mesh> in it")
        return None
    g = kinds[0]
    where = f.where(g)
    if g.tag == "box":
        size = read_floats(ctx, g.findtext("size"), 3, (1.0, 1.0, 1.0), f, g, f"box size of {label}")
        if min(size) <= 0 or _too_large(size):
            return _bad_size(ctx, f"box {label} has size {format_numbers(size, None)}: every side must be positive "
                             f"and under {MAX_SIZE:g} m", where)
        return {"kind": "box", "size": size}
    if g.tag == "cylinder":
        radius = read_floats(ctx, g.findtext("radius"), 1, (1.0,), f, g, f"cylinder radius of {label}")[0]
        length = read_floats(ctx, g.findtext("length"), 1, (1.0,), f, g, f"cylinder length of {label}")[0]
        if radius <= 0 or length <= 0 or _too_large((radius, length)):
            return _bad_size(ctx, f"cylinder {label} has radius {radius:g} and length {length:g}: both must be "
                             f"positive and under {MAX_SIZE:g} m", where)
        return {"kind": "cylinder", "radius": radius, "length": length}
    if g.tag == "sphere":
        radius = read_floats(ctx, g.findtext("radius"), 1, (1.0,), f, g, f"sphere radius of {label}")[0]
        if radius <= 0 or _too_large((radius,)):
            return _bad_size(ctx, f"sphere {label} has radius {radius:g}: it must be positive and under "
                             f"{MAX_SIZE:g} m", where)
        return {"kind": "sphere", "radius": radius}
    if g.tag == "plane":
        normal = np.array(read_floats(ctx, g.findtext("normal"), 3, (0.0, 0.0, 1.0), f, g, f"normal of {label}"))
        norm = float(np.linalg.norm(normal))
        if norm == 0:
            return _bad_size(ctx, f"plane {label} has a zero normal", where)
        plane = {"kind": "plane", "normal": tuple(float(v) for v in normal / norm)}
        if visual and g.findtext("size") is not None:
            sx, sy = read_floats(ctx, g.findtext("size"), 2, (0.0, 0.0), f, g, f"size of {label}")
            if sx > 0 and sy > 0 and not _too_large((sx, sy)):
                plane["size"] = (sx, sy, 0.0)
        return plane
    if g.tag == "mesh":
        return read_mesh(ctx, g, f, label)
    if g.tag == "empty":
        return None
    ctx.note("geometry", "warning", f"collision {label} uses <{g.tag}> geometry, which the reader does not "
             "support; skipped", where, "use box, cylinder, sphere or mesh geometry for obstacles")
    return None


MAX_SIZE = 1e6   # m: a shape larger than this (1000 km) is a typo, and its arithmetic overflows


def _too_large(values) -> bool:
    return any(abs(v) > MAX_SIZE for v in values)


def _bad_size(ctx: ReadContext, message: str, where: str) -> None:
    ctx.note("sizes", "error", message + "; the shape is skipped", where,
             "give the shape a real size (metres, greater than zero)")
    return None


def read_mesh(ctx: ReadContext, g, f: SdfFile, label: str) -> Optional[dict]:
    """A ``<mesh>``: its vertices and faces, scaled; None when it has no URI, cannot be found or loaded."""
    uri = (g.findtext("uri") or "").strip()
    if not uri:
        ctx.note("mesh", "warning", f"mesh of {label} has no <uri>; skipped", f.where(g),
                 "add <uri>model://MODEL/meshes/FILE</uri>")
        return None
    scale = read_floats(ctx, g.findtext("scale"), 3, (1.0, 1.0, 1.0), f, g, f"mesh scale of {label}")
    if min(scale) <= 0 or _too_large(scale):
        return _bad_size(ctx, f"mesh {label} has scale {format_numbers(scale, None)}: every factor must be positive "
                         f"and under {MAX_SIZE:g}", f.where(g))
    if g.find("submesh") is not None:
        ctx.note("mesh", "info", f"mesh {label} names a <submesh>; the whole mesh is used", f.where(g))
    resolved = ctx.resolver.resolve(uri, f.dir, want_dir=False)
    quiet = isinstance(ctx, _Quiet)
    if resolved.path is None:
        missing = ctx.missing_visual_meshes if quiet else ctx.missing_meshes
        entry = missing.setdefault(uri, [f"not found ({resolved.reason})", uri_fix(uri, resolved), f.where(g), []])
        entry[3].append(label)
        return None
    try:
        vertices, faces = ctx.meshes.load(resolved.path, scale)
        if ctx.mesh_triangles + len(faces) > MAX_WORLD_TRIANGLES:
            raise ValueError(f"would bring the world's meshes past {MAX_WORLD_TRIANGLES:,} triangles, the most "
                             "worldgen reads in one world (see Limits in the README)")
    except ValueError as err:
        fix = DECIMATE if "triangles" in str(err) else "re-export the mesh as .dae, .stl or .obj"
        if quiet:
            entry = ctx.missing_visual_meshes.setdefault(uri, [str(err), fix, f.where(g), []])
            entry[3].append(label)
        elif uri not in ctx.unloadable_meshes:
            ctx.unloadable_meshes.add(uri)
            ctx.note("mesh", "warning", f"mesh {resolved.path} of {label} {err}; skipped", f.where(g), fix)
        return None
    ctx.mesh_triangles += len(faces)
    return {"kind": "mesh", "vertices": vertices, "faces": faces}


def report_missing_meshes(ctx: ReadContext) -> None:
    """One warning per mesh URI that could not be found, naming the collisions skipped for it; one info per
    mesh URI only visuals use that could not be found or loaded (what a camera will not see)."""
    for uri, (reason, fix, where, labels) in ctx.missing_meshes.items():
        ctx.note("mesh", "warning", f"mesh {uri} {reason}; {_count(labels, 'collision')} skipped: "
                 f"{_shown(labels)}", where, fix)
    for uri, (reason, fix, where, labels) in ctx.missing_visual_meshes.items():
        if uri not in ctx.missing_meshes and uri not in ctx.unloadable_meshes:   # not said already
            ctx.note("mesh", "info", f"mesh {uri} {reason}; {_count(labels, 'visual')} skipped (a camera will "
                     f"not see {'them' if len(labels) > 1 else 'it'}): {_shown(labels)}", where, fix)


def _count(labels: list, what: str) -> str:
    return f"{len(labels)} {what}{'s' if len(labels) > 1 else ''}"


def _shown(labels: list) -> str:
    return ", ".join(labels[:3]) + (f" and {len(labels) - 3} more" if len(labels) > 3 else "")


class _Quiet:
    """The read's context for a visual's geometry: the same caches and resolver, but its notes are dropped (a
    visual's odd numbers are no obstacle; the collision beside it is checked and reported)."""

    def __init__(self, ctx: ReadContext):
        self._ctx = ctx

    def note(self, *args, **kwargs) -> None:
        pass

    def __getattr__(self, name):
        return getattr(self._ctx, name)
