"""ROS 2 Python launch files read without running them: the world, the spawn pose and the robot model, in the
shapes turtlebot3_gazebo's humble and jazzy launch files use, and a finding (file:line) for what cannot be read."""

from __future__ import annotations

import os
import textwrap
from pathlib import Path

import pytest

from ros2pkgs import (cmake_package, declared_pose_launch, humble_launch, jazzy_spawn_launch, jazzy_world_launch,
                      looped_launch, python_package, room_sdf, unfollowed_call_launch, write)
from worldgen.core.errors import WorldFileError
from worldgen.launch.gazebo_py import command_kind, gazebo_world, gz_world, robot_model
from worldgen.launch.reader import is_python_launch, nothing_to_simulate, read_launch

HEADER = """
    import os
    from pathlib import Path

    from ament_index_python.packages import get_package_share_directory
    from launch import LaunchDescription
    from launch.actions import (DeclareLaunchArgument, ExecuteProcess, GroupAction, IncludeLaunchDescription,
                                OpaqueFunction, RegisterEventHandler, TimerAction)
    from launch.conditions import IfCondition, UnlessCondition
    from launch.event_handlers import OnProcessExit
    from launch.launch_description_sources import PythonLaunchDescriptionSource
    from launch.substitutions import LaunchConfiguration, PathJoinSubstitution
    from launch_ros.actions import Node, PushRosNamespace
    from launch_ros.substitutions import FindPackageShare
    """


@pytest.fixture
def ws(tmp_path) -> Path:
    """A colcon workspace's src/ with a Humble-style ament_python package and a Jazzy-style ament_cmake one."""
    src = tmp_path / "ws" / "src"
    python_package(src, "room_humble", {"room.launch.py": humble_launch("room_humble")}, {"room.world": room_sdf()})
    cmake_package(src, "room_jazzy", {"room.launch.py": jazzy_world_launch("room_jazzy"),
                                      "spawn_robot.launch.py": jazzy_spawn_launch()},
                  {"room.sdf": room_sdf(version="1.8", gz_sim=True)})
    return src


def launch_in(ws: Path, name: str, body: str, package: str = "room_humble") -> Path:
    return write(ws / package / "launch" / name, textwrap.dedent(HEADER) + textwrap.dedent(body))


def messages(info) -> list[str]:
    return [f"{f.severity} {f.check}: {f.message} @ {f.where}" for f in info.findings]


# ---------------------------------------------------------------------------------------- the ROBOTIS shapes

def test_humble_shape_world_from_gzserver_and_spawn_entity_pose(ws):
    launch = ws / "room_humble" / "launch" / "room.launch.py"
    info = read_launch(launch, environ={})
    assert info.world_path == ws / "room_humble" / "worlds" / "room.world"
    assert info.package == "room_humble" and info.simulator == "gazebo"
    assert info.spawn == (1.0, 0.5, 0.01, 0.0)
    assert info.model == "burger"   # os.environ.get('TURTLEBOT3_MODEL', 'burger'), unset
    [robot] = info.robots
    assert (robot.node, robot.model_name, robot.robot, robot.line) == ("/spawn_entity.py", "burger", "burger", 21)
    assert [(n.package, n.type) for n in info.nodes] == [("gazebo_ros", "spawn_entity.py")]
    assert info.findings == []
    assert read_launch(launch, environ={"TURTLEBOT3_MODEL": "waffle_pi"}).model == "waffle_pi"


def test_jazzy_shape_follows_the_spawn_include_with_the_pose_passed_down(ws):
    launch = ws / "room_jazzy" / "launch" / "room.launch.py"
    info = read_launch(launch, environ={"TURTLEBOT3_MODEL": "waffle"})
    assert info.world_path == ws / "room_jazzy" / "worlds" / "room.sdf"   # from gz_args ['-r -s -v2 ', world]
    assert info.simulator == "gz-sim" and info.package == "room_jazzy"
    assert info.spawn == (-1.0, 0.5, 0.01, 0.0)   # x_pose/y_pose defaults here, passed over the included 0.0
    assert info.model == "waffle" and info.includes == [ws / "room_jazzy" / "launch" / "spawn_robot.launch.py"]
    assert info.args == {"x_pose": "-1.0", "y_pose": "0.5"}
    # the image bridge is added only for a model other than burger: the condition is read
    assert [n.type for n in info.nodes] == ["create", "parameter_bridge", "image_bridge"]
    assert info.findings == []
    burger = read_launch(launch, environ={"TURTLEBOT3_MODEL": "burger"})
    assert [n.type for n in burger.nodes] == ["create", "parameter_bridge"]


def test_an_unset_turtlebot3_model_is_an_info_and_leaves_the_model_unknown(ws):
    info = read_launch(ws / "room_jazzy" / "launch" / "room.launch.py", environ={})
    assert info.model is None and info.model_env == "TURTLEBOT3_MODEL"
    assert info.spawn == (-1.0, 0.5, 0.01, 0.0)   # the pose does not depend on it
    assert messages(info) == [
        "info launch-env: the robot model is not known: environment variable TURTLEBOT3_MODEL is not set @ "
        f"{ws / 'room_jazzy' / 'launch' / 'spawn_robot.launch.py'}:10"]


def test_command_line_arguments_override_the_defaults(ws):
    info = read_launch(ws / "room_jazzy" / "launch" / "room.launch.py", {"x_pose": "1.25"},
                       environ={"TURTLEBOT3_MODEL": "burger"})
    assert info.spawn == (1.25, 0.5, 0.01, 0.0)


def test_pose_and_world_from_declare_launch_argument_defaults(ws):
    launch = write(ws / "room_humble" / "launch" / "declared.launch.py", declared_pose_launch("room_humble"))
    info = read_launch(launch, environ={})
    assert info.spawn == (0.8, -0.6, 0.0, 1.57)
    assert info.world_path == ws / "room_humble" / "worlds" / "room.world"   # PathJoinSubstitution(FindPackageShare)
    assert info.model == "waffle"   # EnvironmentVariable('TURTLEBOT3_MODEL', default_value='waffle')
    assert info.robots[0].node == "/spawner"
    assert info.args["x"] == "0.8" and info.args["world"] == str(ws / "room_humble" / "worlds" / "room.world")
    assert read_launch(launch, {"yaw": "-0.5"}, environ={}).spawn == (0.8, -0.6, 0.0, -0.5)


# ------------------------------------------------------------------------------ what cannot be read statically

def test_a_spawn_in_a_loop_is_a_finding_and_no_pose(ws):
    launch = write(ws / "room_humble" / "launch" / "looped.launch.py", looped_launch("room_humble"))
    info = read_launch(launch, environ={})
    assert info.world_path == ws / "room_humble" / "worlds" / "room.world"   # what is outside the loop still is
    assert info.spawn is None and info.robots == []
    [finding] = info.findings
    assert (finding.check, finding.severity, finding.where) == ("launch-static", "warning", f"{launch}:18")
    assert finding.message.startswith("the for loop at line 18 builds Node (spawn_entity.py): not run here")
    assert "--spawn" in finding.fix


def test_a_pose_from_a_call_it_cannot_follow_is_a_finding_naming_the_call(ws):
    launch = write(ws / "room_humble" / "launch" / "called.launch.py", unfollowed_call_launch("room_humble"))
    info = read_launch(launch, environ={})
    assert info.spawn is None and info.robots[0].pose is None
    assert messages(info) == [
        f"warning launch-static: spawn_entity.py -x, -y: room_humble.poses.start_pose() is a call worldgen does not "
        f"follow (launch files are read, never run) (line 14) @ {launch}:20"]


def test_functions_of_the_file_itself_are_followed(ws):
    launch = launch_in(ws, "helper.launch.py", """
        ROBOTS = {'lead': (0.5, -0.25)}


        def spawn(name, x, y, yaw=0.0):
            return Node(package='gazebo_ros', executable='spawn_entity.py', name=f'spawn_{name}',
                        arguments=['-entity', name, '-x', str(x), '-y', str(y), '-Y', f'{yaw:.2f}'])


        def generate_launch_description():
            x, y = ROBOTS['lead']
            return LaunchDescription([spawn('lead', x, y, yaw=1.5)])
        """)
    info = read_launch(launch, environ={})
    assert info.spawn == (0.5, -0.25, 0.0, 1.5) and info.robots[0].node == "/spawn_lead"


def test_a_condition_that_cannot_be_told_around_a_spawn_is_a_finding(ws):
    launch = launch_in(ws, "cond.launch.py", """
        import random


        def generate_launch_description():
            description = LaunchDescription()
            if random.random() > 0.5:
                description.add_action(Node(package='ros_gz_sim', executable='create', arguments=['-x', '1']))
            return description
        """)
    info = read_launch(launch, environ={})
    assert info.robots == []
    [finding] = info.findings
    assert finding.where == f"{launch}:20" and finding.message.startswith(
        "the if at line 20 (its condition cannot be told: random.random() is a call worldgen does not follow")


def test_launch_conditions_are_evaluated(ws):
    launch = launch_in(ws, "gui.launch.py", """
        def generate_launch_description():
            return LaunchDescription([
                DeclareLaunchArgument('spawn_robot', default_value='false'),
                Node(package='gazebo_ros', executable='spawn_entity.py', arguments=['-x', '1.0'],
                     condition=IfCondition(LaunchConfiguration('spawn_robot'))),
                Node(package='gazebo_ros', executable='spawn_entity.py', arguments=['-x', '2.0'],
                     condition=UnlessCondition(LaunchConfiguration('spawn_robot'))),
                Node(package='gazebo_ros', executable='spawn_entity.py', arguments=['-x', '3.0'],
                     condition=IfCondition(LaunchConfiguration('not_declared'))),
            ])
        """)
    info = read_launch(launch, environ={})
    assert [r.pose[0] for r in info.robots] == [2.0, 3.0] and info.spawn[0] == 2.0
    [finding] = info.findings
    assert finding.check == "launch-arg" and "condition= assumed satisfied: launch argument 'not_declared'" in \
        finding.message
    assert read_launch(launch, {"spawn_robot": "true"}, environ={}).spawn[0] == 1.0


def test_groups_namespaces_timers_event_handlers_and_opaque_functions(ws):
    launch = launch_in(ws, "many.launch.py", """
        def late(context, *args, **kwargs):
            x = LaunchConfiguration('x').perform(context)
            return [Node(package='ros_gz_sim', executable='create', name='late', arguments=['-x', x, '-y', '2'])]


        def generate_launch_description():
            first = Node(package='ros_gz_sim', executable='create', name='first', arguments=['-x', '1'])
            return LaunchDescription([
                DeclareLaunchArgument('x', default_value='4.5'),
                GroupAction([PushRosNamespace('tb3_0'), first]),
                TimerAction(period=3.0, actions=[
                    Node(package='ros_gz_sim', executable='create', name='timed', arguments=['-x', '3'])]),
                RegisterEventHandler(OnProcessExit(target_action=first, on_exit=[OpaqueFunction(function=late)])),
            ])
        """)
    info = read_launch(launch, environ={})
    assert [(r.node, r.ns, r.pose[:2]) for r in info.robots] == [
        ("/tb3_0/first", "/tb3_0", (1.0, 0.0)), ("/timed", "/", (3.0, 0.0)), ("/late", "/", (4.5, 2.0))]
    assert info.findings == []


@pytest.mark.parametrize("cmd, simulator", [
    ("['gz', 'sim', '-r', '-v', '4', world]", "gz-sim"),
    ("['gazebo', '--verbose', world, '-s', 'libgazebo_ros_factory.so']", "gazebo"),
])
def test_a_simulator_started_as_a_process(ws, cmd, simulator):
    launch = launch_in(ws, "process.launch.py", f"""
        def generate_launch_description():
            world = str(Path(__file__).resolve().parent.parent / 'worlds' / 'room.world')
            return LaunchDescription([
                ExecuteProcess(cmd={cmd}, output='screen'),
                ExecuteProcess(cmd=['ros2', 'run', 'gazebo_ros', 'spawn_entity.py', '-entity', 'tb3', '-y', '-1.5']),
            ])
        """)
    info = read_launch(launch, environ={})
    assert info.world_path == ws / "room_humble" / "worlds" / "room.world" and info.simulator == simulator
    assert info.spawn == (0.0, -1.5, 0.0, 0.0) and info.package == "room_humble"


def test_module_constants_f_strings_and_string_arithmetic(ws):
    launch = launch_in(ws, "consts.launch.py", """
        PACKAGE = 'room_humble'
        STEM = 'room'
        WORLD = f'{STEM}.world'
        X, Y = 1.5, -0.5


        def generate_launch_description():
            share = get_package_share_directory(PACKAGE)
            gz_args = '-r -s -v2 ' + os.path.join(share, 'worlds', WORLD)
            return LaunchDescription([
                IncludeLaunchDescription(
                    PythonLaunchDescriptionSource(
                        os.path.join(get_package_share_directory('ros_gz_sim'), 'launch', 'gz_sim.launch.py')),
                    launch_arguments=[('gz_args', gz_args)]),
                Node(package='ros_gz_sim', executable='create',
                     arguments='-name turtlebot3_waffle -x {} -y {}'.format(X, Y).split()),
            ])
        """)
    info = read_launch(launch, environ={})
    assert info.world_path == ws / "room_humble" / "worlds" / "room.world"
    assert info.spawn == (1.5, -0.5, 0.0, 0.0) and info.model == "waffle"


def test_the_stock_spawn_file_of_a_package_not_installed_spawns_at_the_pose_passed(ws):
    launch = launch_in(ws, "stock.launch.py", """
        def generate_launch_description():
            tb3 = os.path.join(get_package_share_directory('turtlebot3_gazebo'), 'launch')
            return LaunchDescription([
                IncludeLaunchDescription(
                    PythonLaunchDescriptionSource(os.path.join(tb3, 'spawn_turtlebot3.launch.py')),
                    launch_arguments={'x_pose': '-2.0', 'y_pose': '-0.5'}.items()),
            ])
        """)
    info = read_launch(launch, environ={"TURTLEBOT3_MODEL": "waffle"}, ros_package_path=[])
    assert info.spawn == (-2.0, -0.5, 0.01, 0.0) and info.model == "waffle"
    [finding] = info.findings
    assert finding.severity == "info" and "spawns the TurtleBot3 at the x_pose, y_pose passed to it (-2.0, -0.5)" \
        in finding.message


def test_packages_are_found_in_an_ament_install_prefix(ws, tmp_path):
    prefix = tmp_path / "opt" / "ros" / "jazzy"
    installed = prefix / "share" / "class_worlds"
    write(installed / "package.xml", "<package format='3'><name>class_worlds</name></package>")
    write(installed / "worlds" / "big.world", room_sdf(6.0))
    launch = launch_in(ws, "installed.launch.py", """
        def generate_launch_description():
            world = os.path.join(get_package_share_directory('class_worlds'), 'worlds', 'big.world')
            return LaunchDescription([IncludeLaunchDescription(
                PythonLaunchDescriptionSource(
                    os.path.join(get_package_share_directory('gazebo_ros'), 'launch', 'gzserver.launch.py')),
                launch_arguments={'world': world}.items())])
        """)
    assert read_launch(launch, environ={"AMENT_PREFIX_PATH": str(prefix)}).world_path == installed / "worlds" / \
        "big.world"
    missing = read_launch(launch, environ={})
    assert missing.world_path is None and missing.world_ref == "‹class_worlds›/worlds/big.world"
    assert [f.check for f in missing.findings] == ["launch-find"] and missing.findings[0].severity == "warning"


def test_a_world_installed_from_elsewhere_by_data_files_is_found(tmp_path):
    pkg = python_package(tmp_path / "src", "moved", {"room.launch.py": humble_launch("moved")}, {})
    write(pkg / "world_files" / "room.world", room_sdf())
    setup = (pkg / "setup.py").read_text().replace("glob('worlds/*')", "['world_files/room.world']")
    (pkg / "setup.py").write_text(setup)
    assert read_launch(pkg / "launch" / "room.launch.py", environ={}).world_path == pkg / "world_files" / \
        "room.world"


# ---------------------------------------------------------------------------------------- never run, bounded

def test_the_file_is_never_run(ws, tmp_path):
    marker = tmp_path / "ran"
    launch = launch_in(ws, "evil.launch.py", f"""
        import subprocess
        open({str(marker)!r}, 'w').write('module')
        os.system('touch {marker}')


        def generate_launch_description():
            subprocess.run(['touch', {str(marker)!r}])
            __import__('os').system('touch {marker}')
            raise SystemExit(1)
        """)
    info = read_launch(launch, environ={})
    assert not marker.exists() and info.world_ref is None


def test_hostile_values_stay_small_and_quick(ws):
    doubling = "\n".join(["    s = 'ab'"] + ["    s = s + s"] * 80)
    launch = write(ws / "room_humble" / "launch" / "big.launch.py", f"""
from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description():
{doubling}
    wide = '{{:999999999}}'.format(1)
    n = 10 ** 10 ** 10
    return LaunchDescription([Node(package='gazebo_ros', executable='spawn_entity.py',
                                   arguments=['-x', s, '-y', wide, '-z', str(n)])])
""")
    info = read_launch(launch, environ={})
    assert info.spawn is None and len(info.findings) >= 1


@pytest.mark.parametrize("text, line, words", [
    ("def generate_launch_description(:\n    pass\n", 1, "Python cannot parse the launch file"),
    ("from launch import LaunchDescription\n", None, "no generate_launch_description()"),
    ("x = (" * 200 + ")" * 200 + "\ndef generate_launch_description():\n    return None\n", None,
     "Python cannot parse"),
])
def test_files_ros2_launch_could_not_load_are_errors_with_their_line(ws, text, line, words):
    launch = write(ws / "room_humble" / "launch" / "bad.launch.py", "")
    launch.write_text(text)
    with pytest.raises(WorldFileError, match=words) as err:
        read_launch(launch, environ={})
    if line is not None:
        assert err.value.line == line


def test_a_launch_file_including_itself_is_an_error(ws):
    launch = launch_in(ws, "loop.launch.py", """
        def generate_launch_description():
            return LaunchDescription([IncludeLaunchDescription(PythonLaunchDescriptionSource(__file__))])
        """)
    with pytest.raises(WorldFileError, match="includes itself"):
        read_launch(launch, environ={})


# ------------------------------------------------------------------------------------------------- helpers

def test_file_names_and_what_has_nothing_to_simulate(ws):
    assert is_python_launch("a/room.launch.py") and is_python_launch("room_launch.py")
    assert not is_python_launch("room.launch") and not is_python_launch("setup.py")
    spawn_only = read_launch(ws / "room_jazzy" / "launch" / "spawn_robot.launch.py", environ={})
    assert "a part that other launch files include" in nothing_to_simulate(
        ws / "room_jazzy" / "launch" / "spawn_robot.launch.py", spawn_only)
    assert nothing_to_simulate(ws / "room_humble" / "launch" / "room.launch.py",
                               read_launch(ws / "room_humble" / "launch" / "room.launch.py", environ={})) is None


def test_gz_and_gazebo_command_lines():
    assert gz_world("-r -s -v2 /w/room.sdf") == "/w/room.sdf"
    assert gz_world("-g -v2 ") is None
    assert gz_world("-r -v 4 --render-engine ogre2 shapes.sdf") == "shapes.sdf"
    assert gz_world("'/my worlds/a.sdf' -r") == "/my worlds/a.sdf"
    assert gazebo_world(["--verbose", "-s", "libgazebo_ros_init.so", "/w/a.world"]) == "/w/a.world"
    assert command_kind(["gz", "sim", "-r"]) == ("gz-sim", 2) and command_kind(["/usr/bin/gzserver"]) == ("gazebo", 1)
    assert command_kind(["ros2", "run", "pkg", "exe"]) == ("ros2-run", 2) and command_kind(["ls"]) == (None, 1)
    assert robot_model(["tb3", "/share/turtlebot3_gazebo/models/turtlebot3_waffle_pi/model.sdf"]) == "waffle_pi"
    assert robot_model(["my_robot", None]) is None


@pytest.mark.parametrize("ros, world", [("humble", "room.world"), ("jazzy", "room.sdf")])
def test_the_reader_reads_what_worldgens_ros2_launch_writer_writes(ws, ros, world):
    writer = pytest.importorskip("worldgen.launch.writer_py")
    write(ws / "room_humble" / "worlds" / "room.sdf", room_sdf(version="1.8", gz_sim=True))
    text = writer.launch_py(world, "room_humble", ros, model="optenv", spawn=(1.25, -0.5, 0.0, 1.5708))
    launch = ws / "room_humble" / "launch" / "written.launch.py"
    launch.write_text(text, encoding="utf-8")
    info = read_launch(launch, environ={})
    assert info.world_path == ws / "room_humble" / "worlds" / world
    assert info.simulator == {"humble": "gazebo", "jazzy": "gz-sim"}[ros]
    assert info.spawn == (1.25, -0.5, 0.0, 1.5708) and info.model == "burger"
    assert [f for f in info.findings if f.severity != "info"] == []


# ---------------------------------------------------------------------------------------------- any file at all

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

ATOMS = ["'1.5'", "-2", "x", "y", "None", "True", "[1, 'a']", "{'k': x}", "LaunchConfiguration('x_pose')",
         "LaunchConfiguration('w', default=y)", "os.environ['TURTLEBOT3_MODEL']", "os.environ.get('HOME', 'h')",
         "get_package_share_directory('room_humble')", "get_package_share_directory('nowhere')",
         "PathJoinSubstitution([FindPackageShare('room_humble'), 'worlds', x])", "Path(__file__).parent / x",
         "f'{x}-{y!r:>5}'", "'%s/%d' % (x, 3)", "'{}'.format(y)", "unknown_call(x)", "[v for v in range(3)]",
         "lambda: 1", "x[0]", "y[1:]", "x.split()", "os.path.join(x, y)", "(x if y else None)"]
STATEMENTS = [
    "x = {a}", "y = {a} + {b}", "x, y = {a}, {b}", "x += {a}",
    "ld.add_action(Node(package='gazebo_ros', executable='spawn_entity.py', arguments=['-x', {a}, '-y', {b}]))",
    "ld.add_action(IncludeLaunchDescription(PythonLaunchDescriptionSource({a}), launch_arguments={{'world': {b}, "
    "'gz_args': [{a}, {b}]}}.items()))",
    "ld.add_action(DeclareLaunchArgument({a}, default_value={b}))",
    "ld.add_action(GroupAction([PushRosNamespace({a}), Node(package={a}, executable={b})], "
    "condition=IfCondition({a})))",
    "for v in {a}:\n        ld.add_action(v)", "if {a}:\n        x = {b}\n    else:\n        y = {a}",
    "while {a}:\n        pass", "try:\n        x = {a}\n    except Exception:\n        ld = None",
    "ld.add_action(OpaqueFunction(function=helper))", "ld.add_action(ExecuteProcess(cmd=['gz', 'sim', {a}]))",
    "ld = helper({a})", "return {a}", "raise ValueError({a})", "del x", "print({a})",
]


@st.composite
def launch_file(draw):
    lines = []
    for _ in range(draw(st.integers(0, 8))):
        template = draw(st.sampled_from(STATEMENTS))
        lines.append("    " + template.format(a=draw(st.sampled_from(ATOMS)), b=draw(st.sampled_from(ATOMS))))
    return ("\n\ndef helper(context=None, *args):\n    return [Node(package='ros_gz_sim', executable='create', "
            "arguments=['-x', LaunchConfiguration('x_pose', default='0')])]\n\n\n"
            "def generate_launch_description():\n    x, y = 'a', 'b'\n    ld = LaunchDescription()\n"
            + "\n".join(lines) + "\n    return ld\n")


# HYPO_N=2000 HYPO_RANDOM=1 explores more, and differently each run
@settings(max_examples=int(os.environ.get("HYPO_N", "120")), deadline=None, database=None,
          derandomize=not os.environ.get("HYPO_RANDOM"), suppress_health_check=list(HealthCheck))
@given(body=launch_file())
def test_any_launch_file_is_read_or_refused_with_a_line(tmp_path_factory, body):
    src = tmp_path_factory.mktemp("ws") / "src"
    python_package(src, "room_humble", {}, {"room.world": room_sdf()})
    launch = src / "room_humble" / "launch" / "any.launch.py"
    launch.parent.mkdir(parents=True, exist_ok=True)
    launch.write_text(textwrap.dedent(HEADER) + body, encoding="utf-8")
    try:
        info = read_launch(launch, environ={})
    except WorldFileError as err:
        assert str(err).startswith(str(launch))
        return
    assert all(f.where and f.where.startswith(str(launch)) for f in info.findings), info.findings
    assert all(r.pose is None or len(r.pose) == 4 for r in info.robots)


def test_values_nested_without_end_are_refused_not_recursed(ws):
    nest = "\n".join(["    x = [x]"] * 3000)
    launch = write(ws / "room_humble" / "launch" / "deep.launch.py", "")
    launch.write_text(textwrap.dedent(HEADER) + f"""

def generate_launch_description():
    x = '1'
{nest}
    ld = LaunchDescription([x])
    ld.add_action(ld)
    ld.add_action(Node(package='gazebo_ros', executable='spawn_entity.py', arguments=['-x', x]))
    return ld
""")
    info = read_launch(launch, environ={})
    assert info.spawn is None
    assert {f.message for f in info.findings} >= {
        "launch actions nest more than 32 deep (a LaunchDescription holding itself?); the deeper ones are not read",
        "spawn_entity.py -x: substitutions nested too deeply to read"}


@pytest.mark.parametrize("body", [
    "l = []\n    l.append(l)\n    l.append(l)\n    return LaunchDescription(l)",
    "l = ['a']\n    l.append(l)\n    l.append(l)\n    return LaunchDescription([Node(package='p', executable='x', "
    "arguments=[l])])",
    "s = 'a' * 1000000\n    t = s.replace('a', s)\n    u = ''.join([s] * 1000000)\n"
    "    v = '%(a)99999999s' % {'a': 'x'}\n    w = '{0:{1}}'.format('x', 999999999)\n    return LaunchDescription([])",
])
def test_hostile_launch_files_are_read_quickly_in_little_memory(tmp_path, body):
    """Lists that hold themselves and strings that would grow to gigabytes: read at once, never built."""
    path = tmp_path / "hostile.launch.py"
    path.write_text("from launch import LaunchDescription\nfrom launch_ros.actions import Node\n\n"
                    f"def generate_launch_description():\n    {body}\n")
    read_launch(path, environ={})
