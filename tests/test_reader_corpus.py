"""Every world and model in the shared corpus, read the way a student's file would be, one table row per file.

Each row was worked out by reading the file (model/link/collision poses, the first <state>, sizes), not by printing
what the reader returns: ``static``/``dynamic`` count the non-plane collision shapes of static and non-static models;
``bbox`` is (xmin, ymin, zmin, xmax, ymax, zmax) of the static shapes (of all shapes when none is static), ±1 cm;
``problems`` lists every warning and error expected (no others may appear), ``notes`` some expected infos.
Paths: ``None`` = no model path, ``"tb3"`` = corpus/gazebo_models, ``"linked"`` = the HDLahlou model.sdf files of
corpus/models linked into model folders (their .obj meshes are not in the corpus).

No corpus file is malformed XML (all 35 parse), so the malformed case is a corpus world with one broken attribute.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest

from worldgen.core.errors import WorldFileError
from worldgen.core import poses
from worldgen.sdf.reader import read_world


@pytest.fixture(autouse=True)
def _no_model_path(monkeypatch):
    for name in ("GAZEBO_MODEL_PATH", "SDF_PATH", "ROS_PACKAGE_PATH"):
        monkeypatch.delenv(name, raising=False)


@dataclass(frozen=True)
class Row:
    file: str
    paths: str | None = None
    planes: int = 0
    static: int = 0
    dynamic: int = 0
    bbox: tuple | None = None
    problems: tuple = ()   # (severity, check, text in the message)
    notes: tuple = ()      # (check, text in an info message)


CLASS_WORLD = "worlds/Intro-Robotics-UChicago-Spring-2022__warmup_project__worlds_turtlebot3_in_enclosed_room.world"
CLASS_ROOM = (-7.4068, -3.9114, 0.0, -2.4068, 1.0886, 2.5)   # the class room where its <state> puts it
SQUARE = (-2.0, -2.0, 0.0, 2.0, 2.0, 0.5)                     # turtlebot3_square: 4 × 4 m outside, 0.5 m tall
PLAZA = (-2.5, -2.5, 0.0, 2.5, 2.5, 0.5)
TB3_WORLD = (-3.2996, -3.3985, -0.5, 4.6732, 3.3985, 1.532)   # hexagon wall.dae in inches × 0.25, head/feet hexagons
ALMACEN = (-11.4745, -6.5001, 0.0, 10.6881, 3.4814, 2.5)       # ±11.081 × ±4.991 around (-0.393, -1.509)
GROUND = ("include", "ground_plane")
FUEL_GROUND = ("include", "Ground Plane")

ROWS = [
    Row("worlds/HDLahlou__robotics_final_project__world_w_box_and_separate_light.world", planes=1, dynamic=1,
        bbox=(-0.5, -0.5, 0.0, 0.5, 0.5, 1.0),  # unit_box moved by <state> from (0.36, -2.31) to (0, 0)
        notes=(("state", "'unit_box' 2.34 m"), ("static", "unit_box"))),
    Row("worlds/HDLahlou__robotics_final_project__worlds_tmp.sdf.world", dynamic=14,  # two waffle robots, 7 each
        bbox=(-1.947, 2.2466, 0.0, 1.9486, 2.5534, 0.1412),
        problems=(("warning", "mesh", "model://maze/maze.obj"),), notes=(("static", "hunter"), ("static", "player"))),
    Row("worlds/HDLahlou__robotics_final_project__worlds_turtlebot3_loop.world", "linked", planes=1,
        problems=(("warning", "mesh", "model://loop/loop.obj"),),
        notes=(GROUND, ("structure", "<visual> inside <include>"))),
    Row("worlds/HDLahlou__robotics_final_project__worlds_turtlebot3_maze.world", "linked",
        problems=(("warning", "mesh", "model://maze/maze.obj"), ("warning", "include", "model://player_light"),
                  ("warning", "include", "model://hunter"))),
    Row(CLASS_WORLD, planes=1, static=4, bbox=CLASS_ROOM, notes=(("state", "'5m_room' 1.67 m"),)),
    Row("worlds/Purrsephone__tom-jerry__worlds_turtlebot3_empty.world", planes=1),
    Row("worlds/Purrsephone__tom-jerry__worlds_turtlebot3_in_enclosed_room.world", planes=1, static=4,
        bbox=CLASS_ROOM, notes=(("state", "'5m_room' 1.67 m"),)),
    Row("worlds/ROBOTIS-GIT__turtlebot3_simulations@jazzy__turtlebot3_gazebo_worlds_turtlebot3_dqn_stage4.world",
        "tb3", planes=1, notes=(FUEL_GROUND,),
        problems=(("warning", "include", "model://turtlebot3_dqn_world:"),
                  ("warning", "include", "model://turtlebot3_dqn_world/inner_walls"),
                  ("warning", "include", "model://turtlebot3_dqn_world/obstacle1"),
                  ("warning", "include", "model://turtlebot3_dqn_world/obstacle2"))),
    Row("worlds/ROBOTIS-GIT__turtlebot3_simulations@jazzy__turtlebot3_gazebo_worlds_turtlebot3_house.world", "tb3",
        planes=1, problems=(("warning", "include", "model://turtlebot3_house"),), notes=(FUEL_GROUND,)),
    Row("worlds/ROBOTIS-GIT__turtlebot3_simulations@jazzy__turtlebot3_gazebo_worlds_turtlebot3_world.world", "tb3",
        planes=1, static=15, bbox=TB3_WORLD, notes=(FUEL_GROUND,)),
    Row("worlds/ROBOTIS-GIT__turtlebot3_simulations@noetic-devel__turtlebot3_gazebo_worlds_empty.world", planes=1,
        notes=(GROUND,)),
    Row("worlds/ROBOTIS-GIT__turtlebot3_simulations@noetic-devel__turtlebot3_gazebo_worlds_turtlebot3_house.world",
        "tb3", planes=1, problems=(("warning", "include", "model://turtlebot3_house"),)),
    Row("worlds/ROBOTIS-GIT__turtlebot3_simulations@noetic-devel__turtlebot3_gazebo_worlds_turtlebot3_stage_1.world",
        "tb3", planes=1, static=4, bbox=SQUARE),
    Row("worlds/ROBOTIS-GIT__turtlebot3_simulations@noetic-devel__turtlebot3_gazebo_worlds_turtlebot3_stage_2.world",
        "tb3", planes=1, static=8, bbox=SQUARE),  # + 4 static pillars at (±0.6, ±0.6)
    Row("worlds/ROBOTIS-GIT__turtlebot3_simulations@noetic-devel__turtlebot3_gazebo_worlds_turtlebot3_stage_3.world",
        "tb3", planes=1, static=4, dynamic=4, bbox=SQUARE, notes=(("static", "'obstacle'"),)),
    Row("worlds/ROBOTIS-GIT__turtlebot3_simulations@noetic-devel__turtlebot3_gazebo_worlds_turtlebot3_stage_4.world",
        "tb3", planes=1, static=12, dynamic=2, bbox=PLAZA,
        notes=(("static", "'obstacle_1'"), ("static", "'obstacle_2'"))),
    Row("worlds/ROBOTIS-GIT__turtlebot3_simulations@noetic-devel__turtlebot3_gazebo_worlds_turtlebot3_world.world",
        "tb3", planes=1, static=15, bbox=TB3_WORLD),
    Row("worlds/andreeqp__RobotPallet12__building_editor_models_Untitled_model.sdf.world", planes=1, static=14,
        dynamic=18,  # burger 5, naokoeye's base 1, 12 demo_cube clones; demo_cube itself has a zero size
        bbox=(-12.8523, -5.4685, 0.0, 9.3103, 4.5131, 2.5),
        problems=(("error", "sizes", "demo_cube/link/collision"),
                  ("warning", "mesh", "model://naokoeye/meshes/naokoeyev2.dae")),
        notes=(("state", "scales model 'demo_cube'"), ("static", "turtlebot3_burger"))),
    Row("worlds/gazebosim__gazebo-classic__worlds_willowgarage.world", planes=1,
        problems=(("warning", "include", "model://willowgarage"),), notes=(GROUND,)),
    Row("worlds/husky__husky__husky_gazebo_worlds_clearpath_playpen.world", planes=1,
        static=103,  # 17 jersey barriers × 6 boxes + the 20 × 20 m asphalt slab; barriers turned by <state>
        bbox=(-10.8056, -10.4054, -0.05, 10.588, 10.4054, 1.143),
        problems=tuple(("warning", "mesh", f"model://{m}/") for m in
                       ("fire_hydrant", "dumpster", "construction_cone", "construction_barrel")),
        notes=(("state", "'Construction Barrel_3'"),)),
    Row("worlds/imkishan96__Build_my_world__Project_1_world_EMPTY_STUDIO.world", planes=1, static=28, dynamic=10,
        bbox=(-7.6196, -6.9309, 0.0, 2.869, 2.5728, 2.5),  # the studio turned 90.9° by <state>
        problems=(("warning", "structure", "Domino_population1"), ("warning", "structure", "Domino_population2")),
        notes=(("state", "'studio' 3.96 m, 91°"), ("static", "'Simple_Car'"))),
    Row("worlds/linj24__q_learning_project__worlds_turtlebot3_tags_and_dumbbells_no_robot.world", planes=1,
        problems=tuple(("warning", "mesh", f"gazebo_custom_meshes/{m}.dae") for m in
                       ("robot_tag_1", "robot_tag_2", "robot_tag_3", "robot_dumbbell_red", "robot_dumbbell_blue",
                        "robot_dumbbell_green")),
        notes=(("state", "'robot_dumbbell_test'"), ("state", "'robot_dumbbell_test_clone_0'"))),
    Row("worlds/sydneyjenkins__20600_final_project__worlds_turtlebot3_numbers_and_dumbbells_no_robot.world", planes=1,
        problems=(("warning", "mesh", "model://number1/meshes/number.dae"),
                  ("warning", "mesh", "robot_dumbbell_red.dae"), ("warning", "mesh", "robot_dumbbell_blue.dae"),
                  ("warning", "mesh", "robot_dumbbell_green.dae")),
        notes=(("state", "'robot_dumbbell_test'"),)),
    Row("worlds/unitreerobotics__unitree_ros__unitree_gazebo_worlds_stairs.world", planes=1, static=3,
        bbox=(-1.0, -1.0, 0.0, 6.2, 1.0, 0.72),
        problems=(("warning", "include", "model:///home/unitree/"), ("warning", "structure", "<gravity> inside"))),
    Row("models/HDLahlou__robotics_final_project__models_loop_model.sdf",
        problems=(("warning", "mesh", "model://loop/loop.obj"),)),
    Row("models/HDLahlou__robotics_final_project__models_maze_model.sdf",
        problems=(("warning", "mesh", "model://maze/maze.obj"),)),
    Row("models/HDLahlou__robotics_final_project__models_wall_model.sdf", static=1,
        bbox=(-2.5, -0.025, 0.0, 2.5, 0.025, 0.5)),
    Row("models/ROBOTIS-GIT__turtlebot3_simulations@jazzy__turtlebot3_gazebo_models_turtlebot3_dqn_world_inner_walls"
        "_model.sdf", static=7, bbox=(-2.5, -2.5, 0.0, 2.4, 2.4, 0.5)),
    Row("models/ROBOTIS-GIT__turtlebot3_simulations@noetic-devel__turtlebot3_gazebo_models_turtlebot3_plaza_model.sdf",
        static=12, bbox=PLAZA),
    Row("models/ROBOTIS-GIT__turtlebot3_simulations@noetic-devel__turtlebot3_gazebo_models_turtlebot3_square_model"
        ".sdf", static=4, bbox=SQUARE),
    Row("models/ROBOTIS-GIT__turtlebot3_simulations@noetic-devel__turtlebot3_gazebo_models_turtlebot3_world_model.sdf",
        "tb3", static=15, bbox=TB3_WORLD),
    Row("models/andreeqp__RobotPallet12__building_editor_models_Almacen_RobotPallet_SIN_PUERTA_model.sdf", static=9,
        bbox=ALMACEN),
    Row("models/andreeqp__RobotPallet12__building_editor_models_Almacen_RobotPallet_model.sdf", static=14,
        bbox=ALMACEN),  # Wall_11 split into 4 boxes around a door and a window
    Row("models/imkishan96__Build_my_world__Project_1_model_studio_model.sdf", static=28,
        bbox=(-9.3465, -2.6861, 0.0, 0.0036, 7.664, 2.5)),
    Row("models/unitreerobotics__unitree_ros__unitree_gazebo_worlds_building_editor_models_stairs_model.sdf",
        static=4, bbox=(3.2, -0.991, 0.0, 4.2, 1.009, 0.72)),
]


def aabb(shapes) -> tuple:
    """World-frame bounding box of shapes (a cylinder by its own bounding box, exact when it stands upright)."""
    points = []
    for s in shapes:
        r = poses.quat_matrix(*s.orientation)
        if s.kind == "mesh":
            local = np.asarray(s.vertices)
        else:
            half = (np.array(s.size) / 2 if s.kind == "box" else
                    np.array([s.radius, s.radius, (s.length or 2 * s.radius) / 2]))
            local = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]) * half
        points.append(local @ r.T + np.array(s.position))
    allp = np.vstack(points)
    return tuple(allp.min(axis=0)) + tuple(allp.max(axis=0))


@pytest.fixture()
def linked_models(corpus, tmp_path) -> Path:
    """Model folders for the HDLahlou models: a model.config and a link to the corpus model.sdf (nothing copied)."""
    for name in ("loop", "maze", "wall"):
        folder = tmp_path / "models" / name
        folder.mkdir(parents=True)
        (folder / "model.config").write_text(f"<model><name>{name}</name><sdf version='1.7'>model.sdf</sdf></model>")
        target = corpus / "models" / f"HDLahlou__robotics_final_project__models_{name}_model.sdf"
        (folder / "model.sdf").symlink_to(target)
    return tmp_path / "models"


def test_the_table_covers_every_corpus_world_and_model(corpus):
    on_disk = {f"{d}/{p.name}" for d in ("worlds", "models") for p in (corpus / d).iterdir()}
    assert on_disk == {row.file for row in ROWS}


@pytest.mark.parametrize("row", ROWS, ids=lambda r: r.file.split("/", 1)[1].split("__", 1)[-1][-60:])
def test_corpus_file(row: Row, corpus, request):
    paths = {None: [], "tb3": [corpus / "gazebo_models"]}.get(row.paths)
    if row.paths == "linked":
        paths = [request.getfixturevalue("linked_models")]
    scene = read_world(corpus / row.file, model_paths=paths)

    planes = [s for s in scene.shapes if s.kind == "plane"]
    static = [s for s in scene.obstacles() if s.static]
    dynamic = [s for s in scene.obstacles() if not s.static]
    assert (len(planes), len(static), len(dynamic)) == (row.planes, row.static, row.dynamic)
    if row.bbox is not None:
        assert aabb(static or dynamic) == pytest.approx(row.bbox, abs=0.01)

    problems = [f for f in scene.findings if f.severity in ("error", "warning")]
    assert sorted((f.severity, f.check) for f in problems) == sorted((s, c) for s, c, _ in row.problems), \
        [f.message for f in problems]
    for severity, check, text in row.problems:
        assert any(f.severity == severity and f.check == check and text in f.message for f in problems), text
    for check, text in row.notes:
        assert any(f.severity == "info" and f.check == check and text in f.message for f in scene.findings), text
    assert all(f.where for f in scene.findings)
    assert all(f.fix for f in problems)


def test_class_room_walls_come_out_where_the_state_puts_them(corpus):
    path = corpus / CLASS_WORLD
    walls = {s.link: s.position for s in read_world(path).obstacles()}
    # state: 5m_room at (-3.50426, -1.1439); Wall_1/Wall_3 run along y, Wall_0/Wall_2 along x
    assert walls["Wall_1"][:2] == pytest.approx((-7.33176, -1.4114), abs=1e-4)
    assert walls["Wall_3"][:2] == pytest.approx((-2.48176, -1.4114), abs=1e-4)
    assert walls["Wall_0"][:2] == pytest.approx((-4.90676, 1.0136), abs=1e-4)
    assert walls["Wall_2"][:2] == pytest.approx((-4.90676, -3.8364), abs=1e-4)
    # without the state the room sits at its <pose> (-3.9025, -2.7675): Wall_1 at -3.9025 - 3.8275
    unapplied = {s.link: s.position for s in read_world(path, apply_state=False).obstacles()}
    assert unapplied["Wall_1"][:2] == pytest.approx((-7.73, -3.035), abs=1e-4)


def test_husky_barriers_are_turned_by_the_state(corpus):
    path = corpus / "worlds/husky__husky__husky_gazebo_worlds_clearpath_playpen.world"

    def upright(scene):
        return next(s for s in scene.shapes if s.model == "jersey_barrier_10" and s.name == "upright")

    moved, written = upright(read_world(path)), upright(read_world(path, apply_state=False))
    assert moved.position == pytest.approx((-10.0774, -2.27159, 0.5715), abs=1e-4)
    assert poses.quat_matrix(*moved.orientation)[:2, 0] == pytest.approx((np.cos(1.56), np.sin(1.56)), abs=1e-6)
    assert written.position == pytest.approx((-10.0, -2.0, 0.5715), abs=1e-4)


def test_turtlebot3_world_without_its_model_folder_keeps_only_the_pillars(corpus):
    path = corpus / "models" / ("ROBOTIS-GIT__turtlebot3_simulations@noetic-devel__turtlebot3_gazebo_models_"
                                "turtlebot3_world_model.sdf")
    scene = read_world(path)
    assert [s.kind for s in scene.shapes] == ["cylinder"] * 9
    hexagon, wall = [f for f in scene.findings if f.check == "mesh"]
    assert "hexagon.dae" in hexagon.message and "5 collisions skipped" in hexagon.message
    assert "wall.dae" in wall.message and "1 collision skipped" in wall.message


def test_a_corpus_world_with_a_broken_attribute_raises_with_its_line(corpus, tmp_path):
    text = (corpus / CLASS_WORLD).read_text()
    line = text.splitlines().index("      <link name='Wall_1'>") + 1
    broken = tmp_path / "broken.world"
    broken.write_text(text.replace("<link name='Wall_1'>", "<link name='Wall<1'>"))
    with pytest.raises(WorldFileError) as caught:
        read_world(broken)
    assert caught.value.line == line and f":{line}: not well-formed XML" in str(caught.value)
