"""The class runtime with real rospy nodes: a node importing a module that is not installed is a finding before
anything starts (no master, no simulator), named with its file, line and package; nodes using numpy,
tf.transformations and a stray tkinter import run and drive the robot as they should once the runtime is
installed; `worldgen doctor` reports on real submissions; `worldgen sim` warns about a launch file's nodes.

Real rosmaster and rospy (Debian's); missing ROS packages, or class-runtime modules, skip (fail under CI: .ci/run
installs the class runtime; see rosstubs).
"""

from __future__ import annotations

import json
import math
import subprocess
import time

import pytest

from conftest import CliRunner
from bridgetools import (NODES, ROOM, leftovers, need_ros, no_leftovers, ros_env, tag,  # noqa: F401 (tag: a fixture)
                         worldgen)
from rosstubs import SYSTEM_PYTHON, need_module
from worldgen.cli import main
from worldgen.runtime.table import provider

ABSENT_CANDIDATES = ("sklearn", "pandas", "serial", "pygame")   # in the table, not in the class runtime


def absent_module() -> str:
    """A module of the table that the nodes' Python lacks (skip when it has them all)."""
    code = ("import importlib.util; print(' '.join(m for m in %r if importlib.util.find_spec(m) is None))"
            % (ABSENT_CANDIDATES,))
    absent = subprocess.run([SYSTEM_PYTHON, "-c", code], capture_output=True, text=True, check=True).stdout.split()
    if not absent:
        pytest.skip(f"{SYSTEM_PYTHON} has every one of {ABSENT_CANDIDATES}")
    return absent[0]


def run(args: list[str]):
    result = CliRunner().invoke(main, ["run", *args])
    assert "Traceback" not in result.output, result.output
    return result


def student_node(folder, missing: str):
    """A stop-at-wall node whose line 5 imports ``missing``."""
    folder.mkdir(parents=True, exist_ok=True)
    node = folder / "stop_at_wall.py"
    node.write_text(f"#!/usr/bin/env python3\nimport rospy\nfrom geometry_msgs.msg import Twist\n"
                    f"from sensor_msgs.msg import LaserScan\nimport {missing}\n"
                    f"rospy.init_node('stopper')\nrospy.spin()\n")
    return node


@pytest.fixture
def nothing_may_start(monkeypatch):
    """Fails the test if a run gets as far as starting a master and the simulator."""
    import worldgen.ros1.transport as ros1

    def refuse(*args, **kwargs):
        raise AssertionError("run_nodes was called: a master and the simulator would have started")

    monkeypatch.setattr(ros1, "run_nodes", refuse)


def test_a_missing_module_is_a_finding_and_nothing_starts(tag, tmp_path, nothing_may_start):
    missing = absent_module()
    package = provider(missing).debian
    node = student_node(tmp_path / "ana", missing)
    junit = tmp_path / "report.xml"
    started = time.monotonic()
    result = run([str(ROOM), str(node), "--task", "stop-at-wall", "--rate", "max", "--format", "json",
                  "--junit", str(junit)])
    assert time.monotonic() - started < 15   # a run's own start-up (master, simulator) is not waited for
    assert result.exit_code == 1, result.output
    assert leftovers(tag) == []               # no rosmaster, no simulator, no node
    doc = json.loads(result.stdout)
    assert doc["ok"] is False and doc["metrics"] == {}
    assert doc["findings"] == [{
        "check": "runtime", "severity": "error", "where": f"{node}:5",
        "message": f"{missing} ({package}) is not installed for {SYSTEM_PYTHON}: stop_at_wall.py:5 imports it",
        "fix": f"apt install {package}"}]
    xml = junit.read_text()
    assert 'name="runtime"' in xml and 'type="runtime"' in xml and "<skipped" in xml
    text = run([str(ROOM), str(node), "--task", "stop-at-wall", "--rate", "max"])
    assert text.exit_code == 1
    assert text.stdout.splitlines()[0] == "stop_at_wall: not started, 1 problem(s) found before starting (nothing ran)"
    assert f"runtime: {node}:5: {missing} ({package}) is not installed" in text.stdout
    assert f"fix: apt install {package}" in text.stdout and text.stdout.endswith("stop-at-wall: FAIL\n")


def test_a_folder_of_submissions_checks_every_node_before_any_run(tag, tmp_path, nothing_may_start):
    missing = absent_module()
    subs = tmp_path / "submissions"
    for name in ("ana_lab", "bo_lab"):
        (subs / name).mkdir(parents=True)
        (subs / name / "package.xml").write_text(f"<package format='2'><name>{name}</name></package>")
    node = student_node(subs / "ana_lab" / "scripts", missing)
    (subs / "bo_lab" / "scripts").mkdir()
    (subs / "bo_lab" / "scripts" / "stop_at_wall.py").write_text('import rospy\nprint "stopping"\n')
    result = run([str(subs), "--task", "stop-at-wall", "-j", "2", "--format", "json"])
    assert result.exit_code == 1, result.output
    by_name = {r["path"].rsplit("/", 1)[-1]: r for r in json.loads(result.stdout)["results"]}
    [ana] = by_name["ana_lab"]["findings"]
    assert ana["check"] == "runtime" and ana["where"] == f"{node}:5" and missing in ana["message"]
    assert by_name["ana_lab"]["metrics"]["node"] == "scripts/stop_at_wall.py"
    [bo] = by_name["bo_lab"]["findings"]
    assert bo["check"] == "runtime" and bo["where"].endswith("bo_lab/scripts/stop_at_wall.py:2")
    assert "does not parse as Python 3" in bo["message"]


def test_a_numpy_node_stops_at_the_wall(tag):
    need_module("numpy")
    result = run([str(ROOM), str(NODES / "stop_at_wall_numpy.py"), "--task", "stop-at-wall", "--rate", "max",
                  "--format", "json"])
    assert result.exit_code == 0, result.output
    doc = json.loads(result.stdout)
    assert doc["findings"] == []
    assert doc["metrics"]["final_front_distance_m"] == pytest.approx(0.5, abs=0.1)   # the rubric's tolerance
    assert doc["metrics"]["contacts"] == []


def test_a_tf_transformations_node_turns_90_degrees_by_odometry(tag):
    need_module("tf.transformations")
    # at a fixed pace: at --rate max the odometry callbacks fall behind and it turns past 90° (1 run of 2)
    result = run([str(ROOM), str(NODES / "turn_90_tf.py"), "--rate", "2", "--duration", "8", "--format", "json"])
    assert result.exit_code == 0, result.output
    m = json.loads(result.stdout)["metrics"]
    assert m["rotation_rad"] == pytest.approx(math.pi / 2, abs=0.05)
    assert m["final_pose"][2] == pytest.approx(math.pi / 2, abs=0.05) and m["path_length_m"] < 0.05


def test_a_stray_tkinter_import_runs(tag):
    need_module("tkinter")
    result = run([str(ROOM), str(NODES / "spin_with_tkinter.py"), "--rate", "max", "--duration", "2",
                  "--format", "json"])
    assert result.exit_code == 0, result.output
    doc = json.loads(result.stdout)
    assert doc["findings"] == [] and doc["metrics"]["rotation_rad"] > 1.0


def test_doctor_on_real_submissions(tmp_path, monkeypatch):
    need_ros()
    for module in ("numpy", "tf.transformations"):
        need_module(module)
    missing = absent_module()
    subs = tmp_path / "submissions"
    for name, node in (("ana_lab", NODES / "stop_at_wall_numpy.py"), ("bo_lab", NODES / "turn_90_tf.py")):
        (subs / name / "scripts").mkdir(parents=True)
        (subs / name / "package.xml").write_text(f"<package format='2'><name>{name}</name></package>")
        (subs / name / "scripts" / node.name).write_text(node.read_text())
    student_node(subs / "cy_lab" / "scripts", missing)
    monkeypatch.chdir(tmp_path)
    monkeypatch.delenv("WORLDGEN_ROS_PYTHON", raising=False)
    result = CliRunner().invoke(main, ["doctor", "submissions"])
    assert result.exit_code == 1, result.output
    lines = result.stdout.splitlines()
    assert lines[0].startswith(f"worldgen doctor: 3 node file(s), for {SYSTEM_PYTHON} (Python 3.")
    rows = {ln.split()[0]: ln.split() for ln in lines[2:-1]}
    assert rows["numpy"][-1] == rows["tf"][-1] == rows["rospy"][-1] == "ok"
    assert rows["rospy"][1:5] == ["submissions/ana_lab/scripts/stop_at_wall_numpy.py:5", "and", "2", "more"]
    assert rows[missing][1] == "submissions/cy_lab/scripts/stop_at_wall.py:5" and rows[missing][-1] == "MISSING"
    assert lines[-1] == f"sudo apt-get install {provider(missing).debian}"
    fine = CliRunner().invoke(main, ["doctor", "submissions/ana_lab", "submissions/bo_lab"])
    assert fine.exit_code == 0 and fine.stdout.endswith("nothing to install: every module is found\n")


def test_sim_warns_about_a_launch_files_nodes_and_starts_anyway(tmp_path):
    need_ros()
    missing = absent_module()
    package = tmp_path / "ws" / "src" / "lab_pkg"
    (package / "launch").mkdir(parents=True)
    (package / "package.xml").write_text("<package format='2'><name>lab_pkg</name></package>")
    node = student_node(package / "scripts", missing)
    node.chmod(0o755)
    launch = package / "launch" / "lab.launch"
    launch.write_text('<launch>\n  <node pkg="lab_pkg" type="stop_at_wall.py" name="stopper"/>\n</launch>\n')
    env = ros_env(tmp_path)
    proc = worldgen(["sim", str(ROOM), "--launch", str(launch), "--rate", "max", "--duration", "1"], env)
    out, err = proc.communicate(timeout=120)
    assert proc.returncode == 0, err
    assert f"worldgen sim: warning: {node}:5: {missing} ({provider(missing).debian}) is not installed" in err
    warning = err.index("worldgen sim: warning:")
    assert err.index("worldgen sim: started a ROS master") > warning   # warned before starting, then started
    no_leftovers(env)
