"""The pybullet session behaves like the Gazebo TurtleBot3: scene loading and contact labels, the LDS-01 scan,
the diff drive's ramp, spin in place, and the stop-at-wall loop."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from worldgen.core.stoplaw import StopLaw
from worldgen.robots.profile import DriveParams
from worldgen.core.scene import Scene, Shape
from worldgen.sim.behaviours import settle, spin, stop_at_wall
from worldgen.sim.drive import DiffDrive
from worldgen.sim.lidar import front_distance
from worldgen.sim.session import Session

HALF = 2.5          # room walls on x, y = ±2.5 (centre-lines), 0.15 thick: inner faces at ±2.425
INNER = HALF - 0.075
BURGER_SCAN_X = -0.032   # base_scan in base_footprint


def room(*extra: Shape, half: float = HALF) -> Scene:
    walls = [((half, 0), (0.15, 2 * half)), ((-half, 0), (0.15, 2 * half)),
             ((0, half), (2 * half, 0.15)), ((0, -half), (2 * half, 0.15))]
    shapes = [Shape("box", (x, y, 1.25), size=(sx, sy, 2.5), model="room", link=f"Wall_{i}", name="collision")
              for i, ((x, y), (sx, sy)) in enumerate(walls)]
    return Scene(source=None, shapes=shapes + list(extra))


def test_many_primitives_are_all_there():
    """pybullet keeps 16 children per compound shape; 40 boxes must all stop rays and carry their labels."""
    boxes = [Shape("box", (0.5 * i - 10, 3.0, 0.25), size=(0.2, 0.2, 0.5), model="row", name=f"b{i}")
             for i in range(40)]
    with Session(Scene(source=None, shapes=boxes)) as session:
        import pybullet as pb
        assert len(session.bodies.obstacle_bodies) == 3 and len(session.bodies.planes) == 1
        starts = [[0.5 * i - 10, 3.0, 2.0] for i in range(40)]
        ends = [[0.5 * i - 10, 3.0, -1.0] for i in range(40)]
        hits = pb.rayTestBatch(starts, ends, physicsClientId=session.client)
        assert all(h[0] in session.bodies.obstacle_bodies and h[3][2] == pytest.approx(0.5) for h in hits)
        assert [session.bodies.label(h[0], h[3]) for h in hits] == [f"row/b{i}" for i in range(40)]


def test_a_points_distance_to_each_child_of_a_compound():
    """Signed distances to a turned box, a lying cylinder and a sphere, worked by hand; the nearest child names a
    contact, and follows a child that was moved."""
    from worldgen.sim.scene_loader import Children, SceneBodies

    c, s = math.cos(math.pi / 8), math.sin(math.pi / 8)
    box = Shape("box", (0.0, 0.0, 0.5), (0.0, 0.0, s, c), size=(2.0, 1.0, 1.0), name="box")   # turned 45° about z
    rod = Shape("cylinder", (5.0, 0.0, 0.3), (math.sqrt(0.5), 0.0, 0.0, math.sqrt(0.5)), radius=0.3, length=2.0,
                name="rod")   # its axis along y
    ball = Shape("sphere", (0.0, 6.0, 1.0), radius=0.5, name="ball")
    children = Children([box, rod, ball])
    diagonal = 3 * math.sqrt(0.5)
    assert children.distances((diagonal, diagonal, 0.5))[0] == pytest.approx(2.0)   # off the box's long face
    assert children.distances((0.0, 0.0, 0.5))[0] == pytest.approx(-0.5)           # inside: the nearest face
    assert children.distances((5.0, 3.0, 0.3))[1] == pytest.approx(2.0)             # beyond the rod's end
    assert children.distances((5.0, 0.0, 1.3))[1] == pytest.approx(0.7)             # beside it
    assert children.distances((0.0, 6.0, 3.0))[2] == pytest.approx(1.5)

    bodies = SceneBodies(shapes={7: [box, rod, ball]})
    assert [bodies.label(7, p) for p in ((1.0, 1.0, 0.5), (5.0, 1.2, 0.3), (0.0, 6.4, 1.0))] == ["box", "rod", "ball"]
    ball.position = (5.0, 3.0, 0.3)   # a model moved: its shapes get new poses
    assert bodies.label(7, (5.0, 3.4, 0.3)) == "ball"


def test_ground_plane_added_only_when_missing():
    plane = Shape("plane", (0.0, 0.0, 0.0), normal=(0.0, 0.0, 1.0), model="ground_plane", link="link")
    with Session(Scene(source=None, shapes=[plane])) as session:
        assert [s[0].label for s in session.bodies.shapes.values()] == ["ground_plane/link"]
    with Session(None) as session:
        assert [s[0].name for s in session.bodies.shapes.values()] == ["added"]
        assert settle(session, 0.3).z == pytest.approx(0.0, abs=0.003)


def test_scan_matches_room_geometry_and_gazebo_angles():
    with Session(room(), spawn=(0.0, 0.0, math.pi / 2), seed=None) as session:
        scan = session.scan()
        assert len(scan.ranges) == 360
        assert scan.angle_increment == pytest.approx(6.28319 / 359)
        assert (scan.range_min, scan.range_max) == (0.12, 3.5)
        # robot faces +y, so beam 0 (base_scan +x) sees the north wall, ~beam 90 the west one, ~180 south
        sx, sy = scan.origin[:2]
        assert sy == pytest.approx(BURGER_SCAN_X, abs=0.002)
        expected = {0: INNER - sy, 90: INNER + sx, 180: INNER + sy, 270: INNER - sx}
        for i, distance in expected.items():
            j = round(i * (2 * math.pi / 360) / scan.angle_increment)
            slant = math.cos(j * scan.angle_increment - math.radians(i))   # beam j is a little off i degrees
            assert scan.true_ranges[j] == pytest.approx(distance / slant, abs=0.002)
        # no noise (seed None): each reading is the distance itself, as Gazebo Classic's ray sensor gives it
        # (it reads the xacro's <range><resolution> 0.015 but never rounds to it)
        assert scan.ranges == scan.true_ranges and any(abs(r / 0.015 - round(r / 0.015)) > 1e-3 for r in scan.ranges)
        assert scan.points[0][1] == pytest.approx(INNER, abs=0.002)


def test_noise_is_seeded_gaussian_and_no_hits_read_inf_or_zero():
    with Session(room(half=1.5), seed=7) as a, Session(room(half=1.5), seed=7) as b:
        first, second = a.scan(), b.scan()
        assert first.ranges == second.ranges
        errors = np.array(first.ranges) - np.array(first.true_ranges)
        assert 0.006 < errors.std() < 0.015 and abs(errors.mean()) < 0.003
    for mode, value in (("inf", math.inf), ("zero", 0.0)):
        with Session(None, no_hit=mode) as session:   # nothing but the floor: horizontal beams hit nothing
            scan = session.scan()
            assert scan.ranges == [value] * 360 and all(p is None for p in scan.points)
            assert front_distance(scan) is None


def test_lidar_ignores_the_robot_and_sees_a_mesh():
    """A triangle-mesh wall (concave static mesh) 1 m ahead of the LiDAR; nothing closer (no self hits)."""
    import trimesh

    box = trimesh.creation.box((0.1, 2.0, 1.0))
    wall = Shape("mesh", (1.0 + BURGER_SCAN_X + 0.05, 0.0, 0.5), vertices=np.asarray(box.vertices),
                 faces=np.asarray(box.faces), model="maze", link="link", name="mesh")
    with Session(Scene(source=None, shapes=[wall]), seed=None) as session:
        scan = session.scan()
        assert front_distance(scan, true=True) == pytest.approx(1.0, abs=0.002)
        finite = [r for r in scan.true_ranges if math.isfinite(r)]
        assert min(finite) > 0.99


def _run(drive: DiffDrive, updates: int, current=None) -> list[float]:
    """``updates`` plugin updates at 30 Hz with ideal motors: each wheel turns at the speed last commanded (or
    ``current`` before the first update); returns the rim speeds commanded last."""
    rims = list(current or (0.0, 0.0))
    for _ in range(updates):
        rims = [w * drive.params.wheel_radius for w in drive.update(1 / 30, tuple(rims))]
    return rims


def test_diff_drive_ramp_is_the_plugins():
    params = DriveParams("l", "r", wheel_separation=0.16, wheel_radius=0.033, acceleration=1.0, torque=10.0,
                         update_rate=30.0, from_plugin=True)
    drive = DiffDrive(params, command=(0.2, 1.0))
    assert drive.targets() == pytest.approx((0.2 - 0.08, 0.2 + 0.08))
    left, right = drive.update(1 / 30, (0.0, 0.0))
    assert drive.ramped == pytest.approx([1 / 30, 1 / 30]) and left == pytest.approx(1 / 30 / 0.033)
    drive = DiffDrive(params, command=(0.2, 1.0))
    assert _run(drive, 4) == pytest.approx([0.12, 4 / 30])      # left reached its target, right still ramping
    # once either wheel is within 0.01 m/s of its target the plugin sets both targets directly
    assert _run(drive, 1, (0.12, 4 / 30)) == pytest.approx([0.12, 0.28])
    slow = DiffDrive(dataclasses.replace(params, acceleration=0.15), command=(0.2, 0.0))
    assert _run(slow, 1, (0.192, 0.0)) == pytest.approx([0.2, 0.2])
    instant = DiffDrive(dataclasses.replace(params, acceleration=0.0), command=(0.2, 0.0))
    assert instant.update(1 / 30, (0.0, 0.0)) == pytest.approx((0.2 / 0.033, 0.2 / 0.033))


def test_diff_drive_ramps_from_its_own_stale_speed_as_the_plugin_does():
    """Small command changes are taken at once and leave the ramp's state behind; a large change then ramps
    from that stale speed: slowing from 0.2 to 0.05 m/s in small steps, then commanding 0, first speeds the
    wheels up to 0.2 − 1/30 m/s."""
    params = DriveParams("l", "r", wheel_separation=0.16, wheel_radius=0.033, acceleration=1.0, torque=10.0,
                         update_rate=30.0, from_plugin=True)
    drive = DiffDrive(params, command=(0.2, 0.0))
    rims = _run(drive, 10)
    assert rims == pytest.approx([0.2, 0.2]) and drive.ramped == pytest.approx([0.2, 0.2])
    for v in np.arange(0.192, 0.049, -0.008):
        drive.command = (float(v), 0.0)
        rims = _run(drive, 1, rims)
    assert rims == pytest.approx([0.056, 0.056]) and drive.ramped == pytest.approx([0.2, 0.2])
    drive.command = (0.0, 0.0)
    lurch = _run(drive, 1, rims)
    assert lurch == pytest.approx([0.2 - 1 / 30] * 2)
    assert _run(drive, 4, lurch) == pytest.approx([1 / 30] * 2)
    assert _run(drive, 1, [1 / 30] * 2) == pytest.approx([0.0, 0.0], abs=1e-12)


def test_drives_and_stops_like_the_plugin():
    """0.2 m/s for 2 s: 0.4 m less the ramp's 0.02 m; stopping from 0.22 m/s at 1 m/s² takes ~0.024 m."""
    with Session(None, seed=None) as session:
        settle(session, 0.3)
        session.cmd_vel(0.2)
        session.run(2.0)
        odom = session.odometry()
        assert odom.x == pytest.approx(0.38, abs=0.015) and abs(odom.y) < 0.01
        assert odom.v == pytest.approx(0.2, abs=0.01)
        session.cmd_vel(0.22)
        session.run(1.0)
        x0 = session.odometry().x
        session.cmd_vel(0.0)
        session.run(1.0)
        odom = session.odometry()
        assert odom.x - x0 == pytest.approx(0.0242, abs=0.008) and abs(odom.v) < 0.002


def test_the_body_accelerates_as_hard_as_the_wheels_grip():
    """The wheels ramp their rims at the plugin's 1 m/s², but the xacro gives them μ 0.1 (Gazebo takes the lower
    μ of a contact, the floor's being 100), so traction bounds the body below μ·g = 0.98 m/s²: about 0.84 m/s²,
    the casters carrying the rest of the weight."""
    with Session(None, seed=None) as session:
        settle(session, 0.3)
        session.cmd_vel(0.22)
        speeds = []
        for _ in range(80):
            session.run(session.time_step)
            speeds.append(session.odometry().v)
    rates = np.diff(speeds) / session.time_step
    assert 0.75 < rates.max() < 0.98
    assert speeds[-1] == pytest.approx(0.22, abs=0.005)


def test_spin_in_place():
    with Session(room()) as session:
        result = spin(session, seconds=2 * math.pi / 1.5, omega=1.5)
        assert result.ok and result.contacts == []
        assert result.max_drift < 0.03 and result.drift < 0.01
        assert result.turned == pytest.approx(2 * math.pi, rel=0.05)


def test_spin_waffle():
    with Session(room(), "waffle") as session:
        result = spin(session, seconds=math.pi, omega=1.0)
        assert result.ok and result.turned == pytest.approx(math.pi, rel=0.08)


@pytest.mark.parametrize("kp", [0.5, 1.0])
def test_stop_at_wall_with_a_proportional_gain(kp):
    with Session(room(half=1.5), spawn=(-0.5, 0.0, 0.0)) as session:
        result = stop_at_wall(session, StopLaw(target=0.5, kp=kp), duration=16.0)
    assert result.final_distance == pytest.approx(0.5, abs=0.05)
    assert result.contacts == [] and result.stopped and result.ok
    assert result.overshoot < 0.02
    assert result.settling_time is not None and result.settling_time < 16.0
    assert len(result.series["t"]) == 16 * 5 + 1 and result.series["true"][0] == pytest.approx(
        1.5 - 0.075 - (-0.5 + BURGER_SCAN_X), abs=0.003)


def test_stop_at_wall_too_fast_to_stop_hits_the_wall():
    """Fast, with a target closer than the 1 m/s² ramp's braking distance (and the 5 Hz loop seeing the wall
    late): the robot drives into the wall, and that is reported, not hidden."""
    with Session(room(half=1.5), spawn=(-0.5, 0.0, 0.0)) as session:
        result = stop_at_wall(session, StopLaw(target=0.15, kp=2.0, max_speed=1.0), duration=12.0)
    assert not result.ok and result.contacts
    assert result.contacts[0]["shape"].startswith("room/Wall_")
    assert result.min_distance < 0.15


def test_stop_at_wall_never_reverses_and_holds_with_pi_gains():
    """A PI controller's wound-up integral cannot drive the robot backwards or past the stop: the law stops
    and holds within the stop band, as the generated node does."""
    with Session(room(half=1.5), spawn=(-0.5, 0.0, 0.0)) as session:
        result = stop_at_wall(session, StopLaw(target=0.5, kp=0.5, ki=0.3, kd=0.2), duration=16.0)
    assert min(result.series["v_cmd"]) == 0.0 and min(result.series["v"]) > -0.005
    assert result.ok and result.stopped and result.stop_time is not None
    assert result.overshoot < 0.04   # the ramp's braking distance from 0.22 m/s


def test_contacts_name_the_shape_and_when_it_was_first_touched():
    post = Shape("cylinder", (1.0, 0.0, 0.25), radius=0.1, length=0.5, model="posts", link="l", name="post")
    decoy = Shape("box", (1.0, 1.0, 0.25), size=(0.2, 0.2, 0.5), model="posts", link="l", name="decoy")
    with Session(Scene(source=None, shapes=[post, decoy])) as session:
        assert session.contacts() == []
        session.cmd_vel(0.2)
        session.run(6.0)
        touching = session.contacts()
        assert touching and {c.shape for c in touching} == {"posts/l/post"}
        assert touching[0].link in ("base_link", "base_scan")
        # burger's front (base box and LiDAR housing) is 0.038 m ahead of base_footprint: 0.862 m to the post,
        # 0.02 m of it in the 0.2 s ramp, the rest at 0.2 m/s
        first = session.touches.to_list()[0]
        assert first["shape"] == "posts/l/post" and first["time"] == pytest.approx(0.2 + 0.842 / 0.2, abs=0.05)


def test_a_turn_slowed_in_small_steps_leaves_a_stale_ramp_that_exercises_start_without():
    """As in Gazebo, a forward command after a turn whose slowdown the plugin took at once veers (the ramp starts
    from the turn's stale wheel speeds); each exercise starts with the ramp synced to the standing wheels."""
    headings = []
    for fresh in (False, True):
        with Session(None, seed=None) as session:
            settle(session, 0.3)
            for omega in (1.0, 1.0, 0.9, 0.8, 0.7, 0.6, 0.5, 0.4, 0.3, 0.2, 0.1, 0.0):
                session.cmd_vel(0.0, omega)   # rim steps of 0.008 m/s: each set directly
                session.run(0.1)
            session.run(0.5)
            assert session.drive.ramped == pytest.approx([-0.08, 0.08], abs=0.002)
            if fresh:
                session.start_exercise()
                assert session.drive.ramped == pytest.approx([0.0, 0.0], abs=1e-3)
            yaw = session.odometry().yaw
            session.cmd_vel(0.2)
            session.run(1.0)
            headings.append(math.degrees(math.remainder(session.odometry().yaw - yaw, math.tau)))
    stale, fresh = headings
    assert stale > 5.0 and abs(fresh) < 0.5
