"""ROS 2 packages (--ros humble|jazzy): ros2 pkg create's ament_python shape, the class's colcon workspace, the
rclpy nodes' control law, and colcon building all of it."""

from __future__ import annotations

import importlib.util
import math
import shutil
import subprocess
import sys
import types
from pathlib import Path
from types import SimpleNamespace

import pytest
from conftest import EXAMPLES, CliRunner

from worldgen.cli import main
from worldgen.packages.ament import python_str
from worldgen.packages.course_ros2 import write_course_ros2

LABS = ["lab_a_spin_circles", "lab_a_stop_at_wall"]
WORLD_PACKAGE = "class_meeting_02_custom_gazebo_world"
TESTS = ["test/test_copyright.py", "test/test_flake8.py", "test/test_pep257.py"]
LAUNCH_DEPENDS = {"humble": ["gazebo_ros", "robot_state_publisher", "turtlebot3_description", "turtlebot3_gazebo",
                             "xacro"],
                  "jazzy": ["robot_state_publisher", "ros_gz_bridge", "ros_gz_sim", "turtlebot3_description",
                            "turtlebot3_gazebo", "xacro"]}


def tree(root: Path) -> dict[str, bytes]:
    return {str(p.relative_to(root)): p.read_bytes() for p in sorted(root.rglob("*")) if p.is_file()}


def parse(manifest: Path):
    catkin_pkg = pytest.importorskip("catkin_pkg.package")
    warnings: list = []
    package = catkin_pkg.parse_package(str(manifest), warnings=warnings)
    assert warnings == []
    return package


def names(deps) -> list[str]:
    return sorted(d.name for d in deps)


# ------------------------------------------------------------------------------------------------- scaffold

@pytest.mark.parametrize("ros", ["humble", "jazzy"])
def test_scaffold_is_ros2_pkg_create_ament_python(ros, tmp_path):
    result = CliRunner().invoke(main, ["scaffold", "my_lab", "rclpy", "std_msgs", "geometry_msgs", "sensor_msgs",
                                       "--ros", ros, "-p", str(tmp_path), "-m", "Ada Lovelace <ada@uni.edu>",
                                       "--world", str(EXAMPLES / "enclosed_room.yaml")])
    assert result.exit_code == 0, result.output
    pkg = tmp_path / "my_lab"
    files = set(tree(pkg))
    world = "worlds/enclosed_room.sdf" if ros == "jazzy" else "worlds/enclosed_room.world"
    expected = {"package.xml", "setup.py", "setup.cfg", "resource/my_lab", "my_lab/__init__.py", world,
                "launch/turtlebot3_in_enclosed_room.launch.py"} | set(TESTS)
    if ros == "jazzy":
        expected.add("params/turtlebot3_bridge.yaml")
    assert files == expected
    assert (pkg / "resource" / "my_lab").read_bytes() == b"" and (pkg / "my_lab" / "__init__.py").read_bytes() == b""
    text = (pkg / "package.xml").read_text()
    assert text.startswith('<?xml version="1.0"?>\n<?xml-model href="http://download.ros.org/schema/'
                           'package_format3.xsd"')
    package = parse(pkg / "package.xml")
    assert (package.package_format, package.name, package.version) == (3, "my_lab", "0.0.0")
    assert (package.description, package.licenses) == ("TODO: Package description", ["TODO: License declaration"])
    assert [(m.name, m.email) for m in package.maintainers] == [("Ada Lovelace", "ada@uni.edu")]
    assert names(package.build_depends) == names(package.exec_depends[:0]) + \
        ["geometry_msgs", "rclpy", "sensor_msgs", "std_msgs"]   # <depend>: build, export and exec
    assert names(package.exec_depends) == sorted(["geometry_msgs", "rclpy", "sensor_msgs", "std_msgs"]
                                                 + LAUNCH_DEPENDS[ros])
    assert names(package.test_depends) == ["ament_copyright", "ament_flake8", "ament_pep257", "python3-pytest"]
    assert package.buildtool_depends == []
    assert [(e.tagname, e.content) for e in package.exports] == [("build_type", "ament_python")]
    assert (pkg / "setup.cfg").read_text() == ("[develop]\nscript_dir=$base/lib/my_lab\n"
                                               "[install]\ninstall_scripts=$base/lib/my_lab\n")
    setup = (pkg / "setup.py").read_text()
    compile(setup, "setup.py", "exec")
    assert "package_name = 'my_lab'" in setup and "data_files('launch')" in setup
    assert ("data_files('params')" in setup) == (ros == "jazzy")


def test_scaffold_without_a_world_has_no_launch_depends(tmp_path):
    assert CliRunner().invoke(main, ["scaffold", "bare", "--ros", "humble", "-p", str(tmp_path)]).exit_code == 0
    package = parse(tmp_path / "bare" / "package.xml")
    assert package.exec_depends == [] and package.build_depends == []
    assert sorted(tree(tmp_path / "bare")) == sorted(["package.xml", "setup.py", "setup.cfg", "resource/bare",
                                                      "bare/__init__.py", "launch/.gitkeep", "worlds/.gitkeep"]
                                                     + TESTS)


@pytest.mark.parametrize("args, words", [
    (["test"], "cannot be named 'test'"),
    (["lab", "--meta"], "no catkin metapackages"),
    (["lab", "-b", "thread"], "-b/--boost-comps"),
    (["lab", "rospy"], "depend on rclpy instead"),
    (["lab", "--cmd-vel", "stamped"], "for --ros jazzy"),
])
def test_scaffold_refusals_write_nothing(tmp_path, args, words):
    result = CliRunner().invoke(main, ["scaffold"] + args + ["--ros", "humble", "-p", str(tmp_path)])
    assert result.exit_code == 2 and words in result.output and not list(tmp_path.iterdir())


def test_noetic_hint_names_the_ros2_targets(tmp_path):
    result = CliRunner().invoke(main, ["scaffold", "lab", "--rosdistro", "jazzy", "-p", str(tmp_path)])
    assert result.exit_code == 2 and "--ros humble or --ros jazzy" in result.output


def test_long_python_strings_are_split_at_spaces():
    text = "word " * 40 + "end"
    literal = python_str(text, 16)
    assert literal.startswith("(\n") and all(len(line) <= 99 for line in literal.splitlines())
    assert eval(literal) == text
    assert python_str("it's") == '"it\'s"' and eval(python_str("a\nb")) == "a\nb"


# --------------------------------------------------------------------------------------------------- course

@pytest.fixture(scope="module", params=["humble", "jazzy"])
def course(request, tmp_path_factory):
    return request.param, write_course_ros2(tmp_path_factory.mktemp(request.param), request.param)


def test_course_layout_and_manifests(course):
    ros, root = course
    assert root.parent.name == "src" and root.name == "intro_robo"
    assert sorted(p.name for p in root.iterdir()) == sorted(LABS + [WORLD_PACKAGE])
    files = tree(root)
    world = "enclosed_room.sdf" if ros == "jazzy" else "enclosed_room.world"
    for name in (f"{WORLD_PACKAGE}/worlds/{world}", f"{WORLD_PACKAGE}/launch/turtlebot3_in_enclosed_room.launch.py",
                 "lab_a_spin_circles/lab_a_spin_circles/spin_in_circles.py",
                 "lab_a_stop_at_wall/lab_a_stop_at_wall/stop_at_wall.py",
                 "lab_a_stop_at_wall/launch/stop_at_wall.launch.py", "lab_a_spin_circles/launch/spin_in_circles.launch.py"):
        assert name in files, name
    assert (f"{WORLD_PACKAGE}/params/turtlebot3_bridge.yaml" in files) == (ros == "jazzy")
    for lab in LABS:
        package = parse(root / lab / "package.xml")
        assert package.package_format == 3 and package.version == "0.1.0" and package.licenses == ["BSD"]
        assert names(package.exec_depends) == sorted(["geometry_msgs", "rclpy", "sensor_msgs", "std_msgs", WORLD_PACKAGE]
                                                     + LAUNCH_DEPENDS[ros])
        node = lab.replace("lab_a_", "").replace("spin_circles", "spin_in_circles")
        assert f"'{node} = {lab}.{node}:main'," in (root / lab / "setup.py").read_text()
    for path in root.rglob("*"):
        if path.is_file():
            assert path.stat().st_mode & 0o777 == 0o644, path   # entry points, not executable files


def test_course_is_deterministic_and_all_or_nothing(course, tmp_path):
    ros, root = course
    again = write_course_ros2(tmp_path, ros)
    assert tree(again) == tree(root)
    runner = CliRunner()
    refused = runner.invoke(main, ["course", "--ros", ros, "--workspace", str(tmp_path)])
    assert refused.exit_code == 2 and "exists" in refused.output
    forced = runner.invoke(main, ["course", "--ros", ros, "--workspace", str(tmp_path), "--force"])
    assert forced.exit_code == 0 and "colcon build" in forced.output
    assert tree(again) == tree(root)


def test_jazzy_twist_course_publishes_twist(tmp_path):
    root = write_course_ros2(tmp_path, "jazzy", cmd_vel="twist")
    node = (root / "lab_a_stop_at_wall" / "lab_a_stop_at_wall" / "stop_at_wall.py").read_text()
    assert "from geometry_msgs.msg import Twist\n" in node and "TwistStamped" not in node
    assert '"geometry_msgs/msg/Twist"' in (root / WORLD_PACKAGE / "params" / "turtlebot3_bridge.yaml").read_text()


# ------------------------------------------------------------------------- the rclpy nodes, on a stand-in rclpy

class _Message(SimpleNamespace):
    pass


def _twist():
    return _Message(linear=_Message(x=0.0, y=0.0, z=0.0), angular=_Message(x=0.0, y=0.0, z=0.0))


class _Node:
    """What the nodes use of rclpy.node.Node: parameters, a publisher, a subscription, a timer, a clock."""

    overrides: dict = {}

    def __init__(self, name):
        self.node_name, self.published, self.callbacks = name, [], {}

    def declare_parameter(self, name, default, descriptor=None):
        assert descriptor.dynamic_typing   # kp:=1 and kp:=1.0 both work
        return SimpleNamespace(value=self.overrides.get(name, default))

    def create_publisher(self, kind, topic, depth):
        return SimpleNamespace(publish=lambda message: self.published.append((topic, kind.__name__, message)))

    def create_subscription(self, kind, topic, callback, qos):
        self.callbacks[topic] = (kind.__name__, qos)
        return object()

    def create_timer(self, period, callback):
        self.callbacks["timer"] = period
        return object()

    def get_clock(self):
        return SimpleNamespace(now=lambda: SimpleNamespace(to_msg=lambda: _Message(sec=1, nanosec=0)))

    def get_logger(self):
        return SimpleNamespace(debug=lambda *a: None)


def _stand_in_ros(monkeypatch):
    def module(name, **attrs):
        mod = types.ModuleType(name)
        mod.__dict__.update(attrs)
        monkeypatch.setitem(sys.modules, name, mod)
        return mod

    class Twist:
        def __new__(cls):
            return _twist()

    class TwistStamped:
        def __new__(cls):
            return _Message(header=_Message(stamp=None, frame_id=""), twist=_twist())

    module("rclpy", ok=lambda: True, init=lambda args=None: None, spin=lambda node: None, shutdown=lambda: None)
    module("rclpy.node", Node=_Node)
    module("rclpy.qos", qos_profile_sensor_data="sensor-data")
    module("geometry_msgs")
    module("geometry_msgs.msg", Twist=Twist, TwistStamped=TwistStamped)
    module("sensor_msgs")
    module("sensor_msgs.msg", LaserScan=type("LaserScan", (), {}))
    module("rcl_interfaces")
    module("rcl_interfaces.msg", ParameterDescriptor=lambda dynamic_typing=False: SimpleNamespace(
        dynamic_typing=dynamic_typing))


def load(path: Path):
    spec = importlib.util.spec_from_file_location(f"node_{path.stem}_{abs(hash(path))}", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def scan(ranges, sec, nanosec=0):
    return SimpleNamespace(ranges=ranges, angle_min=0.0, angle_increment=2 * math.pi / len(ranges), range_min=0.12,
                           range_max=3.5, header=SimpleNamespace(stamp=SimpleNamespace(sec=sec, nanosec=nanosec)))


def test_stop_at_wall_runs_drives_law(course, monkeypatch):
    import random

    from worldgen.core import stoplaw

    ros, root = course
    _stand_in_ros(monkeypatch)
    node_module = load(root / "lab_a_stop_at_wall" / "lab_a_stop_at_wall" / "stop_at_wall.py")
    for nothing in (math.inf, 0.0, math.nan):   # inf (Gazebo) and 0 (real LDS-01): nothing seen
        assert node_module.front_distance(scan([nothing] * 360, 0), math.radians(10)) is None
    rng = random.Random(11)
    for run in range(20):
        gains = {"kp": rng.choice([0.1, 0.5, 3.0]), "ki": rng.choice([0.0, 0.2]), "kd": rng.choice([0.0, 0.3]),
                 "max_speed": 0.22, "stop_band": rng.choice([0.0, 0.01])}
        law, ours = node_module.StopLaw(target_distance=0.5, **gains), stoplaw.StopLaw(target=0.5, **gains)
        front = rng.uniform(0.4, 3.0)
        for step in range(50):
            front = max(0.15, front - rng.uniform(-0.02, 0.08))
            reading = None if rng.random() < 0.05 else front + rng.gauss(0.0, 0.01)
            assert law.step(reading, 0.0 if step == 0 else 0.2) == ours.step(reading, 0.0 if step == 0 else 0.2)
    monkeypatch.setattr(_Node, "overrides", {"kp": 1})   # an integer from the command line
    node = node_module.StopAtWall()
    assert node.callbacks["scan"] == ("LaserScan", "sensor-data") and node.law.kp == 1.0
    node.on_scan(scan([3.0] * 360, 10))
    node.on_scan(scan([0.6] * 360, 10, 200_000_000))
    (topic, kind, first), (_, _, second) = node.published
    assert topic == "cmd_vel" and kind == ("TwistStamped" if ros == "jazzy" else "Twist")
    speed = (lambda m: m.twist.linear.x) if ros == "jazzy" else (lambda m: m.linear.x)
    assert speed(first) == 0.22 and speed(second) == pytest.approx(0.1)   # kp 1 · (0.6 − 0.5)
    node.stop()
    assert speed(node.published[-1][2]) == 0.0


def test_spin_in_circles_publishes_its_twist(course, monkeypatch):
    ros, root = course
    _stand_in_ros(monkeypatch)
    node = load(root / "lab_a_spin_circles" / "lab_a_spin_circles" / "spin_in_circles.py").SpinInCircles()
    assert node.callbacks["timer"] == 0.1
    node.on_timer()
    (topic, kind, message), = node.published
    twist = message.twist if ros == "jazzy" else message
    assert (topic, kind, twist.linear.x, twist.angular.z) == (
        "cmd_vel", "TwistStamped" if ros == "jazzy" else "Twist", 0.1, 0.5)


# ---------------------------------------------------------------------------------------------------- colcon

def colcon() -> str:
    found = shutil.which("colcon", path=str(Path(sys.executable).parent)) or shutil.which("colcon")
    if found is None:
        pytest.skip("colcon is not installed (pip install colcon-common-extensions)")
    return found


@pytest.mark.parametrize("ros", ["humble", "jazzy"])
def test_colcon_builds_the_workspace(ros, tmp_path):
    tool = colcon()
    write_course_ros2(tmp_path, ros)
    assert CliRunner().invoke(main, ["scaffold", "my_lab", "rclpy", "--ros", ros, "-p", str(tmp_path / "src"),
                                     "--world", str(EXAMPLES / "enclosed_room.yaml")]).exit_code == 0
    build = subprocess.run([tool, "build", "--event-handlers", "console_direct-"], cwd=tmp_path,
                           capture_output=True, text=True, timeout=600)
    assert build.returncode == 0, build.stdout + build.stderr
    assert "4 packages finished" in build.stdout
    install = tmp_path / "install"
    world = "enclosed_room.sdf" if ros == "jazzy" else "enclosed_room.world"
    for pkg in (WORLD_PACKAGE, "my_lab"):
        share = install / pkg / "share" / pkg
        for rel in (f"worlds/{world}", "launch/turtlebot3_in_enclosed_room.launch.py", "package.xml"):
            assert (share / rel).is_file(), (pkg, rel)
        assert (share / "params" / "turtlebot3_bridge.yaml").is_file() == (ros == "jazzy")
        assert not list(share.rglob(".gitkeep"))
        assert (install / pkg / "share" / "ament_index" / "resource_index" / "packages" / pkg).is_file()
    for lab, node in (("lab_a_spin_circles", "spin_in_circles"), ("lab_a_stop_at_wall", "stop_at_wall")):
        script = install / lab / "lib" / lab / node
        text = script.read_text()
        assert text.startswith("#!") and script.stat().st_mode & 0o111
        assert f"'console_scripts','{node}'" in text or f"from {lab}.{node} import main" in text
        (entry_points,) = (install / lab / "lib").rglob("entry_points.txt")
        assert f"{node} = {lab}.{node}:main" in entry_points.read_text()
        assert (install / lab / "share" / lab / "launch" / f"{node}.launch.py").is_file()
