"""`worldgen drive`'s runs with their path and, asked for (``record_scans``), the scans the controller saw: poses
and ranges checked against the room's geometry and the run's own distance figures."""

from __future__ import annotations

import dataclasses
import json
import math

import numpy as np
import pytest

from worldgen.sim.lidar import Scan, scan_row

from test_drive import ROOM   # the same 3 × 3 m room of four walls
FACE = 1.5 - 0.075    # the walls' inner faces
SCAN_X = -0.032       # base_scan in base_footprint (burger)
SPAWN = [-0.5, 0.0, 0.0]


def wall_distance(ox: float, oy: float, angle: float) -> float:
    """How far a ray from (ox, oy) at world ``angle`` goes before it meets the room's inner wall faces."""
    c, s = math.cos(angle), math.sin(angle)
    return min((math.copysign(FACE, c) - ox) / c if abs(c) > 1e-9 else math.inf,
               (math.copysign(FACE, s) - oy) / s if abs(s) > 1e-9 else math.inf)


def beams_ahead(lidar: dict, half_angle: float = math.radians(10)) -> list[int]:
    """The beams within ±``half_angle`` of straight ahead (what the front distance is the nearest of)."""
    return [i for i in range(lidar["count"])
            if abs(math.remainder(lidar["angle_min"] + i * lidar["angle_increment"], math.tau)) <= half_angle + 1e-9]


@pytest.fixture(scope="module")
def world(tmp_path_factory):
    path = tmp_path_factory.mktemp("drive_scans") / "room.world"
    path.write_text(ROOM)
    return path


def drive(world, **request):
    """``drive_one`` as ``worldgen drive`` calls it (the exercise in a child process), with ``request``'s changes."""
    from worldgen.check.drive_targets import drive_one
    from worldgen.sim.exercise import Exercise, Gains

    base = Exercise(spawn=tuple(SPAWN), gains=(Gains(kp=0.5),), target=0.5, duration=16.0, stop_band=0.02)
    return drive_one(world, "world", dataclasses.replace(base, **request), [], timeout=120.0)


@pytest.fixture(scope="module")
def recorded(world):
    return drive(world, record_scans=True)


def test_scan_row_is_compact_and_marks_no_hits():
    for no_hit in (math.inf, 0.0):
        scan = Scan(angle_min=0.0, angle_max=math.pi, angle_increment=math.pi / 2, range_min=0.12, range_max=3.5,
                    ranges=[1.2345, no_hit, 0.12, 3.5, 0.4996], true_ranges=[1.23, math.inf, 0.11, 3.49, 0.5],
                    hits=np.full((5, 3), np.nan), origin=(1.234567, -2.000049, 0.17, -3.14159265))
        row = scan_row(scan)
        assert row == [1.2346, -2.0, -3.1416, [1234, -1, 120, 3500, 500]]
        assert all(type(v) is int for v in row[3])
        assert json.dumps(row) == "[1.2346, -2.0, -3.1416, [1234, -1, 120, 3500, 500]]"


def test_stop_at_wall_series_has_the_path(recorded):
    run = recorded["runs"][0]
    s = run["series"]
    n = len(s["t"])
    assert n == 16 * 5 + 1 and len(s["x"]) == len(s["y"]) == len(s["yaw"]) == n
    assert s["x"][0] == pytest.approx(SPAWN[0], abs=0.01)
    assert all(b >= a - 1e-3 for a, b in zip(s["x"], s["x"][1:]))   # toward the wall, never back
    assert s["x"][-1] - s["x"][0] > 1.0
    assert max(abs(y) for y in s["y"]) < 0.05 and max(abs(yaw) for yaw in s["yaw"]) < 0.03
    # where the base frame ended says how far base_scan is from the wall: the run's final distance
    scan_x = s["x"][-1] + SCAN_X * math.cos(s["yaw"][-1])
    assert FACE - scan_x == pytest.approx(run["final_distance"], abs=0.005)
    assert run["final_distance"] == pytest.approx(0.5, abs=0.05) and run["ok"]
    # each sample's true front distance is that same geometry, all along
    for x, yaw, true in zip(s["x"], s["yaw"], s["true"]):
        assert FACE - (x + SCAN_X * math.cos(yaw)) == pytest.approx(true, abs=0.005)


def test_stop_at_wall_records_the_scans_the_controller_saw(recorded):
    run, lidar = recorded["runs"][0], recorded["lidar"]
    assert lidar == {"angle_min": 0.0, "angle_increment": pytest.approx(2 * math.pi / 359, rel=1e-3),
                     "range_min": 0.12, "range_max": 3.5, "count": 360}
    s = run["series"]
    ahead = beams_ahead(lidar)
    assert len(ahead) == 20
    assert len(s["scan"]) == len(s["t"]) and all(row is not None for row in s["scan"])   # 5 Hz: every step
    for row, x, y, yaw, measured in zip(s["scan"], s["x"], s["y"], s["yaw"], s["measured"]):
        ox, oy, oyaw, mm = row
        assert len(mm) == lidar["count"] and -1 not in mm   # a 3 m room: every beam hits
        assert (ox, oy) == pytest.approx((x + SCAN_X * math.cos(yaw), y + SCAN_X * math.sin(yaw)), abs=1e-3)
        assert oyaw == pytest.approx(yaw, abs=1e-3)
        # the controller's front distance is the nearest beam within ±10° of ahead, in the recorded ranges
        assert min(mm[i] for i in ahead) / 1000 == pytest.approx(measured, abs=1e-3)
    first, last = s["scan"][0][3], s["scan"][-1][3]
    assert first[0] / 1000 == pytest.approx(FACE - (SPAWN[0] + SCAN_X), abs=0.03)
    assert last[0] / 1000 == pytest.approx(run["final_distance"], abs=0.03)
    # every beam of the last scan: the walls around, as far as the room's geometry says
    ox, oy, oyaw = s["scan"][-1][:3]
    for i, r in enumerate(last):
        angle = oyaw + lidar["angle_min"] + i * lidar["angle_increment"]
        assert r / 1000 == pytest.approx(wall_distance(ox, oy, angle), abs=0.05), i


def test_recording_changes_nothing_else(world, recorded):
    plain = drive(world)
    assert "lidar" not in plain
    run, again = plain["runs"][0], recorded["runs"][0]
    assert "scan" not in run["series"] and {"x", "y", "yaw"} <= set(run["series"])
    assert {k: v for k, v in again["series"].items() if k != "scan"} == run["series"]
    assert again["final_distance"] == run["final_distance"]


def test_a_faster_control_loop_records_at_most_five_scans_a_second(world):
    result = drive(world, rate=30.0, duration=6.0, record_scans=True)
    s = result["runs"][0]["series"]
    assert len(s["scan"]) == len(s["t"]) == 6 * 30 + 1
    kept = [t for t, row in zip(s["t"], s["scan"]) if row is not None]
    assert len(kept) == 6 * 5 + 1 and s["scan"][-1] is not None and s["scan"][0] is not None
    assert all(b - a >= 0.2 - 1e-6 for a, b in zip(kept, kept[1:]))


def test_spin_records_scans_turning_with_the_robot(world):
    result = drive(world, behaviour="spin", spawn=(0.0, 0.0, 0.0), omega=1.5, duration=2.0, record_scans=True)
    s = result["runs"][0]["series"]
    assert result["lidar"]["count"] == 360 and len(s["scan"]) == len(s["t"])
    rows = [(yaw, row) for yaw, row in zip(s["yaw"], s["scan"]) if row is not None]
    assert len(rows) == pytest.approx(5 * 2.5, abs=1)   # 2 s turning and 0.5 s coming to rest, at 5 Hz
    for yaw, (ox, oy, oyaw, mm) in rows:
        assert math.remainder(oyaw - yaw, math.tau) == pytest.approx(0.0, abs=1e-3)
        assert math.hypot(ox, oy) == pytest.approx(-SCAN_X, abs=0.01)   # base_scan, turning about the origin
        assert mm[0] / 1000 == pytest.approx(wall_distance(ox, oy, oyaw), abs=0.03)
