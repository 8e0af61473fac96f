"""The rubrics judge traces as the README says, on traces made by hand (no ROS needed): a square with 90° corners
passes and one with 120° corners does not; a spin whose circles wander fails; a robot still moving fails
stop-at-wall; a wall follower keeping its distance passes and one that strays fails."""

from __future__ import annotations

import math

import pytest

from conftest import REPO
from worldgen.bridge.metrics import compute
from worldgen.bridge.rubrics import judge

DT = 1 / 30


def drive(moves, start=(0.0, 0.0, 0.0)):
    """Odometry rows [t, x, y, yaw, v, ω, cmd_v, cmd_ω] for (v, ω, seconds) moves."""
    x, y, yaw = start
    rows, t = [[0.0, x, y, yaw, 0.0, 0.0, 0.0, 0.0]], 0.0
    for v, w, seconds in moves:
        for _ in range(round(seconds / DT)):
            x, y, yaw, t = x + v * math.cos(yaw) * DT, y + v * math.sin(yaw) * DT, yaw + w * DT, t + DT
            rows.append([t, x, y, math.remainder(yaw, math.tau), v, w, v, w])
    return rows


def verdict(task, trace, target=None, side=None):
    findings, numbers = judge(task, trace, compute(trace), target, side)
    return [f.message for f in findings if f.severity == "error"], numbers


def square(corner_deg: float, sides=(1.0, 1.0, 1.0, 1.0)):
    moves = []
    for side in sides:
        moves += [(0.2, 0.0, side / 0.2), (0.0, 0.5, math.radians(corner_deg) / 0.5)]
    return {"odom": drive(moves)}


def test_a_square_passes_and_a_triangle_like_path_fails():
    errors, numbers = verdict("drive-square", square(90))
    assert errors == [] and numbers["sides_m"] == pytest.approx([1.0] * 4, abs=0.03)
    errors, _ = verdict("drive-square", square(120))
    assert any(e.startswith("corners of 120°, 120°, 120°") for e in errors)
    errors, _ = verdict("drive-square", square(90, sides=(1.0, 0.6, 1.0, 0.6)))
    assert any("differ by 40%" in e for e in errors)


def test_spin_needs_two_turns_about_a_fixed_centre():
    assert verdict("spin", {"odom": drive([(0.1, 0.5, 30)])})[0] == []            # 2.4 turns, radius 0.2
    errors, numbers = verdict("spin", {"odom": drive([(0.1, 0.5, 8)])})
    assert errors == ["the robot turned 0.64 full turns; 2 are needed"]
    wander = {"odom": drive([(0.1, 0.5, 13), (0.3, 0.0, 1.0), (0.1, 0.5, 13)])}   # a straight dash between turns
    assert any("centre of the circles drifted" in e for e in verdict("spin", wander)[0])


def test_stop_at_wall_wants_a_stop_at_the_target():
    still = {"odom": drive([(0.2, 0.0, 9.8), (0.0, 0.0, 2.0)]), "scans": [[12.0, 0.53, 0.53, 0.5, 0.4]]}
    assert verdict("stop-at-wall", still)[0] == []
    moving = {"odom": drive([(0.2, 0.0, 12.0)]), "scans": [[12.0, 0.45, 0.45, 0.4, 0.3]]}
    assert verdict("stop-at-wall", moving)[0] == ["the robot is still moving at the end (0.20 m/s)"]
    short = {"odom": drive([(0.0, 0.0, 2.0)]), "scans": [[2.0, 2.46, 2.46, 2.4, 1.0]]}
    assert verdict("stop-at-wall", short)[0] == [
        "stopped 2.46 m from the wall ahead, 1.96 m short of the 0.5 m target (±0.1 m)"]


def test_wall_follow_share_and_distance():
    odom = drive([(0.15, 0.0, 40)])
    keeps = [[t, None, None, 0.42, 0.3] for t in range(0, 40)]
    assert verdict("wall-follow", {"odom": odom, "scans": keeps}, side=4.85)[0] == []
    strays = [[t, None, None, 0.42 if t < 20 else 1.2, 0.3] for t in range(0, 40)]
    errors, numbers = verdict("wall-follow", {"odom": odom, "scans": strays}, side=4.85)
    assert numbers["share_in_band"] == pytest.approx(0.5) and any("in 50% of the time" in e for e in errors)
    never = [[t, None, None, 1.5, 1.0] for t in range(0, 40)]
    assert verdict("wall-follow", {"odom": odom, "scans": never})[0] == [
        "the robot never came within 0.55 m of a wall"]


@pytest.mark.parametrize("width, points", [
    (0.1, None),    # the line_track loop with 10 cm tape: its bends' pieces are shorter than the tape is wide
    (0.05, [[round(0.6 * math.cos(a * math.tau / 100), 4), round(0.6 * math.sin(a * math.tau / 100), 4)]
            for a in range(100)]),   # a circle of 100 points, 3.8 cm apart
])
def test_the_tape_is_the_whole_loop_however_short_its_pieces(tmp_path, width, points):
    import yaml

    from worldgen.bridge.track import tape_track
    from worldgen.bridge.world import load_world

    spec = yaml.safe_load((REPO / "examples" / "line_track.yaml").read_text())
    spec["lines"][0]["width"] = width
    if points is not None:
        spec["lines"][0]["points"] = points
    path = tmp_path / "track.yaml"
    path.write_text(yaml.safe_dump(spec))
    track = tape_track(load_world(path).scene)
    expected = 7.937 if points is None else 100 * 2 * 0.6 * math.sin(math.pi / 100)
    assert track.loop and track.length == pytest.approx(expected, abs=0.01)


def test_the_cameras_floor_point_follows_a_tilted_camera(tmp_path):
    """The Waffle Pi's level camera meets the floor 0.30 m ahead; tilted 0.3 rad down (a robot description of a
    student's own), its image's bottom edge meets it nearer, where the ray's geometry says."""
    from worldgen.bridge.track import camera_floor_distance
    from worldgen.robots import robot_urdf

    level = camera_floor_distance("waffle_pi")
    urdf = robot_urdf("waffle_pi")
    joint = '<origin rpy="0 0 0" xyz="0.003 0.011 0.009"/>'
    assert joint in urdf
    tilted = tmp_path / "tilted.urdf"
    tilted.write_text(urdf.replace(joint, '<origin rpy="0 0.3 0" xyz="0.003 0.011 0.009"/>'))
    x, h = 0.073 + 0.003, 0.010 + 0.084 + 0.009            # the camera above base_footprint (base_link 0.010 up)
    below = math.atan(math.tan(1.085595 / 2) * 480 / 640)   # half the vertical field of view
    assert level == pytest.approx(x + h / math.tan(below), abs=0.005)
    assert camera_floor_distance(str(tilted)) == pytest.approx(x + h / math.tan(below + 0.3), abs=0.005)
    assert camera_floor_distance("burger") is None
