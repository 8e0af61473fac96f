"""Our packages and launch files through the real ROS 1 tools: catkin_make builds and installs the course,
catkin_lint finds no problems, roslaunch's own loader reads every launch file we write (with stand-ins for the
Gazebo packages), and stop_at_wall.py drives and stops on a real roscore.

Missing tools skip these tests, except under CI (env CI set), where they fail: see :mod:`rosstubs`.
"""

from __future__ import annotations

import json
import shutil
import subprocess
from pathlib import Path

import pytest
from conftest import CliRunner

from rosstubs import (SCAN_DRIVER, SYSTEM_PYTHON, TWIST_ECHO, make_stub_packages, need, need_module, roslaunch_load,
                      ros_env, start_roscore, stop_process)
from worldgen.cli import main
from worldgen.packages.course_ros1 import write_course
from worldgen.core.numbers import format_number
from worldgen.launch.reader import read_launch

ENCLOSED = "worlds/Intro-Robotics-UChicago-Spring-2022__warmup_project__worlds_turtlebot3_in_enclosed_room.world"


@pytest.fixture(scope="module")
def work(tmp_path_factory) -> Path:
    return tmp_path_factory.mktemp("ros")


@pytest.fixture(scope="module")
def workspace(work) -> Path:
    """A catkin workspace holding the course and the packages made by scaffold, build --package and launch."""
    src = write_course(work / "ws").parent
    spec = work / "lab_room.yaml"
    spec.write_text("name: lab_room\nrooms:\n  - name: a\n    polygon: [[0, 0], [4, 0], [4, 3], [1, 3], [0, 2]]\n"
                    "robot: {model: burger, at: [2.0, 1.5], yaw: 1.0}\n")
    runner = CliRunner()
    for args in (["scaffold", "my_world_pkg", "rospy", "std_msgs", "--world", str(spec), "-p", str(src)],
                 ["scaffold", "cpp_pkg", "roscpp", "std_msgs", "-p", str(src)],
                 # system dependencies are not installed here: catkin_lint checks this one, catkin_make does not
                 ["scaffold", "sys_pkg", "roscpp", "-s", "eigen", "python-numpy", "-b", "thread", "-p",
                  str(work / "lint_only")],
                 ["scaffold", "my_msgs", "message_generation", "message_runtime", "std_msgs", "-p", str(src)],
                 ["scaffold", "built_pkg", "-p", str(src)],
                 ["build", str(spec), "--package", str(src / "built_pkg")]):
        result = runner.invoke(main, args)
        assert result.exit_code == 0, (args, result.output)
    # a node a student adds after scaffolding: the CMakeLists installs it with no edit
    later = src / "cpp_pkg" / "scripts" / "added_later.py"
    later.write_text("#!/usr/bin/env python3\nprint('hello')\n")
    later.chmod(0o755)
    return src.parent


@pytest.fixture(scope="module")
def stubs(work) -> Path:
    return make_stub_packages(work / "stubs")


def launch_env(work: Path, stubs: Path, workspace: Path, **extra) -> dict[str, str]:
    return ros_env(work, ROS_PACKAGE_PATH=f"{stubs}:{workspace / 'src'}", **extra)


def test_catkin_make_builds_and_installs(workspace, work):
    proc = subprocess.run([need("catkin_make"), "-C", str(workspace), "install",
                           "-DPYTHON_EXECUTABLE=/usr/bin/python3"], cwd=workspace, capture_output=True, text=True,
                          env=ros_env(work), timeout=300)
    assert proc.returncode == 0, proc.stdout[-3000:] + proc.stderr[-3000:]
    assert "non standard content" not in proc.stdout + proc.stderr   # the metapackage's boilerplate is catkin's
    install = workspace / "install"
    for rel in ("share/class_meeting_02_custom_gazebo_world/worlds/enclosed_room.world",
                "share/class_meeting_02_custom_gazebo_world/launch/turtlebot3_in_enclosed_room.launch",
                "share/my_world_pkg/worlds/lab_room.world", "share/built_pkg/launch/turtlebot3_in_lab_room.launch",
                "share/intro_robo/package.xml"):
        assert (install / rel).is_file(), rel
    for script in ("lab_a_stop_at_wall/stop_at_wall.py", "lab_a_spin_circles/spin_in_circles.py",
                   "cpp_pkg/added_later.py"):   # where rosrun looks after catkin_make install
        assert (install / "lib" / script).stat().st_mode & 0o111, script
    assert sorted(p.name for p in (install / "lib" / "cpp_pkg").iterdir()) == ["added_later.py"]
    assert not list(install.rglob(".gitkeep"))


def test_catkin_lint_finds_no_problems(workspace, work):
    proc = subprocess.run([need("catkin_lint"), "-W2", str(workspace / "src"), str(work / "lint_only")],
                          capture_output=True, text=True, env=ros_env(work), timeout=120)
    problems = [ln for ln in proc.stdout.splitlines() if ": error:" in ln or ": warning:" in ln]
    assert proc.returncode == 0 and problems == [], proc.stdout + proc.stderr
    assert "checked 10 packages" in proc.stderr


def our_launch_files(workspace: Path) -> list[Path]:
    return sorted((workspace / "src").rglob("*.launch"))


def test_roslaunch_loads_every_launch_file_we_write(workspace, work, stubs, corpus):
    need_module("roslaunch")
    # one more, from `worldgen launch` on a real saved world, with an extra node
    pkg = workspace / "src" / "my_world_pkg"
    shutil.copy(corpus / ENCLOSED, pkg / "worlds" / "class_room.world")
    result = CliRunner().invoke(main, ["launch", str(pkg / "worlds" / "class_room.world"),
                                       "--node", "my_world_pkg/go.py:driver"])
    assert result.exit_code == 0, result.output
    launches = our_launch_files(workspace)
    assert len(launches) == 7
    env = launch_env(work, stubs, workspace, TURTLEBOT3_MODEL="burger")
    for launch, config in zip(launches, roslaunch_load([(launch, []) for launch in launches], env)):
        nodes = {n["name"]: n for n in config["nodes"]}
        ours = read_launch(launch, environ={"TURTLEBOT3_MODEL": "burger"}, ros_package_path=[str(stubs)])
        model = "waffle_pi" if "lab_b_line_follower" in str(launch) else "burger"   # the line lab's camera robot
        assert {"gazebo", "gazebo_gui", "spawn_urdf"} <= set(nodes), launch
        assert {n.name for n in ours.nodes} == set(nodes), launch   # our reader sees the same nodes
        x, y, z, yaw = (format_number(v) for v in ours.spawn)
        assert nodes["spawn_urdf"]["args"] == (f"-urdf -model turtlebot3_{model} -x {x} -y {y} -z {z} -Y {yaw} "
                                               "-param robot_description"), launch
        world = Path(nodes["gazebo"]["args"])
        assert world == ours.world_path and world.is_file(), launch
        assert f'<robot name="turtlebot3_{model}"' in config["params"]["/robot_description"]
        assert config["params"]["/use_sim_time"] is True


def test_the_course_launches_with_turtlebot3_model_unset(workspace, work, stubs):
    """A new shell has no TURTLEBOT3_MODEL: roslaunch's own loader still reads every course launch file (the
    model defaults to burger through $(optenv ...)), and each says how to start it from its own package."""
    need_module("roslaunch")
    course = workspace / "src" / "intro_robo"
    launches = sorted(course.rglob("*.launch"))
    assert len(launches) == 4
    env = launch_env(work, stubs, workspace)
    assert "TURTLEBOT3_MODEL" not in env
    for launch, config in zip(launches, roslaunch_load([(launch, []) for launch in launches], env)):
        spawn = {n["name"]: n for n in config["nodes"]}["spawn_urdf"]
        model = "waffle_pi" if "lab_b_line_follower" in str(launch) else "burger"   # its own, whatever the shell
        assert f"-model turtlebot3_{model} " in spawn["args"], launch
        assert f'<robot name="turtlebot3_{model}"' in config["params"]["/robot_description"]
        package = launch.parent.parent.name
        assert f"Start it with: roslaunch {package} {launch.name}" in launch.read_text()


def test_roslaunch_overrides(workspace, work, stubs):
    need_module("roslaunch")
    launch = workspace / "src" / "built_pkg" / "launch" / "turtlebot3_in_lab_room.launch"
    env = launch_env(work, stubs, workspace, TURTLEBOT3_MODEL="burger")   # roslaunch needs it even when passed
    (config,) = roslaunch_load([(launch, ["x_pos:=1.5", "model:=waffle", "gui:=false"])], env)
    nodes = {n["name"]: n for n in config["nodes"]}
    assert nodes["spawn_urdf"]["args"] == ("-urdf -model turtlebot3_waffle -x 1.5 -y 1.5 -z 0.0 -Y 1.0 "
                                           "-param robot_description")
    assert "gazebo_gui" not in nodes
    assert '<robot name="turtlebot3_waffle"' in config["params"]["/robot_description"]
    ours = read_launch(launch, {"x_pos": "1.5", "model": "waffle"}, environ={})
    assert ours.spawn == (1.5, 1.5, 0.0, 1.0) and ours.model == "waffle"


def test_our_reader_agrees_with_roslaunch_on_real_files(work, stubs, corpus):
    """The class's launch file and tom-jerry's two-robot one, placed in packages of a workspace: roslaunch's
    spawn_model args hold the poses read_launch reports."""
    need_module("roslaunch")
    src = work / "real" / "src"
    for name in ("warmup_project", "tom_and_jerry_project", "turtlebot3_gazebo"):
        (src / name / "launch").mkdir(parents=True)
        (src / name / "package.xml").write_text(
            f'<package format="2"><name>{name}</name><version>0.0.0</version><description>d</description>'
            '<maintainer email="a@example.com">a</maintainer><license>BSD</license></package>')
    (room,) = (corpus / "launch").glob("*warmup_project*")
    shutil.copy(room, src / "warmup_project" / "launch" / "room.launch")
    for name in ("action", "one_robot"):
        shutil.copy(corpus / "launch" / f"Purrsephone__tom-jerry__launch_{name}.launch",
                    src / "tom_and_jerry_project" / "launch" / f"{name}.launch")
    env = ros_env(work, ROS_PACKAGE_PATH=f"{stubs}:{src}", TURTLEBOT3_MODEL="burger")
    cases = ((src / "warmup_project" / "launch" / "room.launch", 1),
             (src / "tom_and_jerry_project" / "launch" / "action.launch", 2))
    for (launch, expected), config in zip(cases, roslaunch_load([(launch, []) for launch, _ in cases], env)):
        spawns = [n for n in config["nodes"] if (n["package"], n["type"]) == ("gazebo_ros", "spawn_model")]
        ours = read_launch(launch, environ={"TURTLEBOT3_MODEL": "burger"}, ros_package_path=[str(stubs)])
        assert len(spawns) == len(ours.robots) == expected
        for node, robot in zip(spawns, ours.robots):
            assert node["namespace"].rstrip("/") + "/" + node["name"] == robot.node
            words = node["args"].split()
            pose = [float(words[words.index(flag) + 1]) if flag in words else 0.0 for flag in ("-x", "-y", "-z", "-Y")]
            assert tuple(pose) == robot.pose


# ------------------------------------------------------------------------------------------------ runtime

@pytest.fixture(scope="module")
def roscore(work):
    need_module("rospy")
    proc, env = start_roscore(work / "core")
    yield env
    stop_process(proc)


def run_node(script: Path, params: list[str], env: dict[str, str], driver: str, driver_args: list[str]) -> list:
    node = subprocess.Popen([SYSTEM_PYTHON, str(script), *params], env=env, stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE, start_new_session=True)
    try:
        proc = subprocess.run([SYSTEM_PYTHON, "-c", driver, *driver_args], env=env, capture_output=True, text=True,
                              timeout=90)
    finally:
        stop_process(node)
    assert proc.returncode == 0, proc.stderr[-2000:] + node.stderr.read().decode()[-2000:]
    return [json.loads(line) for line in proc.stdout.splitlines() if line.startswith("{")]


def test_stop_at_wall_on_a_real_roscore(workspace, roscore):
    """Fed LaserScans, the node drives at max_speed while the front reads far, inf (Gazebo) or 0 (the real
    LDS-01), proportionally slower near the target, and publishes a zero Twist once within it, and holds
    (0.45 m after stopping does not start it again)."""
    script = workspace / "src" / "intro_robo" / "lab_a_stop_at_wall" / "scripts" / "stop_at_wall.py"
    fronts = ["2.0", "inf", "0", "nan", "0.6", "0.5", "0.35", "0.45", "0.2", "3.0"]
    answers = run_node(script, ["_target_distance:=0.4", "_kp:=1.0", "_max_speed:=0.15"], roscore, SCAN_DRIVER,
                       fronts)
    linear = [a["linear"] for a in answers]
    assert [a["angular"] for a in answers] == [0.0] * len(fronts)
    assert linear[:4] == [0.15] * 4                      # far, inf, 0 and NaN: full speed
    assert linear[4] == pytest.approx(0.15, abs=1e-6)    # kp · 0.2 = 0.2, capped at 0.15
    assert linear[5] == pytest.approx(0.1, abs=1e-6)     # kp · 0.1
    assert linear[6:9] == [0.0, 0.0, 0.0]                # within the target distance: stop, and hold
    assert linear[9] == 0.15                             # the wall is gone: drive again


def test_spin_in_circles_on_a_real_roscore(workspace, roscore):
    script = workspace / "src" / "intro_robo" / "lab_a_spin_circles" / "scripts" / "spin_in_circles.py"
    (answer,) = run_node(script, ["_angular_speed:=0.8"], roscore, TWIST_ECHO, [])
    assert answer == {"linear": 0.1, "angular": pytest.approx(0.8)}
