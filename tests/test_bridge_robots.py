"""Several robots in one simulation, from one launch file with a `<group ns>` per robot (as final projects and
turtlebot3_gazebo's multi_turtlebot3.launch spawn them): each robot's topics in its namespace, frames prefixed,
each robot driven only by its own cmd_vel, robots seeing each other on their scans; `worldgen run --robot-ns`
grades one of them and reports every robot.

Real rosmaster, real rospy nodes under Debian's python.
"""

from __future__ import annotations

import json
import signal
import subprocess
import sys
import time

import pytest

from bridgetools import NODES, REPO, ROOM, need_ros, no_leftovers, ros_env
from rosstubs import SYSTEM_PYTHON

GROUP = """  <group ns="{ns}">
    <param name="robot_description"
           command="$(find xacro)/xacro $(find turtlebot3_description)/urdf/turtlebot3_$(arg model).urdf.xacro"/>
    <node pkg="robot_state_publisher" type="robot_state_publisher" name="robot_state_publisher">
      <param name="tf_prefix" value="{ns}"/>
    </node>
    <node name="spawn_urdf" pkg="gazebo_ros" type="spawn_model"
          args="-urdf -model {ns} -x {x} -y {y} -z 0.0 -Y {yaw} -param robot_description"/>
  </group>
"""


def two_robot_launch(folder):
    """The class room with tb3_0 at (-0.5, 0) facing +x and tb3_1 at (0.5, 0) facing it."""
    subprocess.run([sys.executable, "-m", "worldgen", "build", str(ROOM), "-o", str(folder)], check=True,
                   capture_output=True, env={"PYTHONPATH": str(REPO), "PATH": "/usr/bin:/bin"})
    text = ('<launch>\n  <arg name="model" default="burger"/>\n'
            '  <include file="$(find gazebo_ros)/launch/empty_world.launch">\n'
            '    <arg name="world_name" value="$(dirname)/enclosed_room.world"/>\n  </include>\n'
            + GROUP.format(ns="tb3_0", x=-0.5, y=0.0, yaw=0.0) + GROUP.format(ns="tb3_1", x=0.5, y=0.0, yaw=3.14159)
            + "</launch>\n")
    path = folder / "two_robots.launch"
    path.write_text(text)
    return path


@pytest.fixture(scope="module")
def sim(tmp_path_factory):
    need_ros()   # at a fixed pace: the probe drives by its own clock (at --rate max 2 runs of 3 failed)
    tmp = tmp_path_factory.mktemp("robots")
    launch = two_robot_launch(tmp)
    env = ros_env(tmp)
    env["WORLDGEN_CACHE"] = str(tmp / "cache")
    log = tmp / "sim.err"
    with open(log, "w") as err:
        proc = subprocess.Popen([sys.executable, "-m", "worldgen", "sim", str(launch), "--rate", "2"], env=env,
                                stdout=subprocess.DEVNULL, stderr=err, text=True)
    deadline = time.monotonic() + 60
    while "worldgen-sim: running" not in log.read_text() and time.monotonic() < deadline:
        assert proc.poll() is None, log.read_text()
        time.sleep(0.1)
    folder = [line.split("export PYTHONPATH=")[1].split(":$")[0] for line in log.read_text().splitlines()
              if "export PYTHONPATH=" in line]
    yield dict(env, PYTHONPATH=":".join(folder + [env["PYTHONPATH"]])), log
    proc.send_signal(signal.SIGINT)
    proc.wait(timeout=30)
    assert proc.returncode == 0, log.read_text()
    no_leftovers(env)


def test_two_robots_each_have_their_topics_frames_and_see_each_other(sim):
    env, log = sim
    assert "/tb3_0: burger at (-0.5, 0, 0)" in log.read_text()
    out = subprocess.run([SYSTEM_PYTHON, str(NODES / "gazebo_probe.py"), "robots", "/tb3_0", "/tb3_1"], env=env,
                         capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr[-3000:]
    got = json.loads(out.stdout.strip().splitlines()[-1])
    # Each LiDAR sees the other robot's LiDAR housing (radius 0.055 m, 0.015 m ahead of base_scan) between them,
    # not the wall 2.425 m beyond: base_scan at x = -0.532 and, facing back, at 0.532; housing front at 0.462.
    assert got["fronts"]["/tb3_0"] == pytest.approx(0.462 + 0.532, abs=0.04)
    assert got["fronts"]["/tb3_1"] == pytest.approx(0.462 + 0.532, abs=0.04)
    # Only tb3_0 was commanded (0.15 m/s for 2 s, then a ramped stop)
    assert got["moved"]["/tb3_0"] > 0.2
    assert got["moved"]["/tb3_1"] < 0.01
    assert got["odom_frames"] == {"/tb3_0": ["tb3_0/odom", "tb3_0/base_footprint"],
                                  "/tb3_1": ["tb3_1/odom", "tb3_1/base_footprint"]}
    assert got["scan_frames"] == {"/tb3_0": "tb3_0/base_scan", "/tb3_1": "tb3_1/base_scan"}
    assert ["tb3_1/odom", "tb3_1/base_footprint"] in got["tf"]


def test_run_grades_the_chosen_robot_and_reports_every_robot(tmp_path):
    """A node in /tb3_1 drives that robot into tb3_0: graded as tb3_1, both robots reported, the bump seen."""
    need_ros()
    launch = two_robot_launch(tmp_path)
    env = ros_env(tmp_path)
    env["WORLDGEN_CACHE"] = str(tmp_path / "cache")
    out = subprocess.run([sys.executable, "-m", "worldgen", "run", str(launch), str(NODES / "drive_into_wall.py"),
                          "__ns:=/tb3_1", "--robot-ns", "tb3_1", "--duration", "6", "--rate", "max",
                          "--format", "json"], env=env, capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr
    got = json.loads(out.stdout)
    robots = got["metrics"]["robots"]
    assert set(robots) == {"/tb3_0", "/tb3_1"} and got["metrics"]["graded_robot"] == "/tb3_1"
    assert got["spawn"][:2] == [0.5, 0.0]
    assert robots["/tb3_0"]["cmd_vel_messages"] == 0 and robots["/tb3_1"]["cmd_vel_messages"] > 10
    assert got["metrics"]["final_pose"] == robots["/tb3_1"]["final_pose"]
    assert got["metrics"]["final_pose"][0] < 0.35   # it drove towards -x, into the other robot
    assert any(c["shape"] == "tb3_0" for c in got["metrics"]["contacts"])
    no_leftovers(env)


def test_an_unknown_robot_namespace_is_one_line_before_anything_starts(tmp_path):
    need_ros()
    launch = two_robot_launch(tmp_path)
    env = ros_env(tmp_path)
    out = subprocess.run([sys.executable, "-m", "worldgen", "run", str(launch), str(NODES / "drive_into_wall.py"),
                          "--robot-ns", "tb3_7"], env=env, capture_output=True, text=True, timeout=120)
    assert out.returncode == 2
    assert out.stderr.count("\n") == 1 and "tb3_7" in out.stderr and "/tb3_0, /tb3_1" in out.stderr
