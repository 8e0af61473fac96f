"""`worldgen sim`: to a rospy node the simulated TurtleBot3 looks like Gazebo's (topics, types, frames, rates,
motion, LiDAR, reset services), it starts a master only when none answers, and it leaves no process behind.

Real rosmaster, real rospy nodes under Debian's python (tests/rosnodes/probe.py); missing ROS packages skip these
tests, or fail them under CI (see rosstubs).
"""

from __future__ import annotations

import math
import signal
import socket
import time

import pytest

from bridgetools import (ROOM, SCAN_X, WALL_FACE, leftovers, need_ros, no_leftovers, probe, ros_env, wait_master,
                         worldgen)
from rosstubs import start_roscore, stop_process


@pytest.fixture(scope="module")
def running_sim(tmp_path_factory):
    """`worldgen sim` on the class room at 4x real time (a fixed pace: the probes measure rates and drive by the
    clock), with the master it started itself."""
    need_ros()
    env = ros_env(tmp_path_factory.mktemp("sim"))
    proc = worldgen(["sim", str(ROOM), "--rate", "4"], env)
    wait_master(env, proc)
    yield env
    proc.send_signal(signal.SIGINT)
    out, err = proc.communicate(timeout=30)
    assert proc.returncode == 0, err
    assert "Traceback" not in err
    no_leftovers(env)


def test_topics_fields_frames_and_rates(running_sim):
    got = probe(["topics", "3"], running_sim)
    assert got["use_sim_time"] is True
    nominal = {"/clock": 120, "/scan": 5, "/odom": 30, "/tf": 30, "/joint_states": 30, "/imu": 120}
    for topic, rate in nominal.items():
        assert got["rates"][topic] == pytest.approx(rate, rel=0.05), topic
    assert got["counts"]["/tf_static"] >= 1
    scan = got["first"]["/scan"]
    assert scan["frame"] == "base_scan" and scan["n"] == 360
    assert scan["angle_min"] == 0.0 and scan["angle_max"] == pytest.approx(6.28319, abs=1e-5)
    assert scan["angle_increment"] == pytest.approx(6.28319 / 359, rel=1e-5)
    assert scan["range_min"] == pytest.approx(0.12) and scan["range_max"] == pytest.approx(3.5)
    odom = got["first"]["/odom"]
    assert (odom["frame"], odom["child"]) == ("odom", "base_footprint")
    assert abs(odom["x"]) < 0.01 and abs(odom["y"]) < 0.01
    joints = got["first"]["/joint_states"]
    assert joints["name"] == ["wheel_left_joint", "wheel_right_joint"]
    assert len(joints["position"]) == 2 and joints["velocity"] == []   # the diff drive's: positions only
    imu = got["first"]["/imu"]   # libgazebo_ros_imu: differenced velocity, no gravity (about 0 at rest)
    assert imu["frame"] == "imu_link" and abs(imu["az"]) < 0.2 and abs(imu["wz"]) < 0.05
    static = {tuple(pair) for pair in got["first"]["/tf_static"]}
    assert {("base_footprint", "base_link"), ("base_link", "base_scan"), ("base_link", "imu_link")} <= static
    moving = {tuple(pair) for pair in got["first"]["/tf"]}
    assert {("odom", "base_footprint"), ("base_link", "wheel_left_link"), ("base_link", "wheel_right_link")} <= moving


def test_front_beam_reads_the_walls_true_distance(running_sim):
    scan = probe(["topics", "0.5"], running_sim)["first"]["/scan"]
    true = WALL_FACE - SCAN_X                       # base_scan sits 3.2 cm behind base_footprint
    ahead = scan["ranges"][:3] + scan["ranges"][-3:]   # within ±3° of straight ahead
    assert scan["front"] == pytest.approx(true, abs=0.05)
    assert sum(ahead) / len(ahead) == pytest.approx(true, abs=0.02)
    behind = scan["ranges"][180]                    # 180 · 6.28319/359 rad ≈ 180.5°: the wall behind
    assert behind == pytest.approx(WALL_FACE + SCAN_X, abs=0.05)


def test_cmd_vel_moves_and_turns_as_commanded(running_sim):
    forward = probe(["drive", "0.1", "0", "5"], running_sim)
    assert forward["distance"] == pytest.approx(0.5, rel=0.10)
    assert abs(forward["end"][1] - forward["start"][1]) < 0.02
    turn = probe(["drive", "0", "1", str(math.pi)], running_sim)
    assert turn["turned"] == pytest.approx(math.pi, rel=0.10)
    assert turn["distance"] < 0.05


def test_reset_services_put_the_robot_back_at_its_spawn(running_sim):
    got = probe(["reset"], running_sim)
    assert math.hypot(*got["moved"][:2]) > 0.1
    x, y, yaw = got["after"]
    assert math.hypot(x, y) < 0.01 and abs(yaw) < 0.01


def test_joins_a_running_master_and_leaves_it_running(tmp_path):
    need_ros()
    core, env = start_roscore(tmp_path)
    try:
        env = dict(env, PYTHONPATH=ros_env(tmp_path)["PYTHONPATH"])
        proc = worldgen(["sim", str(ROOM), "--duration", "1", "--rate", "max"], env)
        out, err = proc.communicate(timeout=60)
        assert proc.returncode == 0, err
        assert "joined the ROS master" in err
        assert core.poll() is None   # not ours to stop
    finally:
        stop_process(core)


def test_bad_world_and_port_in_use_are_one_line_errors(tmp_path):
    need_ros()
    env = ros_env(tmp_path)
    bad = tmp_path / "bad.world"
    bad.write_text("<sdf version='1.6'><world name='w'><model name='m'>")
    proc = worldgen(["sim", str(bad), "--duration", "1"], env)
    out, err = proc.communicate(timeout=60)
    assert proc.returncode == 2 and len(err.strip().splitlines()) == 1 and err.startswith("worldgen: error:"), err
    with socket.socket() as taken:   # something that is not a ROS master holds the port
        taken.bind(("127.0.0.1", int(env["ROS_MASTER_URI"].rsplit(":", 1)[1])))
        taken.listen()
        proc = worldgen(["sim", str(ROOM), "--duration", "1"], env)
        out, err = proc.communicate(timeout=60)
    assert proc.returncode == 2 and "already in use" in err and len(err.strip().splitlines()) == 1, err
    no_leftovers(env)


def test_a_second_sim_on_the_same_master_is_refused_and_the_first_runs_on(running_sim):
    """A second /gazebo would make the master shut the first one down, and with it the master it started: the
    second is refused in one line, and the first still publishes."""
    proc = worldgen(["sim", str(ROOM), "--duration", "1"], running_sim)
    out, err = proc.communicate(timeout=60)
    assert proc.returncode == 2 and len(err.strip().splitlines()) == 1, err
    assert err.startswith(f"worldgen: error: a simulator (/gazebo, pid ") and running_sim["ROS_MASTER_URI"] in err
    got = probe(["topics", "1"], running_sim)
    assert got["counts"]["/scan"] >= 3


@pytest.mark.parametrize("uri, said", [
    ("garbage", "ROS_MASTER_URI=garbage is not a ROS master's address"),
    ("http://localhost:99999", "is not a ROS master's address"),
    ("http://nosuchhost.invalid:11311", "nosuchhost.invalid is not this machine (or cannot be found)"),
])
def test_a_master_uri_worldgen_cannot_use_is_a_one_line_error(tmp_path, uri, said):
    """Not a master started on localhost instead, which the student's other terminals would not find."""
    need_ros()
    env = dict(ros_env(tmp_path), ROS_MASTER_URI=uri)
    proc = worldgen(["sim", str(ROOM), "--duration", "1"], env)
    out, err = proc.communicate(timeout=60)
    assert proc.returncode == 2 and len(err.strip().splitlines()) == 1 and said in err, err
    assert "started a ROS master" not in err


def test_sigterm_stops_everything(tmp_path):
    need_ros()
    env = ros_env(tmp_path)
    proc = worldgen(["sim", str(ROOM), "--rate", "max"], env)
    wait_master(env, proc)
    expected = ("-m worldgen sim ", "rosmaster", "-m worldgen.ros1 ")   # worldgen, the master, the simulator

    def seen() -> list[str]:
        running = leftovers(env)
        return [name for name in expected if any(name in p for p in running)]

    deadline = time.monotonic() + 20
    while seen() != list(expected) and time.monotonic() < deadline:
        time.sleep(0.05)
    assert seen() == list(expected), leftovers(env)
    proc.send_signal(signal.SIGTERM)
    proc.communicate(timeout=30)
    assert proc.returncode == 0   # SIGTERM is a stop asked for, as Ctrl-C is
    no_leftovers(env)
