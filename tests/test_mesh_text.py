"""Mesh files whose text is not UTF-8 still load; a mesh that cannot be read is a warning naming the file."""

from __future__ import annotations

import struct

import numpy as np
import pytest

from worldgen.sdf.meshes import MeshCache
from worldgen.sdf.reader import read_world

# A wall 4 m long, 0.2 m thick, 2 m high, centred on the origin: 8 corners, 12 triangles.
CORNERS = [(x, y, z) for x in (-2.0, 2.0) for y in (-0.1, 0.1) for z in (0.0, 2.0)]
FACES = [(1, 2, 4), (1, 4, 3), (5, 7, 8), (5, 8, 6), (1, 5, 6), (1, 6, 2),
         (3, 4, 8), (3, 8, 7), (1, 3, 7), (1, 7, 5), (2, 6, 8), (2, 8, 4)]


def obj_bytes(comment: bytes) -> bytes:
    lines = [b"# " + comment] + [b"v %g %g %g" % c for c in CORNERS] + [b"f %d %d %d" % f for f in FACES]
    return b"\n".join(lines) + b"\n"


def stl_bytes(header: bytes) -> bytes:
    v = np.array(CORNERS)
    body = b"".join(struct.pack("<12fH", 0, 0, 0, *v[a - 1], *v[b - 1], *v[c - 1], 0) for a, b, c in FACES)
    return header.ljust(80, b"\xff") + struct.pack("<I", len(FACES)) + body


def mesh_world(uri: str) -> str:
    return ("<?xml version='1.0'?><sdf version='1.6'><world name='w'><model name='wall'><static>1</static>"
            f"<link name='l'><collision name='c'><geometry><mesh><uri>{uri}</uri></mesh></geometry></collision>"
            "</link></model></world></sdf>")


def read_world_text_file(folder, uri: str):
    world = folder / "w.world"
    world.write_text(mesh_world(uri))
    return read_world(world)


@pytest.mark.parametrize("name, data", [
    ("latin1.obj", obj_bytes("Mauer für den Raum, 20 °C, café".encode("latin-1"))),
    ("cp1252.obj", obj_bytes("“quoted” – dash".encode("cp1252"))),
    ("header.stl", stl_bytes(b"\xe9\xe8\xff\xfe exported by a tool with a binary header")),
])
def test_mesh_text_in_any_encoding_loads_and_the_wall_is_there(tmp_path, name, data):
    path = tmp_path / name
    path.write_bytes(data)
    with pytest.raises(UnicodeDecodeError):
        data.decode("utf-8")
    vertices, faces = MeshCache().load(path, (1.0, 1.0, 1.0))
    assert faces.shape == (12, 3)
    scene = read_world_text_file(tmp_path, str(path))
    (wall,) = scene.shapes
    assert wall.kind == "mesh" and np.ptp(wall.vertices, axis=0) == pytest.approx([4.0, 0.2, 2.0])
    assert [f for f in scene.findings if f.check == "mesh"] == []


@pytest.mark.parametrize("name, data", [
    ("junk.stl", b"\x00\x01\x02 not a mesh at all " * 7),
    ("junk.obj", b"\xff\xfe\x00garbage\n" * 20),
    ("empty.dae", b""),
    ("faces_out_of_range.obj", b"v 0 0 0\nv 1 0 0\nf 1 2 99\n"),
])
def test_a_mesh_that_cannot_be_read_is_a_warning_naming_the_file(tmp_path, name, data):
    path = tmp_path / name
    path.write_bytes(data)
    scene = read_world_text_file(tmp_path, str(path))
    assert scene.shapes == [] or all(s.kind == "mesh" for s in scene.shapes)
    warnings = [f for f in scene.findings if f.check == "mesh" and f.severity == "warning"]
    if scene.shapes:   # trimesh made something of it: then it must be usable triangles
        assert all(len(s.faces) for s in scene.shapes)
    else:
        assert len(warnings) == 1 and str(path) in warnings[0].message, scene.findings
