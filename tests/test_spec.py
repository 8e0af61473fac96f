"""The floorplan spec: what a valid spec means, in numbers (bad specs are in test_bad_input.py)."""

from __future__ import annotations

import json

import pytest
import yaml
from conftest import CliRunner

from worldgen.cli import main
from worldgen.core.errors import SpecError
from worldgen.spec.load import load_spec, parse_spec, starter_spec
from worldgen.spec.model import DEFAULT_HEIGHT, DEFAULT_MATERIAL, DEFAULT_THICKNESS, Material

DESIGN_EXAMPLE = """\
name: enclosed_room
walls: {thickness: 0.15, height: 2.5, material: Gazebo/Grey}
rooms:
  - name: main
    rect: {center: [0, 0], size: [5, 5]}
    openings:
      - {type: door, wall: 0, offset: 1.2, width: 0.9}
      - {type: window, wall: 2, offset: 2.0, width: 0.8, sill: 0.5, height: 0.8}
  - name: side
    polygon: [[2.5, -1], [5, -1], [5, 1], [2.5, 1]]
obstacles:
  - {shape: box, size: [0.4, 0.4, 0.5], at: [1.0, 1.0], yaw: 0.3}
  - {shape: cylinder, radius: 0.15, height: 0.5, at: [-1, 1]}
robot: {model: burger, at: [0, 0], yaw: 0}
"""


def test_design_example_in_numbers():
    spec = parse_spec(DESIGN_EXAMPLE, "example.yaml")
    assert spec.name == "enclosed_room" and spec.source == "example.yaml"
    main, side = spec.rooms
    # a rect lists its corners from the minimum one, counter-clockwise: wall 0 bottom, 1 right, 2 top, 3 left
    assert main.vertices == ((-2.5, -2.5), (2.5, -2.5), (2.5, 2.5), (-2.5, 2.5))
    assert side.vertices == ((2.5, -1.0), (5.0, -1.0), (5.0, 1.0), (2.5, 1.0))
    door, window = main.openings
    assert (door.type, door.wall, door.offset, door.width, door.height, door.sill) == ("door", 0, 1.2, 0.9, 2.0, 0)
    assert (window.wall, window.offset, window.width, window.height, window.sill) == (2, 2.0, 0.8, 0.8, 0.5)
    assert (door.line, window.line, main.line, side.line) == (7, 8, 4, 9)
    box, cylinder = spec.obstacles
    assert (box.shape, box.size, box.at, box.yaw) == ("box", (0.4, 0.4, 0.5), (1.0, 1.0), 0.3)
    assert (cylinder.radius, cylinder.height, cylinder.at, cylinder.yaw) == (0.15, 0.5, (-1.0, 1.0), 0.0)
    assert (spec.robot.model, spec.robot.at, spec.robot.yaw, spec.robot.line) == ("burger", (0.0, 0.0), 0.0, 14)


def test_defaults_are_the_building_editors():
    spec = parse_spec("""\
name: d
rooms:
  - name: a
    rect: {center: [1, 2], size: [4, 3]}
    openings: [{type: door, wall: 1}, {type: window, wall: 2}]
robot: {at: [1, 2]}
""")
    assert (spec.style.thickness, spec.style.height, spec.style.material) == (0.15, 2.5, Material("Gazebo/Grey"))
    door, window = spec.rooms[0].openings
    assert (door.width, door.height, door.sill) == (0.9, 2.0, 0.0)
    assert (window.width, window.height, window.sill) == (0.8, 0.8, 0.5)
    # without an offset an opening is centred on its wall: wall 1 is 3 m long, wall 2 is 4 m long
    assert door.offset == pytest.approx((3 - 0.9) / 2)
    assert window.offset == pytest.approx((4 - 0.8) / 2)
    assert (spec.robot.model, spec.robot.yaw) == ("burger", 0.0)
    assert (DEFAULT_THICKNESS, DEFAULT_HEIGHT, DEFAULT_MATERIAL) == (0.15, 2.5, "Gazebo/Grey")


def test_room_walls_override_only_what_they_name():
    spec = parse_spec("""\
name: o
walls: {thickness: 0.2, height: 1.0, material: Gazebo/Bricks}
rooms:
  - {name: a, rect: {center: [0, 0], size: [3, 3]}, walls: {height: 0.5}}
  - {name: b, rect: {center: [3, 0], size: [3, 3]}}
""")
    a, b = spec.rooms
    assert (a.style.thickness, a.style.height, a.style.material.script) == (0.2, 0.5, "Gazebo/Bricks")
    assert (b.style.thickness, b.style.height) == (0.2, 1.0)


def test_low_walls_get_full_height_doors_by_default():
    spec = parse_spec("name: low\nwalls: {height: 0.5}\nrooms:\n"
                      "  - {name: a, rect: {center: [0, 0], size: [3, 3]}, openings: [{type: door, wall: 0}]}\n")
    assert spec.rooms[0].openings[0].height == 0.5


def test_polygon_keeps_its_winding_and_drops_a_closing_point():
    cw = parse_spec("name: p\nrooms: [{name: a, polygon: [[0, 0], [0, 3], [4, 3], [4, 0], [0, 0]]}]\n")
    assert cw.rooms[0].vertices == ((0, 0), (0, 3), (4, 3), (4, 0))
    angled = parse_spec("name: p\nrooms: [{name: a, polygon: [[0, 0], [3, 1], [2, 4], [-1, 3]],"
                        " openings: [{type: door, wall: 1, offset: 0.5}]}]\n")
    assert angled.rooms[0].openings[0].offset == 0.5


@pytest.mark.parametrize("text, expected", [
    ("Gazebo/Wood", Material("Gazebo/Wood")),
    ("MyMaterials/Concrete", Material("MyMaterials/Concrete")),
    ("[1, 0.5, 0]", Material(None, (1.0, 0.5, 0.0, 1.0))),
    ("[0.2, 0.3, 0.4, 0.5]", Material(None, (0.2, 0.3, 0.4, 0.5))),
    ("{rgba: [0, 0, 1, 1]}", Material(None, (0.0, 0.0, 1.0, 1.0))),
    ("{script: Gazebo/Bricks}", Material("Gazebo/Bricks")),
])
def test_material_forms(text, expected):
    spec = parse_spec(f"name: m\nwalls: {{material: {text}}}\nobstacles:\n"
                      f"  - {{shape: sphere, radius: 0.2, at: [0, 0], material: {text}}}\n")
    assert spec.style.material == expected
    assert spec.obstacles[0].material == expected


def test_segments_and_their_openings():
    spec = parse_spec("""\
name: s
segments:
  - from: [0, 0]
    to: [4, 0]
    walls: {thickness: 0.1}
    openings: [{type: door, offset: 1}]
  - {from: [0, 1], to: [0, 3]}
""")
    first, second = spec.segments
    assert (first.start, first.end, first.style.thickness, first.line) == ((0, 0), (4, 0), 0.1, 3)
    assert [(o.wall, o.offset, o.width) for o in first.openings] == [(0, 1.0, 0.9)]
    assert second.style.thickness == 0.15 and second.openings == ()


def test_obstacle_shapes_and_names():
    spec = parse_spec("""\
name: o
obstacles:
  - {shape: box, name: table, size: [1.2, 0.8, 0.75], at: [1, 2], yaw: -1.5}
  - {shape: cylinder, name: bin, radius: 0.2, height: 0.6, at: [-1, 0]}
  - {shape: sphere, radius: 0.3, at: [0, -2]}
""")
    table, bin_, ball = spec.obstacles
    assert (table.name, table.size, table.yaw) == ("table", (1.2, 0.8, 0.75), -1.5)
    assert (bin_.name, bin_.radius, bin_.height, bin_.size) == ("bin", 0.2, 0.6, None)
    assert (ball.name, ball.radius, ball.height, ball.line) == (None, 0.3, None, 5)


def test_json_and_yaml_give_the_same_spec(tmp_path):
    data = yaml.safe_load(DESIGN_EXAMPLE)
    as_json = tmp_path / "example.json"
    as_json.write_text(json.dumps(data, indent="\t"))
    as_yaml = tmp_path / "example.yaml"
    as_yaml.write_text(DESIGN_EXAMPLE)
    a, b = load_spec(as_json), load_spec(as_yaml)

    def strip(spec):
        return ([(r.name, r.vertices, [(o.type, o.wall, o.offset, o.width, o.height, o.sill) for o in r.openings])
                 for r in spec.rooms], [(o.shape, o.at, o.size, o.radius) for o in spec.obstacles], spec.robot.at)

    assert strip(a) == strip(b)
    assert len(a.rooms[0].openings) == 2
    assert a.source == str(as_json)


def test_json_errors_have_lines_too(tmp_path):
    path = tmp_path / "bad.json"
    path.write_text('{\n  "name": "j",\n  "rooms": [\n    {"name": "a", "rect": {"center": [0, 0], "sise": [1, 1]}}\n'
                    '  ]\n}\n')
    with pytest.raises(SpecError) as err:
        load_spec(path)
    assert str(err.value).startswith(f"{path}:4: unknown key 'sise' in rect of room 'a'; did you mean 'size'?")


def test_json_numbers_with_exponents_are_numbers(tmp_path):
    """json.dumps writes 0.00001 as 1e-05, which YAML 1.1 alone would read as text."""
    data = {"name": "e", "rooms": [{"name": "a", "rect": {"center": [0.00001, -2.5e-7], "size": [5e0, 4.0]}}],
            "robot": {"at": [1e-05, 0], "yaw": 1e-07}}
    path = tmp_path / "e.json"
    path.write_text(json.dumps(data, separators=(",", ":")))
    assert "1e-05" in path.read_text()
    spec = load_spec(path)
    assert spec.rooms[0].vertices[0] == (round(0.00001 - 2.5, 9), round(-2.5e-7 - 2, 9))
    assert (spec.robot.at, spec.robot.yaw) == ((1e-05, 0.0), 1e-07)
    assert parse_spec("name: y\nobstacles: [{shape: sphere, radius: 2E-1, at: [1e0, -1.5e+0]}]\n").obstacles[0].at \
        == (1.0, -1.5)
    with pytest.raises(SpecError, match="must be a number, not the text '2e-1'"):   # quoted: text, as written
        parse_spec("name: y\nobstacles: [{shape: sphere, radius: '2e-1', at: [0, 0]}]\n")


def test_yaml_anchors_and_merge_keys_work():
    spec = parse_spec("""\
name: a
rooms:
  - &base {name: one, rect: {center: [0, 0], size: [3, 3]}, walls: {height: 1.0}}
  - <<: *base
    name: two
    rect: {center: [3, 0], size: [3, 3]}
""")
    assert [(r.name, r.style.height) for r in spec.rooms] == [("one", 1.0), ("two", 1.0)]


def test_starter_spec_loads_and_says_what_new_promises(tmp_path):
    spec = parse_spec(starter_spec("lab_one"), "lab_one.yaml")
    assert spec.name == "lab_one"
    (room,) = spec.rooms
    xs = [v[0] for v in room.vertices]
    ys = [v[1] for v in room.vertices]
    assert (max(xs) - min(xs), max(ys) - min(ys)) == (5, 5)
    assert [o.type for o in room.openings] == ["window"]   # a door to the outside would open the room
    assert "# - {type: door" in starter_spec("lab_one")   # offered, commented out
    assert len(spec.obstacles) == 1
    assert spec.robot.at == ((min(xs) + max(xs)) / 2, (min(ys) + max(ys)) / 2)


def test_starter_spec_passes_validation_as_written(tmp_path):
    spec = tmp_path / "lab.yaml"
    assert CliRunner().invoke(main, ["new", "lab", "-o", str(spec)]).exit_code == 0
    result = CliRunner().invoke(main, ["validate", str(spec), "--skip-sim", "--format", "json"])
    assert result.exit_code == 0, result.output
    (report,) = json.loads(result.output)["results"]
    assert report["metrics"]["enclosed"] is True and report["metrics"]["min_clearance_m"] > 0.5


def test_new_writes_refuses_existing_and_forces(tmp_path):
    runner = CliRunner()
    out = tmp_path / "specs" / "lab.yaml"
    result = runner.invoke(main, ["new", "lab", "-o", str(out)])
    assert result.exit_code == 0, result.output
    assert load_spec(out).name == "lab"
    out.write_text("# mine\n")
    result = runner.invoke(main, ["new", "lab", "-o", str(out)])
    assert result.exit_code == 2
    assert "exists" in result.output and "--force" in result.output
    assert out.read_text() == "# mine\n"
    assert runner.invoke(main, ["new", "lab", "-o", str(out), "--force"]).exit_code == 0
    assert load_spec(out).name == "lab"
    built = runner.invoke(main, ["build", str(out), "-o", str(tmp_path / "worlds")])
    assert built.exit_code == 0, built.output
    assert (tmp_path / "worlds" / "lab.world").is_file()


def test_new_default_path_and_bad_name(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    runner = CliRunner()
    assert runner.invoke(main, ["new", "room_a"]).exit_code == 0
    assert (tmp_path / "room_a.yaml").is_file()
    result = runner.invoke(main, ["new", "2nd room"])
    assert result.exit_code == 2
    assert "'2nd room' is not a valid name" in result.output and "w_2nd_room" in result.output
    assert sorted(p.name for p in tmp_path.iterdir()) == ["room_a.yaml"]
