"""Helpers for the tests of `worldgen sim` and `worldgen run`: run worldgen as a child process with a private ROS
master port, run probe nodes with Debian's python, and find processes left behind."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import time
import uuid
from pathlib import Path

import pytest

from rosstubs import SYSTEM_PYTHON, free_port, need, need_module

REPO = Path(__file__).resolve().parent.parent
NODES = Path(__file__).resolve().parent / "rosnodes"
ROOM = REPO / "examples" / "enclosed_room.yaml"   # 5 m room, walls 0.15 m thick, burger at (0, 0, 0)
WALL_FACE = 2.5 - 0.075                          # the inner face of the walls around the origin
SCAN_X = -0.032                                   # base_scan in base_footprint (burger)


def need_ros() -> None:
    need("rosmaster")
    need_module("rospy", "nav_msgs.msg", "tf2_msgs.msg", "rosgraph_msgs.msg", "std_srvs.srv", "rosbag")


def ros_env(tmp: Path, port: int | None = None) -> dict[str, str]:
    """A child's environment: this worktree's worldgen, a master URI on a free port, ROS_HOME in ``tmp``."""
    port = port or free_port()
    env = {k: v for k, v in os.environ.items() if not k.startswith("ROS_")}
    env.update(PYTHONPATH=str(REPO), ROS_MASTER_URI=f"http://127.0.0.1:{port}", ROS_HOME=str(tmp / "ros_home"),
               ROS_LOG_DIR=str(tmp / "ros_home" / "log"), ROS_IP="127.0.0.1")
    return env


def worldgen(args: list[str], env: dict[str, str], **kwargs) -> subprocess.Popen:
    return subprocess.Popen([sys.executable, "-m", "worldgen", *args], env=env, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, **kwargs)


def wait_master(env: dict[str, str], proc: subprocess.Popen | None = None, timeout: float = 20) -> None:
    import xmlrpc.client

    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if proc is not None and proc.poll() is not None:
            raise AssertionError(f"worldgen exited: {proc.stderr.read()}")
        try:
            xmlrpc.client.ServerProxy(env["ROS_MASTER_URI"]).getSystemState("/tests")
            return
        except OSError:
            time.sleep(0.05)
    raise AssertionError("no master answered")


def probe(args: list[str], env: dict[str, str], timeout: float = 90) -> dict:
    proc = subprocess.run([SYSTEM_PYTHON, str(NODES / "probe.py"), *args], env=env, capture_output=True, text=True,
                          timeout=timeout)
    assert proc.returncode == 0, proc.stderr[-3000:]
    return json.loads(proc.stdout.strip().splitlines()[-1])


def leftovers(env: dict[str, str] | str) -> list[str]:
    """Processes still running with this test's ROS_MASTER_URI (or, given a string, that ``NAME=value``) in
    their environment (master, simulator, nodes), as "pid cmdline"."""
    marker = (env if isinstance(env, str) else f"ROS_MASTER_URI={env['ROS_MASTER_URI']}").encode()
    found = []
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit() or int(entry.name) == os.getpid():
            continue
        try:
            environ = (entry / "environ").read_bytes()
            cmdline = (entry / "cmdline").read_bytes().replace(b"\0", b" ").decode(errors="replace")
            state = (entry / "stat").read_text().split(") ", 1)[1].split()[0]
        except OSError:
            continue
        if (b"\0" + marker + b"\0") in (b"\0" + environ + b"\0") and state != "Z":
            found.append(f"{entry.name} {cmdline}")
    return found


def no_leftovers(env: dict[str, str] | str, wait: float = 5.0) -> None:
    deadline = time.monotonic() + wait
    while leftovers(env) and time.monotonic() < deadline:
        time.sleep(0.1)
    assert leftovers(env) == []


@pytest.fixture
def tag(monkeypatch, tmp_path) -> str:
    """A marker in the environment every process of the run inherits, to find any left behind."""
    need_ros()
    value = uuid.uuid4().hex
    monkeypatch.setenv("WORLDGEN_TEST_TAG", value)
    monkeypatch.setenv("ROS_HOME", str(tmp_path / "ros_home"))
    monkeypatch.delenv("ROS_MASTER_URI", raising=False)
    yield f"WORLDGEN_TEST_TAG={value}"
    no_leftovers(f"WORLDGEN_TEST_TAG={value}")
