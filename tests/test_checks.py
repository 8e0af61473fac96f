"""The checks as functions: robot outline, enclosed, spawn-clear, and how simulated numbers are judged."""

from __future__ import annotations

import math

import pytest

from test_enclosure import square_room, wall
from worldgen.check.checks import (check_enclosed, check_parse, check_spawn_clear, floor_under, robot_body,
                             sim_findings)
from worldgen.check.sim_results import SimNumbers
from worldgen.core.findings import Finding
from worldgen.core.scene import Scene, Shape

BURGER = robot_body("burger")
WAFFLE = robot_body("waffle")


def errors(outcome, check=None):
    return [f for f in outcome.findings if f.severity == "error" and (check is None or f.check == check)]


def test_robot_outlines_come_from_our_urdf():
    assert BURGER.width == pytest.approx(0.178, abs=1e-3)
    assert WAFFLE.width == pytest.approx(0.306, abs=1e-3)
    assert BURGER.lidar_height == pytest.approx(0.182)
    assert WAFFLE.lidar_height == pytest.approx(0.132)
    # burger: base box x -0.102 … 0.038 → the farthest corner (-0.102, ±0.07) sweeps ≈ 0.124 m when turning
    assert BURGER.turn_radius == pytest.approx(math.hypot(0.102, 0.07), abs=2e-3)
    assert BURGER.height == pytest.approx(0.191, abs=2e-3)


def test_enclosed_room_passes_with_its_area():
    out = check_enclosed(square_room(), (0.0, 0.0, 0.0), BURGER)
    assert out.findings == []
    assert out.metrics["enclosed"] is True
    assert out.metrics["enclosed_area_m2"] == pytest.approx(4.85 ** 2, rel=3e-3)


def test_gap_finding_says_where_how_wide_and_whether_the_robot_fits():
    out = check_enclosed(square_room(door=(0, 3.0, 0.5)), (0.0, 0.0, 0.0), BURGER)
    [finding] = errors(out, "enclosed")
    assert "0.50 m gap at (0.75, -2.5" in finding.message
    assert "can drive out" in finding.message
    assert out.metrics["enclosed"] is False and out.metrics["robot_enclosed"] is False
    [gap] = out.metrics["gaps"]
    assert gap["centre"] == pytest.approx([0.75, -2.5], abs=1e-3) and gap["width"] == pytest.approx(0.5, abs=0.01)
    assert gap["robot_passes"] is True
    # 0.25 m: the burger (0.178 m) drives out, the waffle (0.306 m) does not, but its beams still leave
    assert errors(check_enclosed(square_room(door=(0, 3.0, 0.25)), (0.0, 0.0, 0.0), BURGER))
    narrow = check_enclosed(square_room(door=(0, 3.0, 0.25)), (0.0, 0.0, 0.0), WAFFLE)
    [warning] = narrow.findings
    assert warning.severity == "warning" and "the waffle cannot pass (too narrow)" in warning.message
    assert narrow.metrics["enclosed"] is False and narrow.metrics["robot_enclosed"] is True


def test_low_window_leaks_beams_but_holds_the_robot():
    # wall 0 open between x = -1 and 1 from 0.1 m to 0.4 m: a sill under the beams, a lintel above
    shapes = [s for s in square_room().shapes if s.link != "Wall_0"]
    shapes += [wall((-2.5, -2.5), (-1.0, -2.5), "Wall_0_0"), wall((1.0, -2.5), (2.5, -2.5), "Wall_0_1"),
               wall((-1.0, -2.5), (1.0, -2.5), "Wall_0_2", z1=0.1), wall((-1.0, -2.5), (1.0, -2.5), "Wall_0_3",
                                                                      z0=0.4)]
    out = check_enclosed(Scene(None, shapes=shapes), (0.0, 0.0, 0.0), BURGER)
    [warning] = out.findings
    assert warning.severity == "warning" and "LiDAR beams leave the room through a 2.00 m opening" in warning.message
    assert "something below or above the beams blocks it" in warning.message
    assert out.metrics["enclosed"] is False and out.metrics["robot_enclosed"] is True


def test_no_walls_and_outside_the_room_are_told_apart():
    empty = check_enclosed(Scene(None, shapes=[]), (0.0, 0.0, 0.0), BURGER)
    assert "no walls around the spawn" in errors(empty)[0].message
    room = square_room(centre=(-5.0, -1.0))
    outside = check_enclosed(room, (0.0, 0.0, 0.0), BURGER)
    message = errors(outside)[0].message
    assert "outside the walls" in message
    x0, y0, x1, y1 = outside.metrics["nearest_room"]
    assert (x0, x1) == pytest.approx((-7.425, -2.575), abs=0.002) and (y0, y1) == pytest.approx((-3.425, 1.425),
                                                                                               abs=0.002)


def test_a_far_away_spawn_is_told_in_readable_numbers():
    [far] = errors(check_enclosed(square_room(), (1e308, -2.5, 0.0), BURGER))
    assert far.where == "spawn (1e+308, -2.50)" and "the spawn (1e+308, -2.50) is outside the walls" in far.message
    x0, y0, x1, y1 = check_enclosed(square_room(), (1e9, 0.0, 0.0), BURGER).metrics["nearest_room"]
    assert (x0, y0, x1, y1) == pytest.approx((-2.425, -2.425, 2.425, 2.425), abs=0.002)


def test_spawn_inside_a_wall_fails_both_geometric_checks():
    room = square_room()
    inside = check_enclosed(room, (2.5, 1.0, 0.0), BURGER)
    assert "is inside room/Wall_1" in errors(inside)[0].message
    assert inside.metrics["spawn_inside"] == "room/Wall_1"
    clear = check_spawn_clear(room, (2.5, 1.0, 0.0), BURGER)
    assert "spawns inside room/Wall_1" in errors(clear)[0].message
    assert clear.metrics["min_clearance_m"] == 0.0


def test_clearance_is_measured_from_the_robot_outline():
    room = square_room()   # inner face of the right wall at x = 2.425
    out = check_spawn_clear(room, (2.0, 0.0, 0.0), BURGER)   # the burger's front edge is at x + 0.038
    assert out.findings == []
    assert out.metrics["min_clearance_m"] == pytest.approx(2.425 - 2.038, abs=1e-3)
    assert out.metrics["nearest_obstacle"] == "room/Wall_1"
    facing_away = check_spawn_clear(room, (2.0, 0.0, math.pi), BURGER)   # now its back (0.102) faces the wall
    assert facing_away.metrics["min_clearance_m"] == pytest.approx(2.425 - 2.102, abs=1e-3)


def test_too_close_to_turn_is_a_warning():
    # front edge 2 cm from the wall, but the rear corners sweep 0.124 m round the centre
    out = check_spawn_clear(square_room(), (2.425 - 0.058, 0.0, 0.0), BURGER)
    [finding] = out.findings
    assert finding.severity == "warning" and "too close for it to turn in place" in finding.message
    assert out.metrics["turn_clearance_m"] < 0


def test_obstacles_under_the_climbing_threshold_or_above_the_robot_do_not_count():
    sill = Shape("box", (0.0, 0.0, 0.004), size=(1.0, 1.0, 0.008), model="mat")
    shelf = Shape("box", (0.0, 0.0, 1.0), size=(1.0, 1.0, 0.1), model="shelf")
    low_box = Shape("box", (0.3, 0.0, 0.05), size=(0.2, 0.2, 0.1), model="crate")
    assert check_spawn_clear(square_room(extra=[sill, shelf]), (0.0, 0.0, 0.0), BURGER).findings == []
    hit = check_spawn_clear(square_room(extra=[low_box]), (0.2, 0.0, 0.0), BURGER)
    assert "spawns inside crate" in errors(hit)[0].message
    # the LiDAR plane (0.182 m) passes over the crate, so the room stays closed and the crate is no wall
    assert check_enclosed(square_room(extra=[low_box]), (0.2, 0.0, 0.0), BURGER).metrics["enclosed"] is True


def test_floor_slab_lifts_the_robot_and_the_slice():
    # Gazebo's asphalt_plane: a 20 x 20 x 0.1 box centred on z = 0, so its top is at 0.05
    slab = Shape("box", (0.0, 0.0, 0.0), size=(20.0, 20.0, 0.1), model="asphalt_plane")
    scene = square_room(extra=[slab])
    ground, metrics = floor_under(scene, (0.0, 0.0, 0.0))
    assert ground == pytest.approx(0.05) and metrics["floor"] == "asphalt_plane"
    assert check_spawn_clear(scene, (0.0, 0.0, 0.0), BURGER, ground).findings == []
    enclosed = check_enclosed(scene, (0.0, 0.0, 0.0), BURGER, ground)
    assert enclosed.metrics["enclosed"] is True
    assert enclosed.metrics["slice_height_m"] == pytest.approx(0.232)
    platform = Shape("box", (0.0, 0.0, 0.09), size=(2.0, 2.0, 0.18), model="platform")   # too high to be floor
    assert floor_under(Scene(None, shapes=[platform]), (0.0, 0.0, 0.0))[0] == 0.0


def test_parse_carries_the_reader_findings():
    note = Finding("include", "warning", "cannot find included model model://x")
    scene = Scene(None, sdf_version="1.6", shapes=[wall((0, 0), (1, 0), "Wall_0")], findings=[note])
    out = check_parse(scene)
    assert out.findings == [note]
    assert out.metrics["sdf_version"] == "1.6" and out.metrics["shape_kinds"] == {"box": 1}


# ------------------------------------------------------------------------------------------ simulated numbers

def numbers(**parts) -> SimNumbers:
    """The child's answer (as JSON gives it) with ``parts`` changed, parsed into the record the checks judge."""
    base = {
        "ran": ["settle", "lidar", "spin", "stop-at-wall"], "failed": {},
        "settle": {"time": 1.0, "z": 0.0, "moved": 0.0, "tilt_deg": 0.3, "contact_points": []},
        "lidar": {"beams": 360, "no_hit": 0, "range_max": 3.5, "no_hit_reading": None, "no_hit_bearings_deg": [],
                  "nearest": 1.2, "nearest_bearing_deg": 90.0, "farthest": 3.1},
        "spin": {"drift": 0.01, "turned": 6.28, "touched": [], "contact_points": []},
        "stop": {"distance": 0.51, "touched": [], "time": 12.0, "heading_deg": 0.0},
    }
    for key, value in parts.items():
        base[key] = {**base[key], **value} if isinstance(value, dict) else value
    return SimNumbers.from_dict(base)


def test_good_numbers_give_no_findings_and_the_metrics():
    out = sim_findings(numbers(), "inf")
    assert out.findings == []
    assert out.metrics["lidar_no_hit_beams"] == 0 and out.metrics["spin_drift_m"] == 0.01
    assert out.metrics["stop_distance_m"] == 0.51 and out.metrics["lidar_nearest_bearing_deg"] == 90.0


def test_no_hit_beams_say_once_what_they_mean_for_code_and_warn_only_when_it_matters():
    # a few far corners out of range (any room over 3.5 m): one info line, no warning
    corners = {"no_hit": 22, "no_hit_bearings_deg": [32.0], "no_hit_reading": math.inf, "front_no_hit": False}
    [note] = sim_findings(numbers(lidar=corners), "inf").findings
    assert note.message == ("22 of 360 beams see nothing within 3.5 m and read inf: only the farthest parts of the "
                            "room are out of range") and note.severity == "info"
    # nothing straight ahead, where a stop-at-wall node looks first: a warning
    ahead = {**corners, "front_no_hit": True}
    [gazebo] = sim_findings(numbers(lidar=ahead), "inf").findings
    assert gazebo.severity == "warning" and "(straight ahead too)" in gazebo.message
    assert "inf in Gazebo but 0 on the real robot" in gazebo.message and "code must treat both" in gazebo.message
    [robot] = sim_findings(numbers(lidar={**ahead, "no_hit_reading": 0.0}), "zero").findings
    assert "read 0" in robot.message and robot.severity == "warning"
    # most beams blind: a warning, said once
    [blind] = sim_findings(numbers(lidar={"no_hit": 360}), "inf").findings
    assert blind.severity == "warning" and "all 360 beams see nothing" in blind.message
    assert blind.message.count("Gazebo") == 1
    assert sim_findings(numbers(lidar={"no_hit": 0}), "inf").findings == []


def test_spin_and_stop_failures_are_errors_naming_what_was_touched():
    touched = sim_findings(numbers(spin={"touched": ["room/Wall_1"], "contact_points": [
        {"shape": "room/Wall_1", "link": "base_link", "time": 0.4}]}), "inf")
    [f] = errors(touched, "spin")
    assert "touched room/Wall_1" in f.message and "base_link touched room/Wall_1" in f.where
    drift = sim_findings(numbers(spin={"drift": 0.08}), "inf")
    assert "drifted 8.0 cm" in errors(drift, "spin")[0].message
    bump = sim_findings(numbers(stop={"touched": ["crate"]}), "inf")
    assert "touched crate" in errors(bump, "stop-at-wall")[0].message
    short = sim_findings(numbers(stop={"distance": 0.7}), "inf")
    assert short.findings[0].severity == "warning" and "ended 0.70 m from the wall" in short.findings[0].message
    [lost] = sim_findings(numbers(stop={"distance": None}), "inf").findings
    assert lost.severity == "warning" and "ended with no wall in range ahead instead of 0.5 m" in lost.message
    nothing = sim_findings(numbers(stop={"no_wall": True, "distance": None, "range": 3.5}), "inf")
    assert nothing.findings[0].severity == "info" and "no wall within 3.5 m" in nothing.findings[0].message


def test_settle_failures():
    tipped = sim_findings(numbers(settle={"tilt_deg": 40.0}), "inf")
    assert "tipped 40°" in errors(tipped, "settle")[0].message
    fell = sim_findings(numbers(settle={"z": -0.5}), "inf")
    assert "fell through" in errors(fell, "settle")[0].message
    on_slab = sim_findings(numbers(settle={"z": 0.05}), "inf", ground=0.05)
    assert errors(on_slab) == []


def test_standing_on_a_floor_slab_is_not_touching():
    slab = "asphalt_plane/link/collision"
    rolled = numbers(spin={"touched": [slab], "contact_points": [{"shape": slab, "link": "wheel_left_link",
                                                                  "time": 0.0}]},
                     stop={"touched": [slab]}, settle={"z": 0.05})
    assert errors(sim_findings(rolled, "inf", ground=0.05, floor=slab)) == []
    assert {f.check for f in errors(sim_findings(rolled, "inf"))} == {"spin", "stop-at-wall", "settle"}


def test_the_childs_numbers_cross_as_json_and_parse_into_the_same_record():
    """What the simulator child sends (``to_dict`` through JSON, inf included) is parsed once into the record it
    was; a key the records do not have is refused rather than read by mistake."""
    import json

    sent = numbers(lidar={"no_hit": 3, "no_hit_reading": math.inf, "front_no_hit": True},
                   spin={"touched": ["box"], "contact_points": [{"shape": "box", "link": "base_link", "time": 1.5}]})
    received = SimNumbers.from_dict(json.loads(json.dumps(sent.to_dict())))
    assert received == sent
    assert received.spin.contact_points[0].link == "base_link" and received.lidar.no_hit_reading == math.inf
    assert sim_findings(sent.to_dict(), "inf").findings == sim_findings(sent, "inf").findings
    with pytest.raises(TypeError):
        SimNumbers.from_dict({**sent.to_dict(), "spin": {"drift": 0.0, "turned": 0.0, "drfit": 1.0}})
