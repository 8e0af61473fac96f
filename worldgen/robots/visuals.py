"""What a robot looks like to another robot's camera: each link's ``<visual>`` shapes from its URDF, placed in the
link's frame, with a colour.

Boxes, cylinders and spheres are taken as they are; a mesh is read with trimesh (its ``scale`` applied) when its file
can be found (``package://`` through :func:`.description.absolute_mesh_paths`, or a path relative to the
description), and left out otherwise. The colour is the visual's URDF material (inline, or named and defined at
the top of the file); a link whose ``<gazebo>`` block names a black Gazebo material is drawn black; anything else is
dark grey — what a TurtleBot3 looks like, near enough, to a camera that has to find it.
"""

from __future__ import annotations

import os
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np

from ..core import poses
from ..core.numbers import floats
from ..core.scene import Shape
from ..core.errors import WorldgenError
from .description import absolute_mesh_paths

DARK_GREY = (0.25, 0.25, 0.25, 1.0)
BLACK = (0.05, 0.05, 0.05, 1.0)
BLACK_MATERIALS = ("Gazebo/Black", "Gazebo/FlatBlack")


def link_visuals(urdf: str, source: str | Path | None = None) -> list[Shape]:
    """Every visual shape of the URDF text ``urdf``: a :class:`~worldgen.core.scene.Shape` whose ``link`` names
    its link and whose pose is in that link's frame. ``source`` (the description's file) finds relative meshes."""
    try:
        root = ET.fromstring(urdf)
    except ET.ParseError:
        return []
    named = {m.get("name"): _rgba(m) for m in root.findall("material") if m.get("name")}
    black = {g.get("reference") for g in root.findall("gazebo")
             if (g.findtext("material") or "").strip() in BLACK_MATERIALS}
    shapes = []
    for link in root.findall("link"):
        name = link.get("name", "")
        for visual in link.findall("visual"):
            geometry = visual.find("geometry")
            shape = _shape(geometry[0], source) if geometry is not None and len(geometry) else None
            if shape is None:
                continue
            xyz, rpy = _origin(visual)
            shape.position = xyz
            shape.orientation = poses.matrix_quat(poses.rpy_matrix(*rpy))
            shape.link, shape.name = name, visual.get("name", "")
            shape.color = BLACK if name in black else (_color(visual.find("material"), named) or DARK_GREY)
            shapes.append(shape)
    return shapes


def _origin(elem: ET.Element):
    origin = elem.find("origin")
    if origin is None:
        return (0.0, 0.0, 0.0), (0.0, 0.0, 0.0)
    try:
        return floats(origin.get("xyz"), 3), floats(origin.get("rpy"), 3)
    except ValueError:
        return (0.0, 0.0, 0.0), (0.0, 0.0, 0.0)


def _shape(geom: ET.Element, source) -> Shape | None:
    try:
        if geom.tag == "box":
            size = floats(geom.get("size"), 3)
            return Shape("box", (0.0, 0.0, 0.0), size=size) if all(v > 0 for v in size) else None
        if geom.tag == "cylinder":
            radius, length = float(geom.get("radius", 0)), float(geom.get("length", 0))
            ok = radius > 0 and length > 0
            return Shape("cylinder", (0.0, 0.0, 0.0), radius=radius, length=length) if ok else None
        if geom.tag == "sphere":
            radius = float(geom.get("radius", 0))
            return Shape("sphere", (0.0, 0.0, 0.0), radius=radius) if radius > 0 else None
        if geom.tag == "mesh":
            return _mesh(geom.get("filename", ""), floats(geom.get("scale"), 3, 1.0), source)
    except ValueError:
        return None
    return None


def _mesh(filename: str, scale, source) -> Shape | None:
    try:
        path = absolute_mesh_paths(filename, source)
    except WorldgenError:
        return None
    if path and not os.path.isabs(path) and source is not None:
        path = str(Path(source).parent / path)
    if not path or not os.path.isfile(path):
        return None
    try:
        import trimesh

        mesh = trimesh.load(path, force="mesh")
        vertices = np.asarray(mesh.vertices, float) * np.asarray(scale, float)
        faces = np.asarray(mesh.faces, int)
    except Exception:   # noqa: BLE001  (a mesh trimesh cannot read: the robot is drawn without it)
        return None
    return Shape("mesh", (0.0, 0.0, 0.0), vertices=vertices, faces=faces) if len(faces) else None


def _rgba(material: ET.Element | None):
    color = material.find("color") if material is not None else None
    if color is None:
        return None
    try:
        values = floats(color.get("rgba"), 4, 1.0)
    except ValueError:
        return None
    return tuple(min(1.0, max(0.0, v)) for v in values)


def _color(material: ET.Element | None, named: dict):
    if material is None:
        return None
    return _rgba(material) or named.get(material.get("name"))
