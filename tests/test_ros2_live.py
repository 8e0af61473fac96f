"""Students' rclpy nodes on the simulated TurtleBot3 over DDS (``worldgen run --ros humble|jazzy``), with the real
rclpy of PyPI's Jazzy wheels (``.ci/ros2-peer`` makes the venv; ``WORLDGEN_ROS2_PYTHON`` names another)."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import time
from pathlib import Path

import pytest

from bridgetools import leftovers, no_leftovers

pytest.importorskip("cyclonedds", reason="the ros2 extra (cyclonedds) is not installed for this Python")

REPO = Path(__file__).resolve().parent.parent
NODES = Path(__file__).resolve().parent / "ros2nodes"
ROOM = REPO / "examples" / "enclosed_room.yaml"


def peer_python() -> str:
    from worldgen.ros2.pyenv import ENV_PYTHON, PEER_VENV

    python = os.environ.get(ENV_PYTHON) or str(PEER_VENV / "bin" / "python")
    ok = os.access(python, os.X_OK) and subprocess.run([python, "-c", "import rclpy"], capture_output=True).returncode == 0
    if not ok:
        if os.environ.get("CI"):
            pytest.fail(f"no rclpy at {python}: .ci/run makes it with .ci/ros2-peer")
        pytest.skip(f"no rclpy at {python} (bash .ci/ros2-peer makes one)")
    return python


@pytest.fixture
def tag(monkeypatch) -> str:
    """A marker in the environment every process of the run inherits, to find any left behind."""
    import uuid

    value = uuid.uuid4().hex
    monkeypatch.setenv("WORLDGEN_TEST_TAG", value)
    yield f"WORLDGEN_TEST_TAG={value}"
    no_leftovers(f"WORLDGEN_TEST_TAG={value}")


@pytest.fixture(scope="module")
def rclpy_python():
    return peer_python()


def worldgen(args: list[str], python: str, tag: str, timeout: float = 120):
    """``worldgen ARGS`` as a child, its nodes run by ``python``, every process marked with ``tag``."""
    key, _, value = tag.partition("=")
    env = dict(os.environ, WORLDGEN_ROS2_PYTHON=python, PYTHONPATH=str(REPO), **{key: value})
    return subprocess.run([sys.executable, "-m", "worldgen", "run", *args], env=env, capture_output=True, text=True,
                          timeout=timeout)


def run_json(args: list[str], python: str, tag: str) -> tuple[int, dict]:
    done = worldgen([*args, "--format", "json"], python, tag)
    assert done.stdout, done.stderr
    return done.returncode, json.loads(done.stdout)


@pytest.fixture(scope="module")
def course(tmp_path_factory):
    """The course's own ROS 2 packages, for each stack (``worldgen course --ros``)."""
    root = tmp_path_factory.mktemp("course")
    found = {}
    for stack in ("humble", "jazzy"):
        subprocess.run([sys.executable, "-m", "worldgen", "course", "--ros", stack, "-w", str(root / stack)],
                       check=True, capture_output=True, env=dict(os.environ, PYTHONPATH=str(REPO)))
        found[stack] = root / stack / "src" / "intro_robo"
    return found


@pytest.mark.parametrize("stack", ["humble", "jazzy"])
def test_the_courses_stop_at_wall_node_passes_on_each_stack(stack, course, rclpy_python, tag):
    node = next(course[stack].rglob("stop_at_wall.py"))
    code, doc = run_json([str(ROOM), str(node), "--ros", stack, "--task", "stop-at-wall", "--rate", "max"],
                         rclpy_python, tag)
    assert code == 0, doc["findings"]
    assert doc["metrics"]["final_front_distance_m"] == pytest.approx(0.5, abs=0.1)
    assert doc["metrics"]["cmd_vel_messages"] > 20
    assert leftovers(tag) == []


def test_the_courses_spin_node_turns_on_jazzy(course, rclpy_python, tag):
    """Its timer runs on the wall clock (no use_sim_time), so the run is paced (4x), as a TA would grade it."""
    node = next(course["jazzy"].rglob("spin_in_circles.py"))
    code, doc = run_json([str(ROOM), str(node), "--ros", "jazzy", "--task", "spin", "--rate", "4"], rclpy_python,
                         tag)
    assert code == 0, doc["findings"]
    assert abs(doc["metrics"]["rotation_rad"]) > 4 * 3.14159


@pytest.mark.parametrize("stack, stamped, moves", [("humble", "false", True), ("jazzy", "true", True),
                                                    ("jazzy", "false", False)])
def test_a_timer_node_with_reliable_qos_and_the_stacks_cmd_vel_type(stack, stamped, moves, rclpy_python, tag):
    """A 10 Hz timer node subscribing /scan with depth 10 (reliable): it stops at the wall when it publishes the
    stack's type; a Twist on Jazzy's TwistStamped cmd_vel moves nothing, and a finding says why and how to fix it."""
    # paced (4x real time): a timer node answers on its own clock, not the scans', so at --rate max a loaded machine
    # would let the robot run on between its ticks
    code, doc = run_json([str(ROOM), str(NODES / "timer_stopper.py"), "_use_sim_time:=true", f"_stamped:={stamped}",
                          "--ros", stack, "--task", "stop-at-wall", "--rate", "4", "--spawn", "1.2,0,0",
                          "--duration", "10"], rclpy_python, tag)
    messages = [f["message"] for f in doc["findings"]]
    assert not [m for m in messages if "do not follow /clock" in m]   # use_sim_time: it follows the clock
    if moves:
        assert code == 0, messages
        assert doc["metrics"]["final_front_distance_m"] == pytest.approx(0.5, abs=0.1)
    else:
        assert code == 1
        assert doc["metrics"]["path_length_m"] < 0.05
        wrong = [f for f in doc["findings"] if f["check"] == "ros2"]
        assert wrong and "geometry_msgs/msg/Twist on /cmd_vel" in wrong[0]["message"]
        assert "TwistStamped" in wrong[0]["fix"]


def test_a_sleep_paced_spin_once_node_with_sensor_data_qos_at_real_time(rclpy_python, tag):
    """Paced by time.sleep and the wall clock, as in Gazebo at --rate 1: it stops short of the wall it starts near."""
    code, doc = run_json([str(ROOM), str(NODES / "sleep_loop_stopper.py"), "--ros", "humble", "--task",
                          "stop-at-wall", "--rate", "1", "--duration", "6", "--spawn", "1.4,0,0"], rclpy_python, tag)
    assert code == 0, doc["findings"]
    assert 0.4 < doc["metrics"]["final_front_distance_m"] < 0.6


def test_a_node_that_shuts_down_in_its_callback(rclpy_python, tag):
    code, doc = run_json([str(ROOM), str(NODES / "shutdown_in_callback.py"), "--ros", "jazzy", "--task",
                          "stop-at-wall", "--rate", "max", "--spawn", "1.2,0,0"], rclpy_python, tag)
    assert code == 0, doc["findings"]
    assert doc["metrics"]["final_front_distance_m"] == pytest.approx(0.5, abs=0.1)
    assert not [f for f in doc["findings"] if f["check"] == "node" and f["severity"] == "error"]


@pytest.mark.parametrize("stack", ["humble", "jazzy"])
def test_a_probe_gets_every_topic_reliable_and_best_effort(stack, rclpy_python, tmp_path, tag):
    """Every topic reaches a reliable and a best-effort subscriber (Humble's /clock only the best-effort one), with
    the stack's frames and rates in simulated time."""
    out = tmp_path / "probe.json"
    worldgen([str(ROOM), str(NODES / "probe.py"), f"_out:={out}", "--ros", stack, "--duration", "3", "--rate", "1"],
             rclpy_python, tag)
    seen = json.loads(out.read_text())
    for topic in ("scan", "odom", "imu", "joint_states"):
        for kind in ("reliable", "best_effort"):
            assert seen.get(f"{topic}/{kind}", {}).get("count", 0) > 0, (topic, kind)
    assert seen["scan/reliable"]["frames"] == ["base_scan"] and seen["scan/reliable"]["ranges"] == 360
    assert seen["odom/reliable"]["frames"] == ["odom"] and seen["odom/reliable"]["child"] == "base_footprint"
    imu_frame = "imu_link" if stack == "humble" else "burger/imu_link/tb3_imu"
    assert seen["imu/reliable"]["frames"] == [imu_frame]

    def rate(entry):   # in simulated time: the stamps held at 0 before the start are one
        stamps = sorted(set(entry["stamps"]))
        return (len(stamps) - 1) / (stamps[-1] - stamps[0])

    assert rate(seen["scan/best_effort"]) == pytest.approx(5.0, rel=0.1)
    assert rate(seen["odom/best_effort"]) == pytest.approx(30.0, rel=0.1)
    assert seen.get("clock/best_effort", {}).get("count", 0) > 0
    if stack == "humble":   # gazebo_ros: 10 Hz, best effort (a reliable subscriber gets nothing)
        assert rate(seen["clock/best_effort"]) == pytest.approx(10.0, rel=0.15)
        assert "clock/reliable" not in seen
    else:
        assert seen["clock/reliable"]["count"] > 0


def test_a_folder_of_three_ament_submissions_with_two_jobs(course, rclpy_python, tmp_path, tag):
    """Three students' packages: the course's node, a Twist publisher (moves nothing on Jazzy) and one that crashes."""
    import shutil

    folder = tmp_path / "submissions"
    lab = next(course["jazzy"].rglob("lab_a_stop_at_wall/package.xml")).parent
    for student in ("ana", "bob", "cy"):
        shutil.copytree(lab, folder / student / lab.name)
    bob = next((folder / "bob").rglob("stop_at_wall.py"))
    bob.write_text(bob.read_text().replace("TwistStamped", "Twist").replace("message.header.stamp", "_stamp"))
    cy = next((folder / "cy").rglob("stop_at_wall.py"))
    cy.write_text(cy.read_text().replace("def main(", "raise SystemExit('cy crashed')\n\n\ndef main("))
    done = worldgen([str(folder), "--ros", "jazzy", "--task", "stop-at-wall", "--rate", "max", "-j", "2",
                     "--format", "json"], rclpy_python, tag, timeout=240)
    results = {Path(r["path"]).parent.name: r for r in json.loads(done.stdout)["results"]}
    assert done.returncode == 1
    assert results["ana"]["ok"] is True
    assert results["bob"]["ok"] is False and any(f["check"] == "ros2" for f in results["bob"]["findings"])
    assert results["cy"]["ok"] is False and any("cy crashed" in f["message"] for f in results["cy"]["findings"])
    assert leftovers(tag) == []


def test_a_node_on_the_wall_clock_at_rate_max_is_said(rclpy_python, tag):
    """Without use_sim_time a node's timer follows the wall clock: at --rate max the report says so."""
    code, doc = run_json([str(ROOM), str(NODES / "timer_stopper.py"), "--ros", "jazzy", "--duration", "3",
                          "--rate", "max"], rclpy_python, tag)
    said = [f for f in doc["findings"] if "do not follow /clock" in f["message"]]
    assert len(said) == 1 and said[0]["severity"] == "info" and "use_sim_time" in said[0]["fix"]


@pytest.mark.parametrize("stack, frame", [("humble", "camera_rgb_optical_frame"), ("jazzy", "camera_rgb_frame")])
def test_the_waffle_pi_camera_reaches_an_rclpy_node(stack, frame, rclpy_python, tmp_path, tag):
    """640 x 480 rgb8 on camera/image_raw, with camera_info, stamped on the 30 Hz grid of simulated time (that none
    is dropped is benchmarks/bench_ros2.py's to show, on a quiet machine)."""
    out = tmp_path / "camera.json"
    worldgen([str(ROOM), str(NODES / "camera_count.py"), f"_out:={out}", "--robot", "waffle_pi", "--ros", stack,
              "--duration", "2", "--rate", "0.5"], rclpy_python, tag)   # half pace: a loaded machine keeps up
    seen = json.loads(out.read_text())
    assert seen["first"] == {"width": 640, "height": 480, "encoding": "rgb8", "frame": frame, "bytes": 921600}
    assert seen["info"] > 0 and seen["k"][0] == pytest.approx(530.47, abs=0.01)
    stamps = sorted(set(seen["stamps"]))
    assert len(stamps) >= 5
    assert all(abs(t * 30 - round(t * 30)) < 1e-3 for t in stamps)


def test_the_courses_launch_py_as_world_and_nodes_unbuilt(course, rclpy_python, tag):
    """The lab's own launch.py, never built with colcon: its world, robot and spawn from Gazebo Sim's include, and
    its node run from the package's source through setup.py's entry point, with the launch file's use_sim_time."""
    launch = next(course["jazzy"].rglob("stop_at_wall.launch.py"))
    assert not list(course["jazzy"].parent.parent.glob("install"))
    code, doc = run_json([str(launch), str(launch), "--ros", "jazzy", "--task", "stop-at-wall", "--rate", "max"],
                         rclpy_python, tag)
    assert code == 0, doc["findings"]
    assert not [f for f in doc["findings"] if "do not follow /clock" in f["message"]]   # use_sim_time reached it
    assert doc["metrics"]["final_front_distance_m"] == pytest.approx(0.5, abs=0.1)


def test_namespaced_robots_from_a_launch_py(rclpy_python, tmp_path, tag):
    """Two robots spawned in namespaces by a Humble launch.py (spawn_entity.py -robot_namespace): the student's node
    in /tb3_1 drives that robot only, and the report has both."""
    subprocess.run([sys.executable, "-m", "worldgen", "build", str(ROOM), "-o", str(tmp_path / "room")], check=True,
                   capture_output=True, env=dict(os.environ, PYTHONPATH=str(REPO)))
    spawns = "".join(
        f"        Node(package='gazebo_ros', executable='spawn_entity.py', arguments=['-entity', 'tb3_{i}', '-file',\n"
        f"             'model.sdf', '-robot_namespace', 'tb3_{i}', '-x', '0.0', '-y', '{y}']),\n"
        for i, y in enumerate(("0.0", "1.0")))
    launch = tmp_path / "two.launch.py"
    launch.write_text(
        "import os\nfrom launch import LaunchDescription\nfrom launch.actions import IncludeLaunchDescription\n"
        "from launch.launch_description_sources import PythonLaunchDescriptionSource\n"
        "from launch_ros.actions import Node\nfrom ament_index_python.packages import get_package_share_directory\n\n\n"
        "def generate_launch_description():\n"
        "    world = os.path.join(os.path.dirname(__file__), 'room', 'enclosed_room.world')\n"
        "    gazebo = os.path.join(get_package_share_directory('gazebo_ros'), 'launch', 'gazebo.launch.py')\n"
        "    return LaunchDescription([\n"
        "        IncludeLaunchDescription(PythonLaunchDescriptionSource(gazebo),\n"
        "                                 launch_arguments={'world': world}.items()),\n" + spawns + "    ])\n")
    code, doc = run_json([str(launch), str(NODES / "timer_stopper.py"), "__ns:=/tb3_1", "_use_sim_time:=true",
                          "_stamped:=false", "--robot-ns", "tb3_1", "--ros", "humble", "--task", "stop-at-wall",
                          "--rate", "4", "--duration", "15"], rclpy_python, tag)   # a timer node: paced
    assert code == 0, doc["findings"]
    robots = doc["metrics"]["robots"]
    assert robots["/tb3_1"]["path_length_m"] > 1.5 and robots["/tb3_0"]["path_length_m"] < 0.05
    assert robots["/tb3_1"]["final_pose"][1] == pytest.approx(1.0, abs=0.05)


def test_a_killed_run_leaves_nothing_behind(rclpy_python, tag, tmp_path):
    """SIGTERM to `worldgen run --ros` while its node drives: the simulator and the node end with it."""
    import signal

    key, _, value = tag.partition("=")
    env = dict(os.environ, WORLDGEN_ROS2_PYTHON=rclpy_python, PYTHONPATH=str(REPO), **{key: value})
    said = tmp_path / "stderr.txt"
    with open(said, "wb") as err:
        proc = subprocess.Popen([sys.executable, "-m", "worldgen", "run", str(ROOM), str(NODES / "timer_stopper.py"),
                                 "--ros", "jazzy", "--rate", "1", "--duration", "60"], env=env,
                                stdout=subprocess.DEVNULL, stderr=err)

    def children() -> list[str]:
        return [p for p in leftovers(tag) if int(p.split()[0]) != proc.pid]

    deadline = time.monotonic() + 120   # (the whole suite on two cores has once kept it from starting in 60 s)
    while time.monotonic() < deadline and not any("timer_stopper.py" in p for p in children()):
        time.sleep(0.2)
    running = children()
    assert any("timer_stopper.py" in p for p in running) and any("-m worldgen.ros2 " in p for p in running), \
        (running, said.read_text(errors="replace")[-3000:])
    proc.send_signal(signal.SIGTERM)
    assert proc.wait(timeout=30) != 0
    no_leftovers(tag, wait=10.0)


def test_a_namespace_typo_names_where_the_robots_are(rclpy_python, tag):
    code, doc = run_json([str(ROOM), str(NODES / "timer_stopper.py"), "__ns:=/tmb3_1", "--ros", "jazzy",
                          "--duration", "3", "--rate", "max"], rclpy_python, tag)
    said = [f for f in doc["findings"] if "no robot lives in /tmb3_1" in f["message"]]
    assert code == 1 and len(said) == 1 and "/cmd_vel" in said[0]["message"] and "__ns" in said[0]["fix"]


def test_a_misspelt_scan_topic_is_named(rclpy_python, tag):
    """A remap to /scans (as a typo in the node would be): the node hears nothing, and a finding says what it
    probably meant."""
    code, doc = run_json([str(ROOM), str(NODES / "timer_stopper.py"), "scan:=scans", "--ros", "jazzy",
                          "--task", "stop-at-wall", "--duration", "3", "--rate", "max"], rclpy_python, tag)
    said = [f for f in doc["findings"] if f["message"] == "a node subscribes to /scans, which nothing publishes; "
                                                          "did you mean /scan?"]
    assert code == 1 and [f["severity"] for f in said] == ["warning"], doc["findings"]
    code, doc = run_json([str(ROOM), str(NODES / "timer_stopper.py"), "--ros", "jazzy", "--duration", "2",
                          "--rate", "max"], rclpy_python, tag)
    assert not [f for f in doc["findings"] if "nothing publishes" in f["message"]], doc["findings"]
