"""worldgen course: the class packages, the world they share, the node scripts' control law."""

from __future__ import annotations

import importlib.util
import math
from pathlib import Path
from types import SimpleNamespace

import pytest
from conftest import CliRunner

from conftest import EXAMPLES
from worldgen.cli import main
from worldgen.ros.course import write_course
from worldgen.ros.launch_reader import read_launch
from worldgen.ros.package_check import check_package

PACKAGES = ["class_meeting_02_custom_gazebo_world", "intro_robo", "lab_a_spin_circles", "lab_a_stop_at_wall"]


@pytest.fixture(scope="module")
def course(tmp_path_factory) -> Path:
    return write_course(tmp_path_factory.mktemp("ws"))


def tree(root: Path) -> dict[str, bytes]:
    return {str(p.relative_to(root)): p.read_bytes() for p in sorted(root.rglob("*")) if p.is_file()}


def test_layout(course):
    assert course.parent.name == "src" and course.name == "intro_robo"
    assert sorted(p.name for p in course.iterdir()) == PACKAGES
    files = tree(course)
    for name in ("class_meeting_02_custom_gazebo_world/worlds/enclosed_room.world",
                 "class_meeting_02_custom_gazebo_world/launch/turtlebot3_in_enclosed_room.launch",
                 "lab_a_spin_circles/scripts/spin_in_circles.py", "lab_a_stop_at_wall/scripts/stop_at_wall.py",
                 "lab_a_stop_at_wall/launch/stop_at_wall.launch", "intro_robo/package.xml"):
        assert name in files
    for script in course.rglob("*.py"):
        assert script.read_text().startswith("#!/usr/bin/env python3\n")
        assert script.stat().st_mode & 0o777 == 0o755
    assert (course / "lab_a_stop_at_wall" / "package.xml").stat().st_mode & 0o777 == 0o644


def test_every_package_checks_clean(course):
    for pkg in PACKAGES:
        problems = [f for f in check_package(course / pkg, environ={}) if f.severity in ("error", "warning")]
        assert problems == [], pkg


def test_launch_files_point_at_the_class_world(course):
    world = course / "class_meeting_02_custom_gazebo_world" / "worlds" / "enclosed_room.world"
    for launch in sorted(course.rglob("*.launch")):
        info = read_launch(launch, environ={"TURTLEBOT3_MODEL": "burger"}, ros_package_path=[])
        assert info.world_path == world and info.model == "burger"
        assert info.spawn == (0.0, 0.0, 0.0, 0.0)   # the spec's robot pose: the middle of the room
    stop = read_launch(course / "lab_a_stop_at_wall" / "launch" / "stop_at_wall.launch", environ={})
    assert [(n.package, n.type, n.name) for n in stop.nodes][-1] == ("lab_a_stop_at_wall", "stop_at_wall.py",
                                                                      "stop_at_wall")


def test_the_course_world_is_the_built_example(course, tmp_path):
    """The course builds its world from examples/enclosed_room.yaml (shipped in the wheel as worldgen/examples):
    byte for byte the world `worldgen build examples/enclosed_room.yaml` writes, the robot in its middle."""
    from worldgen.ros.scaffold import world_from_spec

    example = EXAMPLES / "enclosed_room.yaml"
    built = CliRunner().invoke(main, ["build", str(example), "-o", str(tmp_path)])
    assert built.exit_code == 0, built.output
    world = course / "class_meeting_02_custom_gazebo_world" / "worlds" / "enclosed_room.world"
    assert world.read_bytes() == (tmp_path / "enclosed_room.world").read_bytes()
    assert world_from_spec(example)[2] == (0.0, 0.0, 0.0, 0.0)


def test_deterministic_and_all_or_nothing(course, tmp_path):
    again = write_course(tmp_path)
    assert tree(again) == tree(course)
    runner = CliRunner()
    refused = runner.invoke(main, ["course", "--workspace", str(tmp_path)])
    assert refused.exit_code == 2 and "exists" in refused.output
    (again / "lab_a_stop_at_wall" / "scripts" / "stop_at_wall.py").write_text("# changed\n")
    forced = runner.invoke(main, ["course", "--workspace", str(tmp_path), "--force"])
    assert forced.exit_code == 0, forced.output
    assert tree(again) == tree(course)
    assert not [p for p in (tmp_path / "src").iterdir() if p.name != "intro_robo"]   # no staging folder left


# ------------------------------------------------------------------------------------ the node's control law

@pytest.fixture(scope="module")
def stop_at_wall(course):
    pytest.importorskip("rospy")
    path = course / "lab_a_stop_at_wall" / "scripts" / "stop_at_wall.py"
    spec = importlib.util.spec_from_file_location("stop_at_wall_node", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)   # defines functions only; the node starts under __main__
    return module


def scan(ranges, angle_min=0.0):
    return SimpleNamespace(ranges=ranges, angle_min=angle_min, angle_increment=2 * math.pi / len(ranges),
                           range_min=0.12, range_max=3.5)


def test_front_distance_ignores_inf_zero_and_nan(stop_at_wall):
    half = math.radians(10)
    far = [3.0] * 360
    assert stop_at_wall.front_distance(scan(far), half) == 3.0
    ahead = list(far)
    ahead[0], ahead[5], ahead[355], ahead[20] = 1.2, 0.9, 1.0, 0.3   # beam 20 (20°) is outside the window
    assert stop_at_wall.front_distance(scan(ahead), half) == 0.9
    for nothing in (math.inf, 0.0, math.nan, 0.05, 9.0):
        blind = [nothing if (i <= 10 or i >= 350) else 3.0 for i in range(360)]
        assert stop_at_wall.front_distance(scan(blind), half) is None
    # a scan that starts at -pi (as other LiDARs publish): straight ahead is the middle beam
    centred = [3.0] * 360
    centred[180] = 0.7
    assert stop_at_wall.front_distance(scan(centred, angle_min=-math.pi), half) == 0.7


def test_forward_speed_is_proportional_and_capped(stop_at_wall):
    speed = stop_at_wall.forward_speed
    assert speed(None, 0.5, 0.5, 0.2) == 0.2
    assert speed(3.0, 0.5, 0.5, 0.2) == 0.2
    assert speed(0.8, 0.5, 0.5, 0.2) == pytest.approx(0.15)
    assert speed(0.5, 0.5, 0.5, 0.2) == 0.0 and speed(0.3, 0.5, 0.5, 0.2) == 0.0



def test_unwritable_workspace_is_one_line_and_force_replaces_a_file(tmp_path):
    runner = CliRunner()
    (tmp_path / "blocked").mkdir()
    (tmp_path / "blocked" / "src").write_text("a file where the source folder goes\n")
    blocked = runner.invoke(main, ["course", "--workspace", str(tmp_path / "blocked")])
    assert blocked.exit_code == 2 and "Traceback" not in blocked.output
    assert blocked.output.splitlines() == [f"worldgen: error: cannot write {tmp_path / 'blocked' / 'src'}: Not "
                                           "a directory (check that the output folder can be created and written to)"]
    (tmp_path / "ws" / "src").mkdir(parents=True)
    (tmp_path / "ws" / "src" / "intro_robo").write_text("not a folder\n")
    forced = runner.invoke(main, ["course", "--workspace", str(tmp_path / "ws"), "--force"])
    assert forced.exit_code == 0, forced.output
    assert sorted(p.name for p in (tmp_path / "ws" / "src" / "intro_robo").iterdir()) == PACKAGES
