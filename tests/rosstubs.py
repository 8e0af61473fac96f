"""Helpers for tests that run the real ROS 1 tools (Debian's catkin, catkin_lint, roslaunch, roscore, rospy).

Gazebo, gazebo_ros, xacro and turtlebot3_description are not Debian packages, so :func:`make_stub_packages`
writes stand-ins that are just enough for roslaunch to load our launch files: ``gazebo_ros`` with an
``empty_world.launch`` declaring the usual args and an executable ``spawn_model``, ``xacro`` with an executable
``xacro`` that runs the Python xacro of this environment, and ``turtlebot3_description`` with a tiny xacro robot
per model. ``ros_env`` gives a subprocess environment with ROS_HOME and the log folder in a temporary folder.

Tools that are missing make a test skip, except under CI (env ``CI`` set), where they make it fail.
"""

from __future__ import annotations

import functools
import os
import shutil
import socket
import subprocess
import sys
import time
from pathlib import Path

import pytest

SYSTEM_PYTHON = "/usr/bin/python3"   # Debian's python: rospy, roslaunch and catkin_pkg live there


def need(tool: str) -> str:
    """The path of ``tool`` (a command or an absolute path); skips the test without it (fails under CI)."""
    found = tool if os.path.isabs(tool) and os.access(tool, os.X_OK) else shutil.which(tool)
    if found is None:
        message = f"{tool} is not installed (the Debian ROS 1 packages: see .ci/run)"
        if os.environ.get("CI"):
            pytest.fail(message)
        pytest.skip(message)
    return found


@functools.lru_cache(maxsize=None)
def _importable(modules: tuple[str, ...]) -> bool:
    """Whether Debian's python imports every one of ``modules``: asked once per test process (a Python start and
    rospy's imports each time cost about a second of CPU, and every ROS test asks)."""
    return subprocess.run([SYSTEM_PYTHON, "-c", f"import {', '.join(modules)}"], capture_output=True).returncode == 0


def need_module(*modules: str) -> None:
    """Skip (fail under CI) when Debian's python cannot import one of ``modules``, named."""
    need(SYSTEM_PYTHON)
    if _importable(modules):
        return
    for module in modules:
        if not _importable((module,)):
            message = f"{SYSTEM_PYTHON} cannot import {module} (install python3-{module.split('.')[0]})"
            if os.environ.get("CI"):
                pytest.fail(message)
            pytest.skip(message)


def ros_env(tmp: Path, **extra: str) -> dict[str, str]:
    """The environment for a ROS tool: ROS_HOME and ROS_LOG_DIR under ``tmp``, no inherited master or
    package path, plus ``extra``."""
    env = {k: v for k, v in os.environ.items()
           if not k.startswith("ROS_") and k not in ("TURTLEBOT3_MODEL", "PYTHONPATH", "VIRTUAL_ENV", "PWD")}
    (tmp / "ros_home").mkdir(parents=True, exist_ok=True)
    env.update(ROS_HOME=str(tmp / "ros_home"), ROS_LOG_DIR=str(tmp / "ros_home" / "log"), **extra)
    return env


def _package_xml(name: str) -> str:
    return (f'<?xml version="1.0"?>\n<package format="2">\n  <name>{name}</name>\n  <version>0.0.0</version>\n'
            f"  <description>Test stand-in for {name}</description>\n"
            f'  <maintainer email="tests@example.com">tests</maintainer>\n  <license>BSD</license>\n'
            f"  <buildtool_depend>catkin</buildtool_depend>\n</package>\n")


EMPTY_WORLD = """<launch>
  <arg name="world_name" default="worlds/empty.world"/>
  <arg name="paused" default="false"/>
  <arg name="use_sim_time" default="true"/>
  <arg name="gui" default="true"/>
  <arg name="headless" default="false"/>
  <arg name="debug" default="false"/>
  <param name="/use_sim_time" value="$(arg use_sim_time)"/>
  <node name="gazebo" pkg="gazebo_ros" type="gzserver" args="$(arg world_name)"/>
  <group if="$(arg gui)">
    <node name="gazebo_gui" pkg="gazebo_ros" type="gzclient"/>
  </group>
</launch>
"""

# A tiny robot per model: a box body on the footprint frame, sized by a xacro property (so xacro has work to do).
ROBOT_XACRO = """<?xml version="1.0"?>
<robot name="turtlebot3_{model}" xmlns:xacro="http://ros.org/wiki/xacro">
  <xacro:property name="side" value="{side}"/>
  <link name="base_footprint"/>
  <link name="base_link">
    <visual><geometry><box size="${{side}} ${{side}} 0.1"/></geometry></visual>
  </link>
  <joint name="base_joint" type="fixed">
    <parent link="base_footprint"/>
    <child link="base_link"/>
    <origin xyz="0 0 ${{side / 2}}"/>
  </joint>
</robot>
"""


def make_stub_packages(root: Path) -> Path:
    """Write the stand-in packages into ``root`` (put it on ROS_PACKAGE_PATH) and return ``root``."""
    xacro = Path(sys.executable).parent / "xacro"
    xacro_cmd = str(xacro) if xacro.exists() else shutil.which("xacro")
    if xacro_cmd is None:
        pytest.fail("the Python xacro package (a worldgen dependency) is not installed")
    files = {
        "gazebo_ros/package.xml": _package_xml("gazebo_ros"),
        "gazebo_ros/launch/empty_world.launch": EMPTY_WORLD,
        "gazebo_ros/scripts/spawn_model": "#!/bin/sh\nexit 0\n",
        "gazebo_ros/scripts/gzserver": "#!/bin/sh\nexit 0\n",
        "gazebo_ros/scripts/gzclient": "#!/bin/sh\nexit 0\n",
        "xacro/package.xml": _package_xml("xacro"),
        "xacro/xacro": f'#!/bin/sh\nexec "{xacro_cmd}" "$@"\n',
        "turtlebot3_description/package.xml": _package_xml("turtlebot3_description"),
    }
    for model, side in (("burger", 0.14), ("waffle", 0.28), ("waffle_pi", 0.28)):
        files[f"turtlebot3_description/urdf/turtlebot3_{model}.urdf.xacro"] = ROBOT_XACRO.format(model=model,
                                                                                                side=side)
    for rel, text in files.items():
        path = root / rel
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)
        if rel.startswith("gazebo_ros/scripts/") or rel == "xacro/xacro":
            path.chmod(0o755)
    return root


# roslaunch's own loader, run under Debian's python: for each (file, argv) of the JSON argument, the nodes and the
# params it would start and set, as one JSON list.
ROSLAUNCH_LOAD = r"""
import json, sys
import roslaunch.config
out = []
for path, argv in json.loads(sys.argv[1]):
    config = roslaunch.config.load_config_default([(path, argv)], None)
    out.append({
        "nodes": [{"name": n.name, "namespace": n.namespace, "package": n.package, "type": n.type, "args": n.args}
                  for n in config.nodes],
        "params": {k: (v.value if isinstance(v.value, (str, int, float, bool)) else str(v.value))
                   for k, v in config.params.items()},
    })
print(json.dumps(out))
"""


def roslaunch_load(items: list[tuple[Path, list[str]]], env: dict[str, str]) -> list[dict]:
    """roslaunch's parse of each launch file with its argv (``name:=value``), in one process:
    ``[{"nodes": [...], "params": {...}}, ...]``."""
    import json

    request = json.dumps([[str(path), list(argv)] for path, argv in items])
    proc = subprocess.run([SYSTEM_PYTHON, "-c", ROSLAUNCH_LOAD, request], capture_output=True, text=True, env=env,
                          timeout=120)
    if proc.returncode != 0:
        raise AssertionError(f"roslaunch could not load {[str(p) for p, _ in items]}:\n{proc.stderr[-3000:]}")
    return json.loads(proc.stdout.strip().splitlines()[-1])


def free_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return sock.getsockname()[1]


def start_roscore(tmp: Path) -> tuple[subprocess.Popen, dict[str, str]]:
    """A roscore on a free port (ROS_HOME in ``tmp``), waited for until its master answers; returns the process
    and the environment that reaches it."""
    import xmlrpc.client

    port = free_port()
    env = ros_env(tmp, ROS_MASTER_URI=f"http://127.0.0.1:{port}", ROS_IP="127.0.0.1")
    proc = subprocess.Popen([need("roscore"), "-p", str(port)], env=env, stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE, start_new_session=True)
    master = xmlrpc.client.ServerProxy(env["ROS_MASTER_URI"])
    deadline = time.monotonic() + 20
    while time.monotonic() < deadline:
        if proc.poll() is not None:
            raise AssertionError(f"roscore exited: {proc.stderr.read().decode()[-2000:]}")
        try:
            code, _, _ = master.getSystemState("/tests")
            if code == 1 and _has_rosout(master):
                return proc, env
        except OSError:
            pass
        time.sleep(0.1)
    stop_process(proc)
    raise AssertionError("roscore did not answer within 20 s")


def _has_rosout(master) -> bool:
    _, _, (publishers, _, _) = master.getSystemState("/tests")
    return any(topic == "/rosout_agg" for topic, _ in publishers)


def stop_process(proc: subprocess.Popen) -> None:
    """Stop ``proc`` and the process group it leads (roscore starts rosmaster and rosout as children)."""
    import signal

    if proc.poll() is None:
        try:
            os.killpg(proc.pid, signal.SIGINT)
            proc.wait(timeout=10)
        except (ProcessLookupError, subprocess.TimeoutExpired):
            try:
                os.killpg(proc.pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
            proc.wait(timeout=10)


# Feeds LaserScan messages to the node under test and reports the cmd_vel it answers, as JSON lines. Each case
# is a front distance ("inf", "nan" or a number); every other beam reads 3.0 m.
SCAN_DRIVER = r"""
import json, math, sys, time
import rospy
from geometry_msgs.msg import Twist
from sensor_msgs.msg import LaserScan

cases = [float(c) for c in sys.argv[1:]]
rospy.init_node("scan_driver", disable_signals=True)
answers = []
cmd_sub = rospy.Subscriber("cmd_vel", Twist, lambda m: answers.append((m.linear.x, m.angular.z)))
scan_pub = rospy.Publisher("scan", LaserScan, queue_size=1)
deadline = time.monotonic() + 20
while scan_pub.get_num_connections() == 0 or cmd_sub.get_num_connections() == 0:
    if time.monotonic() > deadline:
        sys.exit("the node never connected to scan and cmd_vel")
    time.sleep(0.05)

def scan(front):
    msg = LaserScan()
    msg.header.frame_id = "base_scan"
    msg.angle_min, msg.angle_max = 0.0, 2 * math.pi * 359 / 360
    msg.angle_increment = 2 * math.pi / 360
    msg.range_min, msg.range_max = 0.12, 3.5
    msg.ranges = [front if (i <= 5 or i >= 355) else 3.0 for i in range(360)]
    return msg

for front in cases:
    answers.clear()
    end = time.monotonic() + 5
    while not answers and time.monotonic() < end:
        msg = scan(front)
        msg.header.stamp = rospy.Time.now()
        scan_pub.publish(msg)
        time.sleep(0.05)
    time.sleep(0.15)   # answers to older scans are flushed; keep the last one
    answers.clear()
    end = time.monotonic() + 5
    while not answers and time.monotonic() < end:
        scan_pub.publish(scan(front))
        time.sleep(0.05)
    print(json.dumps({"front": str(front), "linear": answers[-1][0] if answers else None,
                      "angular": answers[-1][1] if answers else None}), flush=True)
"""

# Reports the first geometry_msgs/Twist seen on cmd_vel, as JSON.
TWIST_ECHO = r"""
import json, sys, time
import rospy
from geometry_msgs.msg import Twist

rospy.init_node("twist_echo", disable_signals=True)
seen = []
rospy.Subscriber("cmd_vel", Twist, lambda m: seen.append((m.linear.x, m.angular.z)))
deadline = time.monotonic() + 20
while not seen and time.monotonic() < deadline:
    time.sleep(0.02)
if not seen:
    sys.exit("no Twist on cmd_vel within 20 s")
print(json.dumps({"linear": seen[0][0], "angular": seen[0][1]}), flush=True)
"""
