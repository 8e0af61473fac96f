"""The written SDF, read back with lxml and checked in numbers: poses composed, boxes sliced with shapely. Rooms
close, openings are where the spec puts them, shared walls appear once, output repeats byte for byte, and the
shape is the Building Editor's."""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

import pytest
import shapely
from conftest import CliRunner
from lxml import etree
from shapely.geometry import LineString, Polygon
from shapely.ops import unary_union

from worldgen.cli import main
from worldgen.core.numbers import format_number
from worldgen.geometry.building import build_geometry
from worldgen.sdf.writer import SDF_VERSIONS, model_config, model_sdf, planned_files, world_sdf
from worldgen.spec.model import Material, Obstacle, Opening, Room, Spec, WallStyle

STYLE = WallStyle()
T = STYLE.thickness
LIDAR_Z = 0.18


# ---------------------------------------------------------------------------------------- reading back
@dataclass
class Box:
    model: str
    link: str
    name: str
    footprint: Polygon
    z0: float
    z1: float


def pose_of(element) -> tuple[float, float, float, float]:
    """(x, y, z, yaw) of an element's <pose> (identity when absent); our output never rolls or pitches."""
    p = element.find("pose")
    if p is None:
        return 0.0, 0.0, 0.0, 0.0
    x, y, z, roll, pitch, yaw = map(float, p.text.split())
    assert roll == 0 and pitch == 0
    return x, y, z, yaw


def compose(a, b):
    x, y, z, yaw = a
    c, s = math.cos(yaw), math.sin(yaw)
    return x + c * b[0] - s * b[1], y + s * b[0] + c * b[1], z + b[2], yaw + b[3]


def read_boxes(text: str) -> list[Box]:
    """Every box collision of a world or model file, placed in the world frame."""
    root = etree.fromstring(text.encode())
    world = root.find("world")
    models = world.findall("model") if world is not None else root.findall("model")
    boxes = []
    for model in models:
        mp = pose_of(model)
        for link in model.findall("link"):
            lp = compose(mp, pose_of(link))
            for col in link.findall("collision"):
                size = col.find("geometry/box/size")
                if size is None:
                    continue
                x, y, z, yaw = compose(lp, pose_of(col))
                sx, sy, sz = map(float, size.text.split())
                c, s = math.cos(yaw), math.sin(yaw)
                corners = [(x + c * a - s * b, y + s * a + c * b)
                           for a, b in ((-sx / 2, -sy / 2), (sx / 2, -sy / 2), (sx / 2, sy / 2), (-sx / 2, sy / 2))]
                boxes.append(Box(model.get("name"), link.get("name"), col.get("name"), Polygon(corners),
                                 z - sz / 2, z + sz / 2))
    return boxes


def slice_at(boxes: list[Box], z: float):
    return unary_union([b.footprint for b in boxes if b.z0 <= z <= b.z1])


def written(spec: Spec, version: str = "1.6") -> str:
    return world_sdf(build_geometry(spec), version)


def rect_room(name, x0, y0, x1, y1, openings=(), style=STYLE):
    return Room(name, ((x0, y0), (x1, y0), (x1, y1), (x0, y1)), style, tuple(openings))


def ideal_band(rooms) -> Polygon:
    return unary_union([Polygon(r.vertices).buffer(r.style.thickness / 2, join_style="mitre", mitre_limit=1e3)
                        .difference(Polygon(r.vertices).buffer(-r.style.thickness / 2, join_style="mitre",
                                                               mitre_limit=1e3)) for r in rooms])


def enclosed_floor(union, room: Room):
    """The free region containing a point well inside the room, after closing every gap narrower than 1 mm;
    None when that region reaches the outside."""
    closed = union.buffer(0.0005)
    frame = shapely.box(*closed.buffer(1.0).bounds)
    free = frame.difference(closed)
    inner = Polygon(room.vertices).buffer(-room.style.thickness / 2 - 0.05, join_style="mitre")
    probe = inner.representative_point()
    (region,) = [g for g in getattr(free, "geoms", [free]) if g.contains(probe)]
    touches_outside = region.intersects(frame.exterior)
    return None if touches_outside else region


# ---------------------------------------------------------------------------------------- the world shape
def test_world_has_the_gazebo_classic_shape():
    spec = Spec("shape_test", rooms=(rect_room("r", 0, 0, 4, 3, [Opening("door", 0, 1, 0.9, 2.0)]),),
                obstacles=(Obstacle("box", (1, 1), 0.3, (0.4, 0.4, 0.5)),))
    text = written(spec)
    assert text.startswith('<?xml version="1.0"?>\n<sdf version="1.6">\n  <world name="default">\n')
    world = etree.fromstring(text.encode()).find("world")
    assert [c.tag for c in world] == ["scene", "light", "model", "physics", "gravity", "model", "model", "gui"]
    assert [m.get("name") for m in world.findall("model")] == ["ground_plane", "shape_test", "obstacle_0"]
    assert world.findtext("scene/ambient") == "0.4 0.4 0.4 1"
    assert world.findtext("scene/background") == "0.7 0.7 0.7 1"
    sun = world.find("light")
    assert (sun.get("name"), sun.get("type"), sun.findtext("direction")) == ("sun", "directional", "-0.5 0.1 -0.9")
    ground = world.find("model[@name='ground_plane']")
    assert ground.findtext("static") == "1"
    assert ground.findtext("link/collision/geometry/plane/normal") == "0 0 1"
    assert ground.findtext("link/collision/surface/friction/ode/mu") == "100"
    assert ground.findtext("link/collision/surface/friction/ode/mu2") == "50"
    assert ground.findtext("link/visual/material/script/name") == "Gazebo/Grey"
    physics = world.find("physics")
    assert physics.get("type") == "ode"
    expected = {"max_step_size": 0.001, "real_time_update_rate": 1000, "real_time_factor": 1,
                "ode/solver/type": "quick", "ode/solver/iters": 150, "ode/solver/sor": 1.4,
                "ode/constraints/cfm": 1e-5, "ode/constraints/erp": 0.2,
                "ode/constraints/contact_max_correcting_vel": 2000, "ode/constraints/contact_surface_layer": 0.01}
    for path, value in expected.items():
        got = physics.findtext(path)
        assert (got == value) if isinstance(value, str) else float(got) == value, path
    assert world.findtext("gravity") == "0 0 -9.8"
    assert world.find("gui/camera").get("name") == "user_camera"


def test_building_model_is_the_editor_shape():
    spec = Spec("house", rooms=(rect_room("r", 0, 0, 4, 3, [Opening("window", 2, 1, 0.8, 0.8, 0.5)]),))
    model = etree.fromstring(written(spec).encode()).find("world/model[@name='house']")
    assert model.findtext("pose") == "2 1.5 0 0 0 0"                      # the walls' bounding-box centre
    assert [c.tag for c in model][-1] == "static" and model.findtext("static") == "1"
    links = model.findall("link")
    assert [link.get("name") for link in links] == ["Wall_0", "Wall_1", "Wall_2", "Wall_3"]
    east = links[1]                                                     # unsplit: one box, raised by h/2
    assert east.findtext("pose") == "2 0 0 0 0 1.570796"
    assert [c.get("name") for c in east if c.tag in ("collision", "visual")] == ["Wall_1_Collision", "Wall_1_Visual"]
    assert east.findtext("collision/geometry/box/size") == "3.15 0.15 2.5"
    assert east.findtext("collision/pose") == "0 0 1.25 0 0 0"
    assert east.findtext("visual/material/script/uri") == "file://media/materials/scripts/gazebo.material"
    assert east.findtext("visual/material/script/name") == "Gazebo/Grey"
    north = links[2]                                                    # split around the window
    names = [c.get("name") for c in north.findall("collision")]
    assert names == [f"Wall_2_Collision_{i}" for i in range(4)]
    assert [c.get("name") for c in north.findall("visual")] == [f"Wall_2_Visual_{i}" for i in range(4)]
    sizes = [c.findtext("geometry/box/size") for c in north.findall("collision")]
    assert sizes == ["1.075 0.15 2.5", "0.8 0.15 0.5", "0.8 0.15 1.2", "2.275 0.15 2.5"]   # 4.15 m in all
    assert [c.findtext("pose") for c in north.findall("collision")] == [
        "-1.5375 0 1.25 0 0 0", "-0.6 0 0.25 0 0 0", "-0.6 0 1.9 0 0 0", "0.9375 0 1.25 0 0 0"]


def test_rgba_material_and_obstacle_models():
    red = Material(script=None, rgba=(0.9, 0.1, 0.1, 1))
    spec = Spec("things", rooms=(rect_room("r", 0, 0, 4, 3, style=WallStyle(material=red)),), obstacles=(
        Obstacle("box", (1, 1), 0.5, size=(0.4, 0.6, 0.5), name="crate"),
        Obstacle("cylinder", (2, 1), radius=0.15, height=0.8),
        Obstacle("sphere", (3, 2), radius=0.2)))
    world = etree.fromstring(written(spec).encode()).find("world")
    wall_material = world.find("model[@name='things']/link/visual/material")
    assert wall_material.findtext("ambient") == wall_material.findtext("diffuse") == "0.9 0.1 0.1 1"
    crate, cyl, ball = (world.find(f"model[@name='{n}']") for n in ("crate", "obstacle_1", "obstacle_2"))
    assert crate.findtext("pose") == "1 1 0.25 0 0 0.5" and crate.findtext("static") == "1"
    assert crate.findtext("link/collision/geometry/box/size") == "0.4 0.6 0.5"
    assert cyl.findtext("pose") == "2 1 0.4 0 0 0"
    assert (cyl.findtext("link/collision/geometry/cylinder/radius"),
            cyl.findtext("link/collision/geometry/cylinder/length")) == ("0.15", "0.8")
    assert ball.findtext("pose") == "3 2 0.2 0 0 0" and ball.findtext("link/visual/geometry/sphere/radius") == "0.2"
    assert [c.tag for c in crate] == ["pose", "link", "static"]


def test_numbers_are_short_fixed_and_never_minus_zero():
    values = (0.0, -0.0, -1e-9, 1.5, 2.0, 1 / 3, -2.5e-7, 123456.7, 1e-5)
    assert [format_number(v, 6, point=False) for v in values] == \
        ["0", "0", "0", "1.5", "2", "0.333333", "0", "123456.7", "0.00001"]
    spec = Spec("r", rooms=(Room("hex", tuple((math.cos(t) * 3, math.sin(t) * 3)
                                              for t in (k * math.pi / 3 for k in range(6))), STYLE),))
    text = written(spec)
    numbers = re.findall(r"(?<=[\s>])-?\d[\d.e+-]*(?=[\s<])", text)
    assert numbers and all(re.fullmatch(r"-?\d+(\.\d{1,6})?", n) for n in numbers)
    assert all(n != "-0" for n in numbers)
    assert max(len(line) for line in text.splitlines()) < 120


def test_camera_looks_straight_down_on_the_whole_building():
    spec = Spec("wide", rooms=(rect_room("r", -3, 1, 17, 6),), obstacles=(Obstacle("sphere", (8, -4), radius=0.5),))
    building = build_geometry(spec)
    camera = etree.fromstring(world_sdf(building).encode()).find("world/gui/camera")
    x, y, z, roll, pitch, yaw = map(float, camera.findtext("pose").split())
    assert (roll, pitch, yaw) == (0, pytest.approx(math.pi / 2, abs=1e-6), pytest.approx(math.pi / 2, abs=1e-6))
    x0, y0, x1, y1 = building.bounds
    assert (x, y) == (pytest.approx((x0 + x1) / 2), pytest.approx((y0 + y1) / 2))
    # a 60° field of view across x; at most 4:3, so 2·atan(tan 30° · 3/4) along y; seen at the walls' tops
    distance = z - 2.5
    assert distance * math.tan(math.radians(30)) >= (x1 - x0) / 2 + 0.5
    assert distance * math.tan(math.radians(30)) * 0.75 >= (y1 - y0) / 2 + 0.5
    assert distance < 1.5 * max((x1 - x0) / 2 / math.tan(math.radians(30)), 2)   # not absurdly high either


def test_versions_and_model_folder():
    from worldgen.cli.build import SDF_VERSION_CHOICES, build_command
    from worldgen.launch.targets import SDF_VERSION
    from worldgen.sdf.writer import DEFAULT_SDF_VERSION

    # the command lists the versions itself (so that the CLI starts without lxml); they must be the writer's
    assert SDF_VERSION_CHOICES == SDF_VERSIONS
    # no default of its own: each --ros target's (noetic's and humble's the writer's, jazzy's Gazebo Sim's 1.8)
    assert [p.default for p in build_command.params if p.name == "sdf_version"] == [None]
    assert SDF_VERSION["noetic"] == SDF_VERSION["humble"] == DEFAULT_SDF_VERSION and SDF_VERSION["jazzy"] == "1.8"
    building = build_geometry(Spec("lab", rooms=(rect_room("r", 0, 0, 4, 3),)))
    for version in SDF_VERSIONS:
        assert etree.fromstring(world_sdf(building, version).encode()).get("version") == version
    with pytest.raises(ValueError):
        world_sdf(building, "1.5")
    model = etree.fromstring(model_sdf(building, "1.7").encode())
    assert (model.tag, model.get("version"), model.find("model").get("name")) == ("sdf", "1.7", "lab")
    assert model.find("model/pose").text == "2 1.5 0 0 0 0"
    config = etree.fromstring(model_config(building, "1.7", "a lab").encode())
    assert (config.findtext("name"), config.findtext("sdf"), config.find("sdf").get("version"),
            config.findtext("description")) == ("lab", "model.sdf", "1.7", "a lab")
    files = planned_files(building, "out", model_dir=True)
    assert [str(p) for p in files] == ["out/lab.world", "out/lab/model.config", "out/lab/model.sdf"]
    assert len(read_boxes(files[next(iter(files))])) == len(read_boxes(model_sdf(building))) == 4


def test_editor_room_matches_the_class_world(corpus):
    """Our build of the class's room has the boxes Gazebo saved: four 5 × 0.15 × 2.5 walls whose centres sit
    4.85 m apart, the same after composing poses."""
    path = (corpus / "worlds"
            / "Intro-Robotics-UChicago-Spring-2022__warmup_project__worlds_turtlebot3_in_enclosed_room.world")
    theirs = [b for b in read_boxes(path.read_text()) if b.model == "5m_room"]
    ours = read_boxes(written(Spec("5m_room", rooms=(rect_room("room", 0, 0, 4.85, 4.85),))))

    def shape(boxes):
        centres = sorted((round(b.footprint.centroid.x, 4), round(b.footprint.centroid.y, 4)) for b in boxes)
        x0, y0 = centres[0]
        sizes = sorted(round(b.footprint.area / T, 3) for b in boxes)
        return sorted((round(x - x0, 3), round(y - y0, 3)) for x, y in centres), sizes, {(b.z0, b.z1) for b in boxes}

    assert shape(ours) == shape(theirs)
    assert shape(ours)[1] == [5.0] * 4


# ---------------------------------------------------------------------------------------- rooms close
SHAPES = {
    "rectangle": [(0, 0), (5, 0), (5, 4), (0, 4)],
    "L-shape": [(0, 0), (6, 0), (6, 3), (3, 3), (3, 6), (0, 6)],
    "rotated": [(math.cos(0.4) * x - math.sin(0.4) * y + 2, math.sin(0.4) * x + math.cos(0.4) * y - 1)
                for x, y in [(0, 0), (5, 0), (5, 3), (2, 5), (0, 3)]],
    "acute 30°": [(0, 0), (5, 0), (5 * math.cos(math.pi / 6), 5 * math.sin(math.pi / 6))],
    "obtuse 150°": [(0, 0), (4, 0), (4, 2), (2, 2 + 2 * math.tan(math.radians(15))), (0, 2)],
}


@pytest.mark.parametrize("shape", SHAPES)
def test_rooms_close_in_the_written_world(shape):
    room = Room("r", tuple(SHAPES[shape]), STYLE)
    boxes = read_boxes(written(Spec("p", rooms=(room,))))
    floor = enclosed_floor(slice_at(boxes, LIDAR_Z), room)
    assert floor is not None, "the room's floor reaches the outside"
    inside = Polygon(room.vertices).buffer(-T / 2, join_style="mitre", mitre_limit=1e3)
    assert 0 <= inside.area - floor.area < inside.length * 0.0006     # all of the floor, less the 0.5 mm buffer
    union, ideal = slice_at(boxes, 1.0), ideal_band([room])
    assert union.symmetric_difference(ideal).area < 1e-4
    assert union.difference(ideal.buffer(0.001)).area < 1e-12          # nothing pokes out by more than 1 mm


def test_two_rooms_sharing_a_wall_close_and_the_shared_stretch_is_one_box():
    a, b = rect_room("a", 0, 0, 4, 4), rect_room("b", 4, 1, 7, 3)
    boxes = read_boxes(written(Spec("two", rooms=(a, b))))
    union = slice_at(boxes, LIDAR_Z)
    assert enclosed_floor(union, a) is not None and enclosed_floor(union, b) is not None
    for y in [1 + T + k * (2 - 2 * T) / 10 for k in range(11)]:        # along the shared stretch x = 4
        covering = [bx for bx in boxes if bx.footprint.contains(shapely.Point(4, y))]
        assert len(covering) == 1, y
    assert slice_at(boxes, 1).symmetric_difference(ideal_band([a, b])).area < 1e-4


# ---------------------------------------------------------------------------------------------- openings
def gaps_along(line: LineString, union) -> list[tuple[float, float]]:
    """Where a centre-line is not covered: (from, to) distances from its start."""
    rest = line.difference(union)
    parts = [g for g in getattr(rest, "geoms", [rest]) if not g.is_empty and g.length > 1e-6]
    return sorted(tuple(sorted((line.project(shapely.Point(g.coords[0])), line.project(shapely.Point(g.coords[-1])))))
                  for g in parts)


def test_openings_are_where_the_spec_puts_them():
    vs = [(0, 0), (6, 0), (6, 4), (2, 5), (0, 4)]                      # wall 2 is slanted
    room = Room("r", tuple(vs), STYLE, (Opening("door", 0, 1.2, 0.9, 2.0), Opening("window", 2, 1.5, 1.0, 0.8, 0.6),
                                        Opening("door", 2, 0.3, 0.8, 2.5)))
    boxes = read_boxes(written(Spec("o", rooms=(room,))))
    wall0, wall2 = LineString([vs[0], vs[1]]), LineString([vs[2], vs[3]])
    for z, line, expected in [(1.0, wall0, [(1.2, 2.1)]), (2.2, wall0, []),
                              (1.0, wall2, [(0.3, 1.1), (1.5, 2.5)]), (0.3, wall2, [(0.3, 1.1)]),
                              (1.5, wall2, [(0.3, 1.1)]), (2.45, wall2, [(0.3, 1.1)])]:
        found = gaps_along(line, slice_at(boxes, z))
        assert len(found) == len(expected), (z, found)
        for (a, b), (ea, eb) in zip(found, expected):
            assert abs(a - ea) <= 0.001 and abs(b - eb) <= 0.001, (z, found)


# ------------------------------------------------------------------------------------- repeatability, CLI
ROOM_YAML = """\
name: cli_room
rooms:
  - name: main
    rect: {center: [0, 0], size: [4.85, 4.85]}
    openings:
      - {type: door, wall: 0, offset: 1.2, width: 0.9}
  - name: side
    polygon: [[2.425, -1], [5, -1], [5, 1], [2.425, 1]]
segments:
  - {from: [-1, 0.5], to: [0.5, 2]}
obstacles:
  - {shape: cylinder, radius: 0.15, height: 0.5, at: [-1, -1]}
robot: {model: burger, at: [0, -1], yaw: 0}
"""


def test_build_command_writes_the_world_and_repeats_byte_for_byte(tmp_path):
    spec = tmp_path / "room.yaml"
    spec.write_text(ROOM_YAML)
    runner = CliRunner()
    first = runner.invoke(main, ["build", str(spec), "-o", str(tmp_path / "a"), "--model-dir"])
    assert first.exit_code == 0, first.output
    assert first.output.splitlines() == [f"wrote {tmp_path / 'a' / 'cli_room.world'}",
                                         f"wrote {tmp_path / 'a' / 'cli_room' / 'model.config'}",
                                         f"wrote {tmp_path / 'a' / 'cli_room' / 'model.sdf'}"]
    second = runner.invoke(main, ["build", str(spec), "-o", str(tmp_path / "b"), "--model-dir", "--sdf-version", "1.6"])
    assert second.exit_code == 0
    for rel in ("cli_room.world", "cli_room/model.config", "cli_room/model.sdf"):
        assert (tmp_path / "a" / rel).read_bytes() == (tmp_path / "b" / rel).read_bytes()
    world = etree.parse(str(tmp_path / "a" / "cli_room.world")).getroot().find("world")
    walls = world.findall("model[@name='cli_room']/link")
    assert len(walls) == 4 + 3 + 1             # main, side (its west wall is main's east wall), the segment
    assert world.find("model[@name='obstacle_0']/link/collision/geometry/cylinder") is not None


def test_build_refuses_to_overwrite_and_writes_nothing(tmp_path):
    spec = tmp_path / "room.yaml"
    spec.write_text(ROOM_YAML)
    (tmp_path / "cli_room").mkdir()
    (tmp_path / "cli_room" / "model.sdf").write_text("mine")
    done = CliRunner().invoke(main, ["build", str(spec), "-o", str(tmp_path), "--model-dir"])
    assert done.exit_code == 2 and "exists" in done.output and "--force" in done.output
    assert not (tmp_path / "cli_room.world").exists() and (tmp_path / "cli_room" / "model.sdf").read_text() == "mine"
    forced = CliRunner().invoke(main, ["build", str(spec), "-o", str(tmp_path), "--model-dir", "--force",
                                       "--sdf-version", "1.8"])
    assert forced.exit_code == 0
    assert '<sdf version="1.8">' in (tmp_path / "cli_room" / "model.sdf").read_text()


def test_build_reports_a_geometry_error_on_one_line(tmp_path):
    """A door in the main room's east wall across the point where the side room's wall meets it."""
    spec = tmp_path / "bad.yaml"
    spec.write_text(ROOM_YAML.replace("wall: 0, offset: 1.2, width: 0.9", "wall: 1, offset: 3.0, width: 0.9"))
    done = CliRunner().invoke(main, ["build", str(spec), "-o", str(tmp_path)])
    assert done.exit_code == 2
    assert re.fullmatch(r"worldgen: error: .*bad\.yaml:6: the door on room 'main' wall 1 runs into room 'side' .*\n",
                        done.output)
    assert not list(tmp_path.glob("*.world"))
