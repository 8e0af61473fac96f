"""The ROS bridge (`worldgen sim`, `worldgen run`) against its targets, with a real rosmaster and rospy nodes:

- real-time factor at --rate 1 (target 1.00 ± 0.05);
- the course's stop_at_wall.py graded in the class room at --rate max (target ≥ 20× real time, and a pass);
- the first /scan reaching a subscriber within 2 s of `worldgen sim` starting;
- topic rates against nominal (clock 120, scan 5, odom/tf/joint_states 30, imu 120 Hz; within 5 %), by simulated
  stamps and by arrival times at --rate 1;
- CPU per simulated robot at 1× real time (the simulator node and its master, % of one core).

    .venv/bin/python benchmarks/bench_bridge.py
"""

from __future__ import annotations

import json
import os
import resource
import socket
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))
SYSTEM_PYTHON = "/usr/bin/python3"
PROBE = REPO / "tests" / "rosnodes" / "probe.py"
SPINNER = REPO / "tests" / "rosnodes" / "spin_rate_loop.py"
ROOM = REPO / "examples" / "enclosed_room.yaml"
CLASS_ROOM = (REPO.parent / "shared" / "corpus" / "worlds" /
              "Intro-Robotics-UChicago-Spring-2022__warmup_project__worlds_turtlebot3_in_enclosed_room.world")
NOMINAL = {"/clock": 120, "/scan": 5, "/odom": 30, "/tf": 30, "/joint_states": 30, "/imu": 120}

FIRST_SCAN = r"""
import sys, time
import rospy
from sensor_msgs.msg import LaserScan
rospy.init_node("first_scan", disable_signals=True)
got = []
rospy.Subscriber("/scan", LaserScan, lambda m: got.append(time.time()))
print("ready", flush=True)
while not got:
    time.sleep(0.001)
print(repr(got[0]), flush=True)
"""


def free_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return sock.getsockname()[1]


def env_for(tmp: Path, port: int | None = None) -> dict:
    env = {k: v for k, v in os.environ.items() if not k.startswith("ROS_")}
    env.update(PYTHONPATH=str(REPO), ROS_HOME=str(tmp / "ros_home"), ROS_IP="127.0.0.1",
               ROS_MASTER_URI=f"http://127.0.0.1:{port or free_port()}")
    return env


def worldgen(args, env, **kw):
    return subprocess.run([sys.executable, "-m", "worldgen", *args], env=env, capture_output=True, text=True, **kw)


def real_time_factor(tmp: Path) -> float:
    proc = worldgen(["run", str(ROOM), str(SPINNER), "--rate", "1", "--duration", "10", "--format", "json"],
                    env_for(tmp))
    return json.loads(proc.stdout)["metrics"]["real_time_factor"]


def class_room_stop_at_wall(tmp: Path) -> tuple[float, bool, str]:
    from worldgen.packages.course_ros1 import write_course

    node = write_course(tmp / "ws") / "lab_a_stop_at_wall" / "scripts" / "stop_at_wall.py"
    world, spawn = (CLASS_ROOM, ["--spawn", "-4.905,-1.415,0"]) if CLASS_ROOM.is_file() else (ROOM, [])
    proc = worldgen(["run", str(world), str(node), *spawn, "--task", "stop-at-wall", "--rate", "max", "--format",
                     "json"], env_for(tmp))
    doc = json.loads(proc.stdout)
    return doc["metrics"]["real_time_factor"], doc["ok"], "class room (corpus)" if world == CLASS_ROOM else "5 m room"


def first_scan_and_rates(tmp: Path) -> tuple[float, dict, dict, float]:
    env = env_for(tmp)
    port = int(env["ROS_MASTER_URI"].rsplit(":", 1)[1])
    master = subprocess.Popen(["rosmaster", "--core", "-p", str(port)], env=env, stdout=subprocess.DEVNULL,
                              stderr=subprocess.DEVNULL, start_new_session=True)
    try:
        time.sleep(1.0)
        listener = subprocess.Popen([SYSTEM_PYTHON, "-c", FIRST_SCAN], env=env, stdout=subprocess.PIPE, text=True)
        assert listener.stdout.readline().strip() == "ready"
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        started = time.time()
        sim = subprocess.Popen([sys.executable, "-m", "worldgen", "sim", str(ROOM), "--rate", "1", "--duration", "12"],
                               env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        first = float(listener.stdout.readline()) - started
        listener.wait(timeout=10)
        probe = subprocess.run([SYSTEM_PYTHON, str(PROBE), "topics", "6"], env=env, capture_output=True, text=True,
                               timeout=60)
        sim.wait(timeout=60)
        wall = time.time() - started
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu = (after.ru_utime + after.ru_stime) - (before.ru_utime + before.ru_stime)
        got = json.loads(probe.stdout.strip().splitlines()[-1])
        return first, got["rates"], got["wall_rates"], cpu / wall
    finally:
        master.terminate()
        master.wait(timeout=10)


def main() -> int:
    ok = True
    with tempfile.TemporaryDirectory(prefix="bench_bridge_") as name:
        tmp = Path(name)
        rtf = real_time_factor(tmp)
        good = abs(rtf - 1.0) <= 0.05
        ok &= good
        print(f"real-time factor at --rate 1:           {rtf:.3f}  (target 1.00 ± 0.05) {'ok' if good else 'MISSED'}")
        rtf_max, passed, where = class_room_stop_at_wall(tmp)
        good = rtf_max >= 20 and passed
        ok &= good
        print(f"stop_at_wall.py at --rate max, {where}: {rtf_max:.1f}x real time, "
              f"{'pass' if passed else 'FAIL'}  (target >= 20x) {'ok' if good else 'MISSED'}")
        first, rates, wall_rates, cpu = first_scan_and_rates(tmp)
        good = first <= 2.0
        ok &= good
        print(f"first /scan after `worldgen sim` starts: {first:.2f} s  (target <= 2 s) {'ok' if good else 'MISSED'}")
        for topic, nominal in NOMINAL.items():
            stamped, arrived = rates.get(topic, 0.0), wall_rates.get(topic, 0.0)
            good = abs(stamped / nominal - 1) <= 0.05 and abs(arrived / nominal - 1) <= 0.05
            ok &= good
            print(f"  {topic:<14} nominal {nominal:>3} Hz: {stamped:7.2f} Hz by stamps, {arrived:7.2f} Hz by arrival"
                  f"  {'ok' if good else 'MISSED'}")
        print(f"CPU per simulated robot at 1x real time: {cpu * 100:.0f} % of one core (simulator, master, CLI; "
              f"the probe excluded)")
    print("all targets met" if ok else "some targets missed")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
