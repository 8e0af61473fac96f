"""A teaching assistant grades a folder of submissions: each package's node runs in its own master (two at once
here), one result per submission, JUnit and JSON as `validate` writes them, and nothing left running."""

from __future__ import annotations

import json
import os
import shutil
import signal
import subprocess
import sys
import time
import uuid

import pytest

from conftest import CliRunner

from bridgetools import NODES, REPO, leftovers, need_ros, no_leftovers, tag  # noqa: F401 (tag: a fixture)
from worldgen.cli import main
from worldgen.packages.course_ros1 import write_course


def test_a_folder_of_submissions_is_graded(tmp_path, monkeypatch):
    need_ros()
    tag = f"WORLDGEN_TEST_TAG={uuid.uuid4().hex}"
    monkeypatch.setenv(*tag.split("="))
    monkeypatch.setenv("ROS_HOME", str(tmp_path / "ros_home"))
    course = write_course(tmp_path / "course")
    subs = tmp_path / "submissions"
    runner = CliRunner()
    for name in ("alice", "bob", "carol", "dave"):
        result = runner.invoke(main, ["scaffold", f"{name}_lab", "rospy", "geometry_msgs", "sensor_msgs", "-p",
                                      str(subs)])
        assert result.exit_code == 0, result.output
    shutil.copy(course / "lab_a_stop_at_wall" / "scripts" / "stop_at_wall.py", subs / "alice_lab" / "scripts")
    shutil.copy(NODES / "drive_into_wall.py", subs / "bob_lab" / "scripts" / "stop_at_wall.py")
    shutil.copy(NODES / "crash_on_import.py", subs / "carol_lab" / "scripts" / "stop_at_wall.py")
    grades = tmp_path / "grades.xml"
    monkeypatch.chdir(tmp_path)
    result = runner.invoke(main, ["run", "submissions/", "--task", "stop-at-wall", "-j", "2", "--junit", str(grades),
                                  "--rate", "max", "--format", "json"])
    assert result.exit_code == 1, result.output
    assert "Traceback" not in result.output
    doc = json.loads(result.stdout)
    by_name = {r["path"].rstrip("/").rsplit("/", 1)[-1]: r for r in doc["results"]}
    assert sorted(by_name) == ["alice_lab", "bob_lab", "carol_lab", "dave_lab"]
    assert by_name["alice_lab"]["ok"] and by_name["alice_lab"]["metrics"]["node"] == "scripts/stop_at_wall.py"
    assert by_name["alice_lab"]["metrics"]["final_front_distance_m"] == pytest.approx(0.5, abs=0.1)
    messages = {name: " | ".join(f["message"] for f in r["findings"]) for name, r in by_name.items()}
    assert "touched enclosed_room/Wall_1" in messages["bob_lab"]
    assert "cannot import name 'Twistt'" in messages["carol_lab"]
    assert "cannot tell which node to run" in messages["dave_lab"]
    junit = grades.read_text()
    assert junit.count("<testcase") == 8 and 'failures="4"' in junit and 'name="worldgen run"' in junit
    no_leftovers(tag)


def test_shards_of_a_class_cover_every_submission_once(tmp_path, monkeypatch):
    """--shard K/N on a folder: the N shards' results are disjoint and together one per submission (these
    submissions hold no node, so each fails at once without a simulation)."""
    need_ros()
    monkeypatch.setenv("ROS_HOME", str(tmp_path / "ros_home"))
    runner = CliRunner()
    names = [f"s{i}_lab" for i in range(5)]
    for name in names:
        assert runner.invoke(main, ["scaffold", name, "rospy", "-p", str(tmp_path / "subs")]).exit_code == 0
    seen = []
    for k in (1, 2):
        result = runner.invoke(main, ["run", str(tmp_path / "subs"), "--task", "stop-at-wall", "--shard", f"{k}/2",
                                      "--format", "json"])
        assert result.exit_code == 1 and "Traceback" not in result.output, result.output
        seen.append({r["path"].rstrip("/").rsplit("/", 1)[-1] for r in json.loads(result.stdout)["results"]})
    assert not seen[0] & seen[1] and seen[0] | seen[1] == set(names) and len(seen[0]) == 3
    bad = runner.invoke(main, ["run", str(tmp_path / "subs"), "--shard", "3/2"])
    assert bad.exit_code == 2 and bad.stderr.startswith("worldgen: error: bad --shard value '3/2'")


@pytest.mark.parametrize("files, task, said", [
    ((), "stop-at-wall", "no stop_at_wall.py, and 0 Python files"),
    (("a.py", "b.py"), "spin", "no spin_in_circles.py, and 2 Python files"),
    (("a.py", "b.py"), None, "2 Python files and no --task to pick one by"),
    ((), None, "no Python file"),
])
def test_a_submission_whose_node_cannot_be_told_says_what_it_holds(tmp_path, files, task, said):
    from worldgen.bridge.grade import node_of
    from worldgen.core.errors import InputError

    for name in files:
        (tmp_path / name).write_text("print('hi')\n")
    with pytest.raises(InputError) as err:
        node_of(tmp_path, task, [])
    assert err.value.message == f"cannot tell which node to run: {said}"


def test_a_folders_table_names_where_each_error_is_within_the_submission():
    """A node that does not parse: its row says the file and line, relative to the submission (the JSON has the
    whole path); a finding about the submission as a whole adds nothing after its message."""
    from worldgen.bridge.report import folder_text
    from worldgen.check.report import Result
    from worldgen.core.findings import Finding

    alice = Result(path="/class/alice", findings=[Finding("runtime", "error", "stop_at_wall.py does not parse",
                                                          where="/class/alice/scripts/stop_at_wall.py:2")])
    dave = Result(path="/class/dave", findings=[Finding("node", "error", "cannot tell which node to run",
                                                        where="/class/dave")])
    lines = folder_text([alice, dave]).splitlines()
    assert "    runtime: stop_at_wall.py does not parse (scripts/stop_at_wall.py:2)" in lines
    assert "    node: cannot tell which node to run" in lines


def test_ctrl_c_while_a_folder_is_graded_stops_at_once(tag, tmp_path):
    """Ctrl-C (SIGINT to the foreground group, as a terminal sends it) once the first runs' masters are up: every
    run gives up at once, click's "Aborted!" and exit 1 within seconds (a run waiting for its ended nodes took
    15 s, and a supervisor closed beside the interrupt was reported as worldgen's own error), nothing left."""
    course = write_course(tmp_path / "course")
    subs = tmp_path / "class"
    for name in ("ann", "bob", "cat", "dan"):
        shutil.copytree(course / "lab_a_stop_at_wall", subs / f"{name}_lab")
        manifest = subs / f"{name}_lab" / "package.xml"
        manifest.write_text(manifest.read_text().replace("<name>lab_a_stop_at_wall<", f"<name>{name}_lab<"))
    proc = subprocess.Popen([sys.executable, "-m", "worldgen", "run", str(subs), "--task", "stop-at-wall", "-j", "2"],
                            env=dict(os.environ, PYTHONPATH=str(REPO)), stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, start_new_session=True)
    deadline = time.monotonic() + 60
    while not any("rosmaster" in p for p in leftovers(tag)) and time.monotonic() < deadline and proc.poll() is None:
        time.sleep(0.02)
    assert any("rosmaster" in p for p in leftovers(tag)), proc.communicate()
    os.killpg(proc.pid, signal.SIGINT)
    started = time.monotonic()
    out, err = proc.communicate(timeout=60)
    assert (proc.returncode, out, err.strip()) == (1, "", "Aborted!")
    assert time.monotonic() - started < 5.0
