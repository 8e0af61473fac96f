"""Launch files: the writer's shape, the spawn point it picks or checks, and the reader on our own and real files."""

from __future__ import annotations

import math
import shutil
from pathlib import Path

import pytest
from conftest import CliRunner
from lxml import etree

from worldgen.cli import main
from worldgen.core.errors import InputError, WorldFileError
from worldgen.core.numbers import format_number
from worldgen.launch.writer_xml import launch_xml, parse_node
from worldgen.launch.reader import read_launch
from worldgen.core.spawnpose import parse_spawn
from worldgen.geometry.placement import spawn_problem, world_rooms

ENCLOSED = "worlds/Intro-Robotics-UChicago-Spring-2022__warmup_project__worlds_turtlebot3_in_enclosed_room.world"
CLASS_LAUNCH = "launch/Intro-Robotics-UChicago-Spring-2022__warmup_project__launch_turtlebot3_in_room.launch"
MANIFEST = ('<package format="2"><name>{}</name><version>0.0.0</version><description>d</description>'
            '<maintainer email="a@example.com">a</maintainer><license>BSD</license></package>')


def make_package(root: Path, name: str) -> Path:
    (root / name).mkdir(parents=True, exist_ok=True)
    (root / name / "package.xml").write_text(MANIFEST.format(name))
    return root / name


# ----------------------------------------------------------------------------------------------------- writer

def test_launch_xml_has_the_class_shape():
    text = launch_xml("enclosed_room.world", "class_meeting_02", spawn=(1.25, -0.5, 0.0, 1.5708))
    root = etree.fromstring(text.encode())
    args = {a.get("name"): a for a in root.findall("arg")}
    assert args["model"].get("default") == "$(optenv TURTLEBOT3_MODEL burger)"   # works in a fresh shell
    assert etree.fromstring(launch_xml("w.world", "p", model="env").encode()).find("arg[@name='model']").get(
        "default") == "$(env TURTLEBOT3_MODEL)"   # the class's exact text, on request
    assert "Start it with: roslaunch class_meeting_02 turtlebot3_in_enclosed_room.launch" in text
    assert "roslaunch lab_a turtlebot3_in_w.launch" in launch_xml("w.world", "p", home="lab_a")
    assert args["model"].get("doc") == "model type [burger, waffle, waffle_pi]"
    assert {k: args[k].get("default") for k in ("x_pos", "y_pos", "z_pos", "yaw")} == \
        {"x_pos": "1.25", "y_pos": "-0.5", "z_pos": "0.0", "yaw": "1.5708"}
    assert {k: args[k].get("default") for k in ("paused", "use_sim_time", "gui", "headless", "debug")} == \
        {"paused": "false", "use_sim_time": "true", "gui": "true", "headless": "false", "debug": "false"}
    include = root.find("include")
    assert include.get("file") == "$(find gazebo_ros)/launch/empty_world.launch"
    passed = {a.get("name"): a.get("value") for a in include.findall("arg")}
    assert passed.pop("world_name") == "$(find class_meeting_02)/worlds/enclosed_room.world"
    assert passed == {k: f"$(arg {k})" for k in ("paused", "use_sim_time", "gui", "headless", "debug")}
    param = root.find("param")
    assert (param.get("name"), param.get("command")) == (
        "robot_description",
        "$(find xacro)/xacro $(find turtlebot3_description)/urdf/turtlebot3_$(arg model).urdf.xacro")
    (node,) = root.findall("node")
    assert (node.get("pkg"), node.get("type"), node.get("name")) == ("gazebo_ros", "spawn_model", "spawn_urdf")
    assert node.get("args") == ("-urdf -model turtlebot3_$(arg model) -x $(arg x_pos) -y $(arg y_pos) "
                                "-z $(arg z_pos) -Y $(arg yaw) -param robot_description")


def test_launch_xml_model_nodes_and_determinism():
    nodes = [parse_node("lab_a_stop_at_wall/stop_at_wall.py"), parse_node("teleop/teleop_key:keys")]
    text = launch_xml("w.world", "pkg", model="waffle_pi", nodes=nodes)
    assert text == launch_xml("w.world", "pkg", model="waffle_pi", nodes=nodes)
    root = etree.fromstring(text.encode())
    assert root.find("arg[@name='model']").get("default") == "waffle_pi"
    extra = [(n.get("pkg"), n.get("type"), n.get("name")) for n in root.findall("node")][1:]
    assert extra == [("lab_a_stop_at_wall", "stop_at_wall.py", "stop_at_wall"), ("teleop", "teleop_key", "keys")]


@pytest.mark.parametrize("kwargs, words", [
    ({"model": "burgr"}, "unknown robot model"),
    ({"package": "bad package"}, "bad package name"),
    ({"world_file_name": "my world.world"}, "cannot be passed to Gazebo"),
    ({"nodes": [parse_node("a/x:spawn_urdf")]}, "two nodes would be named 'spawn_urdf'"),
])
def test_launch_xml_refuses(kwargs, words):
    args = {"world_file_name": "w.world", "package": "pkg", **kwargs}
    with pytest.raises(InputError, match=words):
        launch_xml(**args)


def test_numbers_nodes_and_spawn_values():
    assert [format_number(v) for v in (0, -0.0, 1.5, -5.5, 0.125, 2.0, 1e-7, 3.14159265)] == \
        ["0.0", "0.0", "1.5", "-5.5", "0.125", "2.0", "0.0", "3.1416"]
    assert parse_node("pkg/my-node.py") == parse_node("pkg/my-node.py:my_node")
    for bad in ("pkg", "pkg/", "/type", "pkg/type:9name", "pkg/ty pe"):
        with pytest.raises(InputError):
            parse_node(bad)
    assert parse_spawn("1, -2") == (1.0, -2.0, 0.0)
    assert parse_spawn("1,2,1.57") == (1.0, 2.0, 1.57)
    assert parse_spawn("0,0,-6.28") == (0.0, 0.0, -6.28)
    for bad, words in (("1", "1 numbers, not 2 or 3"), ("a,b", "must be numbers"),
                       ("1,2,3,4", "4 numbers, not 2 or 3, and there is no Z"), ("1,2,3,4,5", "5 numbers"),
                       ("nan,1", "finite"), ("1,inf", "finite"), ("1,2,90", "probably degrees")):
        with pytest.raises(InputError, match=words) as err:
            parse_spawn(bad)
        assert "X,Y,YAW" in err.value.hint or "in radians" in err.value.hint
    with pytest.raises(InputError) as err:
        parse_spawn("1,2,-90")
    assert "-1.571 for -90°" in err.value.hint


# ----------------------------------------------------------------------------------------------------- spawn

def test_default_spawn_is_the_middle_of_the_class_room(corpus, tmp_path):
    """The class's saved world: the room's walls, moved by the <state> block, are centred on (-4.907, -1.411);
    the deepest free point of a square room is its centre."""
    from worldgen.launch.spawn import spawn_for_world

    world = tmp_path / "room.world"
    shutil.copy(corpus / ENCLOSED, world)
    pose, source = spawn_for_world(world)
    assert source == "world"
    assert pose[0] == pytest.approx(-4.907, abs=0.01) and pose[1] == pytest.approx(-1.411, abs=0.01)
    # the class's own spawn point is inside; one 3 m off is not, nor one on a wall
    assert spawn_for_world(world, spawn=(-5.5, -1.0))[0] == (-5.5, -1.0, 0.0, 0.0)
    with pytest.raises(InputError, match="outside the room"):
        spawn_for_world(world, spawn=(-1.0, -1.4))
    with pytest.raises(InputError, match="inside a wall"):
        spawn_for_world(world, spawn=(-2.48, -1.4))
    with pytest.raises(InputError, match="0.04 m from a wall"):
        spawn_for_world(world, spawn=(-2.6, -1.4))


@pytest.mark.parametrize("model", ["burger", "waffle", "waffle_pi"])
def test_a_spawn_the_launch_writer_accepts_leaves_room_to_turn(model):
    """The spawn check's radius holds the robot's collision shapes (what validate's spawn-clear sweeps): a
    burger 0.115 m from a wall would put its base box's back corners (0.124 m out) into it when turned."""
    from worldgen.check.checks import robot_body
    from worldgen.core.scene import Scene, Shape
    from worldgen.geometry.placement import robot_radius

    reach = robot_body(model).turn_radius
    assert robot_radius(model) >= reach
    wall = Scene(source=None, shapes=[Shape("box", (0.5, 0.0, 1.0), size=(0.2, 4.0, 2.0), model="m", name="w")])
    rooms = world_rooms(wall, robot_radius(model))
    assert "from a wall" in spawn_problem(rooms, 0.4 - (reach - 0.009), 0.0)
    assert spawn_problem(rooms, 0.4 - robot_radius(model) - 0.001, 0.0) is None


def test_spawn_comes_from_the_spec_beside_the_world(corpus, tmp_path):
    world = tmp_path / "room.world"
    shutil.copy(corpus / ENCLOSED, world)
    (tmp_path / "room.yaml").write_text("name: room\nrooms:\n  - name: a\n    rect: {center: [0, 0], size: [5, 5]}\n"
                                        "robot: {model: burger, at: [-5.5, -1.0], yaw: 1.5}\n")
    from worldgen.launch.spawn import spawn_for_world

    assert spawn_for_world(world) == ((-5.5, -1.0, 0.0, 1.5), "spec")
    (tmp_path / "room.yaml").write_text((tmp_path / "room.yaml").read_text().replace("-5.5", "5.5"))
    with pytest.raises(InputError, match="the spec's robot pose"):
        spawn_for_world(world)


def test_every_default_spawn_in_the_corpus_is_free(corpus):
    """For every corpus world with something at robot height, the chosen point is one the robot may use, and
    in a world with a closed room it is in that room."""
    from worldgen.geometry.placement import deepest_point
    from worldgen.sdf.reader import read_world

    checked = 0
    for world in sorted((corpus / "worlds").iterdir()):
        rooms = world_rooms(read_world(world))
        point = deepest_point(rooms)
        if rooms.centre is None:
            continue
        checked += 1
        assert point is not None, world.name
        assert spawn_problem(rooms, *point) is None, world.name
        assert rooms.blocked.distance(__import__("shapely").Point(point)) >= rooms.radius
    assert checked >= 8


def test_launch_command(corpus, tmp_path):
    pkg = make_package(tmp_path / "src", "my_worlds")
    (pkg / "worlds").mkdir()
    shutil.copy(corpus / ENCLOSED, pkg / "worlds" / "room.world")
    runner = CliRunner()
    result = runner.invoke(main, ["launch", str(pkg / "worlds" / "room.world"), "--model", "burger",
                                  "--node", "my_worlds/stop_at_wall.py"])
    assert result.exit_code == 0, result.output
    written = pkg / "launch" / "turtlebot3_in_room.launch"
    info = read_launch(written, environ={})
    assert info.package == "my_worlds" and info.world_path == (pkg / "worlds" / "room.world").resolve()
    assert info.model == "burger"
    assert info.spawn[0] == pytest.approx(-4.91, abs=0.01) and info.spawn[1] == pytest.approx(-1.41, abs=0.01)
    assert [n.full_name for n in info.nodes] == ["/spawn_urdf", "/stop_at_wall"]
    # again: refused without --force, and nothing changes
    before = written.read_bytes()
    again = runner.invoke(main, ["launch", str(pkg / "worlds" / "room.world"), "--spawn", "-5.5,-1,0.5"])
    assert again.exit_code == 2 and "exists" in again.output and written.read_bytes() == before
    forced = runner.invoke(main, ["launch", str(pkg / "worlds" / "room.world"), "--spawn", "-5.5,-1,0.5",
                                  "--force"])
    assert forced.exit_code == 0, forced.output
    assert "yaw 0.5" in forced.output
    info = read_launch(written, environ={})   # X,Y,YAW as in every command; z on the floor
    assert info.spawn == (-5.5, -1.0, 0.0, 0.5)
    assert info.model == "burger"   # $(optenv TURTLEBOT3_MODEL burger) with TURTLEBOT3_MODEL unset
    assert read_launch(written, environ={"TURTLEBOT3_MODEL": "waffle"}).model == "waffle"


@pytest.mark.parametrize("extra, words", [
    (["--model", "tank"], "Invalid value for '--model'"),
    (["--spawn", "0,0"], "outside the room"),
    (["--spawn", "x"], "bad --spawn value"),
    (["--spawn", "-5.5,-1,0,0.5"], "4 numbers, not 2 or 3"),
    (["--spawn", "-5.5,-1,90"], "probably degrees"),
    (["--node", "nonode"], "bad --node value"),
    (["--name", "a/b.launch"], "is a path"),
    (["--name", "my room"], "cannot be passed to roslaunch"),
    (["--name", ".launch"], "cannot be passed to roslaunch"),
])
def test_launch_command_bad_input(corpus, tmp_path, extra, words):
    world = tmp_path / "room.world"
    shutil.copy(corpus / ENCLOSED, world)
    result = CliRunner().invoke(main, ["launch", str(world), "--package", "p", "-o", str(tmp_path / "out"),
                                       *extra])
    assert result.exit_code == 2
    (line,) = [ln for ln in result.output.splitlines() if "rror" in ln]   # one line says what is wrong
    assert words in line
    assert not (tmp_path / "out").exists()


def test_launch_command_needs_a_package(corpus, tmp_path):
    world = tmp_path / "room.world"
    shutil.copy(corpus / ENCLOSED, world)
    result = CliRunner().invoke(main, ["launch", str(world)])
    assert result.exit_code == 2 and "--package" in result.output


def test_launch_warns_of_what_roslaunch_will_not_find(corpus, tmp_path, monkeypatch):
    """The file is written (exit 0) and one warning line says what validate would fail it for: its own package's
    node not written yet, a --package no workspace holds, a package without the world; none once they are there."""
    monkeypatch.delenv("ROS_PACKAGE_PATH", raising=False)
    pkg = make_package(tmp_path / "src", "my_worlds")
    (pkg / "worlds").mkdir()
    shutil.copy(corpus / ENCLOSED, pkg / "worlds" / "room.world")
    world = str(pkg / "worlds" / "room.world")

    def warnings(*argv) -> list[str]:
        result = CliRunner().invoke(main, ["launch", *argv, "--force"])
        assert result.exit_code == 0, result.output
        return [line for line in result.stderr.splitlines() if line.startswith("worldgen: warning: ")]

    [missing] = warnings(world, "--node", "my_worlds/stop_at_wall.py", "--node", "turtlebot3_teleop/teleop.py")
    assert "my_worlds/stop_at_wall.py is not in" in missing and "write scripts/stop_at_wall.py" in missing
    (pkg / "scripts").mkdir()
    (pkg / "scripts" / "stop_at_wall.py").write_text("#!/usr/bin/env python3\n")
    assert warnings(world, "--node", "my_worlds/stop_at_wall.py") == []
    loose = tmp_path / "room.world"
    shutil.copy(corpus / ENCLOSED, loose)
    [nowhere] = warnings(str(loose), "--package", "nowhere", "-o", str(tmp_path / "out"))
    assert "the package nowhere is neither in the workspace" in nowhere and "--package DIR" in nowhere
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(tmp_path / "src"))
    assert warnings(str(loose), "--package", "my_worlds", "-o", str(tmp_path / "out")) == []
    (tmp_path / "other.world").write_bytes(loose.read_bytes())
    [no_world] = warnings(str(tmp_path / "other.world"), "--package", "my_worlds", "-o", str(tmp_path / "out"))
    assert "the package my_worlds" in no_world and "has no worlds/other.world" in no_world


# ----------------------------------------------------------------------------------------------------- reader

def test_reader_round_trip(tmp_path):
    pkg = make_package(tmp_path / "ws" / "src", "demo")
    (pkg / "launch").mkdir()
    launch = pkg / "launch" / "a.launch"
    launch.write_text(launch_xml("w.world", "demo", spawn=(1.5, -2.0, 0.01, 3.0)))
    info = read_launch(launch, environ={"TURTLEBOT3_MODEL": "waffle"}, ros_package_path=[])
    assert info.world_path == pkg / "worlds" / "w.world" and info.package == "demo"
    assert info.world_ref == "$(find demo)/worlds/w.world"
    assert info.spawn == (1.5, -2.0, 0.01, 3.0) and info.model == "waffle"
    assert info.args["x_pos"] == "1.5" and info.args["model"] == "waffle"
    overridden = read_launch(launch, {"x_pos": "-1", "model": "burger"}, environ={}, ros_package_path=[])
    assert overridden.spawn == (-1.0, -2.0, 0.01, 3.0) and overridden.model == "burger"
    unset = read_launch(launch, environ={}, ros_package_path=[])
    assert unset.model == "burger" and unset.spawn == (1.5, -2.0, 0.01, 3.0)   # $(optenv ... burger)
    launch.write_text(launch_xml("w.world", "demo", model="env", spawn=(1.5, -2.0, 0.01, 3.0)))
    unset = read_launch(launch, environ={}, ros_package_path=[])
    assert unset.model is None and unset.model_env == "TURTLEBOT3_MODEL" and unset.spawn == (1.5, -2.0, 0.01, 3.0)


# What each real launch file says, read alone (no package on the path, TURTLEBOT3_MODEL unset):
# (file tail, package of the world, world file, spawn of the first robot, number of spawn_model nodes)
CORPUS_LAUNCHES = [
    ("turtlebot3_laser.launch", "robotics_final_project", "turtlebot3_laser.world", (-2.0, 1.0, 0.0, 0.0), 2),
    ("turtlebot3_in_room.launch", "warmup_project", "turtlebot3_in_enclosed_room.world", (-5.5, -1.0, 0.0, 0.0), 1),
    ("launch_action.launch", "turtlebot3_gazebo", "turtlebot3_house.world", None, 0),
    ("launch_one_robot.launch", None, None, None, 1),
    ("playpen.launch", "husky_gazebo", "clearpath_playpen.world", None, 0),
    ("linj24__q_learning_project__launch_turtlebot3_intro_robo_manipulation.launch", "q_learning_project",
     "turtlebot3_tags_and_dumbbells_no_robot.world", (0.0, 0.0, 0.0, 0.0), 1),
    ("sydneyjenkins__20600_final_project__launch_turtlebot3_intro_robo_manipulation.launch", "q_learning_project",
     "turtlebot3_numbers_and_dumbbells_no_robot.world", (0.0, 0.0, 0.0, 0.0), 1),
]


@pytest.mark.parametrize("tail, package, world, spawn, robots", CORPUS_LAUNCHES, ids=[c[0] for c in CORPUS_LAUNCHES])
def test_reader_on_every_corpus_launch_file(corpus, tail, package, world, spawn, robots):
    (path,) = [p for p in (corpus / "launch").iterdir() if p.name.endswith(tail)]
    info = read_launch(path, environ={}, ros_package_path=[])
    assert info.package == package
    assert (info.world_ref.rsplit("/", 1)[-1] if info.world_ref else None) == world
    assert info.world_path is None   # their packages are not here
    assert info.spawn == spawn and len(info.robots) == robots
    if package:   # the package that is missing is named in a finding
        assert any(f.check == "launch-find" and package in f.message for f in info.findings)


def test_reader_multi_robot_namespaces(corpus):
    (path,) = (corpus / "launch").glob("*turtlebot3_laser.launch")
    info = read_launch(path, environ={"TURTLEBOT3_MODEL": "waffle_pi"}, ros_package_path=[])
    assert [(r.node, r.model_name, r.robot, r.pose) for r in info.robots] == [
        ("/tb3_0/spawn_urdf", "tb3_0", "waffle_pi", (-2.0, 1.0, 0.0, 0.0)),
        ("/tb3_1/spawn_urdf", "tb3_1", "waffle_pi", (-2.0, 0.0, 0.0, 0.0))]
    assert info.model == "waffle_pi" and info.spawn == (-2.0, 1.0, 0.0, 0.0)


def test_reader_follows_includes_in_a_workspace(corpus, tmp_path):
    """tom-jerry's action.launch includes one_robot.launch twice, in namespaces, passing the pose as an arg;
    with both in a package of a catkin workspace, both robots and their models are found."""
    pkg = make_package(tmp_path / "ws" / "src", "tom_and_jerry_project")
    (pkg / "launch").mkdir()
    for name in ("action", "one_robot"):
        (src,) = (corpus / "launch").glob(f"Purrsephone__tom-jerry__launch_{name}.launch")
        shutil.copy(src, pkg / "launch" / f"{name}.launch")
    info = read_launch(pkg / "launch" / "action.launch", environ={}, ros_package_path=[])
    assert [(r.node, r.model_name, r.robot, r.pose) for r in info.robots] == [
        ("/tom/spawn_minibot_model", "tom", "waffle", (-6.0, 0.0, 0.0, 0.0)),
        ("/jerry/spawn_minibot_model", "jerry", "burger", (-5.0, 1.0, 0.0, 0.0))]
    assert info.spawn == (-6.0, 0.0, 0.0, 0.0) and info.model == "waffle"
    assert info.includes == [pkg / "launch" / "one_robot.launch"] * 2
    alone = read_launch(pkg / "launch" / "one_robot.launch", environ={}, ros_package_path=[])
    assert alone.spawn is None and any("init_pose" in f.message for f in alone.findings)
    passed = read_launch(pkg / "launch" / "one_robot.launch", {"init_pose": "-x 1 -y 2 -Y 0.5", "robot_name": "r",
                                                                "robot_description": "d"}, environ={})
    assert passed.spawn == (1.0, 2.0, 0.0, 0.5)


def test_reader_finds_worlds_in_own_sibling_and_path_packages(corpus, tmp_path):
    src = tmp_path / "ws" / "src"
    own = make_package(src, "warmup_project")
    (own / "launch").mkdir()
    (launch,) = (corpus / "launch").glob("*warmup_project*")
    shutil.copy(launch, own / "launch" / "room.launch")
    (own / "worlds").mkdir()
    shutil.copy(corpus / ENCLOSED, own / "worlds" / "turtlebot3_in_enclosed_room.world")
    info = read_launch(own / "launch" / "room.launch", environ={}, ros_package_path=[])
    assert info.world_path == own / "worlds" / "turtlebot3_in_enclosed_room.world" and info.world_path.is_file()
    # a launch file in a sibling package naming the world package; and one outside any workspace, found
    # through ROS_PACKAGE_PATH
    other = make_package(src / "group", "labs")
    (other / "launch").mkdir()
    (other / "launch" / "x.launch").write_text(launch_xml("turtlebot3_in_enclosed_room.world", "warmup_project"))
    assert read_launch(other / "launch" / "x.launch", environ={}, ros_package_path=[]).world_path == info.world_path
    loose = tmp_path / "loose.launch"
    loose.write_text(launch_xml("turtlebot3_in_enclosed_room.world", "warmup_project"))
    assert read_launch(loose, environ={}, ros_package_path=[]).world_path is None
    assert read_launch(loose, environ={}, ros_package_path=[str(src)]).world_path == info.world_path


@pytest.mark.parametrize("text, line, words", [
    ("<launch>\n  <arg name='a' default='1'>\n</launch>\n", 3, "not well-formed"),
    ("<?xml version='1.0'?>\n<robot/>\n", 2, "not <launch>"),
    ("<launch>\n\n  <arg default='1'/>\n</launch>\n", 3, "<arg> without a name"),
    ("<launch>\n  <node pkg='a'/>\n</launch>\n", 2, "without pkg or type"),
    ("<launch>\n  <arg name='a' value='1' default='2'/>\n</launch>\n", 2, "both value and default"),
    ("<launch>\n  <include file='$(dirname)/bad.launch'/>\n</launch>\n", 2, "includes itself"),
    ("", 1, "empty"),
])
def test_reader_errors_name_the_line(tmp_path, text, line, words):
    path = tmp_path / "bad.launch"
    path.write_text(text)
    with pytest.raises(WorldFileError, match=words) as caught:
        read_launch(path, environ={}, ros_package_path=[])
    assert caught.value.line == line and caught.value.path == str(path)


def test_reader_does_not_expand_entities(tmp_path):
    path = tmp_path / "x.launch"
    path.write_text('<?xml version="1.0"?>\n<!DOCTYPE l [<!ENTITY e SYSTEM "file:///etc/passwd">]>\n'
                    '<launch><arg name="x_pos" default="&e;"/></launch>\n')
    with pytest.raises(WorldFileError, match="external entity") as caught:
        read_launch(path, environ={}, ros_package_path=[])
    assert caught.value.line == 3 and "root:" not in str(caught.value)


def test_spawn_with_unreadable_numbers_is_a_finding(tmp_path):
    path = tmp_path / "x.launch"
    path.write_text('<launch><node pkg="gazebo_ros" type="spawn_model" name="s" args="-urdf -x one -y 2"/></launch>')
    info = read_launch(path, environ={}, ros_package_path=[])
    assert info.spawn is None
    assert [f.check for f in info.findings if f.severity == "error"] == ["launch-spawn"]


def test_yaw_is_an_angle_in_radians():
    root = etree.fromstring(launch_xml("w.world", "p", spawn=(0, 0, 0, math.pi / 2)).encode())
    assert float(root.find("arg[@name='yaw']").get("default")) == pytest.approx(math.pi / 2, abs=1e-4)
