"""Several robots in one simulation (a launch file with a `<group ns>` per TurtleBot3, as final projects write it),
each driven by its own student-style node (tests/rosnodes/stop_zero_callback.py: subscribes to its /scan,
publishes its cmd_vel):

- CPU of the simulator process for 1, 2 and 4 robots at --rate 1, while running (start-up excluded), and what each
  added robot costs (% of one core);
- the real-time factor at --rate max with 4 robots (`worldgen run`, every robot's node running).

    .venv/bin/python benchmarks/bench_robots.py
"""

from __future__ import annotations

import json
import os
import socket
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from procs import cpu_seconds, simulator_pid   # benchmarks/procs.py, beside this script

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))
SYSTEM_PYTHON = "/usr/bin/python3"
NODE = REPO / "tests" / "rosnodes" / "stop_zero_callback.py"
ROOM = REPO / "examples" / "enclosed_room.yaml"
POSES = [(-1.0, -1.0, 3.14159), (1.0, 1.0, 0.0), (1.0, -1.0, -1.5708), (-1.0, 1.0, 1.5708)]
GROUP = """  <group ns="tb3_{i}">
    <param name="robot_description"
           command="$(find xacro)/xacro $(find turtlebot3_description)/urdf/turtlebot3_burger.urdf.xacro"/>
    <node pkg="robot_state_publisher" type="robot_state_publisher" name="robot_state_publisher">
      <param name="tf_prefix" value="tb3_{i}"/>
    </node>
    <node name="spawn_urdf" pkg="gazebo_ros" type="spawn_model"
          args="-urdf -model tb3_{i} -x {x} -y {y} -z 0.0 -Y {yaw} -param robot_description"/>
  </group>
"""
MEASURE = 10.0   # s of wall time the running simulator is measured over


def free_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return sock.getsockname()[1]


def env_for(tmp: Path) -> dict:
    env = {k: v for k, v in os.environ.items() if not k.startswith("ROS_")}
    env.update(PYTHONPATH=str(REPO), ROS_HOME=str(tmp / "ros_home"), ROS_IP="127.0.0.1",
               ROS_MASTER_URI=f"http://127.0.0.1:{free_port()}")
    return env


def robots_launch(folder: Path, count: int) -> Path:
    """The class room with ``count`` burgers, each in its own namespace, facing a wall."""
    subprocess.run([sys.executable, "-m", "worldgen", "build", str(ROOM), "-o", str(folder), "--force"], check=True,
                   capture_output=True, env=dict(os.environ, PYTHONPATH=str(REPO)))
    groups = "".join(GROUP.format(i=i, x=x, y=y, yaw=yaw) for i, (x, y, yaw) in enumerate(POSES[:count]))
    path = folder / f"robots_{count}.launch"
    path.write_text('<launch>\n  <include file="$(find gazebo_ros)/launch/empty_world.launch">\n'
                    '    <arg name="world_name" value="$(dirname)/enclosed_room.world"/>\n  </include>\n'
                    f"{groups}</launch>\n")
    return path


def simulator_cpu(tmp: Path, count: int) -> float:
    """The simulator's share of one core while it runs ``count`` robots at 1x, each with its node."""
    launch = robots_launch(tmp, count)
    env = env_for(tmp)
    log = tmp / f"sim_{count}.err"
    port = env["ROS_MASTER_URI"].rsplit(":", 1)[1]
    master = subprocess.Popen(["rosmaster", "--core", "-p", port], env=env, stdout=subprocess.DEVNULL,
                              stderr=subprocess.DEVNULL, start_new_session=True)
    nodes = []
    try:
        time.sleep(1.0)
        with open(log, "w") as err:
            sim = subprocess.Popen([sys.executable, "-m", "worldgen", "sim", str(launch), "--rate", "1"], env=env,
                                   stdout=subprocess.DEVNULL, stderr=err)
        deadline = time.monotonic() + 60
        while "worldgen-sim: running" not in log.read_text() and time.monotonic() < deadline:
            time.sleep(0.1)
        for i in range(count):
            nodes.append(subprocess.Popen([SYSTEM_PYTHON, str(NODE), f"__ns:=/tb3_{i}"], env=env,
                                          stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
        time.sleep(3.0)   # the nodes up and connected
        pid = simulator_pid(f"ROS_MASTER_URI={env['ROS_MASTER_URI']}".encode())
        before, start = cpu_seconds(pid), time.monotonic()
        time.sleep(MEASURE)
        share = (cpu_seconds(pid) - before) / (time.monotonic() - start)
        sim.send_signal(2)
        sim.wait(timeout=30)
        return share
    finally:
        for proc in nodes:
            proc.terminate()
            proc.wait(timeout=10)
        master.terminate()
        master.wait(timeout=10)


def max_rate_with(tmp: Path, count: int) -> tuple[float, dict]:
    """`worldgen run` of ``count`` robots at --rate max, every robot's node running; its real-time factor and each
    robot's final front distance."""
    launch = robots_launch(tmp, count)
    nodes = []
    for i in range(count):
        nodes += [str(NODE), f"__ns:=/tb3_{i}"]
    proc = subprocess.run([sys.executable, "-m", "worldgen", "run", str(launch), *nodes, "--rate", "max",
                           "--duration", "20", "--format", "json"], env=env_for(tmp), capture_output=True, text=True)
    doc = json.loads(proc.stdout)
    fronts = {ns: m.get("final_front_distance_m") for ns, m in doc["metrics"].get("robots", {}).items()}
    return doc["metrics"]["real_time_factor"], fronts


def main() -> int:
    with tempfile.TemporaryDirectory(prefix="bench_robots_") as name:
        tmp = Path(name)
        shares = {n: simulator_cpu(tmp, n) for n in (1, 2, 4)}
        for n, share in shares.items():
            print(f"{n} robot(s) at --rate 1: simulator {share * 100:5.1f} % of one core "
                  f"({share * 100 / n:4.1f} % per robot)")
        added = (shares[4] - shares[1]) / 3
        print(f"each robot added to the first: {added * 100:.1f} % of one core")
        rtf, fronts = max_rate_with(tmp, 4)
        print(f"4 robots at --rate max (worldgen run, 4 nodes): {rtf:.1f}x real time; final front distances "
              + ", ".join(f"{ns} {d:.2f} m" for ns, d in sorted(fronts.items()) if d is not None))
    return 0


if __name__ == "__main__":
    sys.exit(main())
