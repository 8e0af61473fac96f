"""A teaching assistant runs the course's own lab package, handed in unchanged by two students, with the course's
world package beside them in the folder: the two labs are graded, the world package (which they depend on and which
holds no node for the task) is left out with one line saying so, a third student's copy without its package.xml is a
failed row of its own, and nothing is left running."""

from __future__ import annotations

import json
import shutil
import uuid

from conftest import CliRunner

from bridgetools import need_ros, no_leftovers
from worldgen.cli import main
from worldgen.packages.course_ros1 import write_course

WORLD_PACKAGE = "class_meeting_02_custom_gazebo_world"


def test_the_course_lab_handed_in_unchanged_is_graded_beside_its_world_package(tmp_path, monkeypatch):
    need_ros()
    tag = f"WORLDGEN_TEST_TAG={uuid.uuid4().hex}"
    monkeypatch.setenv(*tag.split("="))
    monkeypatch.setenv("ROS_HOME", str(tmp_path / "ros_home"))
    monkeypatch.delenv("ROS_PACKAGE_PATH", raising=False)
    course = write_course(tmp_path / "course")
    subs = tmp_path / "submissions"
    for student in ("alice", "bob", "eve"):
        shutil.copytree(course / "lab_a_stop_at_wall", subs / student / "lab_a_stop_at_wall")
    (subs / "eve" / "lab_a_stop_at_wall" / "package.xml").unlink()   # handed in without it: a row, not left out
    shutil.copytree(course / WORLD_PACKAGE, subs / WORLD_PACKAGE)
    result = CliRunner().invoke(main, ["run", str(subs), "--task", "stop-at-wall", "-j", "2", "--rate", "max",
                                       "--format", "json"])
    assert result.exit_code == 1, result.output
    doc = json.loads(result.stdout)
    assert [r["path"] for r in doc["results"]] == [str(subs / s / "lab_a_stop_at_wall") for s in ("alice", "bob")] \
        + [str(subs / "eve")]
    assert all(r["ok"] and r["findings"] == [] for r in doc["results"][:2])
    [eve] = doc["results"][2]["findings"]
    assert not doc["results"][2]["ok"] and eve["check"] == "package" and "no package.xml" in eve["message"]
    [line] = [x for x in result.stderr.splitlines() if WORLD_PACKAGE in x]
    assert line == (f"worldgen: {subs / WORLD_PACKAGE}: not graded: packages in the folder depend on it and it "
                    "holds no node for the task")
    no_leftovers(tag)
