"""Meshes within a budget: a file over MAX_MESH_TRIANGLES is skipped with a warning before it is parsed, a world
whose meshes add up past MAX_WORLD_TRIANGLES skips the ones past it, and a triangle soup (large triangles crossing
one another everywhere) is simulated as its convex hull, as its sections are taken."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from conftest import CliRunner

from worldgen.cli import main
from worldgen.sdf.meshes import MAX_MESH_TRIANGLES, MAX_WORLD_TRIANGLES, triangles_in_file
from worldgen.sdf.reader import read_world

ROOM = "".join(
    f"<model name='w{i}'><static>1</static><pose>{x} {y} 0.5 0 0 0</pose><link name='l'><collision name='c'>"
    f"<geometry><box><size>{sx} {sy} 1</size></box></geometry></collision></link></model>"
    for i, (x, y, sx, sy) in enumerate(((0, -1.5, 3.1, 0.1), (0, 1.5, 3.1, 0.1), (-1.5, 0, 0.1, 3.1),
                                        (1.5, 0, 0.1, 3.1))))


def soup(count: int, seed: int = 0) -> np.ndarray:
    """``count`` random triangles (count × 3 × 3) in a 4 × 4 × 1 m box beside the room."""
    rng = np.random.default_rng(seed)
    return rng.uniform((2, -2, 0), (6, 2, 1), size=(count, 3, 3))


def binary_stl(path: Path, triangles: np.ndarray) -> Path:
    record = np.zeros(len(triangles), dtype=[("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")])
    record["v"] = triangles
    path.write_bytes(b"\0" * 80 + np.uint32(len(triangles)).tobytes() + record.tobytes())
    return path


def world(tmp_path: Path, meshes) -> Path:
    models = "".join(f"<model name='m{i}'><static>1</static><pose>{5 * i} 0 0 0 0 0</pose><link name='l'>"
                     f"<collision name='c'><geometry><mesh><uri>{m}</uri></mesh></geometry></collision></link>"
                     "</model>" for i, m in enumerate(meshes))
    path = tmp_path / "w.world"
    path.write_text(f"<sdf version='1.6'><world name='w'>{ROOM}{models}</world></sdf>\n")
    return path


def warnings(path: Path) -> list:
    return [f.message for f in read_world(path).findings if f.check == "mesh"]


def test_a_mesh_over_the_budget_is_skipped_before_it_is_parsed(tmp_path):
    binary_stl(tmp_path / "big.stl", soup(MAX_MESH_TRIANGLES + 1))
    obj = tmp_path / "big.obj"   # faces counted from the text: far more than the vertices would need
    obj.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\n" + "f 1 2 3\n" * (MAX_MESH_TRIANGLES + 1))
    assert triangles_in_file(tmp_path / "big.stl") == triangles_in_file(obj) == MAX_MESH_TRIANGLES + 1
    said = warnings(world(tmp_path, ["big.stl", "big.obj"]))
    assert len(said) == 2
    assert all(f"holds {MAX_MESH_TRIANGLES + 1:,} triangles, more than the {MAX_MESH_TRIANGLES:,}" in m for m in said)
    done = CliRunner().invoke(main, ["validate", "--skip-sim", str(tmp_path / "w.world")])
    assert done.exit_code == 0 and "decimate it to under" in done.output


def test_a_world_past_its_triangle_budget_skips_the_meshes_past_it(tmp_path):
    each = MAX_WORLD_TRIANGLES // 3 + 1
    names = []
    for i in range(3):
        binary_stl(tmp_path / f"part{i}.stl", soup(each, seed=i))
        names.append(f"part{i}.stl")
    scene = read_world(world(tmp_path, names))
    assert sum(len(s.faces) for s in scene.shapes if s.kind == "mesh") == 2 * each
    (said,) = [f.message for f in scene.findings if f.check == "mesh"]
    assert "part2.stl" in said and f"past {MAX_WORLD_TRIANGLES:,} triangles" in said


def test_a_soup_is_simulated_as_its_convex_hull_and_a_surface_as_itself():
    pytest.importorskip("pybullet")
    import trimesh

    from worldgen.sim.scene_loader import soup_hull

    triangles = soup(20_000)
    hull = soup_hull(triangles.reshape(-1, 3), np.arange(60_000).reshape(-1, 3))
    assert hull is not None and len(hull) < 1000
    assert hull.min(axis=0) == pytest.approx(triangles.reshape(-1, 3).min(axis=0))
    sphere = trimesh.creation.icosphere(subdivisions=6)
    assert soup_hull(np.asarray(sphere.vertices), np.asarray(sphere.faces)) is None
    box = trimesh.creation.box((10, 0.1, 2))
    assert soup_hull(np.asarray(box.vertices), np.asarray(box.faces)) is None


def test_a_soup_within_the_budget_gets_a_verdict(tmp_path):
    binary_stl(tmp_path / "soup.stl", soup(60_000))
    done = CliRunner().invoke(main, ["validate", str(world(tmp_path, ["soup.stl"]))])
    assert done.exit_code in (0, 1), done.output
    assert "verdict" in done.output or "passed" in done.output
