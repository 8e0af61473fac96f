"""Launch files as roslaunch runs them, for the nodes `worldgen run` starts: `<param>` (typed as roslaunch types
it), `<rosparam>` (a file and inline YAML), private `~` parameters, `<remap>`, `<env>`, `ns`, `required` honoured and
`respawn` noted. Real rosmaster and rospy (Debian's); the nodes are student-style scripts in a catkin package.
"""

from __future__ import annotations

import json
import shutil
import signal
import subprocess
import time
from pathlib import Path

import pytest
from conftest import CliRunner

from bridgetools import NODES, ROOM, WALL_FACE, SCAN_X, need_ros, no_leftovers, ros_env, wait_master, worldgen
from rosstubs import SYSTEM_PYTHON, need
from worldgen.cli import main

PACKAGE_XML = """<?xml version="1.0"?>
<package format="2">
  <name>param_lab</name>
  <version>0.0.1</version>
  <description>Nodes configured by their launch file</description>
  <maintainer email="ta@example.edu">TA</maintainer>
  <license>BSD</license>
  <buildtool_depend>catkin</buildtool_depend>
  <exec_depend>rospy</exec_depend>
</package>
"""

STOP_LAUNCH = """<launch>
  <arg name="distance" default="0.8"/>
  <rosparam command="load" file="$(find param_lab)/config/speeds.yaml"/>
  <param name="course_name" value="intro robo"/>
  <param name="lab_number" value="2"/>
  <param name="strict" value="True"/>
  <rosparam>
    gains: {kp: 0.5, ki: 0.0}
    heading: !degrees 90
  </rosparam>
  <node pkg="param_lab" type="param_stopper.py" name="stopper" output="screen">
    <param name="~target_distance" value="$(arg distance)"/>
    <param name="label" type="str" value="12"/>
    <rosparam param="weights">[1, 2, 3]</rosparam>
    <remap from="velocity" to="cmd_vel"/>
    <env name="PARAM_DUMP" value="{dump}"/>
  </node>
  <node pkg="param_lab" type="quit_after.py" name="helper" respawn="true">
    <param name="duration" value="0.5"/>
    <remap from="cmd_vel" to="unused_cmd_vel"/>
  </node>
</launch>
"""


@pytest.fixture
def package(tmp_path, monkeypatch) -> Path:
    need_ros()
    monkeypatch.setenv("ROS_HOME", str(tmp_path / "ros_home"))
    monkeypatch.delenv("ROS_MASTER_URI", raising=False)
    root = tmp_path / "ws" / "src" / "param_lab"
    (root / "scripts").mkdir(parents=True)
    (root / "config").mkdir()
    (root / "launch").mkdir()
    (root / "package.xml").write_text(PACKAGE_XML)
    for node in ("param_stopper.py", "quit_after.py"):
        shutil.copy2(NODES / node, root / "scripts" / node)
    (root / "config" / "speeds.yaml").write_text("speeds:\n  cruise: 0.12\n  slow: 0.03\n")
    yield root
    no_leftovers(f"ROS_HOME={tmp_path / 'ros_home'}")


def run(args: list[str]):
    result = CliRunner().invoke(main, ["run", *args])
    assert "Traceback" not in result.output, result.output
    return result


def test_a_node_uses_the_parameters_its_launch_file_sets(package, tmp_path):
    """The node stops at its ~target_distance (0.65, passed as an arg) at the speed of the <rosparam> file, publishing
    on a topic the launch file remaps to cmd_vel; every parameter is on the master, typed as roslaunch types it."""
    dump = tmp_path / "params.json"
    launch = package / "launch" / "stop.launch"
    launch.write_text(STOP_LAUNCH.replace("{dump}", str(dump)))
    result = run([str(ROOM), str(launch), "distance:=0.65", "--task", "stop-at-wall", "--target", "0.65",
                  "--duration", "25", "--rate", "max", "--format", "json"])
    report = json.loads(result.stdout)
    assert result.exit_code == 0, result.output
    assert report["metrics"]["final_front_distance_m"] == pytest.approx(0.65, abs=0.06)
    assert report["metrics"]["final_pose"][0] == pytest.approx(WALL_FACE - 0.65 - SCAN_X, abs=0.08)
    seen = json.loads(dump.read_text())
    assert seen["stopper"] == {"target_distance": 0.65, "label": "12", "weights": [1, 2, 3]}
    assert seen["helper"] == {"duration": 0.5}
    assert seen["speeds"] == {"cruise": 0.12, "slow": 0.03}
    assert seen["gains"] == {"kp": 0.5, "ki": 0.0}
    assert seen["heading"] == pytest.approx(1.5707963, abs=1e-6)
    assert (seen["course_name"], seen["lab_number"], seen["strict"]) == ("intro robo", 2, True)
    assert seen["use_sim_time"] is True
    notes = [f["message"] for f in report["findings"]]
    assert any("helper has respawn=\"true\"" in n for n in notes), notes


def test_a_required_node_ends_the_run(package, tmp_path):
    """roslaunch stops everything when a required node exits: so does the run, long before its duration."""
    launch = package / "launch" / "quit.launch"
    launch.write_text('<launch>\n  <node pkg="param_lab" type="quit_after.py" name="quitter" required="true">\n'
                      '    <param name="duration" value="1.5"/>\n  </node>\n</launch>\n')
    # at a fixed pace: at --rate max simulated time races on while the node's process exits (20.8 s, not under 10)
    result = run([str(ROOM), str(launch), "--duration", "60", "--rate", "4", "--format", "json"])
    report = json.loads(result.stdout)
    sim_time = report["metrics"]["sim_time_s"]
    assert 1.5 <= sim_time < 10, report["metrics"]   # its 1.5 s, and the time its process takes to exit
    assert report["metrics"]["rotation_rad"] == pytest.approx(0.3 * sim_time, abs=0.3)   # turning until the end
    ended = [f for f in report["findings"] if "required node quitter exited" in f["message"]]
    assert ended and ended[0]["where"] == f"{launch}:2", report["findings"]


def test_a_launch_file_whose_parameter_roslaunch_refuses_says_so(package, tmp_path):
    """A value that is not of its type= is an error finding with the file and line; the other nodes still run."""
    launch = package / "launch" / "bad.launch"
    launch.write_text('<launch>\n  <node pkg="param_lab" type="quit_after.py" name="quitter">\n'
                      '    <param name="duration" type="int" value="one"/>\n  </node>\n</launch>\n')
    result = run([str(ROOM), str(launch), "--duration", "3", "--rate", "max", "--format", "json"])
    bad = [f for f in json.loads(result.stdout)["findings"] if f["check"] == "launch-param"]
    assert bad and bad[0]["where"] == f"{launch}:3" and "'one' is not an int" in bad[0]["message"], bad


def test_sim_sets_what_roslaunch_would_so_rosparam_get_sees_it(package, tmp_path):
    """`worldgen sim --launch FILE` stands in for `roslaunch FILE`: its parameters (a node's private ones under the
    node's name) are on the master, where `rosparam get` and a node started by hand find them."""
    launch = package / "launch" / "stop.launch"
    launch.write_text(STOP_LAUNCH.replace("{dump}", str(tmp_path / "unused.json")))
    env = ros_env(tmp_path)
    proc = worldgen(["sim", str(ROOM), "--launch", str(launch), "--rate", "max"], env)
    try:
        wait_master(env, proc)
        rosparam = need("rosparam")
        deadline = time.monotonic() + 20
        got = ""
        while "target_distance" not in got and time.monotonic() < deadline:
            got = subprocess.run([SYSTEM_PYTHON, rosparam, "get", "/stopper"], env=env, capture_output=True,
                                 text=True, timeout=30).stdout
        assert "target_distance: 0.8" in got and "label: '12'" in got, got
        speeds = subprocess.run([SYSTEM_PYTHON, rosparam, "get", "/speeds/cruise"], env=env, capture_output=True,
                                text=True, timeout=30).stdout
        assert speeds.strip() == "0.12"
    finally:
        proc.send_signal(signal.SIGINT)
        out, err = proc.communicate(timeout=30)
    assert "set the launch file's" in err and "Traceback" not in err, err
    no_leftovers(env)


def test_a_ros2_launch_file_as_a_node_is_one_line(package, tmp_path):
    """worldgen run starts rospy nodes: a ROS 2 launch.py given as the nodes says so, before anything starts."""
    launch = package / "launch" / "stop.launch.py"
    launch.write_text("from launch import LaunchDescription\n\ndef generate_launch_description():\n"
                      "    return LaunchDescription([])\n")
    result = run([str(ROOM), str(launch)])
    assert result.exit_code == 2 and "is a ROS 2 launch file: worldgen run starts ROS 1 (rospy) nodes" in \
        result.output, result.output
