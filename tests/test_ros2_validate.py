"""``worldgen validate`` on ROS 2: ament packages in a colcon workspace, each Python launch file checked from the
spawn pose it gives (gazebo_ros's spawn_entity.py on Humble, ros_gz_sim's create on Jazzy), what cannot be read
statically a finding and a check as for a world with no spawn, Gazebo Sim worlds with Fuel includes."""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import CliRunner
from ros2pkgs import (cmake_package, declared_pose_launch, humble_launch, jazzy_spawn_launch, jazzy_world_launch,
                      looped_launch, python_package, room_sdf, unfollowed_call_launch, write)
from worldgen.cli import main

FUEL_CONE = """
    <include>
      <uri>https://fuel.gazebosim.org/1.0/OpenRobotics/models/Construction Cone</uri>
      <pose>0.5 -1 0 0 0 0</pose>
    </include>"""


def validate(*args, env=None) -> tuple[int, dict, str]:
    proc = subprocess.run([sys.executable, "-m", "worldgen", "validate", "--format", "json", *map(str, args)],
                          capture_output=True, text=True, timeout=600, env=env)
    assert "Traceback" not in proc.stderr, proc.stderr
    return proc.returncode, json.loads(proc.stdout), proc.stderr


def errors(row: dict) -> list[str]:
    return [f"{f['check']}: {f['message']}" for f in row["findings"] if f["severity"] == "error"]


@pytest.fixture(scope="module")
def workspace(tmp_path_factory) -> Path:
    """A built colcon workspace: a Humble-style ament_python package (Gazebo Classic), a Jazzy-style ament_cmake
    one (Gazebo Sim), copies of a manifest in install/, and a package colcon is told to ignore."""
    ws = tmp_path_factory.mktemp("ros2") / "colcon_ws"
    src = ws / "src"
    python_package(src, "room_humble", {
        "room.launch.py": humble_launch("room_humble"),
        "declared.launch.py": declared_pose_launch("room_humble"),
        "looped.launch.py": looped_launch("room_humble"),
        "called.launch.py": unfollowed_call_launch("room_humble"),
    }, {"room.world": room_sdf()}, exec_depends=("gazebo_ros",))
    cmake_package(src, "room_jazzy", {"room.launch.py": jazzy_world_launch("room_jazzy"),
                                      "spawn_robot.launch.py": jazzy_spawn_launch()},
                  {"room.sdf": room_sdf(version="1.8", gz_sim=True, extra=FUEL_CONE)})
    ignored = python_package(src / "old", "room_old", {"room.launch.py": humble_launch("room_old")}, {})
    (ignored.parent / "COLCON_IGNORE").write_text("")
    share = ws / "install" / "room_humble" / "share" / "room_humble"
    share.mkdir(parents=True)
    shutil.copy(src / "room_humble" / "package.xml", share)
    (ws / "build" / "room_humble").mkdir(parents=True)
    (ws / "log").mkdir()
    return ws


@pytest.fixture(scope="module")
def checked(workspace):
    code, doc, stderr = validate(workspace, "--skip-sim", "-j", "2")
    return code, {Path(r["path"]).relative_to(workspace / "src").as_posix(): r for r in doc["results"]}, stderr


def test_a_colcon_workspace_reports_each_ament_package_and_launch_file(checked):
    code, rows, stderr = checked
    assert "colcon_ws: 2 ament packages found" in stderr
    assert list(rows) == [
        "room_humble", "room_humble/launch/called.launch.py", "room_humble/launch/declared.launch.py",
        "room_humble/launch/looped.launch.py", "room_humble/launch/room.launch.py",
        "room_jazzy", "room_jazzy/launch/room.launch.py", "room_jazzy/launch/spawn_robot.launch.py"]
    assert code == 0, {path: errors(r) for path, r in rows.items() if errors(r)}
    for package in ("room_humble", "room_jazzy"):
        assert rows[package]["checks"] == ["package"] and errors(rows[package]) == []


def test_a_humble_package_is_checked_from_its_spawn_entity_pose(checked, workspace):
    _, rows, _ = checked
    row = rows["room_humble/launch/room.launch.py"]
    launch = workspace / "src" / "room_humble" / "launch" / "room.launch.py"
    assert row["spawn"] == [1.0, 0.5, 0.0] and row["spawn_source"] == f"from launch file {launch}"
    assert row["checks"] == ["launch", "parse", "enclosed", "spawn-clear"] and row["metrics"]["enclosed"] is True


def test_a_jazzy_package_is_checked_from_its_create_pose(checked):
    _, rows, _ = checked
    row = rows["room_jazzy/launch/room.launch.py"]
    assert row["spawn"] == [-1.0, 0.5, 0.0] and row["metrics"]["enclosed"] is True
    # the spawn file it includes has no world of its own: a row that says so, not a failure
    part = rows["room_jazzy/launch/spawn_robot.launch.py"]
    assert part["ok"] is True and part["checks"] == ["launch"]
    assert any("a part that other launch files include" in f["message"] for f in part["findings"])


def test_a_spawn_pose_from_declare_launch_argument_defaults_is_used(checked):
    _, rows, _ = checked
    row = rows["room_humble/launch/declared.launch.py"]
    assert row["spawn"] == [0.8, -0.6, 1.57] and row["robot"] == "waffle"


@pytest.mark.parametrize("name, line, words", [
    ("looped.launch.py", 18, "the for loop at line 18 builds Node (spawn_entity.py): not run here"),
    ("called.launch.py", 20, "room_humble.poses.start_pose() is a call worldgen does not follow"),
])
def test_what_cannot_be_read_is_a_finding_and_the_world_is_checked_as_one_without_a_spawn(checked, workspace,
                                                                                            name, line, words):
    _, rows, _ = checked
    row = rows[f"room_humble/launch/{name}"]
    [finding] = [f for f in row["findings"] if f["check"] == "launch-static"]
    assert finding["severity"] == "warning" and words in finding["message"]
    assert finding["where"] == f"{workspace / 'src' / 'room_humble' / 'launch' / name}:{line}"
    assert row["spawn_source"] == ("no spawn given: checked from the deepest free point of the world's only closed "
                                   "room at (0.00, 0.00)")
    assert row["metrics"]["enclosed"] is True


def test_a_fuel_include_is_a_warning_naming_the_model(checked):
    _, rows, _ = checked
    notes = {(f["severity"], f["message"]) for f in rows["room_jazzy/launch/room.launch.py"]["findings"]
             if f["check"] == "include"}
    assert ("warning", "the Fuel model 'Construction Cone' (OpenRobotics) is an online model, never downloaded here: "
            "its geometry is missing (not counted as walls) (https://fuel.gazebosim.org/1.0/OpenRobotics/models/"
            "Construction Cone)") in notes
    assert ("info", "the Fuel model 'Ground Plane' (OpenRobotics): Gazebo's stock ground plane, never downloaded; "
            "stood in for by a plane at z = 0") in notes
    assert any(m.startswith("the Fuel model 'Sun' (OpenRobotics)") for _, m in notes)


def test_humble_and_jazzy_launch_files_pass_in_the_simulator(workspace):
    src = workspace / "src"
    code, doc, _ = validate(src / "room_humble" / "launch" / "room.launch.py",
                            src / "room_jazzy" / "launch" / "room.launch.py", "-j", "2",
                            env={k: v for k, v in __import__("os").environ.items() if k != "TURTLEBOT3_MODEL"})
    assert code == 0, [errors(r) for r in doc["results"]]
    assert [r["spawn"] for r in doc["results"]] == [[1.0, 0.5, 0.0], [-1.0, 0.5, 0.0]]
    for r in doc["results"]:
        assert r["checks"][-4:] == ["settle", "lidar", "spin", "stop-at-wall"]
        assert r["metrics"]["stop_distance_m"] == pytest.approx(0.5, abs=0.05) and r["metrics"]["stop_touched"] == []


def test_a_world_given_with_a_python_launch_file_takes_its_spawn(workspace):
    src = workspace / "src" / "room_humble"
    code, doc, _ = validate(src / "worlds" / "room.world", "--launch", src / "launch" / "declared.launch.py",
                            "--skip-sim")
    [row] = doc["results"]
    assert code == 0 and row["spawn"] == [0.8, -0.6, 1.57] and row["robot"] == "waffle"


# ------------------------------------------------------------------------------------------ package checks

def package_findings(pkg: Path) -> list[tuple[str, str, str]]:
    result = CliRunner().invoke(main, ["validate", str(pkg), "--skip-sim", "--format", "json"])
    doc = json.loads(result.stdout)
    return [(f["severity"], f["check"], f["message"]) for f in doc["results"][0]["findings"]]


def test_an_ament_python_package_missing_what_colcon_and_ros2_need(tmp_path):
    pkg = python_package(tmp_path, "broken_py", {"room.launch.py": humble_launch("broken_py")},
                         {"room.world": room_sdf()}, exec_depends=("gazebo_ros",))
    assert package_findings(pkg) == []
    (pkg / "setup.cfg").unlink()
    (pkg / "resource" / "broken_py").unlink()
    setup = (pkg / "setup.py").read_text().replace("        (os.path.join('share', package_name, 'worlds'), "
                                                   "glob('worlds/*')),\n", "")
    (pkg / "setup.py").write_text(setup)
    write(pkg / "launch" / "drive.launch.py", """
        from launch import LaunchDescription
        from launch_ros.actions import Node


        def generate_launch_description():
            return LaunchDescription([Node(package='broken_py', executable='stop_at_wall')])
        """)
    found = package_findings(pkg)
    checks = [(severity, check) for severity, check, _ in found]
    assert ("error", "package-setup") in checks and ("error", "package-resource") in checks
    assert any(c == "package-install" and "worlds/ is not installed by data_files (worlds/room.world)" in m
               for _, c, m in found)
    assert any(c == "package-launch-node" and "broken_py installs no executable 'stop_at_wall'" in m
               for _, c, m in found)


def test_an_ament_cmake_package_without_ament_package_or_installs(tmp_path):
    pkg = cmake_package(tmp_path, "broken_cmake", {"room.launch.py": jazzy_world_launch("broken_cmake"),
                                                   "spawn_robot.launch.py": jazzy_spawn_launch()},
                        {"room.sdf": room_sdf(version="1.8", gz_sim=True)})
    assert [f for f in package_findings(pkg) if f[0] != "info"] == []
    (pkg / "CMakeLists.txt").write_text("cmake_minimum_required(VERSION 3.8)\nproject(broken_cmake)\n"
                                        "find_package(ament_cmake REQUIRED)\n")
    found = {(severity, message) for severity, _, message in package_findings(pkg)}
    assert ("error", "CMakeLists.txt never calls ament_package(): colcon builds it, but ros2 cannot find the "
                     "package") in found
    assert ("warning", "launch/ is not installed: after colcon build, get_package_share_directory('broken_cmake') "
                       "has no launch/") in found


def test_a_folder_of_catkin_and_ament_packages(tmp_path):
    subs = tmp_path / "submissions"
    python_package(subs / "ana", "ana_room", {"room.launch.py": humble_launch("ana_room")}, {"room.world": room_sdf()},
                   exec_depends=("gazebo_ros",))
    result = CliRunner().invoke(main, ["scaffold", "ben_room", "rospy", "-p", str(subs / "ben")])
    assert result.exit_code == 0, result.output
    result = CliRunner().invoke(main, ["validate", str(subs), "--skip-sim", "--format", "json"])
    assert "submissions: 1 catkin package and 1 ament package found" in result.output
    paths = [r["path"] for r in json.loads(result.stdout)["results"]]
    assert paths == [str(subs / "ana" / "ana_room"), str(subs / "ana" / "ana_room" / "launch" / "room.launch.py"),
                     str(subs / "ben" / "ben_room")]


# ------------------------------------------------------------------------------ ROBOTIS's own Gazebo Sim world

def test_robotis_jazzy_world_through_a_package_of_that_shape(corpus, tmp_path):
    """turtlebot3_world.world as ROBOTIS's jazzy turtlebot3_gazebo ships it (Fuel ground plane and sun, gz-sim
    systems), its model found through the package's own model path export, from the launch file's (-2, -0.5)."""
    world = "ROBOTIS-GIT__turtlebot3_simulations@jazzy__turtlebot3_gazebo_worlds_turtlebot3_world.world"
    pkg = cmake_package(tmp_path / "src", "tb3_class", {
        "turtlebot3_world.launch.py": jazzy_world_launch("tb3_class", "turtlebot3_world.world", "-2.0", "-0.5"),
        "spawn_robot.launch.py": jazzy_spawn_launch()}, {}, models=True)
    (pkg / "worlds").mkdir()
    shutil.copy(corpus / "worlds" / world, pkg / "worlds" / "turtlebot3_world.world")
    shutil.copytree(corpus / "gazebo_models" / "turtlebot3_world", pkg / "models" / "turtlebot3_world")
    code, doc, _ = validate(pkg / "launch" / "turtlebot3_world.launch.py", "--skip-sim",
                            env={k: v for k, v in __import__("os").environ.items()
                                 if k not in ("GAZEBO_MODEL_PATH", "GZ_SIM_RESOURCE_PATH")})
    [row] = doc["results"]
    assert code == 0, errors(row)
    assert row["spawn"] == [-2.0, -0.5, 0.0] and row["metrics"]["enclosed"] is True
    assert {f["message"].split(":")[0] for f in row["findings"] if f["check"] == "include"} == {
        "the Fuel model 'Ground Plane' (OpenRobotics)", "the Fuel model 'Sun' (OpenRobotics)"}


def test_a_setup_py_that_installs_with_a_loop_is_not_checked_but_not_failed(tmp_path):
    pkg = python_package(tmp_path, "walked", {"room.launch.py": humble_launch("walked")}, {"room.world": room_sdf()},
                         exec_depends=("gazebo_ros",))
    write(pkg / "models" / "box" / "model.sdf", "<sdf version='1.6'/>")
    setup = (pkg / "setup.py").read_text().replace("setup(\n", """def tree(folder):
    found = []
    for where, _, files in os.walk(folder):
        found.append((os.path.join('share', package_name, where), [os.path.join(where, f) for f in files]))
    return found


setup(
""", 1).replace("glob('worlds/*')),\n", "glob('worlds/*')),\n    ] + tree('models') + [\n")
    (pkg / "setup.py").write_text(setup)
    found = package_findings(pkg)
    assert [(severity, check) for severity, check, _ in found] == [("info", "package-setup")]
    assert found[0][2].startswith("what setup.py installs is not checked: the for loop at line 10 is not run here")
