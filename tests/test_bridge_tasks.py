"""`worldgen run --task`: each exercise's rubric passes a node written the way students write it, and fails a
deliberately wrong one with a finding that says what went wrong. Real rosmaster and rospy; --rate max."""

from __future__ import annotations

import json

import pytest
from conftest import CliRunner

from bridgetools import NODES, ROOM, need_ros
from worldgen.cli import main


def graded(task: str, node: str, duration: float, *extra: str, rate: str = "max") -> dict:
    need_ros()
    result = CliRunner().invoke(main, ["run", str(ROOM), str(NODES / node), *extra, "--task", task, "--rate", rate,
                                       "--duration", str(duration), "--format", "json"])
    assert "Traceback" not in result.output and result.exit_code in (0, 1), result.output
    doc = json.loads(result.stdout)
    assert doc["task"] == task and (result.exit_code == 0) == doc["ok"]
    return doc


def errors(doc: dict, check: str) -> list[str]:
    return [f["message"] for f in doc["findings"] if f["check"] == check and f["severity"] == "error"]


@pytest.mark.parametrize("task, node, duration, extra, rate", [
    ("spin", "spin_rate_loop.py", 14, (), "max"),
    # an /odom square paced by rospy.Rate turns by what it reads between loop turns: at --rate max a busy machine
    # lets simulated time run past its corners, so it is graded at a fixed multiple of real time, as a TA would
    ("drive-square", "square_odom.py", 38, ("_side:=0.6",), "4"),
    ("wall-follow", "wall_follower.py", 60, (), "max"),
    ("person-follow", "person_follower.py", 30, (), "max"),
])
def test_a_students_node_passes(task, node, duration, extra, rate):
    doc = graded(task, node, duration, *extra, rate=rate)
    assert doc["ok"], doc["findings"]


@pytest.mark.parametrize("task, node, duration, says", [
    ("stop-at-wall", "drive_into_wall.py", 13, "touched enclosed_room/Wall_1"),
    ("spin", "spin_briefly.py", 8, "full turns; 2 are needed"),
    ("drive-square", "spin_rate_loop.py", 10, "found 0 straight sides; a square has 4"),
    ("wall-follow", "spin_rate_loop.py", 10, "never came within 0.55 m of a wall"),
    ("person-follow", "stand_still.py", 20, "m from the person in"),
])
def test_a_wrong_node_fails_with_a_clear_finding(task, node, duration, says):
    doc = graded(task, node, duration)
    assert not doc["ok"]
    assert any(says in m for m in errors(doc, task)), doc["findings"]
