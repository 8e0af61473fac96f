"""`worldgen run` recording every published scan for a replay (RunOptions.record_scans): the trace's ``lidar`` and
``ranges`` rows hold the sensor's pose and the ranges the student's node was sent, checked against the room's
geometry; without the option the trace has neither.

Real rosmaster and rospy (Debian's), a node that stands still; missing ROS packages skip (see rosstubs).
"""

from __future__ import annotations

import json
import math

import pytest

from bridgetools import NODES, ROOM, SCAN_X, WALL_FACE, tag  # noqa: F401 (a fixture)

SPAWN = (1.0, 0.5, math.pi / 2)   # facing the +y wall of the 5 m room, off-centre so x, y and yaw all matter


def run_still(duration: float, no_hit: str = "inf", record_scans: bool = False):
    """A run of the stand-still node in the enclosed room from :data:`SPAWN` at rate max."""
    from worldgen.ros1.nodes import resolve_nodes
    from worldgen.ros1.rosenv import node_python
    from worldgen.bridge.outcome import RunOptions
    from worldgen.ros1.run import run_nodes
    from worldgen.bridge.world import load_world

    world = load_world(ROOM, spawn=SPAWN)
    nodes = resolve_nodes([str(NODES / "stand_still.py")], node_python())
    return run_nodes(world, nodes, RunOptions(duration=duration, rate=0.0, no_hit=no_hit, record_scans=record_scans))


def room_distance(ox: float, oy: float, angle: float) -> float:
    """How far a ray from (ox, oy) at world ``angle`` goes before it meets the room's inner wall faces."""
    c, s = math.cos(angle), math.sin(angle)
    reach = [(math.copysign(WALL_FACE, c) - ox) / c if abs(c) > 1e-9 else math.inf,
             (math.copysign(WALL_FACE, s) - oy) / s if abs(s) > 1e-9 else math.inf]
    return min(reach)


def test_recorded_scans_are_what_the_node_was_sent(tag):
    outcome = run_still(3.0, no_hit="zero", record_scans=True)
    trace = outcome.trace
    lidar, rows = trace["lidar"], trace["ranges"]
    assert lidar == {"angle_min": 0.0, "angle_increment": pytest.approx(2 * math.pi / 359, rel=1e-3),
                     "range_min": 0.12, "range_max": 3.5, "count": 360}
    # the LiDAR's 5 Hz: a row every 0.2 s of simulated time from the first scan at 0.2 s
    times = [row[0] for row in rows]
    assert times[0] == pytest.approx(0.2, abs=1e-3) and len(rows) == pytest.approx(15, abs=1)
    assert all(b - a == pytest.approx(0.2, abs=2e-3) for a, b in zip(times, times[1:]))
    assert all(len(row) == 5 and len(row[4]) == lidar["count"] for row in rows)
    assert all(type(r) is int for row in rows for r in row[4])
    assert rows == trace["robots"][0]["ranges"] and lidar == trace["robots"][0]["lidar"]

    t, ox, oy, yaw, mm = rows[0]
    # the sensor sits SCAN_X along the robot's heading from its base frame, at the spawn pose
    assert math.hypot(ox - SPAWN[0], oy - SPAWN[1]) < 0.05
    assert (ox, oy) == pytest.approx((SPAWN[0] + SCAN_X * math.cos(SPAWN[2]), SPAWN[1] + SCAN_X * math.sin(SPAWN[2])),
                                     abs=0.005)
    assert yaw == pytest.approx(SPAWN[2], abs=0.01)
    odom = next(r for r in trace["odom"] if abs(r[0] - t) < 1e-6)   # the pose published with this scan
    assert (ox, oy) == pytest.approx((odom[1] + SCAN_X * math.cos(odom[3]), odom[2] + SCAN_X * math.sin(odom[3])),
                                     abs=1e-3)
    # beam 0 points along the robot's heading, at the +y wall
    assert mm[0] / 1000 == pytest.approx(WALL_FACE - oy, abs=0.03)
    assert WALL_FACE - oy == pytest.approx(WALL_FACE - SPAWN[1] - SCAN_X, abs=0.005)
    # every beam: the room's wall at noise's distance, or -1 beyond range (published as 0 with --lidar-no-hit zero)
    misses = 0
    for i, r in enumerate(mm):
        expected = room_distance(ox, oy, yaw + lidar["angle_min"] + i * lidar["angle_increment"])
        if abs(expected - lidar["range_max"]) < 0.05:
            continue   # at the edge of the range: either may be
        if expected > lidar["range_max"]:
            assert r == -1, (i, expected, r)
            misses += 1
        else:
            assert r / 1000 == pytest.approx(expected, abs=0.05), (i, expected, r)
    assert misses > 20   # the far corners are out of range from here
    # the published ranges had noise: the rows differ from scan to scan where the robot stands still
    assert rows[0][4] != rows[1][4]
    assert len(json.dumps(rows[0])) < 2500   # compact: whole millimetres


def test_without_the_option_the_trace_has_no_scans(tag):
    trace = run_still(1.0).trace
    for part in (trace, trace["robots"][0]):
        assert "ranges" not in part and "lidar" not in part
    assert len(trace["scans"]) == pytest.approx(5, abs=1)
