"""The closed-room geometry: shapes sliced at LiDAR height, enclosure of the spawn, and where the way out is."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from conftest import CliRunner
from worldgen.cli import main
from worldgen.geometry.enclosure import analyse, enclosure
from worldgen.geometry.slices import footprints, section
from worldgen.core.scene import Scene, Shape

LIDAR_Z = 0.182   # burger


def quat_yaw(yaw: float):
    return (0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2))


def wall(start, end, name, thickness=0.15, z0=0.0, z1=2.5, model="room"):
    """A Building-Editor wall box along the centre-line start → end, spanning heights z0..z1."""
    (x0, y0), (x1, y1) = start, end
    yaw = math.atan2(y1 - y0, x1 - x0)
    return Shape("box", ((x0 + x1) / 2, (y0 + y1) / 2, (z0 + z1) / 2), quat_yaw(yaw),
                 size=(math.dist(start, end), thickness, z1 - z0), model=model, link=name)


def square_room(size=5.0, door=None, centre=(0.0, 0.0), yaw=0.0, extra=()):
    """A size × size room as the Building Editor saves it (walls of the side's length meeting at the corners).
    ``door`` = (wall index, offset from the wall's start, width) cuts a floor-to-top opening."""
    h = size / 2
    c, s = math.cos(yaw), math.sin(yaw)

    def world(p):
        return (centre[0] + c * p[0] - s * p[1], centre[1] + s * p[0] + c * p[1])

    corners = [(-h, -h), (h, -h), (h, h), (-h, h)]
    shapes = [Shape("plane", (0.0, 0.0, 0.0), normal=(0.0, 0.0, 1.0), model="ground_plane")]
    for i in range(4):
        a, b = corners[i], corners[(i + 1) % 4]
        if door and door[0] == i:
            _, offset, width = door
            ux, uy = (b[0] - a[0]) / size, (b[1] - a[1]) / size
            p = (a[0] + ux * offset, a[1] + uy * offset)
            q = (a[0] + ux * (offset + width), a[1] + uy * (offset + width))
            shapes += [wall(world(a), world(p), f"Wall_{i}_0"), wall(world(q), world(b), f"Wall_{i}_1")]
        else:
            shapes.append(wall(world(a), world(b), f"Wall_{i}"))
    return Scene(None, shapes=shapes + list(extra))


def test_closed_room_is_enclosed_with_its_free_floor():
    e = enclosure(square_room(), (0.3, -0.7), LIDAR_Z)
    assert e.enclosed is True and e.gaps == ()
    assert e.region_area == pytest.approx(4.85 ** 2 - 4 * 0.001 * 4.85, rel=2e-3)   # 0.5 mm sliver buffer
    assert e.nearest == pytest.approx(2.425 - 0.7, abs=1e-3)


def test_half_metre_gap_is_found_and_named():
    # wall 0 (bottom, y = -2.5) has a 0.5 m opening from x = 0.5 to 1.0
    e = enclosure(square_room(door=(0, 3.0, 0.5)), (0.0, 0.0), LIDAR_Z)
    assert e.enclosed is False
    assert len(e.gaps) == 1
    gap = e.gaps[0]
    assert gap.centre == pytest.approx((0.75, -2.5), abs=1e-3)
    assert [x for x, _ in gap.ends] == pytest.approx([0.5, 1.0], abs=1e-3)   # the walls' ends, either side
    assert gap.width == pytest.approx(0.5, abs=0.002)
    assert set(gap.between) == {"room/Wall_0_0", "room/Wall_0_1"}


def test_gap_in_a_rotated_offset_room_is_in_world_coordinates():
    yaw, centre = 0.7, (-4.0, 3.0)
    e = enclosure(square_room(door=(2, 1.0, 0.9), centre=centre, yaw=yaw), centre, LIDAR_Z)
    # wall 2 runs from (2.5, 2.5) to (-2.5, 2.5); the opening spans local x 1.5 .. 0.6, centre (1.05, 2.5)
    lx, ly = 1.05, 2.5
    c, s = math.cos(yaw), math.sin(yaw)
    expected = (centre[0] + c * lx - s * ly, centre[1] + s * lx + c * ly)
    assert e.enclosed is False and len(e.gaps) == 1
    assert e.gaps[0].centre == pytest.approx(expected, abs=1e-3)
    assert e.gaps[0].width == pytest.approx(0.9, abs=0.01)


def test_two_gaps_are_both_listed_widest_first():
    room = square_room(door=(0, 3.0, 0.5))
    # and a 1.2 m gap in wall 3 (left, x = -2.5): drop it and put two pieces back
    shapes = [s for s in room.shapes if s.link != "Wall_3"]
    shapes += [wall((-2.5, 2.5), (-2.5, 0.6), "Wall_3_0"), wall((-2.5, -0.6), (-2.5, -2.5), "Wall_3_1")]
    e = enclosure(Scene(None, shapes=shapes), (0.0, 0.0), LIDAR_Z)
    assert e.enclosed is False
    assert [round(g.width, 1) for g in e.gaps] == [1.2, 0.5]
    assert e.gaps[0].centre == pytest.approx((-2.5, 0.0), abs=1e-3)
    assert e.gaps[1].centre == pytest.approx((0.75, -2.5), abs=1e-3)


def test_way_out_is_the_door_not_the_space_beside_a_partition():
    # an L-shaped hall with a 1 m door in its right wall (x = 6, y 1 … 2) and a free-standing partition in the
    # wide part: the narrowest cut lies beside the partition (0.6–0.75 m), but the way out is the door
    corners = [(0, 0), (6, 0), (6, 3), (3, 3), (3, 6), (0, 6)]
    shapes = []
    for i, (a, b) in enumerate(zip(corners, corners[1:] + corners[:1])):
        if i == 1:
            shapes += [wall(a, (6, 1), "Wall_1_0"), wall((6, 2), b, "Wall_1_1")]
        else:
            shapes.append(wall(a, b, f"Wall_{i}"))
    shapes.append(wall((4.5, 0.9), (4.5, 2.4), "partition", z1=1.0))
    e = enclosure(Scene(None, shapes=shapes), (1.5, 1.5), LIDAR_Z)
    assert e.enclosed is False
    assert [(round(g.centre[0], 1), round(g.centre[1], 1), round(g.width, 2)) for g in e.gaps] == [(6.0, 1.5, 1.0)]


def test_way_out_of_a_room_through_a_corridor_is_the_corridor_end():
    # room (±2.5) with a 0.8 m door in its right wall into a 2 m wide corridor whose far end (x = 6) has a 1 m gap
    room = square_room(door=(1, 2.1, 0.8))
    corridor = [wall((2.5, 1.0), (6.0, 1.0), "corridor_n"), wall((2.5, -1.0), (6.0, -1.0), "corridor_s"),
                wall((6.0, -1.0), (6.0, -0.5), "end_s"), wall((6.0, 0.5), (6.0, 1.0), "end_n")]
    e = enclosure(Scene(None, shapes=room.shapes + corridor), (0.0, 0.0), LIDAR_Z)
    [gap] = e.gaps
    assert gap.centre == pytest.approx((6.0, 0.0), abs=1e-3) and gap.width == pytest.approx(1.0, abs=0.01)


def test_missing_wall_is_one_wide_gap_on_that_side():
    shapes = [s for s in square_room().shapes if s.link != "Wall_2"]
    e = enclosure(Scene(None, shapes=shapes), (0.0, -1.0), LIDAR_Z)
    assert e.enclosed is False and len(e.gaps) == 1
    assert e.gaps[0].width == pytest.approx(4.85, abs=0.05)
    assert e.gaps[0].centre == pytest.approx((0.0, 2.5), abs=1e-3)


def walls(*centre_lines, **kw):
    """Building-Editor walls W0, W1, … along the given centre-lines (start, end)."""
    return [wall(a, b, f"W{i}", **kw) for i, (a, b) in enumerate(centre_lines)]


def gaps_of(shapes, spawn):
    e = enclosure(Scene(None, shapes=shapes), spawn, LIDAR_Z)
    assert e.enclosed is False
    return e.gaps


U_CORRIDOR = (((0, 0), (12, 0)), ((12, 0), (12, 2)), ((12, 2), (0, 2)))   # 12 m x 2 m, open at x = 0


@pytest.mark.parametrize("spawn", [(6, 1), (3, 0.3), (11.8, 1.8), (11.9, 0.1), (0.5, 1.0)])
def test_corridor_open_at_one_end_is_named_at_that_end(spawn):
    # no disc wider than the corridor fits anywhere in it: the way out is its open end, 12 m from the closed one,
    # between the walls' ends (a gap as wide as the corridor between the walls' inner faces)
    [gap] = gaps_of(walls(*U_CORRIDOR), spawn)
    assert gap.centre == pytest.approx((0.0, 1.0), abs=0.03)
    assert gap.width == pytest.approx(2 - 0.15, abs=0.01)
    assert set(gap.between) == {"room/W0", "room/W2"}


def test_corridor_open_at_both_ends_names_both():
    gaps = gaps_of(walls(((0, 0), (12, 0)), ((12, 2), (0, 2))), (6.0, 1.0))
    assert sorted(round(g.centre[0], 1) for g in gaps) == [0.0, 12.0]
    for gap in gaps:
        assert gap.centre[1] == pytest.approx(1.0, abs=0.03) and gap.width == pytest.approx(1.85, abs=0.01)
        assert set(gap.between) == {"room/W0", "room/W1"}


@pytest.mark.parametrize("spawn", [(5, 1), (9, 4), (9, 1)])   # an arm, the other arm, the bend
def test_l_shaped_corridor_open_at_both_ends_names_both_ends(spawn):
    # east along y 0…2, then north along x 8…10 up to y = 8; open at x = 0 and at y = 8. At the bend a disc wider
    # than the corridor fits: the neck is then a whole arm, named where it opens, not half-way along it
    shapes = walls(((0, 0), (10, 0)), ((10, 0), (10, 8)), ((8, 8), (8, 2)), ((8, 2), (0, 2)))
    found = {(round(g.centre[0], 1), round(g.centre[1], 1)): g for g in gaps_of(shapes, spawn)}
    assert sorted(found) == [(0.0, 1.0), (9.0, 8.0)]
    assert set(found[0.0, 1.0].between) == {"room/W0", "room/W3"}
    assert set(found[9.0, 8.0].between) == {"room/W1", "room/W2"}
    assert all(g.width == pytest.approx(1.85, abs=0.01) for g in found.values())


@pytest.mark.parametrize("spawn", [(3, 2), (5.9, 0.1), (1, 1.5)])
def test_three_metre_missing_wall_is_the_way_out(spawn):
    # a 6 m x 4 m room whose west wall is 1 m long (y 3…4): the wall ends 2.925 m apart
    shapes = walls(((0, 0), (6, 0)), ((6, 0), (6, 4)), ((6, 4), (0, 4)), ((0, 4), (0, 3)))
    [gap] = gaps_of(shapes, spawn)
    assert gap.width == pytest.approx(3 - 0.075, abs=0.01)
    assert gap.centre == pytest.approx((0.0375, 1.5375), abs=0.075)   # across the west wall's thickness
    assert set(gap.between) == {"room/W0", "room/W3"}


def test_spawn_in_a_corner_names_the_rooms_way_out_not_the_corner():
    # only small discs reach into the corner, whatever the room's way out: it used to be named as a 1.5 m "gap"
    # between the two walls meeting there
    shapes = [s for s in square_room().shapes if s.link != "Wall_2"]
    [gap] = gaps_of(shapes, (2.2, -2.0))
    assert gap.centre == pytest.approx((0.0, 2.5), abs=1e-3) and gap.width == pytest.approx(4.85, abs=0.05)


def test_spawn_near_a_wide_open_end_names_it():
    # a short, wide dead end (4 m x 3.3 m, open at x = 0), the spawn 0.4 m inside: discs far wider than the opening
    # reach it from outside, resting on the two walls' ends
    [gap] = gaps_of(walls(((0, 0), (4, 0)), ((4, 0), (4, 3.3)), ((4, 3.3), (0, 3.3))), (0.4, 1.65))
    assert gap.centre == pytest.approx((0.0, 1.65), abs=0.03) and gap.width == pytest.approx(3.15, abs=0.01)
    assert set(gap.between) == {"room/W0", "room/W2"}


def test_open_corridor_from_a_spec_is_an_error_naming_its_segments(tmp_path):
    spec = tmp_path / "u.yaml"
    spec.write_text("name: ucorridor\nsegments:\n  - {from: [0, 0], to: [12, 0]}\n  - {from: [12, 0], to: [12, 2]}\n"
                    "  - {from: [12, 2], to: [0, 2]}\nrobot: {model: burger, at: [6, 1], yaw: 0}\n")
    out = CliRunner().invoke(main, ["validate", str(spec), "--skip-sim", "--format", "json"])
    [r] = json.loads(out.stdout)["results"]
    [finding] = [f for f in r["findings"] if f["check"] == "enclosed"]
    [gap] = r["metrics"]["gaps"]
    assert out.exit_code == 1 and finding["severity"] == "error" and gap["robot_passes"] is True
    # the spec's walls run on past their end points by half their thickness: the opening is at x = -0.075
    assert gap["centre"] == pytest.approx([-0.075, 1.0], abs=0.01) and gap["width"] == pytest.approx(1.85, abs=0.01)
    assert finding["message"].startswith("the room is open: a 1.85 m gap at (-0.07, 1.00) between segment 1 "
                                         "(from (0,0) to (12,0)) and segment 3 (from (12,2) to (0,2))")


def test_window_above_lidar_keeps_the_room_closed_a_door_does_not():
    # a window: wall 1 with a sill up to 0.5 m and a lintel above 1.3 m between y = -0.4 and 0.4
    shapes = [s for s in square_room().shapes if s.link != "Wall_1"]
    shapes += [wall((2.5, -2.5), (2.5, -0.4), "Wall_1_0"), wall((2.5, 0.4), (2.5, 2.5), "Wall_1_1"),
               wall((2.5, -0.4), (2.5, 0.4), "Wall_1_2", z0=0.0, z1=0.5),
               wall((2.5, -0.4), (2.5, 0.4), "Wall_1_3", z0=1.3, z1=2.5)]
    assert enclosure(Scene(None, shapes=shapes), (0.0, 0.0), LIDAR_Z).enclosed is True
    door = [s for s in shapes if s.link != "Wall_1_2"]   # no sill: an opening from the floor
    e = enclosure(Scene(None, shapes=door), (0.0, 0.0), LIDAR_Z)
    assert e.enclosed is False and e.gaps[0].width == pytest.approx(0.8, abs=0.01)
    assert e.gaps[0].centre == pytest.approx((2.5, 0.0), abs=1e-3)


def test_low_wall_under_the_lidar_plane_does_not_close_the_room():
    shapes = [s for s in square_room().shapes if s.link != "Wall_0"]
    shapes.append(wall((-2.5, -2.5), (2.5, -2.5), "Wall_0", z0=0.0, z1=0.1))
    assert enclosure(Scene(None, shapes=shapes), (0.0, 0.0), LIDAR_Z).enclosed is False
    assert enclosure(Scene(None, shapes=shapes), (0.0, 0.0), 0.05).enclosed is True


def test_sub_millimetre_sliver_counts_as_closed_but_3_mm_does_not():
    sliver = enclosure(square_room(door=(0, 2.0, 0.0008)), (0.0, 0.0), LIDAR_Z)
    assert sliver.enclosed is True
    crack = enclosure(square_room(door=(0, 2.0, 0.003)), (0.0, 0.0), LIDAR_Z)
    assert crack.enclosed is False
    assert crack.gaps[0].width == pytest.approx(0.003, abs=0.0005)
    assert crack.gaps[0].centre == pytest.approx((-0.4985, -2.5), abs=1e-4)


def test_spawn_inside_a_wall_or_obstacle_is_reported_as_such():
    e = enclosure(square_room(), (2.5, 0.0), LIDAR_Z)
    assert e.enclosed is None and e.inside == "room/Wall_1"
    pillar = Shape("cylinder", (1.0, 1.0, 0.25), radius=0.15, length=0.5, model="pillar")
    e = enclosure(square_room(extra=[pillar]), (1.05, 0.95), LIDAR_Z)
    assert e.enclosed is None and e.inside == "pillar"


@pytest.mark.parametrize("x", [2.4248, 2.5752])   # 0.2 mm inside and outside the right wall (faces at ±0.075)
def test_spawn_within_the_sliver_of_a_wall_counts_as_in_it(x):
    e = enclosure(square_room(), (x, 0.0), LIDAR_Z)
    assert e.enclosed is None and e.inside == "room/Wall_1"
    assert e.nearest == pytest.approx(0.0002, abs=1e-9)


def test_empty_world_and_lone_wall_are_not_enclosed():
    empty = enclosure(Scene(None, shapes=[Shape("plane", (0, 0, 0), normal=(0, 0, 1))]), (0.0, 0.0), LIDAR_Z)
    assert empty.enclosed is False and empty.has_walls is False
    lone = enclosure(Scene(None, shapes=[wall((-2, 1), (2, 1), "Wall_0")]), (0.0, 0.0), LIDAR_Z)
    assert lone.enclosed is False and lone.has_walls is True and lone.gaps == ()
    assert lone.nearest == pytest.approx(0.925, abs=1e-3)


def test_spawn_outside_a_closed_room_is_not_enclosed():
    e = enclosure(square_room(), (6.0, 0.0), LIDAR_Z)
    assert e.enclosed is False


# ------------------------------------------------------------------------------------------------ slicing

def test_box_sections_exact_for_upright_and_tilted_boxes():
    upright = section(Shape("box", (1.0, 2.0, 0.5), quat_yaw(0.3), size=(2.0, 0.5, 1.0)), LIDAR_Z)
    assert upright.area == pytest.approx(1.0)
    assert upright.centroid.x == pytest.approx(1.0) and upright.centroid.y == pytest.approx(2.0)
    # a 1 m cube tipped 45° about x, centred at z = 0.5: at height z the section is 1 m (x) by
    # 2·(0.5√2 − |z − 0.5|)
    a = math.pi / 4
    tipped = Shape("box", (0.0, 0.0, 0.5), (math.sin(a / 2), 0.0, 0.0, math.cos(a / 2)), size=(1.0, 1.0, 1.0))
    depth = 2 * (0.5 * math.sqrt(2) - (0.5 - LIDAR_Z))
    assert section(tipped, LIDAR_Z).area == pytest.approx(1.0 * depth, rel=1e-9)
    assert section(Shape("box", (0, 0, 1.0), size=(1, 1, 0.5)), LIDAR_Z) is None


def test_cylinder_and_sphere_sections():
    upright = section(Shape("cylinder", (0.0, 0.0, 0.25), radius=0.15, length=0.5), LIDAR_Z)
    assert upright.area == pytest.approx(math.pi * 0.15 ** 2, rel=0.01)
    # lying along x, axis at z = 0.15: the cut is a rectangle 1 m long and 2·sqrt(r² − 0.032²) wide
    lying = Shape("cylinder", (0.0, 0.0, 0.15), (0.0, math.sin(math.pi / 4), 0.0, math.cos(math.pi / 4)),
                  radius=0.15, length=1.0)
    assert section(lying, LIDAR_Z).area == pytest.approx(2 * math.sqrt(0.15 ** 2 - 0.032 ** 2), rel=0.01)
    ball = section(Shape("sphere", (0.0, 0.0, 0.2), radius=0.1), LIDAR_Z)
    assert ball.area == pytest.approx(math.pi * (0.1 ** 2 - 0.018 ** 2), rel=0.01)


def hex_ring_mesh(inner: float, outer: float, height: float):
    """A closed hexagonal ring (a wall round a hexagonal arena), vertices on ±x, as a triangle mesh."""
    angles = [i * math.pi / 3 for i in range(6)]
    verts = []
    for r in (outer, inner):
        for z in (0.0, height):
            verts += [(r * math.cos(a), r * math.sin(a), z) for a in angles]
    idx = {(ring, level, k): (ring * 2 + level) * 6 + k for ring in (0, 1) for level in (0, 1) for k in range(6)}
    faces = []
    for k in range(6):
        n = (k + 1) % 6
        for ring in (0, 1):        # the outer and inner side walls
            a, b, c, d = idx[ring, 0, k], idx[ring, 0, n], idx[ring, 1, n], idx[ring, 1, k]
            faces += [(a, b, c), (a, c, d)]
        for level in (0, 1):       # bottom and top annuli
            a, b, c, d = idx[0, level, k], idx[0, level, n], idx[1, level, n], idx[1, level, k]
            faces += [(a, b, c), (a, c, d)]
    return np.array(verts), np.array(faces)


def test_mesh_ring_section_is_the_ring_and_encloses_its_inside():
    v, f = hex_ring_mesh(2.933, 3.300, 1.27)
    ring = Shape("mesh", (0.0, 0.0, 0.0), vertices=v, faces=f, model="turtlebot3_world", link="wall")
    cut = section(ring, LIDAR_Z)
    hexagon_area = lambda r: 3 * math.sqrt(3) / 2 * r * r  # noqa: E731
    assert cut.area == pytest.approx(hexagon_area(3.3) - hexagon_area(2.933), rel=0.01)
    e = enclosure(Scene(None, shapes=[ring]), (-2.0, -0.5), LIDAR_Z)
    assert e.enclosed is True
    assert e.region_area == pytest.approx(hexagon_area(2.933), rel=0.01)


def test_open_mesh_sheet_still_blocks():
    # four zero-thickness vertical sheets (two triangles each) around the origin: not a closed solid
    verts, faces = [], []
    for (x0, y0), (x1, y1) in [((-1, -1), (1, -1)), ((1, -1), (1, 1)), ((1, 1), (-1, 1)), ((-1, 1), (-1, -1))]:
        n = len(verts)
        verts += [(x0, y0, 0.0), (x1, y1, 0.0), (x1, y1, 1.0), (x0, y0, 1.0)]
        faces += [(n, n + 1, n + 2), (n, n + 2, n + 3)]
    sheets = Shape("mesh", (0.0, 0.0, 0.0), vertices=np.array(verts, float), faces=np.array(faces))
    assert enclosure(Scene(None, shapes=[sheets]), (0.0, 0.0), LIDAR_Z).enclosed is True


def test_footprints_keep_labels_and_skip_what_the_plane_misses():
    scene = square_room(extra=[Shape("box", (1, 1, 1.5), size=(0.5, 0.5, 0.5), model="shelf")])
    labels = [p.label for p in footprints(scene, LIDAR_Z)]
    assert labels == ["room/Wall_0", "room/Wall_1", "room/Wall_2", "room/Wall_3"]


def test_analyse_without_footprints():
    assert analyse([], (0, 0), LIDAR_Z).has_walls is False
