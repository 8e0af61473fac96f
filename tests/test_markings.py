"""Floor markings: a spec's ``lines:`` and ``patches:`` read with line-numbered errors, written as visual-only
pieces lying on the floor that cover the tape exactly, drawn by the preview in their colours, invisible to the
LiDAR and the enclosure check, and judged by what the Waffle Pi's camera will see of them."""

from __future__ import annotations

import io
import json
import math

import numpy as np
import pytest
from conftest import EXAMPLES, CliRunner
from lxml import etree
from matplotlib.image import imread

from worldgen.check.camera_view import MIN_PIXELS, apparent_pixels
from worldgen.cli import main
from worldgen.core.errors import SpecError
from worldgen.geometry.building import build_geometry
from worldgen.geometry.markings import floor_markings
from worldgen.view.preview import figure, picture, render
from worldgen.sdf.reader import read_world_text
from worldgen.sdf.writer import world_sdf
from worldgen.spec.load import parse_spec, starter_spec
from worldgen.spec.model import MAX_LINE_POINTS, MAX_MARKINGS, Material

ROOM = "name: t\nrooms:\n  - name: main\n    rect: {center: [0, 0], size: [4, 3]}\n"   # lines 1-4
LOOP = [[-1, -0.5], [1, -0.5], [1.2, 0], [1, 0.5], [-1, 0.5], [-1.4, 0.1]]   # corners of 90° and sharper


def spec_text(lines: str = "", patches: str = "", robot: str = "robot: {model: waffle_pi, at: [0, -1], yaw: 0}\n"):
    return ROOM + (f"lines:\n{lines}" if lines else "") + (f"patches:\n{patches}" if patches else "") + robot


# ------------------------------------------------------------------------------------------------- the spec

def test_lines_and_patches_in_numbers():
    spec = parse_spec(spec_text(
        "  - {name: track, points: " + json.dumps(LOOP) + ", closed: true, color: Gazebo/Yellow}\n"
        "  - {points: [[0, 0], [1, 0]], width: 0.02, color: [1, 0, 0]}\n",
        "  - {name: start, rect: {center: [0, -0.5], size: [0.3, 0.2], yaw: 0.5}, color: {rgba: [0, 1, 0, 0.5]}}\n"
        "  - {disc: {center: [1, 1], radius: 0.1}, color: {script: Gazebo/Blue}}\n"), "t.yaml")
    track, red = spec.lines
    assert (track.name, track.closed, track.width, track.color, track.line) == \
        ("track", True, 0.05, Material("Gazebo/Yellow"), 6)
    assert track.points == tuple(tuple(float(v) for v in p) for p in LOOP)
    assert (red.name, red.closed, red.width, red.color) == (None, False, 0.02, Material(None, (1.0, 0.0, 0.0, 1.0)))
    start, dot = spec.patches
    assert (start.shape, start.center, start.size, start.yaw, start.color.rgba, start.line) == \
        ("rect", (0.0, -0.5), (0.3, 0.2), 0.5, (0.0, 1.0, 0.0, 0.5), 9)
    assert (dot.shape, dot.radius, dot.color, dot.name) == ("disc", 0.1, Material("Gazebo/Blue"), None)


def test_a_loop_may_repeat_its_first_point():
    spec = parse_spec(spec_text("  - {points: [[0, 0], [1, 0], [1, 1], [0, 0]], closed: true, color: Gazebo/Red}\n"))
    assert spec.lines[0].points == ((0.0, 0.0), (1.0, 0.0), (1.0, 1.0))


def test_markings_alone_are_something_to_build():
    spec = parse_spec("name: floor\nlines:\n  - {points: [[0, 0], [1, 0]], color: Gazebo/Black}\n")
    assert spec.lines and not spec.rooms


BAD = [
    ("unknown-key", "  - {points: [[0, 0], [1, 0]], colour: Gazebo/Red}\n", "", 6,
     ["unknown key 'colour' in line_0; did you mean 'color'?"], "line_0 takes: name, points, width, color, closed"),
    ("no-color", "  - {points: [[0, 0], [1, 0]]}\n", "", 6, ["line_0 has no 'color'"], "color: Gazebo/Yellow"),
    ("no-points", "  - {name: a, color: Gazebo/Red}\n", "", 6, ["line_0 has no 'points'"], "points: [[0, 0]"),
    ("one-point", "  - {name: a, points: [[0, 0]], color: Gazebo/Red}\n", "", 6,
     ["line 'a' has 1 point; a line needs at least 2"], "list the points"),
    ("loop-of-two", "  - {name: a, points: [[0, 0], [1, 0]], closed: true, color: Gazebo/Red}\n", "", 6,
     ["line 'a' has 2 points; a closed line (a loop) needs at least 3"], "list the points"),
    ("zero-length", "  - name: a\n    color: Gazebo/Red\n    points:\n      - [0, 0]\n      - [1, 0]\n      - [1, 0]\n",
     "", 11, ["points 1 and 2 of line 'a' are at the same place (1, 0): a segment needs a length"], "remove point 2"),
    ("open-loop", "  - {name: a, points: [[0, 0], [1, 0], [1, 1], [0, 0]], color: Gazebo/Red}\n", "", 6,
     ["line 'a' ends where it starts, but it is not closed"], "closed: true"),
    ("thin", "  - {points: [[0, 0], [1, 0]], width: 0.0001, color: Gazebo/Red}\n", "", 6,
     ["width of line_0 is 0.0001 m: less than 1 mm"], "metres"),
    ("wide", "  - {points: [[0, 0], [1, 0]], width: 5, color: Gazebo/Red}\n", "", 6,
     ["width of line_0 is 5 m: a line is at most 1 m wide"], "patches: with a rect"),
    ("closed-text", "  - {points: [[0, 0], [1, 0]], closed: 'yes', color: Gazebo/Red}\n", "", 6,
     ["closed of line_0 must be true or false, not the text 'yes'"], "true or false"),
    ("bad-colour", "  - {points: [[0, 0], [1, 0]], color: Gazebo/Yelow}\n", "", 6,
     ["color of line_0 'Gazebo/Yelow' is not a Gazebo material; did you mean 'Gazebo/Yellow'?"], "Gazebo/Grey"),
    ("colour-number", "  - {points: [[0, 0], [1, 0]], color: 7}\n", "", 6,
     ["color of line_0 must be a Gazebo material name or an [r, g, b, a] colour"], "color: Gazebo/Wood"),
    ("colour-range", "  - {points: [[0, 0], [1, 0]], color: [255, 0, 0]}\n", "", 6,
     ["color of line_0 colour component 255 is outside 0–1"], "255 is 1"),
    ("far", "  - {points: [[0, 0], [5000, 0]], color: Gazebo/Red}\n", "", 6,
     ["x of point 1 of line_0 is 5000: farther than 1000 m from the origin"], "millimetres"),
    ("patch-no-shape", "", "  - {name: p, color: Gazebo/Red}\n", 6, ["patch 'p' needs exactly one of 'rect' or 'disc'"],
     "disc: {center"),
    ("patch-two-shapes", "", "  - {rect: {center: [0, 0], size: [1, 1]}, disc: {center: [0, 0], radius: 1}, "
     "color: Gazebo/Red}\n", 6, ["patch_0 needs exactly one of 'rect' or 'disc'"], "rect: {center"),
    ("patch-size", "", "  - {rect: {center: [0, 0], size: [1]}, color: Gazebo/Red}\n", 6,
     ["size of patch_0 must be [x size, y size] in metres, not a list of 1 number"], "size: [0.5, 0.3]"),
    ("patch-radius", "", "  - {disc: {center: [0, 0], radius: -1}, color: Gazebo/Red}\n", 6,
     ["radius of patch_0 must be more than 0, not -1"], "metres"),
    ("patch-yaw-degrees", "", "  - {rect: {center: [0, 0], size: [1, 1], yaw: 90}, color: Gazebo/Red}\n", 6,
     ["yaw of patch_0 is 90: angles are in radians"], "1.5708"),
    ("patch-no-color", "", "  - {disc: {center: [0, 0], radius: 1}}\n", 6, ["patch_0 has no 'color'"], "color:"),
    ("names-twice", "  - {name: a, points: [[0, 0], [1, 0]], color: Gazebo/Red}\n",
     "  - {name: a, disc: {center: [0, 0], radius: 1}, color: Gazebo/Red}\n", 8,
     ["patch name 'a' is already the name of the line on line 6"], "its own name"),
    ("default-name-taken", "  - {name: patch_0, points: [[0, 0], [1, 0]], color: Gazebo/Red}\n",
     "  - {disc: {center: [0, 0], radius: 1}, color: Gazebo/Red}\n", 8,
     ["patch_0 (the name an unnamed patch gets) is already the name of the line on line 6"],
     "its own name"),
    ("bad-name", "  - {name: my track, points: [[0, 0], [1, 0]], color: Gazebo/Red}\n", "", 6,
     ["line name 'my track' is not a valid name"], "my_track"),
    ("not-a-list", "  {points: [[0, 0], [1, 0]]}\n", "", 6, ["lines must be a list"], "'- '"),
]


@pytest.mark.parametrize("lines, patches, line, words, hint", [c[1:] for c in BAD], ids=[c[0] for c in BAD])
def test_bad_markings_name_the_file_line_and_fix(lines, patches, line, words, hint):
    with pytest.raises(SpecError) as caught:
        parse_spec(spec_text(lines, patches), "bad.yaml")
    err = caught.value
    assert (err.path, err.line) == ("bad.yaml", line), str(err)
    for word in words:
        assert word in err.message, err.message
    assert hint in (err.hint or ""), err.hint


def test_the_markings_model_name_is_taken():
    with pytest.raises(SpecError, match="'floor_markings' names the model") as caught:
        parse_spec(spec_text("  - {points: [[0, 0], [1, 0]], color: Gazebo/Red}\n") +
                   "obstacles:\n  - {name: floor_markings, shape: sphere, radius: 0.1, at: [1, 1]}\n", "o.yaml")
    assert caught.value.line == 9
    assert parse_spec(ROOM + "obstacles:\n  - {name: floor_markings, shape: sphere, radius: 0.1, at: [1, 1]}\n")


def test_every_list_of_markings_is_bounded(tmp_path):
    many = "".join(f"  - {{points: [[0, {i / 1000}], [1, {i / 1000}]], color: Gazebo/Red}}\n"
                   for i in range(MAX_MARKINGS + 1))
    with pytest.raises(SpecError, match=f"more than the {MAX_MARKINGS} worldgen builds") as caught:
        parse_spec(spec_text(many), "many.yaml")
    assert caught.value.line == 5 + MAX_MARKINGS + 1
    dense = [[i / 100, 0] for i in range(MAX_LINE_POINTS + 1)]
    with pytest.raises(SpecError, match=f"more than {MAX_LINE_POINTS:,} points in all"):
        parse_spec(spec_text(f"  - {{points: {json.dumps(dense)}, color: Gazebo/Red}}\n"))


# ------------------------------------------------------------------------------------------------ the world

def _loop_spec(width: float = 0.05):
    return parse_spec(spec_text(f"  - {{name: track, points: {json.dumps(LOOP)}, closed: true, width: {width}, "
                                "color: Gazebo/Yellow}\n"
                                "  - {name: tail, points: [[-1.5, -1], [0, -1.2], [0.3, -0.8]], color: [1, 0, 0]}\n",
                                "  - {name: start, rect: {center: [0, -0.5], size: [0.3, 0.2], yaw: 0.5}, "
                                "color: Gazebo/Green}\n"), "m.yaml")


def _pieces_union(scene, link: str):
    import shapely

    from worldgen.geometry.markings import footprint

    parts = []
    for v in scene.visuals:
        if v.model == "floor_markings" and v.link == link:
            if v.kind == "cylinder":   # an exact circle, not the outline's 32 sides
                parts.append(shapely.Point(v.position[:2]).buffer(v.radius, quad_segs=256))
            else:
                parts.append(footprint(v))
    return shapely.union_all(parts)


def test_a_line_is_covered_by_its_segments_and_joint_discs_without_a_gap():
    import shapely

    scene = read_world_text(world_sdf(build_geometry(_loop_spec())))
    loop = _pieces_union(scene, "track")
    ideal = shapely.LinearRing(LOOP).buffer(0.025, quad_segs=256, join_style="round")
    assert loop.geom_type == "Polygon" and len(loop.interiors) == 1   # one band round one hole: no gap anywhere
    perimeter = shapely.LinearRing(LOOP).length
    assert loop.symmetric_difference(ideal).area < 1e-6 * perimeter   # within 1 mm² per metre of tape
    tail = _pieces_union(scene, "tail")
    open_line = shapely.LineString([[-1.5, -1], [0, -1.2], [0.3, -0.8]])
    ideal_open = open_line.buffer(0.025, quad_segs=256, cap_style="flat", join_style="round")
    assert tail.geom_type == "Polygon" and tail.symmetric_difference(ideal_open).area < 1e-6 * open_line.length


def test_markings_are_visual_only_flat_on_the_floor_and_layered():
    text = world_sdf(build_geometry(_loop_spec()))
    root = etree.fromstring(text.encode())
    (model,) = root.findall("world/model[@name='floor_markings']")
    assert model.findtext("static") == "1" and model.find(".//collision") is None
    assert [link.get("name") for link in model.findall("link")] == ["start", "track", "tail"]
    track = model.find("link[@name='track']")
    assert len(track.findall("visual")) == 2 * len(LOOP)   # a segment and a joint disc per corner of the loop
    assert len(model.find("link[@name='tail']").findall("visual")) == 2 + 1   # an open line: inner joints only
    assert track.find("visual/material/script/name").text == "Gazebo/Yellow"
    assert model.find("link[@name='tail']/visual/material/diffuse").text == "1 0 0 1"
    scene = read_world_text(text)
    marks = {m.link: m for m in floor_markings(scene)}
    assert set(marks) == {"start", "track", "tail"} and marks["track"].width == pytest.approx(0.05)
    assert marks["start"].top < marks["track"].top < marks["tail"].top <= 0.01   # later ones lie on top
    assert not [f for f in scene.findings if f.check == "collision"]


def test_markings_are_byte_identical_and_pass_libsdformat(tmp_path):
    from worldgen.check.sdformat import sdformat_check

    first, second = (world_sdf(build_geometry(_loop_spec())) for _ in range(2))
    assert first == second
    path = tmp_path / "m.world"
    path.write_text(first)
    checked = sdformat_check(path)
    if checked is None:
        pytest.skip("libsdformat is not installed")
    assert checked[0], checked[1]


def test_the_preview_draws_the_tape_in_its_colour():
    pic = picture(EXAMPLES / "line_track.yaml")
    data = render(pic)
    image = imread(io.BytesIO(data))
    ax = figure(pic).axes[0]
    ax.apply_aspect()

    def rgb(x, y):
        px, py = ax.transData.transform((x, y))
        return image[image.shape[0] - 1 - int(round(py)), int(round(px)), :3]

    for x, y in ((0.7, -0.85), (1.35, 0.0), (-0.5, 0.85), (-1.35, 0.0)):   # on the yellow tape
        assert np.allclose(rgb(x, y), (1, 1, 0), atol=0.05), (x, y, rgb(x, y))
    assert np.all(rgb(0.7, -0.6) > 0.9)   # the floor beside it stays white
    assert b"floor marking" not in data   # (the legend's text is drawn, not stored)
    assert render(pic) == data


# ----------------------------------------------------------------------------------------------- validate

def _validate(tmp_path, text: str, name: str, *extra: str) -> dict:
    path = tmp_path / f"{name}.yaml"
    path.write_text(text)
    result = CliRunner().invoke(main, ["validate", str(path), "--format", "json", *extra])
    assert result.exit_code in (0, 1), result.output
    (report,) = json.loads(result.stdout)["results"]
    return report


@pytest.mark.parametrize("width, warned", [(0.001, True), (0.05, False)])
def test_the_camera_warns_about_a_line_too_thin_to_see(tmp_path, width, warned):
    text = spec_text(f"  - {{name: tape, points: [[-1, 0], [1, 0]], width: {width}, color: Gazebo/Red}}\n")
    report = _validate(tmp_path, text, "thin", "--skip-sim")
    camera = [f for f in report["findings"] if f["check"] == "camera"]
    warnings = [f for f in camera if f["severity"] == "warning"]
    assert bool(warnings) == warned and "camera" in report["checks"]
    px = apparent_pixels(width)
    assert (px < MIN_PIXELS) == warned and report["metrics"]["narrowest_marking_px"] == pytest.approx(px, abs=1e-3)
    if warned:
        (w,) = warnings
        assert "line 'tape'" in w["message"] and f"{px:.1f} px at 0.5 m" in w["message"]
        assert w["where"].endswith("thin.yaml:6") and "mm wide" in w["fix"]
    (info,) = [f for f in camera if f["severity"] == "info"]
    assert "can see 1 floor marking (Gazebo/Red)" in info["message"] and f"{px:.1f} px" in info["message"]


def test_no_camera_check_without_markings(tmp_path):
    report = _validate(tmp_path, spec_text(), "plain", "--skip-sim")
    assert "camera" not in report["checks"] and not [f for f in report["findings"] if f["check"] == "camera"]
    assert "floor_markings" not in report["metrics"]


def test_the_line_track_template_validates_and_its_tape_changes_no_other_check(tmp_path):
    """The template as `worldgen new --template line-track` writes it passes every check, simulated ones included,
    and the same world without its tape gets the same verdict and the same numbers from every check but the
    camera's."""
    text = starter_spec("track", "line-track")
    spec = parse_spec(text, "track.yaml")
    (track,) = spec.lines
    assert track.closed and track.width == 0.05 and track.color == Material("Gazebo/Yellow")
    assert spec.robot.model == "waffle_pi" and spec.robot.at == (0.0, -0.85) and spec.robot.yaw == 0
    xs, ys = [p[0] for p in track.points], [p[1] for p in track.points]
    assert min(2 - 0.075 - max(map(abs, xs)), 1.5 - 0.075 - max(map(abs, ys))) - 0.025 >= 0.5   # ≥ 0.5 m from walls
    turns = [math.atan2(b[1] - a[1], b[0] - a[0]) for a, b in zip(track.points, track.points[1:] + track.points[:1])]
    assert max(abs(math.remainder(b - a, 2 * math.pi)) for a, b in zip(turns, turns[1:])) <= math.radians(10.1)
    with_tape = _validate(tmp_path, text, "track")
    bare = text[:text.index("\nlines:")] + "\n" + text[text.index("# Patches"):]
    without = _validate(tmp_path, bare, "bare")
    assert with_tape["ok"] and not [f for f in with_tape["findings"] if f["severity"] != "info"], with_tape
    camera = ("floor_markings", "marking_colors", "narrowest_marking_m", "narrowest_marking_px")
    assert with_tape["metrics"]["models"] == without["metrics"]["models"] + 1   # the floor_markings model
    assert {k: v for k, v in with_tape["metrics"].items() if k not in camera + ("models",)} == \
        {k: v for k, v in without["metrics"].items() if k != "models"}
    assert [f for f in with_tape["findings"] if f["check"] != "camera"] == \
        json.loads(json.dumps(without["findings"]).replace("bare.yaml", "track.yaml"))
    assert with_tape["checks"] == ["parse", "camera", "enclosed", "spawn-clear", "settle", "lidar", "spin",
                                   "stop-at-wall"]


def test_new_writes_the_line_track_template(tmp_path):
    from worldgen.cli.new import TEMPLATES
    from worldgen.spec.load import STARTERS

    assert TEMPLATES == tuple(STARTERS)
    out = tmp_path / "lab.yaml"
    result = CliRunner().invoke(main, ["new", "lab", "--template", "line-track", "-o", str(out)])
    assert result.exit_code == 0, result.output
    assert out.read_text() == starter_spec("lab", "line-track") and "color: Gazebo/Yellow" in out.read_text()
    bad = CliRunner().invoke(main, ["new", "lab2", "--template", "oval", "-o", str(tmp_path / "x.yaml")])
    assert bad.exit_code == 2 and "line-track" in bad.output and not (tmp_path / "x.yaml").exists()


GAZEBO_SAVED = """<sdf version='1.7'><world name='default'>
  <model name='walls'><static>1</static><link name='w'>
    <collision name='c'><pose>0 2 0.5 0 0 0</pose><geometry><box><size>4 0.1 1</size></box></geometry></collision>
    <visual name='v'><pose>0 2 0.5 0 0 0</pose><geometry><box><size>4 0.1 1</size></box></geometry></visual>
  </link></model>
  <model name='tape'><static>1</static><pose>0 0 0.0005 0 0 0.3</pose>
    <link name='thin'><visual name='v'><geometry><box><size>2 0.001 0.001</size></box></geometry>
      <material><diffuse>0.1 0.2 0.9 1</diffuse></material></visual></link>
    <link name='wide'><pose>0 0.5 0 0 0 0</pose><visual name='v'><geometry><box><size>2 0.3 0.001</size></box>
      </geometry></visual></link>
  </model>
</world></sdf>
"""


def test_markings_in_a_world_saved_by_gazebo(tmp_path):
    path = tmp_path / "taped.world"
    path.write_text(GAZEBO_SAVED)
    result = CliRunner().invoke(main, ["validate", str(path), "--skip-sim", "--spawn", "0,-1", "--format", "json"])
    (report,) = json.loads(result.stdout)["results"]
    camera = [f for f in report["findings"] if f["check"] == "camera"]
    assert [(f["severity"], f.get("where")) for f in camera] == [("warning", "tape/thin"), ("info", None)]
    assert "floor marking tape/thin is 1.0 mm wide: 1.1 px" in camera[0]["message"]
    assert "can see 2 floor markings (rgb(0.1, 0.2, 0.9), colour not known)" in camera[1]["message"]
    assert not [f for f in report["findings"] if f["check"] == "collision"]   # markings are meant to be driven over
    pic = picture(path)
    data = render(pic)
    image = imread(io.BytesIO(data))
    ax = figure(pic).axes[0]
    ax.apply_aspect()
    x, y = ax.transData.transform((-0.5 * math.sin(0.3), 0.5 * math.cos(0.3)))   # the wide one's middle
    assert np.allclose(image[image.shape[0] - 1 - int(round(y)), int(round(x)), :3], 0.7, atol=0.03)   # grey


def test_a_world_built_beside_its_spec_names_the_specs_line(tmp_path):
    spec = tmp_path / "t.yaml"   # the world is named after the spec's name: t.world, its spec beside it
    spec.write_text(spec_text("  - {name: hair, points: [[-1, 0], [1, 0]], width: 0.001, color: Gazebo/Red}\n"
                              "  - {points: [[-1, 0.5], [1, 0.5]], width: 0.0015, color: Gazebo/Blue}\n"))
    assert CliRunner().invoke(main, ["build", str(spec), "-o", str(tmp_path)]).exit_code == 0
    result = CliRunner().invoke(main, ["validate", str(tmp_path / "t.world"), "--skip-sim", "--format", "json"])
    (report,) = json.loads(result.stdout)["results"]
    warnings = [(f["message"].split(" is ")[0], f["where"]) for f in report["findings"]
                if f["check"] == "camera" and f["severity"] == "warning"]
    assert warnings == [("line 'hair'", f"{spec}:6"), ("line_1", f"{spec}:7")]   # as the world names it
