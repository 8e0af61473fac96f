"""Bad specs: each one is refused with the file, the line and what to change; `worldgen build` exits 2 and
writes nothing; an existing output is kept unless --force."""

from __future__ import annotations

import pytest
from conftest import CliRunner

from worldgen.cli import main
from worldgen.core.errors import SpecError
from worldgen.spec.load import load_spec, parse_spec

ROOM = "name: t\nrooms:\n  - name: main\n    rect: {center: [0, 0], size: [5, 5]}\n"   # lines 1-4
OPENINGS = ROOM + "    openings:\n"                                                          # line 5

# id, spec text, line of the error, words the message must hold
CASES = [
    ("yaml-syntax", "name: t\nrooms: [\n  - a\n", 3, ["invalid YAML"]),
    ("yaml-tab", "name: t\nrooms:\n\t- name: a\n", 3, ["invalid YAML", "spaces, not tabs"]),
    ("empty", "", None, ["the spec is empty", "worldgen new"]),
    ("not-a-mapping", "- a\n- b\n", 1, ["must be a block of keys", "not a list"]),
    ("unknown-top-key", "name: t\nroms: []\n", 2, ["unknown key 'roms' in the spec; did you mean 'rooms'?"]),
    ("unknown-opening-key", OPENINGS + "      - {type: door, wall: 0, widht: 1}\n", 6,
     ["unknown key 'widht' in opening 1 of room 'main'; did you mean 'width'?"]),
    ("duplicate-key", "name: t\nname: u\n", 2, ["'name' is given twice", "line 1"]),
    ("duplicate-key-after-merge", "name: t\nrooms:\n  - &a {name: a, rect: {center: [0, 0], size: [3, 3]}}\n"
                                  "  - <<: *a\n    name: b\n    name: c\n", 6, ["'name' is given twice", "line 5"]),
    ("missing-name", "rooms: []\n", 1, ["has no 'name'", "name: my_world"]),
    ("missing-shape", ROOM.replace("    rect: {center: [0, 0], size: [5, 5]}\n", ""), 3,
     ["room 'main' needs exactly one of 'rect' or 'polygon'"]),
    ("missing-rect-size", "name: t\nrooms:\n  - name: a\n    rect: {center: [0, 0]}\n", 4,
     ["rect of room 'a' has no 'size'"]),
    ("missing-opening-wall", OPENINGS + "      - {type: door}\n", 6, ["has no 'wall'", "wall: 0"]),
    ("missing-obstacle-at", ROOM + "obstacles:\n  - {shape: sphere, radius: 0.2}\n", 6, ["has no 'at'"]),
    ("missing-cylinder-height", ROOM + "obstacles:\n  - {shape: cylinder, radius: 0.2, at: [0, 0]}\n", 6,
     ["obstacle 1 has no 'height'"]),
    ("missing-robot-at", ROOM + "robot: {model: burger}\n", 5, ["robot has no 'at'"]),
    ("nothing-to-build", "name: t\n", 1, ["nothing to build"]),
    ("wrong-type-size", "name: t\nrooms:\n  - name: a\n    rect: {center: [0, 0], size: 5}\n", 4,
     ["size of room 'a' must be [width, depth]", "not the number 5"]),
    ("wrong-type-text", "name: t\nrooms:\n  - name: a\n    rect: {center: [0, 0], size: [5, '5']}\n", 4,
     ["must be a number, not the text '5'"]),
    ("wrong-type-bool", ROOM + "robot: {at: [0, true]}\n", 5, ["must be a number, not true"]),
    ("wrong-type-point", ROOM + "robot: {at: [0, 1, 2]}\n", 5, ["must be a point [x, y]", "of 3 numbers"]),
    ("wrong-length-size", "name: t\nrooms:\n  - name: a\n    rect: {center: [0, 0], size: [5]}\n", 4,
     ["size of room 'a' must be [width, depth] in metres, not a list of 1 number (e.g. size: [5, 4])"]),
    ("wrong-length-box", ROOM + "obstacles:\n  - {shape: box, size: [1, 1], at: [0, 0]}\n", 6,
     ["size of obstacle 1 must be [x, y, z] in metres, not a list of 2 numbers"]),
    ("grid-rows-unquoted-list", "name: t\ngrid:\n  rows:\n    - '###'\n    - #R#\n", 5,
     ["grid row 2 must be a line of text, not nothing", "an unquoted # starts a comment"]),
    ("wrong-type-rooms", "name: t\nrooms: {name: a}\n", 2, ["rooms must be a list"]),
    ("wrong-type-wall-index", OPENINGS + "      - {type: door, wall: 1.5}\n", 6, ["must be a wall number"]),
    ("zero-size", "name: t\nrooms:\n  - name: a\n    rect: {center: [0, 0], size: [0, 5]}\n", 4,
     ["width (x size) of room 'a' must be more than 0"]),
    ("negative-size", "name: t\nrooms:\n  - name: a\n    rect:\n      center: [0, 0]\n      size: [5, -5]\n", 6,
     ["depth (y size) of room 'a' must be more than 0, not -5"]),
    ("negative-radius", ROOM + "obstacles:\n  - {shape: sphere, radius: -0.2, at: [0, 0]}\n", 6,
     ["radius of obstacle 1 must be more than 0"]),
    ("nan", "name: t\nrooms:\n  - name: a\n    rect: {center: [.nan, 0], size: [5, 5]}\n", 4,
     ["x of center of room 'a' must be a finite number"]),
    ("inf", "name: t\nrooms:\n  - name: a\n    rect: {center: [0, 0], size: [.inf, 5]}\n", 4,
     ["must be a finite number, not inf"]),
    ("huge-size", "name: t\nrooms:\n  - name: a\n    rect: {center: [0, 0], size: [5000, 5]}\n", 4,
     ["5000 m: more than 1000 m"]),
    ("huge-coordinate", "name: t\nrooms:\n  - name: a\n    polygon: [[0, 0], [2000, 0], [0, 5]]\n", 4,
     ["corner 1 of room 'a' is 2000: farther than 1000 m"]),
    ("huge-wall-height", "name: t\nwalls:\n  height: 2500\nrooms: []\n", 3, ["walls height is 2500 m"]),
    ("tiny-room", "name: t\nrooms:\n  - name: a\n    rect: {center: [0, 0], size: [0.1, 5]}\n", 4,
     ["not more than its walls' thickness 0.15 m"]),
    ("polygon-two-points", "name: t\nrooms:\n  - name: a\n    polygon: [[0, 0], [2, 0]]\n", 4,
     ["has 2 points; a room needs at least 3"]),
    ("polygon-repeated-point",
     "name: t\nrooms:\n  - name: a\n    polygon:\n      - [0, 0]\n      - [2, 0]\n      - [2, 0]\n      - [0, 2]\n",
     7, ["corner 2 of room 'a' repeats corner 1 (2, 0)"]),
    ("polygon-crossing", "name: t\nrooms:\n  - name: a\n    polygon: [[0, 0], [2, 2], [2, 0], [0, 2]]\n", 4,
     ["walls 0 and 2 of room 'a' cross"]),
    ("polygon-fold-back", "name: t\nrooms:\n  - name: a\n    polygon: [[0, 0], [4, 0], [2, 0], [2, 3]]\n", 4,
     ["cross or overlap"]),
    ("polygon-collinear", "name: t\nrooms:\n  - name: a\n    polygon: [[0, 0], [1, 1], [3, 3]]\n", 4,
     ["cross or overlap"]),
    ("opening-wider-than-wall", OPENINGS + "      - {type: door, wall: 0, width: 6}\n", 6,
     ["door 1 of room 'main' is 6 m wide", "only 4.85 m between its corners", "at most 4.85"]),
    ("openings-overlap", OPENINGS + "      - {type: door, wall: 0, offset: 1, width: 1}\n"
                                    "      - {type: window, wall: 0, offset: 1.5}\n", 7,
     ["openings 1 and 2 of room 'main' overlap", "wall 0"]),
    ("openings-touch", OPENINGS + "      - {type: window, wall: 3, offset: 1, width: 1}\n"
                                  "      - {type: window, wall: 3, offset: 2, width: 1}\n", 7,
     ["overlap or touch"]),
    ("opening-in-start-corner", OPENINGS + "      - {type: door, wall: 1, offset: 0.05}\n", 6,
     ["starts 0.05 m along wall 1", "inside the corner", "from 0.075 to 4.025"]),
    ("opening-in-end-corner", OPENINGS + "      - {type: window, wall: 2,\n         offset: 4.2}\n", 7,
     ["ends 5 m along wall 2", "inside the corner"]),
    ("door-taller-than-wall", OPENINGS + "      - {type: door, wall: 1, height: 3}\n", 6,
     ["door 1 of room 'main' is 3 m tall, but the walls of room 'main' are 2.5 m"]),
    ("door-in-low-wall", "name: t\nwalls: {height: 1.5}\nrooms:\n  - name: a\n"
                         "    rect: {center: [0, 0], size: [5, 5]}\n"
                         "    openings: [{type: door, wall: 0, height: 2.0}]\n", 6, ["2 m tall", "are 1.5 m"]),
    ("window-above-wall", OPENINGS + "      - {type: window, wall: 1, sill: 2, height: 1}\n", 6,
     ["window 1 of room 'main' reaches 3 m up", "above the 2.5 m walls"]),
    ("door-with-sill", OPENINGS + "      - {type: door, wall: 1, sill: 0.2}\n", 6, ["a door starts at the floor"]),
    ("wall-index-out-of-range", OPENINGS + "      - {type: door, wall: 4}\n", 6,
     ["is on wall 4, but room 'main' has 4 walls", "wall 0 to 3"]),
    ("segment-wall-index", "name: t\nsegments:\n  - from: [0, 0]\n    to: [3, 0]\n"
                           "    openings: [{type: door, wall: 1}]\n", 5, ["segment 1 has 1 wall"]),
    ("segment-zero-length", "name: t\nsegments:\n  - {from: [1, 1], to: [1, 1]}\n", 3,
     ["starts and ends at the same point"]),
    ("opening-type", OPENINGS + "      - {type: dor, wall: 1}\n", 6, ["not 'dor'; did you mean 'door'?"]),
    ("unknown-robot-model", ROOM + "robot: {model: burgerr, at: [0, 0]}\n", 5,
     ["robot model must be one of burger, waffle, waffle_pi, not 'burgerr'; did you mean 'burger'?"]),
    ("robot-yaw-degrees", ROOM + "robot: {at: [0, 0], yaw: 90}\n", 5, ["radians", "1.5708"]),
    ("invalid-spec-name", "name: 3d world\nrooms: []\n", 1, ["'3d world' is not a valid name", "w_3d_world"]),
    ("spec-name-not-text", "name: 42\nrooms: []\n", 1, ["must be text, not the number 42"]),
    ("invalid-room-name", "name: t\nrooms:\n  - name: my room\n    rect: {center: [0, 0], size: [5, 5]}\n", 3,
     ["room name 'my room' is not a valid name", "my_room"]),
    ("invalid-obstacle-name", ROOM + "obstacles:\n  - {shape: box, size: [1, 1, 1], at: [0, 0], name: box-1}\n", 6,
     ["obstacle name 'box-1' is not a valid name", "box_1"]),
    ("duplicate-room-names", ROOM + "  - name: main\n    rect: {center: [9, 0], size: [5, 5]}\n", 5,
     ["two rooms are named 'main'", "line 3"]),
    ("duplicate-obstacle-names", ROOM + "obstacles:\n  - {shape: sphere, radius: 0.2, at: [1, 1], name: a}\n"
                                        "  - {shape: sphere, radius: 0.2, at: [-1, 1], name: a}\n", 7,
     ["obstacle name 'a' is already used"]),
    ("unknown-shape", ROOM + "obstacles:\n  - {shape: cube, size: [1, 1, 1], at: [0, 0]}\n", 6,
     ["shape of obstacle 1 must be one of box, cylinder, sphere, not 'cube'"]),
    ("key-of-other-shape", ROOM + "obstacles:\n  - {shape: box, radius: 1, at: [0, 0]}\n", 6,
     ["obstacle 1 is a box, which has no 'radius'", "size"]),
    ("material-without-namespace", "name: t\nwalls: {material: grey}\nrooms: []\n", 2,
     ["'grey' is not a Gazebo material; did you mean 'Gazebo/Grey'?"]),
    ("material-typo", "name: t\nwalls: {material: Gazebo/Gray}\nrooms: []\n", 2, ["did you mean 'Gazebo/Grey'?"]),
    ("colour-out-of-range", "name: t\nwalls: {material: [255, 0, 0, 1]}\nrooms: []\n", 2, ["outside 0–1"]),
    ("grid-bad-character", "name: t\ngrid:\n  cell: 0.5\n  rows: |\n    ####\n    #x.#\n    ####\n", 6,
     ["the grid has 'x' in row 2, column 2"]),
    ("grid-two-robots", "name: t\ngrid:\n  rows: |\n    #R#\n    #R#\n", 5, ["places the robot twice"]),
    ("grid-and-robot-at", "name: t\ngrid:\n  rows: |\n    ####\n    #R.#\n    ####\nrobot: {at: [1, 1]}\n", 7,
     ["the robot is placed twice"]),
    ("grid-folded", "name: t\ngrid:\n  rows: >\n    ###\n    # #\n", 3, ["folded into one line"]),
    ("grid-zero-cell", "name: t\ngrid:\n  cell: 0\n  rows: |\n    ###\n", 3, ["grid cell must be more than 0"]),
    ("recursive-alias", "name: t\nrooms: &r [*r]\n", 2, ["refers to itself"]),
    ("two-documents", ROOM + "---\nname: u\n", 5,
     ["expected a single document in the stream but found another document", "one YAML document"]),
    ("nested-too-deeply", "name: t\nrooms: " + "[" * 3000 + "]" * 3000 + "\n", None, ["nested too deeply"]),
    ("huge-integer", "name: t\nrooms:\n  - name: a\n    rect: {center: [0, 0], size: [5, " + "9" * 400 + "]}\n", 4,
     ["depth (y size) of room 'a' is a 400-digit number"]),
    ("huge-integer-name", "name: " + "9" * 400 + "\nrooms: []\n", 1, ["must be text, not a very long number"]),
    ("polygon-corner-within-1mm", "name: t\nrooms:\n  - name: a\n    polygon:\n      - [0, 0]\n      - [4, 0]\n"
                                  "      - [4, 0.0005]\n      - [0, 4]\n", 7,
     ["corner 2 of room 'a' repeats corner 1 (4, 0) to within 0.5 mm"]),
    ("opening-on-too-short-wall", "name: t\nwalls: {thickness: 0.5}\nsegments:\n"
                                  "  - {from: [0, 0], to: [0.2, 0], openings: [{type: door}]}\n", 4,
     ["door 1 of segment 1 is on wall 0, which is 0.2 m long", "no room for an opening"]),
    ("empty-material", "name: t\nwalls: {material: ''}\nrooms: []\n", 2, ["walls material is empty"]),
    ("robot-yaw-degrees-over-360", ROOM + "robot: {at: [0, 0], yaw: 400}\n", 5, ["for 400 degrees write 0.6981"]),
]


@pytest.mark.parametrize("text, line, words", [c[1:] for c in CASES], ids=[c[0] for c in CASES])
def test_message_names_file_line_and_fix(text, line, words):
    with pytest.raises(SpecError) as err:
        parse_spec(text, "bad.yaml")
    message = str(err.value)
    assert message.startswith(f"bad.yaml:{line}: " if line else "bad.yaml: "), message
    assert "\n" not in message
    for word in words:
        assert word in message, message
    assert err.value.hint, "every message says what to change"


@pytest.mark.parametrize("text, line, words", [c[1:] for c in CASES], ids=[c[0] for c in CASES])
def test_build_exits_2_and_writes_nothing(tmp_path, text, line, words):
    spec = tmp_path / "bad.yaml"
    spec.write_text(text)
    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["build", str(spec), "-o", str(out)])
    assert result.exit_code == 2, result.output
    assert result.stderr.startswith(f"worldgen: error: {spec}:{line}: " if line else f"worldgen: error: {spec}: ")
    assert result.stderr.count("\n") == 1 and "Traceback" not in result.output
    assert words[0] in result.stderr
    assert not out.exists() or not any(out.iterdir())
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bad.yaml"] + (["out"] if out.exists() else [])


def test_unreadable_inputs(tmp_path):
    with pytest.raises(SpecError, match="no such file"):
        load_spec(tmp_path / "missing.yaml")
    with pytest.raises(SpecError, match="is a folder"):
        load_spec(tmp_path)
    latin = tmp_path / "latin.yaml"
    latin.write_bytes("name: caf\xe9\n".encode("latin-1"))
    with pytest.raises(SpecError, match="not UTF-8"):
        load_spec(latin)


GOOD = "name: keep\nrooms:\n  - name: a\n    rect: {center: [0, 0], size: [3, 3]}\nrobot: {at: [0, 0]}\n"


def test_build_keeps_an_existing_world_without_force(tmp_path):
    spec = tmp_path / "keep.yaml"
    spec.write_text(GOOD)
    out = tmp_path / "out"
    runner = CliRunner()
    first = runner.invoke(main, ["build", str(spec), "-o", str(out)])
    assert first.exit_code == 0, first.output
    world = out / "keep.world"
    assert world.is_file()
    world.write_text("edited by hand\n")
    again = runner.invoke(main, ["build", str(spec), "-o", str(out)])
    assert again.exit_code == 2
    assert "exists" in again.stderr and "--force" in again.stderr
    assert world.read_text() == "edited by hand\n"
    forced = runner.invoke(main, ["build", str(spec), "-o", str(out), "--force"])
    assert forced.exit_code == 0, forced.output
    assert world.read_text().startswith("<?xml")


def test_preview_keeps_an_existing_picture_without_force(tmp_path):
    spec = tmp_path / "keep.yaml"
    spec.write_text(GOOD)
    png = tmp_path / "keep.png"
    png.write_bytes(b"mine")
    result = CliRunner().invoke(main, ["preview", str(spec), "-o", str(png)])
    assert result.exit_code == 2
    assert "exists" in result.stderr
    assert png.read_bytes() == b"mine"


def test_preview_of_a_bad_spec_exits_2_and_writes_nothing(tmp_path):
    spec = tmp_path / "bad.yaml"
    spec.write_text(ROOM + "robot: {model: burgerr, at: [0, 0]}\n")
    png = tmp_path / "bad.png"
    result = CliRunner().invoke(main, ["preview", str(spec), "-o", str(png)])
    assert result.exit_code == 2
    assert result.stderr.startswith(f"worldgen: error: {spec}:5: robot model")
    assert not png.exists()


@pytest.mark.parametrize("spawn", ["1", "a,b", "1,2,3,4,5", "nan,0"])
def test_preview_bad_spawn(tmp_path, spawn):
    spec = tmp_path / "keep.yaml"
    spec.write_text(GOOD)
    result = CliRunner().invoke(main, ["preview", str(spec), "-o", str(tmp_path / "p.png"), "--spawn", spawn])
    assert result.exit_code == 2
    assert "X,Y or X,Y,YAW" in result.stderr
    assert not (tmp_path / "p.png").exists()


# Errors only the geometry finds: `worldgen build` still names the file, the line and the fix, counting segments
# and obstacles from 1 as the spec's own messages do.
GEOMETRY_CASES = [
    ("segments-too-sharp", "name: t\nsegments:\n  - {from: [0, 0], to: [4, 0]}\n  - {from: [4, 0], to: [0, 0.01]}\n",
     3, "segment 1 and segment 2 meet at 0.14°, too sharp a corner"),
    ("default-obstacle-name-taken", "name: t\nobstacles:\n  - {shape: sphere, radius: 1, at: [0, 0], name: obstacle_1}\n"
                                    "  - {shape: sphere, radius: 1, at: [3, 0]}\n",
     4, "obstacle 2 has no name, and the one it gets, 'obstacle_1', is already used by the obstacle on line 3"),
]


@pytest.mark.parametrize("text, line, words", [c[1:] for c in GEOMETRY_CASES], ids=[c[0] for c in GEOMETRY_CASES])
def test_geometry_errors_name_the_line_and_count_from_one(tmp_path, text, line, words):
    spec = tmp_path / "bad.yaml"
    spec.write_text(text)
    result = CliRunner().invoke(main, ["build", str(spec), "-o", str(tmp_path / "out")])
    assert result.exit_code == 2
    assert result.stderr.startswith(f"worldgen: error: {spec}:{line}: {words}"), result.stderr
    assert result.stderr.count("\n") == 1 and not (tmp_path / "out").exists()


def test_unwritable_output_is_one_line_and_writes_nothing(tmp_path):
    spec = tmp_path / "keep.yaml"
    spec.write_text(GOOD)
    blocker = tmp_path / "a_file"
    blocker.write_text("")
    runner = CliRunner()
    result = runner.invoke(main, ["build", str(spec), "-o", str(blocker / "out")])
    assert result.exit_code == 2
    assert result.stderr == f"worldgen: error: cannot write {blocker / 'out'}: Not a directory " \
                            "(check that the output folder can be created and written to)\n"
    (tmp_path / "out" / "keep.world").mkdir(parents=True)   # a folder where the world goes: kept, even with --force
    result = runner.invoke(main, ["build", str(spec), "-o", str(tmp_path / "out"), "--force"])
    assert result.exit_code == 2
    assert result.stderr.startswith(f"worldgen: error: {tmp_path / 'out' / 'keep.world'} is a folder")
    assert (tmp_path / "out" / "keep.world").is_dir() and len(list((tmp_path / "out").iterdir())) == 1
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a_file", "keep.yaml", "out"]


def test_build_of_a_world_file_says_to_validate_it_instead(tmp_path):
    world = tmp_path / "room.world"
    world.write_text("<sdf version='1.6'><world name='default'/></sdf>\n")
    result = CliRunner().invoke(main, ["build", str(world), "-o", str(tmp_path / "out")])
    assert result.exit_code == 2
    assert "is a Gazebo world, not a floorplan spec" in result.output and "worldgen validate" in result.output
    assert not (tmp_path / "out").exists()
