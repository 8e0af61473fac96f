"""Every limit of the README's Limits section, tripped by a small bomb: one line and exit 2 (or, in validate, a failed
parse check), never a traceback; and the big inputs under the limits handled the way the README says. How fast each
is refused or handled is measured by benchmarks/bench_limits.py, not here."""

from __future__ import annotations

import os
import random
import re
import struct
import sys

import numpy as np
import pytest
from conftest import REPO, CliRunner

from worldgen.cli import main
from worldgen.core import inputs
from worldgen.geometry import disc_space, enclosure, growth, slices
from worldgen.pyread import values as pyvalues
from worldgen.sdf import includes
from worldgen.spec import maps, model, nodes

README = (REPO / "README.md").read_text(encoding="utf-8")


def one_line_refusal(result, *words):
    """Exit 2, exactly one line on stderr naming ``words``, no traceback."""
    assert result.exit_code == 2, result.output
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("worldgen: error: "), result.stderr
    assert "Traceback" not in result.output
    for word in words:
        assert word in lines[0], lines[0]
    return lines[0]


def box(name, x, y, sx=0.2, sy=0.2, h=1.0):
    return (f"<model name='{name}'><static>1</static><pose>{x} {y} {h / 2} 0 0 0</pose><link name='l'>"
            f"<collision name='c'><geometry><box><size>{sx} {sy} {h}</size></box></geometry></collision></link>"
            "</model>")


def world(body):
    return f"<sdf version='1.6'><world name='default'>{body}</world></sdf>\n"


def room(half=1.5):
    return "".join(box(f"w{i}", x, y, sx, sy) for i, (x, y, sx, sy) in enumerate(
        ((0, -half, 2 * half + 0.1, 0.1), (0, half, 2 * half + 0.1, 0.1), (-half, 0, 0.1, 2 * half + 0.1),
         (half, 0, 0.1, 2 * half + 0.1))))


# ------------------------------------------------------------------------------------------------ the README

@pytest.mark.parametrize("number", [
    f"{inputs.MAX_INPUT_BYTES // 2 ** 20} MiB", f"{inputs.MAX_SPEC_BYTES // 2 ** 20} MiB", f"{nodes.MAX_DEPTH} levels",
    f"{nodes.MAX_VALUES:,}".replace(",", " "), f"{includes.MAX_INCLUDES:,}".replace(",", " "),
    f"{includes.MAX_INCLUDE_DEPTH} deep", f"{maps.MAX_MAP_PIXELS:,}".replace(",", " "),
    f"{maps.MAX_MAP_PIECES:,}".replace(",", " "), f"under {maps.SPECK_PIXELS} pixels",
    f"{model.MAX_MARKINGS} lines and patches", f"{model.MAX_LINE_POINTS:,} points".replace(",", " "),
    f"{pyvalues.MAX_PYTHON_BYTES // 2 ** 20} MiB; {pyvalues.MAX_WORK:,} reading steps".replace(",", " "),
    f"nested {pyvalues.MAX_NESTING} deep", f"{pyvalues.MAX_CALL_DEPTH} nested and {pyvalues.MAX_CALLS:,} followed"
    .replace(",", " ")])
def test_readme_states_each_limit(number):
    section = README[README.index("## Limits"):README.index("## Design")]
    assert number in section


# ------------------------------------------------------------------------------------------- files and pipes

def test_a_fifo_or_device_is_refused_at_once(tmp_path):
    fifo = tmp_path / "pipe.world"
    os.mkfifo(fifo)
    one_line_refusal(CliRunner().invoke(main, ["validate", "--skip-sim", str(fifo)]), "not a regular file")
    spec = tmp_path / "zero.yaml"
    spec.symlink_to("/dev/zero")
    one_line_refusal(CliRunner().invoke(main, ["build", str(spec), "-o", str(tmp_path / "out")]),
                     "not a regular file")
    assert not (tmp_path / "out").exists()


def test_a_world_over_the_size_limit_is_not_read(tmp_path):
    big = tmp_path / "big.world"
    with open(big, "wb") as out:
        out.write(b"<sdf version='1.6'><world name='default'>")
        out.truncate(inputs.MAX_INPUT_BYTES + 1)   # sparse: costs no disk
    result = CliRunner().invoke(main, ["validate", "--skip-sim", "--format", "json", str(big)])
    assert result.exit_code == 1 and "larger than 64 MiB" in result.stdout
    one_line_refusal(CliRunner().invoke(main, ["preview", str(big), "-o", str(tmp_path / "p.png")]),
                     "larger than 64 MiB")
    assert not (tmp_path / "p.png").exists()


def test_a_spec_over_the_size_limit_is_refused(tmp_path):
    spec = tmp_path / "big.yaml"
    with open(spec, "wb") as out:
        out.write(b"name: big\n#")
        out.truncate(inputs.MAX_SPEC_BYTES + 1)
    one_line_refusal(CliRunner().invoke(main, ["build", str(spec), "-o", str(tmp_path / "out")]),
                     "larger than 4 MiB")


def test_read_capped_stops_at_the_limit(tmp_path):
    path = tmp_path / "f"
    path.write_bytes(b"x" * 101)
    assert inputs.read_capped(path, limit=101) == b"x" * 101
    with pytest.raises(inputs.WorldFileError, match="larger than 100 bytes"):
        inputs.read_capped(path, limit=100)


# ------------------------------------------------------------------------------------------------------ YAML

@pytest.mark.parametrize("text, words", [
    ("name: t\nwhen: 2001-13-45\n", ["t.yaml:2", "not a valid timestamp"]),
    ("name: !!int abc\n", ["t.yaml:1", "not a valid int"]),
    ("name: !!float .\n", ["t.yaml:1", "not a valid float"]),
    ("name: t\nx: !!binary 'a'\n", ["t.yaml:2", "base64"]),
    ("name: t\nx: !!timestamp 2001-02-30\n", ["t.yaml:2", "day is out of range"]),
    ("name: t\nwalls: " + "[" * 40000 + "\n", ["nested too deeply"]),
    ("name: t\nwalls: " + "[" * 150 + "]" * 150 + "\n", ["nested too deeply (more than 64 levels)"]),
])
def test_bad_yaml_is_one_line(tmp_path, text, words):
    spec = tmp_path / "t.yaml"
    spec.write_text(text)
    one_line_refusal(CliRunner().invoke(main, ["build", str(spec), "-o", str(tmp_path / "out")]), *words)
    assert not (tmp_path / "out").exists()


def bomb(merge: bool, fan: int = 9, levels: int = 7) -> str:
    lines = ["a: &a {x: 1, y: 2}" if merge else "a: &a [x, x, x, x, x, x, x, x, x]"]
    for i in range(1, levels):
        prev, name = chr(ord("a") + i - 1), chr(ord("a") + i)
        refs = ", ".join([f"*{prev}"] * fan)
        lines.append(f"{name}: &{name} {{<<: [{refs}]}}" if merge else f"{name}: &{name} [{refs}]")
    return "\n".join(lines) + "\nname: bomb\n"


@pytest.mark.parametrize("merge", [True, False])
def test_alias_and_merge_bombs_are_refused_fast(tmp_path, merge):
    spec = tmp_path / "bomb.yaml"
    spec.write_text(bomb(merge))
    assert len(spec.read_bytes()) < 600
    one_line_refusal(CliRunner().invoke(main, ["build", str(spec), "-o", str(tmp_path / "out")]),
                     f"more than {nodes.MAX_VALUES:,} values")


def test_aliases_that_stay_small_still_work(tmp_path):
    spec = tmp_path / "ok.yaml"
    spec.write_text("name: ok\nwalls: &w {height: 1.5}\nrooms:\n  - name: a\n    rect: {center: [0, 0], size: [4, 3]}\n"
                    "    walls: {<<: *w, thickness: 0.2}\n")
    result = CliRunner().invoke(main, ["build", str(spec), "-o", str(tmp_path / "out")])
    assert result.exit_code == 0, result.output


def test_a_bad_spec_beside_a_good_world_is_left_alone(tmp_path):
    out = tmp_path / "out"
    spec = REPO / "examples" / "enclosed_room.yaml"
    assert CliRunner().invoke(main, ["build", str(spec), "-o", str(out)]).exit_code == 0
    (built,) = out.glob("*.world")
    built.with_suffix(".yaml").write_text("name: x\nwhen: 2001-13-45\nx: !!int abc\n")
    result = CliRunner().invoke(main, ["validate", "--skip-sim", str(built)])
    assert result.exit_code == 0, result.output


@pytest.mark.parametrize("lines, words", [
    ("".join(f"  - {{points: [[0, {i}], [1, {i}]], color: Gazebo/Red}}\n" for i in range(model.MAX_MARKINGS + 1)),
     f"more than the {model.MAX_MARKINGS} worldgen builds"),
    ("  - {color: Gazebo/Red, points: [" + ", ".join(f"[{i / 100}, 0]" for i in range(model.MAX_LINE_POINTS + 1))
     + "]}\n", f"more than {model.MAX_LINE_POINTS:,} points in all"),
])
def test_floor_markings_are_bounded(tmp_path, lines, words):
    spec = tmp_path / "marks.yaml"
    spec.write_text(f"name: marks\nlines:\n{lines}")
    one_line_refusal(CliRunner().invoke(main, ["build", str(spec), "-o", str(tmp_path / "out")]), words, "README")
    assert not (tmp_path / "out").exists()


# -------------------------------------------------------------------------------------------------- includes

def fanout(tmp_path, fan, depth):
    models = tmp_path / "models"
    for level in range(depth + 1):
        folder = models / f"m{level}"
        folder.mkdir(parents=True)
        (folder / "model.config").write_text(f"<model><name>m{level}</name><sdf>model.sdf</sdf></model>")
        inner = "".join(f"<include><uri>model://m{level + 1}</uri><name>i{k}</name></include>"
                        for k in range(fan)) if level < depth else ""
        (folder / "model.sdf").write_text(f"<sdf version='1.6'><model name='m{level}'><static>1</static>"
                                          f"{inner}</model></sdf>")
    path = tmp_path / "fan.world"
    path.write_text(world("".join(f"<include><uri>model://m0</uri><name>t{k}</name></include>"
                                  for k in range(fan))))
    return path, models


@pytest.mark.parametrize("fan, depth, words", [
    (6, 4, f"includes more than {includes.MAX_INCLUDES} models"),        # 6 + 36 + … + 6^5 = 9330 includes
    (1, 30, f"nested more than {includes.MAX_INCLUDE_DEPTH} includes deep"),
])
def test_include_fanout_and_depth_are_refused(tmp_path, fan, depth, words):
    path, models = fanout(tmp_path, fan, depth)
    result = CliRunner().invoke(main, ["preview", str(path), "--model-path", str(models), "-o",
                                       str(tmp_path / "p.png")])
    one_line_refusal(result, words, "README")


def test_includes_under_the_limit_are_read(tmp_path):
    from worldgen.sdf.reader import read_world

    path, models = fanout(tmp_path, 3, 3)   # 3 + 9 + 27 + 81 includes
    assert len(read_world(path, model_paths=[models]).models) == 3


# ---------------------------------------------------------------------------------------------------- meshes

def stl(path, triangles):
    with open(path, "wb") as out:
        out.write(b"\0" * 80 + struct.pack("<I", len(triangles)))
        for tri in triangles:
            out.write(struct.pack("<12fH", 0, 0, 0, *[c for v in tri for c in v], 0))


def test_a_triangle_soup_is_taken_as_its_hull_with_a_warning(tmp_path):
    rng = random.Random(3)
    stl(tmp_path / "soup.stl", [[(rng.uniform(2, 4), rng.uniform(-1, 1), rng.uniform(0, 1)) for _ in range(3)]
                                for _ in range(4000)])
    mesh = ("<model name='soup'><static>1</static><link name='l'><collision name='c'><geometry><mesh>"
            "<uri>soup.stl</uri></mesh></geometry></collision></link></model>")
    path = tmp_path / "soup.world"
    path.write_text(world(room() + mesh))
    result = CliRunner().invoke(main, ["validate", "--skip-sim", "--spawn", "3,0", "--format", "json", str(path)])
    assert "triangle soup" in result.stdout and "convex hull" in result.stdout
    assert '"spawn_inside": "soup/l/c"' in result.stdout   # the hull is solid: (3, 0) lies inside it


def test_a_closed_mesh_is_cut_exactly():
    from worldgen.geometry.mesh_section import tangled

    ring = np.array([[[np.cos(a), np.sin(a)], [np.cos(b), np.sin(b)]]
                     for a, b in zip(np.linspace(0, 6.28, 3000), np.linspace(0, 6.28, 3000)[1:])])
    assert tangled(ring) is None
    rng = np.random.default_rng(1)
    assert "triangle soup" in tangled(rng.uniform(0, 1, (800, 2, 2)))


# ------------------------------------------------------------------------------------------ many shapes

def test_many_boxes_give_the_same_enclosure_as_the_exact_path(monkeypatch):
    """Past 200 shapes the footprints are grown part by part and boxes sliced as rectangles: the verdict, the
    gaps and their widths are those of GEOS's own union and buffer (used as they are for fewer shapes)."""
    from worldgen.sdf.reader import read_world_text

    rng = random.Random(5)
    clutter = "".join(box(f"b{i}", round(rng.uniform(-1.2, 1.2), 3), round(rng.uniform(-1.2, 1.2), 3), 0.05, 0.05)
                      for i in range(40))
    walls = room().replace("<pose>1.5 0 ", "<pose>1.5 0.9 ").replace("0.1 3.1 1.0</size>", "0.1 1.2 1.0</size>", 1)
    scene = read_world_text(world(walls + clutter))
    exact = enclosure.enclosure(scene, (-1.3, -1.3), 0.2)
    monkeypatch.setattr(growth, "SMALL", 3)
    monkeypatch.setattr(disc_space, "SMALL", 3)   # as disc_space imported it
    monkeypatch.setattr(slices, "FAST_BOXES", 3)
    fast = enclosure.enclosure(scene, (-1.3, -1.3), 0.2)
    assert fast.enclosed is exact.enclosed is False
    assert len(fast.gaps) == len(exact.gaps) >= 1
    for a, b in zip(fast.gaps, exact.gaps):
        assert a.width == pytest.approx(b.width, abs=0.005)
        assert a.centre == pytest.approx(b.centre, abs=0.01)


def test_ten_thousand_boxes_are_checked_in_seconds(tmp_path):
    body = "".join(box(f"b{i}", 1 + (i % 100) * 0.5, 1 + (i // 100) * 0.5) for i in range(10000))
    path = tmp_path / "grid.world"
    path.write_text(world(body))
    result = CliRunner().invoke(main, ["validate", "--skip-sim", "--spawn", "-1,-1", str(path)])
    assert result.exit_code == 1 and "the walls do not surround the spawn" in result.stdout


def test_unite_equals_union_all():
    import shapely

    rng = np.random.default_rng(2)
    boxes = [shapely.box(x, y, x + 0.3, y + 0.3) for x, y in rng.uniform(0, 10, (400, 2))]
    assert growth.unite(boxes).symmetric_difference(shapely.union_all(boxes)).area < 1e-9
    grown = growth.grown(shapely.union_all(boxes), 0.4, 8)
    assert grown.symmetric_difference(shapely.union_all(boxes).buffer(0.4, quad_segs=8)).area < 1e-6


# ------------------------------------------------------------------------------------------------------ maps

def map_yaml(tmp_path, pixels):
    from PIL import Image

    Image.fromarray(np.where(pixels, 0, 254).astype(np.uint8), mode="L").save(tmp_path / "m.pgm")
    path = tmp_path / "m.yaml"
    path.write_text("image: m.pgm\nresolution: 0.05\norigin: [0.0, 0.0, 0.0]\n")
    return path


def test_a_speckled_map_loses_its_specks_past_the_wall_limit(tmp_path, monkeypatch):
    rng = np.random.default_rng(4)
    pixels = rng.random((200, 200)) < 0.02
    pixels[0:2, :] = pixels[:, 0:2] = pixels[-2:, :] = pixels[:, -2:] = True
    path = map_yaml(tmp_path, pixels)
    monkeypatch.setattr(maps, "MAX_MAP_PIECES", 300)
    result = CliRunner().invoke(main, ["build", str(path), "-o", str(tmp_path / "out")])
    assert result.exit_code == 0, result.output
    (built,) = (tmp_path / "out").glob("*.world")
    assert built.read_text().count("<collision") < 40   # the walls and the specks touching them, of ~800


def test_a_map_still_too_busy_is_refused(tmp_path, monkeypatch):
    rng = np.random.default_rng(5)
    path = map_yaml(tmp_path, rng.random((200, 200)) < 0.3)
    monkeypatch.setattr(maps, "MAX_MAP_PIECES", 300)
    one_line_refusal(CliRunner().invoke(main, ["build", str(path), "-o", str(tmp_path / "out")]),
                     "walls and posts even without its specks")  # noqa
    assert not (tmp_path / "out").exists()


def test_a_huge_map_is_refused_before_it_is_decoded(tmp_path):
    (tmp_path / "m.pgm").write_bytes(b"P5\n9000 9000\n255\n" + b"\0" * 1000)   # the header says 81 Mpixel
    path = tmp_path / "m.yaml"
    path.write_text("image: m.pgm\nresolution: 0.05\norigin: [0.0, 0.0, 0.0]\n")
    line = one_line_refusal(CliRunner().invoke(main, ["build", str(path), "-o", str(tmp_path / "out")]),
                            "9000 × 9000 pixels")
    assert re.search(r"m\.yaml:1:", line)


def test_without_specks_keeps_blobs_of_five():
    grid = np.zeros((8, 8), dtype=bool)
    grid[1, 1:5] = True            # 4: a speck
    grid[5, 1:4] = grid[6, 4] = grid[7, 5] = True   # 5, diagonally joined: kept
    kept, blobs = maps.without_specks(grid)
    assert not kept[1].any() and kept[5:].sum() == 5 and blobs == 1


@pytest.mark.skipif(sys.platform != "linux", reason="FIFOs and /dev/zero as Linux has them")
def test_dev_zero_as_a_world_is_refused():
    one_line_refusal(CliRunner().invoke(main, ["validate", "--skip-sim", "/dev/zero"]), "not a regular file")


def test_a_launch_include_fanout_is_refused(tmp_path):
    for level in range(6):
        inner = "".join(f"<include file='{tmp_path}/l{level + 1}.launch'/>" for _ in range(5)) if level < 5 else ""
        (tmp_path / f"l{level}.launch").write_text(f"<launch>{inner}</launch>")
    result = CliRunner().invoke(main, ["validate", "--skip-sim", str(tmp_path / "l0.launch")])
    assert result.exit_code == 1 and "more than 1000 launch files" in result.stdout


def test_past_many_shapes_the_gap_search_lists_one_way_out(monkeypatch):
    from worldgen.sdf.reader import read_world_text

    walls = room().replace("<pose>1.5 0 ", "<pose>1.5 0.9 ").replace("0.1 3.1 1.0</size>", "0.1 1.2 1.0</size>", 1)
    posts = "".join(box(f"p{i}", -1.2 + 0.3 * i, -1.2, 0.05, 0.05) for i in range(6))
    scene = read_world_text(world(walls + posts))
    monkeypatch.setattr(enclosure, "MANY_SHAPES", 5)
    found = enclosure.enclosure(scene, (0.0, 0.0), 0.2)
    assert len(found.gaps) == 1 and found.more
    assert any("more than 5: only the widest way out" in n for n in found.notes)


def test_a_grid_of_lone_cells_is_refused(tmp_path):
    from worldgen.spec import grid

    path = tmp_path / "checker.txt"
    path.write_text("\n".join("#." * 170 if r % 2 == 0 else ".#" * 170 for r in range(340)) + "\n")  # 57 800 posts
    assert grid.MAX_PIECES == 50_000
    one_line_refusal(CliRunner().invoke(main, ["build", str(path), "-o", str(tmp_path / "out")]),
                     "57,800 posts (lone # cells) at least, more than the 50,000")
    assert not (tmp_path / "out").exists()


def test_a_closed_way_out_reaches_a_point_as_the_whole_space_does():
    """Past 200 shapes, whether a point is still reached at radius 0 once a way out is closed comes from the free
    space without the plug, cut by it with only the holes that can matter kept: the same answer as the space
    computed whole, for a point in the closed room, outside it, in a closed box beside it, in the plug itself, and
    beside posts touching at a corner."""
    import shapely

    walls = [shapely.box(-3, -3, 3, -2.9), shapely.box(-3, 2.9, 3, 3), shapely.box(-3, -3, -2.9, 3),
             shapely.box(2.9, -3, 3, -0.5), shapely.box(2.9, 0.5, 3, 3)]
    posts = [shapely.box(x, y, x + 0.1, y + 0.1) for x in np.arange(-2.5, 2.5, 0.3) for y in np.arange(-2.5, 2.5, 0.3)]
    box_room = [shapely.box(5, 5, 7, 5.1), shapely.box(5, 6.9, 7, 7), shapely.box(5, 5, 5.1, 7),
                shapely.box(6.9, 5, 7, 7)]
    corners = [shapely.box(3.5, -0.3, 3.6, -0.2), shapely.box(3.6, -0.2, 3.7, -0.1), shapely.box(3.5, -0.1, 3.6, 0)]
    prints = [slices.Footprint(f"s{i}", g) for i, g in enumerate(walls + posts + box_room + corners)]
    assert len(prints) > disc_space.SMALL
    obstacles = disc_space.obstacle_union(prints)
    frame = shapely.box(-10, -10, 10, 10)
    space = disc_space.Space(obstacles, frame)
    plug = shapely.LineString([(2.95, -0.5), (2.95, 0.5)]).buffer(0.001, quad_segs=1)
    plugged = space.plugged(plug)
    parts, outside = disc_space._parts_and_outside(frame.difference(plugged.obstacles), frame)
    for point in [(-2.3, -2.3), (0.05, 0.05), (8.0, 8.0), (6.0, 6.0), (2.95, 0.0), (3.6, -0.15), (3.05, 0.0)]:
        exact = outside.distance(shapely.Point(point)) > 1e-9
        assert plugged.cut_off(point, 0.0) is exact, point
    assert [plugged.cut_off(p, 0.0) for p in [(-2.3, -2.3), (8.0, 8.0), (6.0, 6.0)]] == [True, False, True]
