"""ROS 2 launch files (--ros humble|jazzy) read statically (ast, never run): the actions of the launch
description, the world path, the spawn arguments, the bridge's parameter file; the bridge YAML; the CLI."""

from __future__ import annotations

import ast
import py_compile

import pytest
import yaml
from conftest import EXAMPLES, CliRunner

from worldgen.cli import main
from worldgen.core.errors import InputError
from worldgen.launch.gz_bridge_params import bridge_yaml
from worldgen.launch.writer_xml import parse_node
from worldgen.launch.writer_py import launch_py
from worldgen.launch.targets import cmd_vel_type

# ------------------------------------------------------------------ a small reader of our launch files (ast)


class Launch:
    """What a generated launch file's ``generate_launch_description`` returns, read from its source: each action
    as (callee, {keyword: value}, [positional]), values evaluated where they are plain (strings, lists, dicts,
    os.path.join, get_package_share_directory → ``share/PKG``, LaunchConfiguration → ``$(NAME)``, ``model``)."""

    def __init__(self, text: str):
        tree = ast.parse(text)
        self.function = next(n for n in tree.body if isinstance(n, ast.FunctionDef)
                             and n.name == "generate_launch_description")
        self.names = {"model": "<model>"}
        for node in self.function.body:
            if isinstance(node, ast.Assign) and isinstance(node.targets[0], ast.Name):
                if node.targets[0].id == "model":   # kept as <model>: the file picks it at launch time
                    self.model = self.value(node.value)
                else:
                    self.names[node.targets[0].id] = self.value(node.value)
        returned = next(n for n in self.function.body if isinstance(n, ast.Return)).value
        assert isinstance(returned, ast.Call) and returned.func.id == "LaunchDescription"
        self.actions = [(call.func.id, {k.arg: self.value(k.value) for k in call.keywords},
                         [self.value(a) for a in call.args]) for call in returned.args[0].elts]

    def value(self, node):
        if isinstance(node, ast.Constant):
            return node.value
        if isinstance(node, ast.Name):
            return self.names.get(node.id, f"<{node.id}>")
        if isinstance(node, (ast.List, ast.Tuple)):
            return [self.value(e) for e in node.elts]
        if isinstance(node, ast.Dict):
            return {self.value(k): self.value(v) for k, v in zip(node.keys, node.values)}
        if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Add):
            return f"{self.value(node.left)}{self.value(node.right)}"
        if isinstance(node, ast.Call):
            callee = dotted(node.func)
            args = [self.value(a) for a in node.args]
            if callee == "os.path.join":
                return "/".join(args)
            if callee == "get_package_share_directory":
                return f"share/{args[0]}"
            if callee == "LaunchConfiguration":
                return f"$({args[0]})"
            if callee == "items" or callee.endswith(".items"):
                return self.value(node.func.value)
            return (callee, args, {k.arg: self.value(k.value) for k in node.keywords})
        if isinstance(node, ast.Attribute) and node.attr == "items":
            return self.value(node.value)
        return ast.dump(node)

    def called(self, name):
        return [a for a in self.actions if a[0] == name]

    def node(self, package, executable):
        (found,) = [kw for callee, kw, _ in self.actions if callee == "Node" and kw.get("package") == package
                    and kw.get("executable") == executable]
        return found


def dotted(node) -> str:
    """``os.path.join`` for the callee of ``os.path.join(...)`` (ast.unparse is Python 3.9+)."""
    if isinstance(node, ast.Attribute):
        return f"{dotted(node.value)}.{node.attr}"
    return getattr(node, "id", "?")


def arguments(launch: Launch) -> dict:
    return {args[0]: kw["default_value"] for _, kw, args in launch.called("DeclareLaunchArgument")}


def flags(argv):
    return {argv[i]: argv[i + 1] for i in range(0, len(argv), 2)}


# ------------------------------------------------------------------------------------------------- writer

@pytest.mark.parametrize("ros", ["humble", "jazzy"])
def test_launch_py_compiles_and_reads_back(ros, tmp_path):
    world = "room.sdf" if ros == "jazzy" else "room.world"
    text = launch_py(world, "class_world", ros, spawn=(1.25, -0.5, 0.0, 1.5708),
                     nodes=[parse_node("lab_a/stop_at_wall")], home="lab_a")
    assert text == launch_py(world, "class_world", ros, spawn=(1.25, -0.5, 0.0, 1.5708),
                             nodes=[parse_node("lab_a/stop_at_wall")], home="lab_a")   # byte-identical
    path = tmp_path / "t.launch.py"
    path.write_text(text)
    py_compile.compile(str(path), doraise=True)
    assert "ros2 launch lab_a turtlebot3_in_room.launch.py" in text
    launch = Launch(text)
    assert arguments(launch) == {"x_pose": "1.25", "y_pose": "-0.5", "z_pose": "0.0", "yaw": "1.5708",
                                 "use_sim_time": "true", "gui": "true"}
    assert launch.names["world"] == f"share/class_world/worlds/{world}"
    assert launch.model == ("os.environ.get", ["TURTLEBOT3_MODEL", "burger"], {})
    assert launch.names["robot_sdf"] == "share/turtlebot3_gazebo/models/turtlebot3_<model>/model.sdf"
    rsp = launch.node("robot_state_publisher", "robot_state_publisher")
    (params,) = rsp["parameters"]
    assert params["use_sim_time"] == "$(use_sim_time)"
    description = params["robot_description"]   # ParameterValue(Command(['xacro ', urdf]), value_type=str)
    assert description[0] == "ParameterValue" and description[1][0][0] == "Command"
    assert description[1][0][1] == [["xacro ", "share/turtlebot3_description/urdf/turtlebot3_<model>.urdf"]]
    spawn = launch.node(*(("ros_gz_sim", "create") if ros == "jazzy" else ("gazebo_ros", "spawn_entity.py")))
    assert flags(spawn["arguments"]) == {"-name" if ros == "jazzy" else "-entity": "turtlebot3_<model>",
                                         "-file": launch.names["robot_sdf"], "-x": "$(x_pose)", "-y": "$(y_pose)",
                                         "-z": "$(z_pose)", "-Y": "$(yaw)"}
    extra = launch.node("lab_a", "stop_at_wall")
    assert extra["name"] == "stop_at_wall" and extra["parameters"] == [{"use_sim_time": "$(use_sim_time)"}]
    includes = launch.called("IncludeLaunchDescription")
    sources = [args[0][1][0] for _, _, args in includes]
    if ros == "humble":
        assert sources == ["share/gazebo_ros/launch/gzserver.launch.py", "share/gazebo_ros/launch/gzclient.launch.py"]
        assert includes[0][1]["launch_arguments"] == {"world": launch.names["world"]}
        assert "condition" in includes[1][1] and not launch.called("AppendEnvironmentVariable")
        assert "ros_gz" not in text
    else:
        assert sources == ["share/ros_gz_sim/launch/gz_sim.launch.py"] * 2
        server, gui = (kw["launch_arguments"] for _, kw, _ in includes)
        assert server == {"gz_args": ["-r -s -v2 ", launch.names["world"]], "on_exit_shutdown": "true"}
        assert gui == {"gz_args": "-g -v2 ", "on_exit_shutdown": "true"}
        assert includes[1][1]["condition"] == ("IfCondition", ["$(gui)"], {})
        assert launch.called("AppendEnvironmentVariable")[0][2] == ["GZ_SIM_RESOURCE_PATH",
                                                                     "share/turtlebot3_gazebo/models"]
        bridge = launch.node("ros_gz_bridge", "parameter_bridge")
        assert bridge["arguments"] == ["--ros-args", "-p",
                                       "config_file:=share/class_world/params/turtlebot3_bridge.yaml"]
        assert "gazebo_ros" not in text


@pytest.mark.parametrize("model, line", [
    ("optenv", "model = os.environ.get('TURTLEBOT3_MODEL', 'burger')"),
    ("env", "model = os.environ['TURTLEBOT3_MODEL']"),
    ("waffle_pi", "model = 'waffle_pi'"),
])
def test_the_model_comes_from_turtlebot3_model(model, line):
    assert f"    {line}\n" in launch_py("w.world", "p", "humble", model=model)


@pytest.mark.parametrize("kwargs, words", [
    ({"ros": "noetic"}, "not a ROS 2 target"),
    ({"model": "burgr"}, "unknown robot model"),
    ({"package": "bad package"}, "bad package name"),
    ({"world_file": "my world.sdf"}, "cannot be passed to Gazebo"),
    ({"world_file": "back\\slash.sdf"}, "Python launch file"),
    ({"nodes": [parse_node("a/x:robot_state_publisher")]}, "two nodes would be named"),
])
def test_launch_py_refuses(kwargs, words):
    args = {"world_file": "w.sdf", "package": "p", "ros": "jazzy", **kwargs}
    with pytest.raises(InputError, match=words):
        launch_py(**args)


# ---------------------------------------------------------------------------------------------------- bridge

def test_bridge_yaml_has_turtlebot3s_topics():
    entries = yaml.safe_load(bridge_yaml())
    by_topic = {e["ros_topic_name"]: e for e in entries}
    assert list(by_topic) == ["clock", "joint_states", "odom", "tf", "cmd_vel", "imu", "scan"]
    assert all(e["gz_topic_name"] == e["ros_topic_name"] for e in entries)
    assert {t: (e["ros_type_name"], e["gz_type_name"], e["direction"]) for t, e in by_topic.items()} == {
        "clock": ("rosgraph_msgs/msg/Clock", "gz.msgs.Clock", "GZ_TO_ROS"),
        "joint_states": ("sensor_msgs/msg/JointState", "gz.msgs.Model", "GZ_TO_ROS"),
        "odom": ("nav_msgs/msg/Odometry", "gz.msgs.Odometry", "GZ_TO_ROS"),
        "tf": ("tf2_msgs/msg/TFMessage", "gz.msgs.Pose_V", "GZ_TO_ROS"),
        "cmd_vel": ("geometry_msgs/msg/TwistStamped", "gz.msgs.Twist", "ROS_TO_GZ"),
        "imu": ("sensor_msgs/msg/Imu", "gz.msgs.IMU", "GZ_TO_ROS"),
        "scan": ("sensor_msgs/msg/LaserScan", "gz.msgs.LaserScan", "GZ_TO_ROS"),
    }
    twist = {e["ros_topic_name"]: e["ros_type_name"] for e in yaml.safe_load(bridge_yaml("twist"))}
    assert twist["cmd_vel"] == "geometry_msgs/msg/Twist"
    assert bridge_yaml() == bridge_yaml() and bridge_yaml("twist") != bridge_yaml()


def test_cmd_vel_types_per_target():
    assert [cmd_vel_type("jazzy"), cmd_vel_type("jazzy", "twist"), cmd_vel_type("humble"),
            cmd_vel_type("noetic", "twist")] == ["stamped", "twist", "twist", "twist"]
    with pytest.raises(InputError, match="for --ros jazzy"):
        cmd_vel_type("humble", "stamped")


# -------------------------------------------------------------------------------------------------------- CLI

def test_build_package_and_launch_for_jazzy(tmp_path):
    runner = CliRunner()
    pkg = tmp_path / "my_lab"
    created = runner.invoke(main, ["scaffold", "my_lab", "rclpy", "--ros", "jazzy", "-p", str(tmp_path)])
    assert created.exit_code == 0, created.output
    built = runner.invoke(main, ["build", str(EXAMPLES / "enclosed_room.yaml"), "--ros", "jazzy", "--package",
                                 str(pkg)])
    assert built.exit_code == 0, built.output
    for rel in ("worlds/enclosed_room.sdf", "launch/turtlebot3_in_enclosed_room.launch.py",
                "params/turtlebot3_bridge.yaml"):
        assert (pkg / rel).is_file(), rel
    first = Launch((pkg / "launch" / "turtlebot3_in_enclosed_room.launch.py").read_text())
    assert first.names["world"] == "share/my_lab/worlds/enclosed_room.sdf"
    # a second world in the same package shares the bridge file: no --force needed for it
    other = runner.invoke(main, ["launch", str(pkg / "worlds" / "enclosed_room.sdf"), "--ros", "jazzy",
                                 "--name", "again", "--spawn", "1.0,-0.5,1.57", "--node", "my_lab/driver"])
    assert other.exit_code == 0, other.output
    again = Launch((pkg / "launch" / "again.launch.py").read_text())
    assert {k: v for k, v in arguments(again).items() if k in ("x_pose", "y_pose", "yaw")} == \
        {"x_pose": "1.0", "y_pose": "-0.5", "yaw": "1.57"}
    assert again.node("my_lab", "driver")["name"] == "driver"
    # a bridge file that would differ (--cmd-vel twist) is refused without --force
    twist = runner.invoke(main, ["launch", str(pkg / "worlds" / "enclosed_room.sdf"), "--ros", "jazzy",
                                 "--name", "twist", "--cmd-vel", "twist"])
    assert twist.exit_code == 2 and "turtlebot3_bridge.yaml exists" in twist.output
    assert not (pkg / "launch" / "twist.launch.py").exists()


def test_launch_for_humble_and_its_refusals(tmp_path):
    runner = CliRunner()
    pkg = tmp_path / "h"
    assert runner.invoke(main, ["scaffold", "h", "--ros", "humble", "-p", str(tmp_path), "--world",
                                str(EXAMPLES / "enclosed_room.yaml")]).exit_code == 0
    world = pkg / "worlds" / "enclosed_room.world"
    assert runner.invoke(main, ["build", str(EXAMPLES / "enclosed_room.yaml"), "-o", str(tmp_path)]).exit_code == 0
    assert world.read_bytes() == (tmp_path / "enclosed_room.world").read_bytes()   # the classic world, as noetic's
    made = runner.invoke(main, ["launch", str(world), "--ros", "humble", "--name", "mine.launch.py"])
    assert made.exit_code == 0, made.output
    assert not (pkg / "params").exists()
    stamped = runner.invoke(main, ["launch", str(world), "--ros", "humble", "--cmd-vel", "stamped", "--force"])
    assert stamped.exit_code == 2 and "for --ros jazzy" in stamped.output
