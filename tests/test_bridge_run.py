"""`worldgen run WORLD NODE…`: students' nodes, written the ways students write them, run unmodified on the
simulated robot with a private master; the report says what the robot did; crashes and bad input are findings or
one-line errors, and no process outlives a run.

Real rosmaster and rospy (Debian's); missing ROS packages skip, or fail under CI (see rosstubs).
"""

from __future__ import annotations

import json
import math
import shutil
import signal
import subprocess
import sys
import time
import os

import pytest
from conftest import CliRunner

from rosstubs import SYSTEM_PYTHON
from bridgetools import NODES, REPO, ROOM, leftovers, need_ros, no_leftovers, tag, wait_master  # noqa: F401 (tag: a fixture)
from worldgen.bridge.outcome import ends_in_traceback
from worldgen.interface.topics import near_topic
from worldgen.cli import main
from worldgen.packages.course_ros1 import write_course


@pytest.fixture(scope="module")
def course(tmp_path_factory):
    return write_course(tmp_path_factory.mktemp("course"))


def node_running(marker: str) -> bool:
    return any(p.split(" ", 1)[1].startswith(f"{SYSTEM_PYTHON} ") and "spin_rate_loop" in p
               for p in leftovers(marker))


def start_run_until_the_node_runs(marker: str, **popen) -> subprocess.Popen:
    """``worldgen run`` of the room and spin_rate_loop.py for 60 s, returned once the node itself is running
    (asserted: a run stopped before its node started would prove nothing about stopping nodes)."""
    env = dict(os.environ, PYTHONPATH=str(REPO))
    proc = subprocess.Popen([sys.executable, "-m", "worldgen", "run", str(ROOM), str(NODES / "spin_rate_loop.py"),
                             "--duration", "60"], env=env, **popen)
    deadline = time.monotonic() + 60
    while not node_running(marker) and time.monotonic() < deadline and proc.poll() is None:
        time.sleep(0.1)
    assert node_running(marker), f"the node never started (worldgen run exited {proc.poll()})"
    return proc


def run(args: list[str]):
    result = CliRunner().invoke(main, ["run", *args])
    assert "Traceback" not in result.output, result.output
    return result


def test_the_courses_stop_at_wall_passes(tag, course, tmp_path):
    node = course / "lab_a_stop_at_wall" / "scripts" / "stop_at_wall.py"
    result = run([str(ROOM), str(node), "--task", "stop-at-wall", "--rate", "max", "--format", "json"])
    assert result.exit_code == 0, result.output
    doc = json.loads(result.stdout)
    assert doc["ok"] is True and doc["task"] == "stop-at-wall" and doc["findings"] == []
    m = doc["metrics"]
    for key in ("cmd_vel_messages", "path_length_m", "rotation_rad", "final_pose", "final_front_distance_m",
                "min_clearance_m", "contacts", "sim_time_s", "real_time_factor"):
        assert key in m, key
    assert m["final_front_distance_m"] == pytest.approx(0.5, abs=0.1)
    assert m["cmd_vel_messages"] > 50 and m["contacts"] == [] and m["sim_time_s"] == pytest.approx(20.0)
    assert m["path_length_m"] == pytest.approx(2.425 + 0.032 - m["final_front_distance_m"], abs=0.05)
    assert m["real_time_factor"] > 5



def test_a_run_whose_free_port_another_master_took_starts_again_on_another(tag, tmp_path, monkeypatch):
    """The free port a run picked is taken by another job's master before its own starts (a class graded
    beside other CI jobs): the run starts again on another port and reports as any run, not exit 2."""
    import worldgen.ros1.master as master_module

    taken = master_module.free_port()
    other = subprocess.Popen(["rosmaster", "--core", "-p", str(taken)], env=dict(os.environ, ROS_HOME=str(tmp_path)),
                             stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        wait_master({"ROS_MASTER_URI": f"http://127.0.0.1:{taken}"}, other)
        picks = iter([taken])
        real = master_module.free_port
        monkeypatch.setattr(master_module, "free_port", lambda: next(picks, None) or real())
        result = run([str(ROOM), str(NODES / "spin_rate_loop.py"), "--rate", "max", "--duration", "2",
                      "--format", "json"])
        assert result.exit_code in (0, 1), result.output
        assert json.loads(result.stdout)["metrics"]["sim_time_s"] == pytest.approx(2.0)
        assert next(picks, "used") == "used"   # the taken port was the first pick
    finally:
        other.terminate()
        other.wait(10)


def test_a_wall_met_at_an_angle_is_graded_as_the_node_measures_it(tag, course):
    """A generated world whose spawn faces a wall obliquely: the course's node stops on the nearest beam within
    ±10° of ahead, 0.52 m, and is graded by that front distance, not by the single beam straight ahead (0.60 m,
    which failed the reference solution as 'short of the target')."""
    node = course / "lab_a_stop_at_wall" / "scripts" / "stop_at_wall.py"
    result = run(["--worlds", "clutter:1@104", str(node), "--task", "stop-at-wall", "--rate", "max",
                  "--format", "json"])
    assert result.exit_code == 0, result.output
    [world] = json.loads(result.stdout)["worlds"]
    assert world["ok"] and world["result"]["metrics"]["final_front_distance_m"] == pytest.approx(0.5, abs=0.05)


def test_the_courses_node_and_drive_stop_at_the_same_place(tag, course):
    """The generated stop_at_wall.py on the simulated robot and `worldgen drive` run one law: from the same spawn in
    the same world they stop within 2 cm of each other (true distances from base_scan to the wall)."""
    from bridgetools import SCAN_X, WALL_FACE

    node = course / "lab_a_stop_at_wall" / "scripts" / "stop_at_wall.py"
    ran = run([str(ROOM), str(node), "--rate", "max", "--duration", "30", "--format", "json"])
    x, y, yaw = json.loads(ran.stdout)["metrics"]["final_pose"]
    node_distance = WALL_FACE - (x + SCAN_X * math.cos(yaw))
    driven = CliRunner().invoke(main, ["drive", str(ROOM), "--duration", "30", "--format", "json"])
    assert driven.exit_code == 0, driven.output
    drive_distance = json.loads(driven.stdout)["runs"][0]["final_distance"]
    assert abs(y) < 0.02 and abs(yaw) < 0.05
    assert abs(node_distance - drive_distance) < 0.02, (node_distance, drive_distance)

def test_callback_node_reading_zero_for_no_return(tag):
    """A scan callback that publishes, ignoring 0 (the real LDS-01's no-return), with --lidar-no-hit zero."""
    result = run([str(ROOM), str(NODES / "stop_zero_callback.py"), "--task", "stop-at-wall", "--rate", "max",
                  "--lidar-no-hit", "zero", "--duration", "25"])
    assert result.exit_code == 0, result.output
    assert "stop-at-wall: PASS" in result.output


def test_a_time_time_loop_runs_at_real_time(tag):
    """Paced by the wall clock: 3 s at 0.1 m/s covers about 0.3 m only when simulated time runs at real time."""
    result = run([str(ROOM), str(NODES / "forward_time_loop.py"), "--duration", "4.5", "--format", "json"])
    assert result.exit_code == 0, result.output
    m = json.loads(result.stdout)["metrics"]
    assert m["path_length_m"] == pytest.approx(0.3, rel=0.15)
    assert m["real_time_factor"] == pytest.approx(1.0, abs=0.1)


def test_a_node_failing_on_import_is_a_finding(tag):
    result = run([str(REPO / "examples" / "enclosed_room.yaml"), str(NODES / "crash_on_import.py"), "--rate", "max",
                  "--duration", "2", "--format", "json"])
    assert result.exit_code == 1, result.output
    messages = [f["message"] for f in json.loads(result.stdout)["findings"]]
    assert any("crash_on_import failed" in m and "cannot import name 'Twistt'" in m for m in messages), messages
    assert any("no message on /cmd_vel" in m for m in messages)


def test_a_node_crashing_midway_is_a_finding_at_full_speed(tag):
    """At --rate max the 20 simulated seconds may end while the node, its exception raised at 2 s, is still in
    rospy's shutdown: the crash is still the finding it is at any rate."""
    result = run([str(REPO / "examples" / "enclosed_room.yaml"), str(NODES / "crash_midway.py"), "--rate", "max",
                  "--format", "json"])
    assert result.exit_code == 1, result.output
    doc = json.loads(result.stdout)
    messages = [f["message"] for f in doc["findings"]]
    assert any("crash_midway failed (exit code 1): ValueError: the ranges were empty" in m for m in messages), messages
    assert doc["metrics"]["cmd_vel_messages"] == 1


@pytest.mark.parametrize("node, severity, said", [
    ("scan_topic_typo.py", "warning", "/stopper subscribes to /scans, which nothing publishes; did you mean /scan?"),
    ("twist_stamped.py", "error", "a node publishes geometry_msgs/TwistStamped on /cmd_vel, but the simulated "
                                  "TurtleBot3 takes geometry_msgs/Twist there (as Gazebo's does): the robot does not "
                                  "move"),
])
def test_a_misspelt_topic_or_a_wrong_type_is_named(tag, node, severity, said):
    """The robot never moves either way; the finding says why, not only that it stood still."""
    result = run([str(ROOM), str(NODES / node), "--task", "stop-at-wall", "--rate", "max", "--duration", "3",
                  "--format", "json"])
    assert result.exit_code == 1, result.output
    doc = json.loads(result.stdout)
    assert doc["metrics"]["path_length_m"] < 0.01
    assert [f["severity"] for f in doc["findings"] if f["message"] == said] == [severity], doc["findings"]


def test_the_courses_node_draws_no_topic_finding(tag, course):
    node = course / "lab_a_stop_at_wall" / "scripts" / "stop_at_wall.py"
    doc = json.loads(run([str(ROOM), str(node), "--task", "stop-at-wall", "--rate", "max", "--duration", "4",
                          "--format", "json"]).stdout)
    assert not [f for f in doc["findings"] if f["check"] == "node"], doc["findings"]


def test_output_ending_in_a_traceback_is_told_from_output_going_on():
    crash = subprocess.run([sys.executable, "-c", "print('started')\ntry:\n    {}['ranges']\n"
                            "except KeyError:\n    raise ValueError('the ranges were empty')"],
                           capture_output=True, text=True)
    assert crash.returncode == 1 and "During handling" in crash.stderr   # a chained traceback, as Python prints it
    assert ends_in_traceback(crash.stdout + crash.stderr)
    assert not ends_in_traceback(crash.stdout + crash.stderr + "[INFO] caught it, going on\n")
    assert not ends_in_traceback("started\n[INFO] spinning\n")
    assert not ends_in_traceback("Traceback (most recent call last):\n")   # cut off before its frames
    # rospy logs an exception raised in a callback, and the node lives on: no crash to wait for
    logged = ("[ERROR] [1700000000.1]: bad callback: <bound method Stopper.on_scan of <Stopper object>>\n"
              "Traceback (most recent call last):\n  File \"stop_at_wall.py\", line 9, in on_scan\n"
              "    front = min([])\nValueError: min() arg is an empty sequence\n")
    assert not ends_in_traceback(logged)
    assert not ends_in_traceback("Exception in thread Thread-1:\n" + crash.stderr)


def test_a_topic_nothing_publishes_is_matched_only_to_a_near_name():
    robot = ["/clock", "/scan", "/odom", "/tf", "/tf_static", "/joint_states", "/imu", "/gazebo/model_states",
             "/rosout"]
    near = {name: near_topic(name, robot) for name in ("/scans", "/Scan", "/imus", "/gazebo/model_state", "/image",
                                                       "/color", "/odometry", "/sensor_state", "/rosout_agg",
                                                       "/base_scan", "/camera/scan")}
    assert near == {"/scans": "/scan", "/Scan": "/scan", "/imus": "/imu", "/gazebo/model_state": "/gazebo/model_states",
                    "/image": None, "/color": None, "/odometry": None, "/sensor_state": None, "/rosout_agg": None,
                    "/base_scan": None, "/camera/scan": None}


@pytest.mark.parametrize("make, expected", [
    (lambda d: d / "missing.py", "no such node file"),
    (lambda d: (d / "notes.txt").write_text("hello") and d / "notes.txt", "is not a Python node"),
    (lambda d: (d / "bin.py").write_bytes(b"\x7fELF\x00\x01") and d / "bin.py", "is not a Python node"),
])
def test_bad_node_files_are_one_line_errors(tag, tmp_path, make, expected):
    result = run([str(ROOM), str(make(tmp_path)), "--rate", "max", "--duration", "1"])
    assert result.exit_code == 2
    assert result.output.startswith("worldgen: error:") and expected in result.output
    assert len(result.output.strip().splitlines()) == 1


def test_a_world_that_does_not_load_is_a_one_line_error(tag, tmp_path):
    bad = tmp_path / "bad.world"
    bad.write_text("<sdf version='1.6'><world name='w'>")
    result = run([str(bad), str(NODES / "spin_rate_loop.py"), "--rate", "max", "--duration", "1"])
    assert result.exit_code == 2 and len(result.output.strip().splitlines()) == 1, result.output


def test_ctrl_c_stops_every_process(tag, tmp_path):
    """Ctrl-C in the middle of a run: click's one-line "Aborted!" and exit 1, no report; the ``tag`` fixture then
    finds no process of the run left (master, simulator, node)."""
    proc = start_run_until_the_node_runs(tag, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    running = " ".join(leftovers(tag))
    assert "rosmaster" in running and "-m worldgen.ros1 " in running, running   # and worldgen, and the node
    proc.send_signal(signal.SIGINT)
    out, err = proc.communicate(timeout=60)
    assert (proc.returncode, out, err.strip()) == (1, "", "Aborted!")


def test_a_killed_run_leaves_no_orphans(tag):
    """SIGKILL leaves worldgen no time to stop anything: its children stop themselves (the ``tag`` fixture finds
    none left)."""
    proc = start_run_until_the_node_runs(tag, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    proc.kill()
    assert proc.wait() == -signal.SIGKILL


BAG_READER = r"""
import json, sys
import rosbag
with rosbag.Bag(sys.argv[1]) as bag:
    info = bag.get_type_and_topic_info().topics
    print(json.dumps({t: [i.msg_type, i.message_count] for t, i in info.items()}))
"""


def test_plot_csv_bag_and_junit(tag, tmp_path):
    files = {k: tmp_path / f"run.{k}" for k in ("png", "csv", "bag", "xml")}
    result = run([str(ROOM), str(NODES / "spin_rate_loop.py"), "--task", "spin", "--rate", "max", "--duration", "4",
                  "--plot", str(files["png"]), "--csv", str(files["csv"]), "--bag", str(files["bag"]),
                  "--junit", str(files["xml"])])
    assert result.exit_code == 1, result.output          # 4 s is not two turns
    assert "spin: FAIL" in result.output and "full turns; 2 are needed" in result.output
    assert files["png"].read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and files["png"].stat().st_size > 10_000
    rows = files["csv"].read_text().splitlines()
    assert rows[0] == "t,x,y,yaw,v,omega,cmd_v,cmd_omega,front_m,nearest_m,clearance_m"
    assert len(rows) - 1 == pytest.approx(4 * 30, abs=2)
    assert float(rows[-1].split(",")[7]) == pytest.approx(1.0)   # the spin command in force at the end
    proc = subprocess.run([SYSTEM_PYTHON, "-c", BAG_READER, str(files["bag"])], capture_output=True, text=True,
                          timeout=60)
    assert proc.returncode == 0, proc.stderr
    topics = json.loads(proc.stdout)
    assert topics["/scan"] == ["sensor_msgs/LaserScan", pytest.approx(20, abs=1)]
    assert topics["/odom"][0] == "nav_msgs/Odometry" and topics["/odom"][1] == pytest.approx(120, abs=2)
    assert topics["/cmd_vel"][0] == "geometry_msgs/Twist" and topics["/cmd_vel"][1] > 20
    junit = files["xml"].read_text()
    assert 'name="spin"' in junit and "<failure" in junit
    again = run([str(ROOM), str(NODES / "spin_rate_loop.py"), "--duration", "1", "--plot", str(files["png"])])
    assert again.exit_code == 2 and "--force" in again.output   # an existing output is kept
    manifest = tmp_path / "package.xml"
    manifest.write_text("<package format='2'><name>lab</name></package>\n")
    refused = run([str(ROOM), str(NODES / "spin_rate_loop.py"), "--duration", "1", "--junit", str(manifest)])
    assert refused.exit_code == 2 and "is not a JUnit report" in refused.output and "--force" in refused.output
    assert "<package" in manifest.read_text()
    replaced = run([str(ROOM), str(NODES / "spin_rate_loop.py"), "--task", "spin", "--rate", "max", "--duration",
                    "1", "--junit", str(files["xml"])])   # the earlier report: replaced without --force
    assert replaced.exit_code == 1 and files["xml"].read_text() != junit


def test_rospy_missing_names_the_package(tag, tmp_path):
    """With rospy unimportable (a stand-in that fails as a missing module does), one line names the package."""
    blocker = tmp_path / "block" / "rospy"
    blocker.mkdir(parents=True)
    (blocker / "__init__.py").write_text("raise ImportError(\"No module named 'rospy'\")\n")
    env = dict(os.environ, PYTHONPATH=f"{blocker.parent}:{REPO}")
    for command in (["run", str(ROOM), str(NODES / "spin_rate_loop.py"), "--duration", "1"],
                    ["sim", str(ROOM), "--duration", "1"]):
        proc = subprocess.run([sys.executable, "-m", "worldgen", *command], env=env, capture_output=True, text=True,
                              timeout=60)
        assert proc.returncode == 2, proc.stderr
        assert proc.stderr.startswith("worldgen: error: rospy (ROS 1's Python client) is not installed: install "
                                      "python3-rospy") and len(proc.stderr.strip().splitlines()) == 1, proc.stderr


def test_a_launch_files_script_that_is_not_executable_fails_the_run(tag, course, tmp_path, monkeypatch):
    """roslaunch cannot start a script without its x bit: the run still shows what the node does, and fails
    with an error naming the script and the chmod that fixes it."""
    monkeypatch.setenv("TURTLEBOT3_MODEL", "burger")
    workspace = shutil.copytree(course.parent.parent, tmp_path / "ws", symlinks=True)
    lab = workspace / course.relative_to(course.parent.parent) / "lab_a_stop_at_wall"
    script = lab / "scripts" / "stop_at_wall.py"
    script.chmod(0o644)
    launch = lab / "launch" / "stop_at_wall.launch"
    result = run([str(launch), str(launch), "--task", "stop-at-wall", "--rate", "max", "--format", "json"])
    assert result.exit_code == 1, result.output
    doc = json.loads(result.stdout)
    assert doc["metrics"]["final_front_distance_m"] == pytest.approx(0.5, abs=0.1)   # it ran
    [said] = [f for f in doc["findings"] if "is not executable" in f["message"]]
    assert said["severity"] == "error" and said["where"] == str(script) and said["fix"] == f"chmod +x {script}"


def test_a_package_node_with_arguments_and_a_launch_files_node(tag, course, monkeypatch):
    """PKG/TYPE found on ROS_PACKAGE_PATH as rosrun finds it, with a private parameter after it; and the course's
    own launch file as both the world (its world, robot and spawn) and the nodes (its node; Gazebo's are ours)."""
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(course))
    monkeypatch.setenv("TURTLEBOT3_MODEL", "burger")
    result = run([str(ROOM), "lab_a_stop_at_wall/stop_at_wall.py", "_target_distance:=0.7", "--task", "stop-at-wall",
                  "--target", "0.7", "--rate", "max", "--format", "json"])
    assert result.exit_code == 0, result.output
    assert json.loads(result.stdout)["metrics"]["final_front_distance_m"] == pytest.approx(0.7, abs=0.06)
    launch = course / "lab_a_stop_at_wall" / "launch" / "stop_at_wall.launch"
    result = run([str(launch), str(launch), "--task", "stop-at-wall", "--rate", "max"])
    assert result.exit_code == 0, result.output
    assert "stop_at_wall on burger at (0, 0, 0) from launch file" in result.output
