"""worldgen course: the class packages, the world they share, the node scripts' control law."""

from __future__ import annotations

import importlib.util
import os
import math
from pathlib import Path
from types import SimpleNamespace

import pytest
from conftest import CliRunner

from conftest import EXAMPLES
from worldgen.cli import main
from worldgen.packages.course_ros1 import write_course
from worldgen.launch.reader import read_launch
from worldgen.packages.check import check_package

PACKAGES = ["class_meeting_02_custom_gazebo_world", "intro_robo", "lab_a_spin_circles", "lab_a_stop_at_wall",
            "lab_b_line_follower"]


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


def test_a_misspelt_node_package_is_an_error_naming_the_right_one(course, tmp_path):
    """pkg="lab_a_stop_at_wal": roslaunch cannot start the node; not a warning to depend on the misspelt name but
    an error naming the package meant. A package that is only not installed here (gazebo_ros) is no typo."""
    import shutil

    workspace = tmp_path / "src"
    shutil.copytree(course, workspace / "intro_robo")
    lab = workspace / "intro_robo" / "lab_a_stop_at_wall"
    launch = lab / "launch" / "stop_at_wall.launch"
    launch.write_text(launch.read_text().replace('pkg="lab_a_stop_at_wall" type=', 'pkg="lab_a_stop_at_wal" type='))
    found = [f for f in check_package(lab, environ={}, ros_package_path=[]) if f.severity in ("error", "warning")]
    [typo] = found
    assert typo.severity == "error" and "no package 'lab_a_stop_at_wal' is found" in typo.message
    assert "did you mean 'lab_a_stop_at_wall'?" in typo.message and typo.where.startswith(f"{launch}:")


def test_launch_files_point_at_the_class_world(course):
    world = course / "class_meeting_02_custom_gazebo_world" / "worlds" / "enclosed_room.world"
    for launch in sorted(p for p in course.rglob("*.launch") if "lab_b_" not in str(p)):
        info = read_launch(launch, environ={"TURTLEBOT3_MODEL": "burger"}, ros_package_path=[])
        assert info.world_path == world and info.model == "burger"
        assert info.spawn == (0.0, 0.0, 0.0, 0.0)   # the spec's robot pose: the middle of the room
    stop = read_launch(course / "lab_a_stop_at_wall" / "launch" / "stop_at_wall.launch", environ={})
    assert [(n.package, n.type, n.name) for n in stop.nodes][-1] == ("lab_a_stop_at_wall", "stop_at_wall.py",
                                                                      "stop_at_wall")


def test_the_line_lab_starts_a_waffle_pi_on_its_tape(course, tmp_path):
    """Lab B's launch file starts its own world, the line_track example built byte for byte, with a Waffle Pi (the
    camera) where the spec puts it, on the tape, and the line follower; the package depends on cv_bridge."""
    lab = course / "lab_b_line_follower"
    info = read_launch(lab / "launch" / "line_follower.launch", environ={}, ros_package_path=[])
    assert info.world_path == lab / "worlds" / "line_track.world" and info.model == "waffle_pi"
    assert info.spawn == (0.0, -0.85, 0.0, 0.0)
    assert [(n.package, n.type) for n in info.nodes][-1] == ("lab_b_line_follower", "line_follower.py")
    built = CliRunner().invoke(main, ["build", str(EXAMPLES / "line_track.yaml"), "-o", str(tmp_path)])
    assert built.exit_code == 0, built.output
    assert (lab / "worlds" / "line_track.world").read_bytes() == (tmp_path / "line_track.world").read_bytes()
    assert "<exec_depend>cv_bridge</exec_depend>" in (lab / "package.xml").read_text()
    assert "cv2.moments" in (lab / "scripts" / "line_follower.py").read_text()


def test_the_course_world_is_the_built_example(course, tmp_path):
    """The course builds its world from examples/enclosed_room.yaml (shipped in the wheel as worldgen/examples):
    byte for byte the world `worldgen build examples/enclosed_room.yaml` writes, the robot in its middle."""
    from worldgen.packages.catkin import world_from_spec

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


def test_the_node_runs_drives_law(stop_at_wall):
    """The generated node's StopLaw and worldgen drive's (worldgen.core.stoplaw) give the same command for every
    scan of the same runs: noisy approaches, nothing seen, a wall that moves away, PID gains."""
    import random

    from worldgen.core import stoplaw

    rng = random.Random(7)
    for run in range(40):
        gains = {"kp": rng.choice([0.1, 0.5, 1.2, 3.0]), "ki": rng.choice([0.0, 0.2]),
                 "kd": rng.choice([0.0, 0.3]), "max_speed": rng.choice([0.15, 0.22]),
                 "stop_band": rng.choice([0.0, 0.01, 0.05])}
        target = rng.choice([0.3, 0.5])
        node = stop_at_wall.StopLaw(target_distance=target, **gains)
        ours = stoplaw.StopLaw(target=target, **gains)
        front = rng.uniform(0.3, 3.0)
        for step in range(60):
            front = max(0.15, front - rng.uniform(-0.02, 0.08))
            reading = None if rng.random() < 0.05 else front + rng.gauss(0.0, 0.01)
            dt = 0.0 if step == 0 else 0.2
            assert node.step(reading, dt) == ours.step(reading, dt), (run, step)
            assert node.holding == ours.holding


def test_the_law_never_reverses_and_holds_through_noise(stop_at_wall):
    law = stop_at_wall.StopLaw(target_distance=0.5, kp=0.5, ki=0.0, kd=0.0, max_speed=0.22, stop_band=0.01)
    assert law.step(None, 0.0) == 0.22 and law.step(3.0, 0.2) == 0.22       # nothing seen, far: full speed
    assert law.step(0.8, 0.2) == pytest.approx(0.15)                          # kp · 0.3
    assert law.step(0.505, 0.2) == 0.0 and law.holding                        # within the band: stop
    for noisy in (0.52, 0.55, 0.6, 0.3):                                      # noise cannot start it again
        assert law.step(noisy, 0.2) == 0.0
    assert law.step(0.7, 0.2) == pytest.approx(0.1) and not law.holding      # moved 0.2 m away: drive again
    pid = stop_at_wall.StopLaw(target_distance=0.5, kp=0.0, ki=0.0, kd=10.0, max_speed=0.22, stop_band=0.01)
    pid.step(1.0, 0.0)
    assert pid.step(1.5, 0.2) == 0.22 and pid.step(1.0, 0.2) == 0.0          # de/dt < 0: clamped at 0, not back


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


@pytest.mark.skipif(not os.path.isfile("/usr/bin/python3"), reason="no system Python to name")
def test_the_build_command_names_ros_python_when_a_venv_python_comes_first(tmp_path):
    """course says how to build what it wrote: with a virtualenv's python3 first on PATH, plain catkin_make picks
    it and fails (no catkin_pkg), so the command names ROS's Python, as the README advises."""
    from worldgen.packages.catkin_make import catkin_make_command

    for folder, venv in (("venv", True), ("plain", False)):
        bin_dir = tmp_path / folder / "bin"
        bin_dir.mkdir(parents=True)
        (bin_dir / "python3").write_text("#!/bin/sh\n")
        (bin_dir / "python3").chmod(0o755)
        if venv:
            (tmp_path / folder / "pyvenv.cfg").write_text("home = /usr/bin\n")
        expected = "catkin_make -DPYTHON_EXECUTABLE=/usr/bin/python3" if venv else "catkin_make"
        assert catkin_make_command(str(bin_dir)) == expected
