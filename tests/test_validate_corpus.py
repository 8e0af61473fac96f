"""Every world and model file of the shared corpus goes through ``worldgen validate``, each with a stated
expectation derived by reading the file; several of them also through the simulator at their launch file's spawn.

The spawn is the world's origin (``--spawn 0,0``) unless said otherwise, the robot a burger, and
``--model-path corpus/gazebo_models`` stands in for the ROBOTIS models folder. Never a traceback: every file
ends as a result with findings.
"""

from __future__ import annotations

import json
import math
import subprocess
import sys

import pytest

# file name → (the error checks expected, why; None = passes)
WORLDS = {
    "HDLahlou__robotics_final_project__world_w_box_and_separate_light.world":
        ({"enclosed", "spawn-clear"}, "its <state> puts unit_box on the origin: the robot spawns inside it"),
    "HDLahlou__robotics_final_project__worlds_tmp.sdf.world":
        ({"enclosed"}, "the maze is model://maze/maze.obj, not on the model path: no walls"),
    "HDLahlou__robotics_final_project__worlds_turtlebot3_loop.world":
        ({"enclosed"}, "model://loop is not on the model path: no walls"),
    "HDLahlou__robotics_final_project__worlds_turtlebot3_maze.world":
        ({"enclosed"}, "model://maze is not on the model path: no walls"),
    "Intro-Robotics-UChicago-Spring-2022__warmup_project__worlds_turtlebot3_in_enclosed_room.world":
        ({"enclosed"}, "the room sits at x -7.3 … -2.6 after its <state>: the origin is outside it"),
    "Purrsephone__tom-jerry__worlds_turtlebot3_empty.world":
        ({"enclosed"}, "sun and ground plane only: no walls"),
    "Purrsephone__tom-jerry__worlds_turtlebot3_in_enclosed_room.world":
        ({"enclosed"}, "a copy of the class room: the origin is outside it"),
    "ROBOTIS-GIT__turtlebot3_simulations@jazzy__turtlebot3_gazebo_worlds_turtlebot3_dqn_stage4.world":
        ({"enclosed"}, "model://turtlebot3_dqn_world is not in the corpus models: no walls"),
    "ROBOTIS-GIT__turtlebot3_simulations@jazzy__turtlebot3_gazebo_worlds_turtlebot3_house.world":
        ({"enclosed"}, "model://turtlebot3_house is not in the corpus models: no walls"),
    "ROBOTIS-GIT__turtlebot3_simulations@jazzy__turtlebot3_gazebo_worlds_turtlebot3_world.world":
        ({"enclosed", "spawn-clear"}, "the middle one of the nine pillars stands on the origin"),
    "ROBOTIS-GIT__turtlebot3_simulations@noetic-devel__turtlebot3_gazebo_worlds_empty.world":
        ({"enclosed"}, "sun and ground plane only: no walls"),
    "ROBOTIS-GIT__turtlebot3_simulations@noetic-devel__turtlebot3_gazebo_worlds_turtlebot3_house.world":
        ({"enclosed"}, "model://turtlebot3_house is not in the corpus models: no walls"),
    "ROBOTIS-GIT__turtlebot3_simulations@noetic-devel__turtlebot3_gazebo_worlds_turtlebot3_stage_1.world":
        (None, "the 4 m square arena round the origin"),
    "ROBOTIS-GIT__turtlebot3_simulations@noetic-devel__turtlebot3_gazebo_worlds_turtlebot3_stage_2.world":
        (None, "the square arena; its four pillars stand at (±0.6, ±0.6)"),
    "ROBOTIS-GIT__turtlebot3_simulations@noetic-devel__turtlebot3_gazebo_worlds_turtlebot3_stage_3.world":
        (None, "as stage 2, the pillars not static"),
    "ROBOTIS-GIT__turtlebot3_simulations@noetic-devel__turtlebot3_gazebo_worlds_turtlebot3_stage_4.world":
        (None, "the 5 m plaza with inner walls; the origin is free"),
    "ROBOTIS-GIT__turtlebot3_simulations@noetic-devel__turtlebot3_gazebo_worlds_turtlebot3_world.world":
        ({"enclosed", "spawn-clear"}, "the middle pillar stands on the origin"),
    "andreeqp__RobotPallet12__building_editor_models_Untitled_model.sdf.world":
        ({"sizes", "enclosed"}, "a zero-height box, and the warehouse's 2.95 m doorway in its west wall"),
    "gazebosim__gazebo-classic__worlds_willowgarage.world":
        ({"enclosed"}, "model://willowgarage is not in the corpus models: no walls"),
    "husky__husky__husky_gazebo_worlds_clearpath_playpen.world":
        ({"enclosed"}, "jersey barriers with gaps between them, on a 0.1 m asphalt slab (the floor)"),
    "imkishan96__Build_my_world__Project_1_world_EMPTY_STUDIO.world":
        ({"enclosed"}, "the studio's 0.9 m door in Wall_9"),
    "linj24__q_learning_project__worlds_turtlebot3_tags_and_dumbbells_no_robot.world":
        ({"enclosed"}, "tags and dumbbells are meshes of a package not on the path: nothing stands"),
    "sydneyjenkins__20600_final_project__worlds_turtlebot3_numbers_and_dumbbells_no_robot.world":
        ({"enclosed"}, "number and dumbbell meshes not on the path: nothing stands"),
    "unitreerobotics__unitree_ros__unitree_gazebo_worlds_stairs.world":
        ({"enclosed", "spawn-clear"}, "a 0.18 m platform (too high to be floor) on the origin, no walls"),
}
MODELS = {
    "HDLahlou__robotics_final_project__models_loop_model.sdf":
        ({"enclosed"}, "its only collision is model://loop/loop.obj, not on the path"),
    "HDLahlou__robotics_final_project__models_maze_model.sdf":
        ({"enclosed"}, "its only collision is model://maze/maze.obj, not on the path"),
    "HDLahlou__robotics_final_project__models_wall_model.sdf":
        ({"enclosed", "spawn-clear"}, "one wall box through the origin"),
    "ROBOTIS-GIT__turtlebot3_simulations@jazzy__turtlebot3_gazebo_models_turtlebot3_dqn_world_inner_walls_model.sdf":
        ({"enclosed"}, "the stage's inner walls only, with gaps between them"),
    "ROBOTIS-GIT__turtlebot3_simulations@noetic-devel__turtlebot3_gazebo_models_turtlebot3_plaza_model.sdf":
        (None, "the closed 5 m plaza"),
    "ROBOTIS-GIT__turtlebot3_simulations@noetic-devel__turtlebot3_gazebo_models_turtlebot3_square_model.sdf":
        (None, "the closed 4 m square"),
    "ROBOTIS-GIT__turtlebot3_simulations@noetic-devel__turtlebot3_gazebo_models_turtlebot3_world_model.sdf":
        ({"enclosed", "spawn-clear"}, "the middle pillar stands on the origin"),
    "andreeqp__RobotPallet12__building_editor_models_Almacen_RobotPallet_SIN_PUERTA_model.sdf":
        ({"enclosed"}, "the warehouse without its door: three openings"),
    "andreeqp__RobotPallet12__building_editor_models_Almacen_RobotPallet_model.sdf":
        ({"enclosed"}, "the warehouse: the 2.95 m doorway in its west wall"),
    "imkishan96__Build_my_world__Project_1_model_studio_model.sdf":
        ({"enclosed", "spawn-clear"}, "Wall_11 runs through the model origin"),
    "unitreerobotics__unitree_ros__unitree_gazebo_worlds_building_editor_models_stairs_model.sdf":
        ({"enclosed"}, "one wall and stairs: nothing surrounds the origin"),
}


def validate_json(*args) -> tuple[int, dict, str]:
    proc = subprocess.run([sys.executable, "-m", "worldgen", "validate", "--format", "json", *map(str, args)],
                          capture_output=True, text=True, timeout=600)
    assert "Traceback" not in proc.stderr, proc.stderr
    assert proc.returncode in (0, 1), proc.stderr
    return proc.returncode, json.loads(proc.stdout), proc.stderr


@pytest.fixture(scope="module")
def at_origin(corpus):
    """All corpus worlds and models at the origin, geometric checks only, two at a time."""
    files = sorted((corpus / "worlds").iterdir()) + sorted((corpus / "models").iterdir())
    code, doc, _ = validate_json(*files, "--skip-sim", "-j", "2", "--spawn", "0,0",
                                 "--model-path", corpus / "gazebo_models")
    assert code == 1
    return {r["path"].rsplit("/", 1)[-1]: r for r in doc["results"]}, files


def test_every_corpus_file_has_a_stated_expectation(at_origin):
    results, files = at_origin
    assert sorted(f.name for f in files) == sorted({**WORLDS, **MODELS})
    assert len(results) == len(files)


@pytest.mark.parametrize("name", sorted({**WORLDS, **MODELS}))
def test_corpus_file_outcome(at_origin, name):
    results, _ = at_origin
    expected, why = {**WORLDS, **MODELS}[name]
    r = results[name]
    failed = {f["check"] for f in r["findings"] if f["severity"] == "error"}
    assert failed == (expected or set()), f"{why}: {failed}"
    assert r["ok"] is (expected is None)
    assert r["checks"] == ["parse", "enclosed", "spawn-clear"]


def test_corpus_details_at_origin(at_origin):
    results, _ = at_origin
    studio = results["imkishan96__Build_my_world__Project_1_world_EMPTY_STUDIO.world"]["metrics"]
    [door] = studio["gaps"]
    # Wall_9's pieces leave local x 0.6531 … 1.5531 open; <state> puts the wall at (0.368159, -6.73856) turned
    # 0.014944 rad, so the door's middle is at (1.4711, -6.7221) on the centre-line, the wall 0.15 m thick
    assert door["width"] == pytest.approx(0.9, abs=0.01) and math.dist(door["centre"], (1.4711, -6.7221)) < 0.075
    assert door["robot_passes"] is True
    warehouse = results["andreeqp__RobotPallet12__building_editor_models_Almacen_RobotPallet_model.sdf"]["metrics"]
    widths = sorted(round(g["width"], 3) for g in warehouse["gaps"])
    assert widths[-1] == pytest.approx(2.95, abs=0.01)
    assert widths[0] < 0.005   # the free-standing Door_0 box leaves a 1 mm crack: a warning, no way out
    playpen = results["husky__husky__husky_gazebo_worlds_clearpath_playpen.world"]["metrics"]
    assert playpen["floor"] == "asphalt_plane/link/collision" and playpen["floor_height_m"] == pytest.approx(0.05)
    assert playpen["slice_height_m"] == pytest.approx(0.232)
    room = results["Intro-Robotics-UChicago-Spring-2022__warmup_project__worlds_turtlebot3_in_enclosed_room.world"]
    assert room["metrics"]["nearest_room"] == pytest.approx([-7.257, -3.761, -2.557, 0.939], abs=0.01)
    robotis = "ROBOTIS-GIT__turtlebot3_simulations@noetic-devel__turtlebot3_gazebo_"
    for name in (robotis + "worlds_turtlebot3_world.world", robotis + "models_turtlebot3_world_model.sdf"):
        assert results[name]["metrics"]["spawn_inside"] == "ros_symbol/symbol/two_two"


def test_without_a_spawn_the_moved_class_room_is_checked_from_its_middle(corpus):
    """No spawn given: the room the <state> block moved to x -7.3 … -2.6 is checked from its deepest point, not
    from the origin outside it, and the report says so."""
    room = corpus / "worlds" / "Intro-Robotics-UChicago-Spring-2022__warmup_project__worlds_turtlebot3_in_enclosed_room.world"
    code, doc, _ = validate_json(room, "--skip-sim")
    [r] = doc["results"]
    assert code == 0 and r["metrics"]["enclosed"] is True
    # the room's inner faces are x -7.257 … -2.557, y -3.761 … 0.939: its middle is (-4.907, -1.411)
    assert math.dist(r["spawn"][:2], (-4.907, -1.411)) < 0.05
    assert r["spawn_source"].startswith("no spawn given: checked from the deepest free point of the world's only "
                                        "closed room at (-4.9")


# -------------------------------------------------------------------------------- with the simulator

SIM_RUNS = [
    # spawn from the launch files in turtlebot3_gazebo (reference/turtlebot3.md §10)
    ("0,0", ["ROBOTIS-GIT__turtlebot3_simulations@noetic-devel__turtlebot3_gazebo_worlds_turtlebot3_stage_1.world",
             "ROBOTIS-GIT__turtlebot3_simulations@noetic-devel__turtlebot3_gazebo_worlds_turtlebot3_stage_2.world"]),
    ("-0.7,0", ["ROBOTIS-GIT__turtlebot3_simulations@noetic-devel__turtlebot3_gazebo_worlds_turtlebot3_stage_4.world"]),
    ("-2,-0.5", ["ROBOTIS-GIT__turtlebot3_simulations@noetic-devel__turtlebot3_gazebo_worlds_turtlebot3_world.world",
                 "ROBOTIS-GIT__turtlebot3_simulations@jazzy__turtlebot3_gazebo_worlds_turtlebot3_world.world"]),
]


@pytest.mark.parametrize("spawn, names", SIM_RUNS, ids=["stage_1_2", "stage_4", "turtlebot3_world"])
def test_robotis_worlds_pass_with_their_launch_spawn(corpus, spawn, names):
    code, doc, _ = validate_json(*(corpus / "worlds" / n for n in names), "--spawn", spawn, "-j", "2",
                                 "--model-path", corpus / "gazebo_models")
    assert code == 0, [f for r in doc["results"] for f in r["findings"] if f["severity"] == "error"]
    for r in doc["results"]:
        m = r["metrics"]
        assert r["checks"][-4:] == ["settle", "lidar", "spin", "stop-at-wall"]
        assert m["enclosed"] is True and m["spin_drift_m"] < 0.05 and m["spin_touched"] == []
        assert m["stop_distance_m"] == pytest.approx(0.5, abs=0.05) and m["stop_touched"] == []
        # the 4 m square keeps every wall within the LiDAR's 3.5 m; the turtle world's far side is 4.9 m away
        if "stage_1" in r["path"]:
            assert m["lidar_no_hit_beams"] == 0
        if "turtlebot3_world" in r["path"]:
            assert m["lidar_no_hit_beams"] > 0


def test_empty_world_in_the_simulator(corpus):
    empty = corpus / "worlds" / "ROBOTIS-GIT__turtlebot3_simulations@noetic-devel__turtlebot3_gazebo_worlds_empty.world"
    code, doc, _ = validate_json(empty, "--lidar-no-hit", "zero")
    [r] = doc["results"]
    assert code == 1 and r["metrics"]["enclosed"] is False
    assert r["metrics"]["lidar_no_hit_beams"] == 360 and r["metrics"]["lidar_no_hit_reading"] == 0.0
    assert [f["severity"] for f in r["findings"] if f["check"] == "stop-at-wall"] == ["info"]
    assert r["metrics"]["settle_height_m"] == pytest.approx(0.0, abs=0.01)


def test_robotis_jazzy_worlds_name_their_fuel_includes_without_fetching(at_origin):
    """Gazebo Sim worlds include Fuel's "Ground Plane" and "Sun" by URL: each is named as the Fuel model it is,
    stood in for (a plane at z = 0; a light, nothing to collide with), never downloaded, never a warning."""
    results, _ = at_origin
    jazzy = "ROBOTIS-GIT__turtlebot3_simulations@jazzy__turtlebot3_gazebo_worlds_"
    for name, fuel in (("turtlebot3_world.world", {"Ground Plane", "Sun"}),
                       ("turtlebot3_house.world", {"Ground Plane", "Sun"}),
                       ("turtlebot3_dqn_stage4.world", {"Ground Plane"})):
        notes = [f for f in results[jazzy + name]["findings"] if f["check"] == "include" and "Fuel" in f["message"]]
        assert {f["message"].split("'")[1] for f in notes} == fuel, notes
        assert {f["severity"] for f in notes} == {"info"}
