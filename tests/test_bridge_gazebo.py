"""Gazebo's ROS interface on `worldgen sim`: gazebo_msgs types wire-compatible with Gazebo's, and the services
and topics students' nodes call (set/get_model_state, spawn_sdf_model, delete_model, pause/unpause, model_states)
answered as Gazebo answers them, with their effect on /odom and the LiDAR.

Real rosmaster, real rospy nodes under Debian's python (tests/rosnodes/gazebo_probe.py).
"""

from __future__ import annotations

import math
import signal
import subprocess

import pytest

from bridgetools import NODES, ROOM, SCAN_X, WALL_FACE, need_ros, no_leftovers, ros_env
from rosstubs import SYSTEM_PYTHON

# MD5 sums of Gazebo Classic's gazebo_msgs (ROS Melodic/Noetic), as its generated code and every client library
# publish them: a node built against the real package talks to ours only when these agree.
GAZEBO_MD5 = {"msg/ModelState": "9330fd35f2fcd82d457e54bd54e10593",
              "msg/ModelStates": "48c080191eb15c41858319b4d8a609c2",
              "srv/GetModelState": "4c515e936d3319c9610c559c60bfc3d4",
              "srv/SpawnModel": "9ed9c82c96abe1a00c3e8cdaeee24413"}


def test_generated_gazebo_msgs_match_gazebos_md5sums(tmp_path):
    need_ros()
    import os

    env = dict(os.environ, WORLDGEN_CACHE=str(tmp_path / "cache"))
    code = ("import json, sys\n"
            "from worldgen.ros1.gazebo_types import gazebo_msgs_path\n"
            "sys.path.insert(0, gazebo_msgs_path())\n"
            "import gazebo_msgs.msg as m, gazebo_msgs.srv as s\n"
            "print(json.dumps({f'{k}/{n}': getattr(mod, n)._md5sum for k, mod in (('msg', m), ('srv', s))"
            " for n in dir(mod) if hasattr(getattr(mod, n), '_md5sum') and not n.endswith(('Request', 'Response'))}))")
    import json
    import sys

    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    md5 = json.loads(out.stdout.strip().splitlines()[-1])
    for name, expected in GAZEBO_MD5.items():
        assert md5[name] == expected, name


@pytest.fixture(scope="module")
def sim(tmp_path_factory):
    """`worldgen sim` on the class room at 2x real time; its stderr in a file (it names the gazebo_msgs folder)."""
    import sys
    import time

    need_ros()
    tmp = tmp_path_factory.mktemp("gz")
    env = ros_env(tmp)
    env["WORLDGEN_CACHE"] = str(tmp / "cache")
    log = tmp / "sim.err"
    with open(log, "w") as err:
        proc = subprocess.Popen([sys.executable, "-m", "worldgen", "sim", str(ROOM), "--rate", "2"], env=env,
                                stdout=subprocess.DEVNULL, stderr=err, text=True)
    deadline = time.monotonic() + 60
    while "worldgen-sim: running" not in log.read_text() and time.monotonic() < deadline:
        assert proc.poll() is None, log.read_text()
        time.sleep(0.1)
    folder = [line.split("export PYTHONPATH=")[1].split(":$")[0] for line in log.read_text().splitlines()
              if "export PYTHONPATH=" in line]
    yield dict(env, PYTHONPATH=":".join(folder + [env["PYTHONPATH"]]))
    proc.send_signal(signal.SIGINT)
    proc.wait(timeout=30)
    assert proc.returncode == 0, log.read_text()
    assert "Traceback" not in log.read_text()
    no_leftovers(env)


def gazebo_probe(env, *args):
    import json

    out = subprocess.run([SYSTEM_PYTHON, str(NODES / "gazebo_probe.py"), *args], env=env, capture_output=True,
                         text=True, timeout=120)
    assert out.returncode == 0, out.stderr[-3000:]
    return json.loads(out.stdout.strip().splitlines()[-1])


def test_set_model_state_teleports_the_robot_on_odom_and_model_states(sim):
    got = gazebo_probe(sim, "teleport", "turtlebot3_burger", "1.0", "-0.5", "1.2")
    assert got["success"] and got["status"] == "SetModelState: set model state done"
    for key in ("odom", "model_states", "get_model_state"):
        x, y, yaw = got[key][:3]
        assert math.hypot(x - 1.0, y + 0.5) < 0.02, (key, got[key])
        assert abs(math.remainder(yaw - 1.2, math.tau)) < 0.03, (key, got[key])
    assert got["get_model_state"][3:] == [True, "GetModelState: got properties"]
    assert "turtlebot3_burger" in got["names"] and "enclosed_room" in got["names"]


def test_a_spawned_box_is_seen_by_the_lidar_at_its_true_distance_until_deleted(sim):
    gazebo_probe(sim, "teleport", "turtlebot3_burger", "0", "0", "0")
    got = gazebo_probe(sim, "spawn", "1.2", "0", "0.4")
    sensor_x = SCAN_X
    assert got["before"] == pytest.approx(WALL_FACE - sensor_x, abs=0.05)
    assert got["with_box"] == pytest.approx(1.2 - 0.2 - sensor_x, abs=0.05)   # the box's near face
    assert got["after"] == pytest.approx(WALL_FACE - sensor_x, abs=0.05)
    assert got["spawned"] == [True, "SpawnModel: Successfully spawned entity"]
    assert got["again"][0] is False and "already exists" in got["again"][1]
    assert got["deleted"] == [True, "DeleteModel: successfully deleted model"]
    assert "box_1" in got["names"]


def test_pause_physics_stops_the_clock_and_unpause_restarts_it(sim):
    got = gazebo_probe(sim, "pause")
    assert got["paused_later"] - got["paused_first"] < 0.02    # 1 s of real time, the clock still
    assert got["resumed"] > got["paused_later"] + 0.3           # 0.5 s at 2x real time


def test_unknown_models_get_gazebos_failure_answers(sim):
    got = gazebo_probe(sim, "missing")
    assert got["get"] == [False, "GetModelState: model [no_such_model] does not exist"]
    assert got["set"] == [False, "SetModelState: model [no_such_model] does not exist"]
    assert got["delete"] == [False, "DeleteModel: model does not exist"]


def test_a_robot_spawned_with_spawn_urdf_model_is_seen_and_driven_in_its_namespace(sim, tmp_path):
    """A second TurtleBot3 (our burger's URDF, as a node would send its robot_description) 1.2 m ahead: the first
    robot's front beam reads its body, it publishes /second/odom and backs away on /second/cmd_vel, and it goes
    when deleted."""
    from worldgen.robots import robot_urdf

    gazebo_probe(sim, "teleport", "turtlebot3_burger", "0", "0", "0")
    urdf = tmp_path / "burger.urdf"
    urdf.write_text(robot_urdf("burger"))
    got = gazebo_probe(sim, "robot", str(urdf), "1.2", "0", "/second")
    assert got["spawned"] == [True, "SpawnModel: Successfully spawned entity"]
    assert got["before"] == pytest.approx(WALL_FACE - SCAN_X, abs=0.05)
    assert 1.2 - 0.12 - SCAN_X < got["seen"] < 1.2 - SCAN_X, got   # its body, ahead of its centre
    assert got["start"] == pytest.approx([1.2, 0.0], abs=0.03)
    # backed away from us (+x) at 0.1 m/s for the simulated time between the probe's two commands: 2 s, more when a
    # loaded machine kept the probe from its second command a while (at --rate 2, simulated time goes on meanwhile)
    assert got["drove_s"] >= 2.0 - 0.05
    assert got["end"][0] - got["start"][0] == pytest.approx(0.1 * got["drove_s"], abs=0.06)
    assert "second_robot" in got["names"]
    assert got["deleted"][0] is True and got["after"] == pytest.approx(WALL_FACE - SCAN_X, abs=0.05)


def test_reset_world_puts_a_teleported_robot_back_at_its_spawn(sim):
    got = gazebo_probe(sim, "reset", "1.0", "1.0", "0.5")
    assert got["moved"] == pytest.approx([1.0, 1.0], abs=0.03)
    assert got["back"] == pytest.approx([0.0, 0.0, 0.0], abs=0.03)
