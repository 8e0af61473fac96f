"""Floorplan geometry in numbers: corners close exactly, shared walls are written once, openings split walls where
the spec puts them, and what only geometry can tell is refused with the spec line."""

from __future__ import annotations

import math
import re

import pytest
import shapely
import shapely.ops
from shapely.geometry import LineString, Point, Polygon
from shapely.ops import unary_union

from worldgen.core.errors import SpecError
from worldgen.geometry.building import build_geometry
from worldgen.geometry.joins import JOIN_TOLERANCE
from worldgen.spec.model import Material, Obstacle, Opening, Room, Segment, Spec, WallStyle

STYLE = WallStyle()
T = STYLE.thickness


def rect_room(name, x0, y0, x1, y1, openings=(), style=STYLE, line=None):
    return Room(name, ((x0, y0), (x1, y0), (x1, y1), (x0, y1)), style, tuple(openings), line=line)


def door(wall, offset, width=0.9, height=2.0, line=None):
    return Opening("door", wall, offset, width, height, 0.0, line=line)


def window(wall, offset, width=0.8, height=0.8, sill=0.5, line=None):
    return Opening("window", wall, offset, width, height, sill, line=line)


def piece_polygons(building, z):
    """Footprints of every box (wall piece or filler) that spans height z."""
    polys = []
    for w in building.walls:
        dx, dy = (w.end[0] - w.start[0]) / w.length, (w.end[1] - w.start[1]) / w.length
        nx, ny, h = -dy, dx, w.thickness / 2
        for p in w.pieces:
            if p.z0 <= z <= p.z1:
                a = (w.start[0] + dx * p.s0, w.start[1] + dy * p.s0)
                b = (w.start[0] + dx * p.s1, w.start[1] + dy * p.s1)
                polys.append(Polygon([(a[0] - nx * h, a[1] - ny * h), (b[0] - nx * h, b[1] - ny * h),
                                      (b[0] + nx * h, b[1] + ny * h), (a[0] + nx * h, a[1] + ny * h)]))
    return polys


def ideal_band(spec):
    """The mitred wall band a person means: every room's ring, every chain of segments (mitred where two meet,
    flat where they end on another wall) and a half-thickness square at each free end."""
    parts = [Polygon(r.vertices).buffer(r.style.thickness / 2, join_style="mitre", mitre_limit=1e3).difference(
             Polygon(r.vertices).buffer(-r.style.thickness / 2, join_style="mitre", mitre_limit=1e3))
             for r in spec.rooms]
    if spec.segments:
        h = spec.segments[0].style.thickness / 2
        lines = [LineString([s.start, s.end]) for s in spec.segments]
        merged = shapely.line_merge(unary_union(lines))
        parts += [g.buffer(h, cap_style="flat", join_style="mitre", mitre_limit=1e3)
                  for g in getattr(merged, "geoms", [merged])]
        for line in lines:
            for a, b in ((0, 1), (-1, -2)):
                end, prev = line.coords[a], line.coords[b]
                if sum(Point(end).distance(g) < 1e-9 for g in lines + [Polygon(r.vertices).exterior
                                                                         for r in spec.rooms]) == 1:
                    cap = LineString([end, (2 * end[0] - prev[0], 2 * end[1] - prev[1])])
                    parts.append(shapely.ops.substring(cap, 0, h).buffer(h, cap_style="flat"))
    return unary_union(parts)


def assert_matches_ideal(union, ideal, tol=JOIN_TOLERANCE):
    """No box pokes out of the ideal band by more than tol, no part of the band is farther than tol from a box,
    and the symmetric difference is below 1e-4 m²."""
    assert union.difference(ideal.buffer(tol)).area < 1e-12
    assert ideal.difference(union.buffer(tol)).area < 1e-12
    assert union.symmetric_difference(ideal).area < 1e-4


def polyline_spec(points, style=STYLE):
    return Spec("c", segments=tuple(Segment(points[i], points[i + 1], style) for i in range(len(points) - 1)))


# ------------------------------------------------------------------------------------------------ corners
def test_editor_room_has_the_editor_numbers():
    """The class's enclosed room: centre-lines 4.85 m apart make four 5.0 m boxes (4.85 + 0.15) meeting at the
    corners, and the model pose is the walls' bounding-box centre."""
    b = build_geometry(Spec("room", rooms=(rect_room("main", -1, -2, 3.85, 2.85),)))
    assert [round(w.length, 9) for w in b.walls] == [5.0] * 4
    assert b.origin == pytest.approx((1.425, 0.425))
    assert b.bounds == pytest.approx((-1.075, -2.075, 3.925, 2.925))
    assert all(len(w.pieces) == 1 and not w.filler for w in b.walls)


@pytest.mark.parametrize("degrees", [5, 30, 45, 60, 89, 90, 100, 120, 150, 175])
def test_corner_closes_like_the_ideal_mitre(degrees):
    """Two walls meeting at any angle: the boxes' union equals the mitred band within 1 mm (nothing pokes out,
    nothing is missing). Corners sharper than 90° need filler boxes; the others none."""
    a = math.radians(degrees)
    o = (1.0, 2.0)
    spec = polyline_spec([(o[0] + 3, o[1]), o, (o[0] + 3 * math.cos(a), o[1] + 3 * math.sin(a))])
    b = build_geometry(spec)
    assert_matches_ideal(unary_union(piece_polygons(b, 1.0)), ideal_band(spec))
    fillers = sum(w.filler for w in b.walls)
    assert (fillers > 0) == (degrees < 90)
    assert fillers <= 2 * 12


def test_free_ends_reach_half_the_thickness():
    b = build_geometry(Spec("s", segments=(Segment((0, 0), (5, 0), STYLE),)))
    (w,) = b.walls
    assert w.start == pytest.approx((-T / 2, 0)) and w.end == pytest.approx((5 + T / 2, 0))


@pytest.mark.parametrize("vertices", [
    [(0, 0), (6, 0), (6, 3), (3, 3), (3, 6), (0, 6)],                                  # L-shape (a 270° corner)
    [(0, 0), (5, 0), (5 * math.cos(math.pi / 6), 5 * math.sin(math.pi / 6))],           # 30°, 75°, 75°
    [(0, 0), (4, 0), (4, 2), (2, 2 + 2 * math.tan(math.radians(15))), (0, 2)],          # a 150° corner
    [(math.cos(t) * 3 + 1, math.sin(t) * 3 - 2) for t in (0.3 + k * math.pi / 3 for k in range(6))],  # hexagon
])
def test_polygon_rooms_close_exactly(vertices):
    spec = Spec("p", rooms=(Room("r", tuple(vertices), STYLE),))
    b = build_geometry(spec)
    union = unary_union(piece_polygons(b, 0.18))
    assert_matches_ideal(union, ideal_band(spec))
    inside = Polygon(vertices).buffer(-T / 2, join_style="mitre")
    free = inside.buffer(-0.01).representative_point()
    region = [g for g in getattr(shapely.box(*union.buffer(1).bounds).difference(union.buffer(0.0005)), "geoms", [])
              if g.contains(free)]
    assert len(region) == 1    # the room's floor, closed off, and all of it (less the 0.5 mm buffer):
    assert 0 <= inside.area - region[0].area < inside.length * 0.0006


def test_y_junction_and_fan_close():
    """Three walls ending at one point 120° apart (a Y), and a wall ending in a room's corner (a fan)."""
    y = Spec("y", segments=tuple(Segment((0, 0), (3 * math.cos(t), 3 * math.sin(t)), STYLE)
                                 for t in (0.2, 0.2 + 2 * math.pi / 3, 0.2 + 4 * math.pi / 3)))
    assert_matches_ideal(unary_union(piece_polygons(build_geometry(y), 1)), ideal_band(y))
    fan = Spec("f", rooms=(rect_room("r", 0, 0, 4, 4),), segments=(Segment((0, 0), (2, 1.2), STYLE),))
    assert_matches_ideal(unary_union(piece_polygons(build_geometry(fan), 1)), ideal_band(fan))


def test_t_junction_stem_reaches_the_far_face_at_any_angle():
    for degrees in (90, 60, 30):
        a = math.radians(degrees)
        spec = Spec("t", segments=(Segment((-3, 0), (3, 0), STYLE),
                                   Segment((0, 0), (2 * math.cos(a), 2 * math.sin(a)), STYLE)))
        assert_matches_ideal(unary_union(piece_polygons(build_geometry(spec), 1)), ideal_band(spec))


# ------------------------------------------------------------------------------------------- shared walls
def boxes_covering(building, point, z=1.0):
    return sum(poly.contains(Point(point)) for poly in piece_polygons(building, z))


def test_shared_wall_is_one_box():
    spec = Spec("two", rooms=(rect_room("a", 0, 0, 4, 3), rect_room("b", 4, 0, 7, 3)))
    b = build_geometry(spec)
    assert len(b.walls) == 7 - 2      # 8 sides, the shared one once, the bottoms and tops merged into one line each
    for y in (0.3, 1.5, 2.7):
        assert boxes_covering(b, (4.0, y)) == 1
    shared = [w for w in b.walls if w.rooms == ("a", "b") and abs(w.start[0] - w.end[0]) < 1e-9]
    assert len(shared) == 1
    assert_matches_ideal(unary_union(piece_polygons(b, 1)), ideal_band(spec))


def test_big_side_stays_one_wall_when_a_small_room_shares_part_of_it():
    spec = Spec("lr", rooms=(rect_room("big", 0, 0, 6, 6), rect_room("small", 6, 2, 9, 4)))
    b = build_geometry(spec)
    east = [w for w in b.walls if abs(w.start[0] - 6) < 1e-9 and abs(w.end[0] - 6) < 1e-9]
    assert len(east) == 1 and east[0].length == pytest.approx(6 + T)
    assert east[0].rooms == ("big", "small")
    assert boxes_covering(b, (6, 3)) == 1
    assert_matches_ideal(unary_union(piece_polygons(b, 1)), ideal_band(spec))


def test_collinear_walls_of_different_materials_stay_two_and_still_close():
    brick = WallStyle(material=Material(script="Gazebo/Bricks"))
    spec = Spec("m", rooms=(rect_room("a", 0, 0, 4, 3), rect_room("b", 4, 0, 7, 3, style=brick)))
    b = build_geometry(spec)
    bottoms = sorted((w for w in b.walls if abs(w.start[1]) < 1e-9 and abs(w.end[1]) < 1e-9),
                     key=lambda w: min(w.start[0], w.end[0]))
    assert [w.material.script for w in bottoms] == ["Gazebo/Grey", "Gazebo/Bricks"]
    assert max(bottoms[0].start[0], bottoms[0].end[0]) >= min(bottoms[1].start[0], bottoms[1].end[0])  # no gap
    assert_matches_ideal(unary_union(piece_polygons(b, 1)), ideal_band(spec))
    shared = [w for w in b.walls if w.rooms == ("a", "b")]
    assert len(shared) == 1 and shared[0].material.script == "Gazebo/Grey"   # the first room drawn wins


def test_grid_of_rooms_closes_every_room():
    rooms = tuple(rect_room(f"r{i}{j}", 3 * i, 3 * j, 3 * i + 3, 3 * j + 3, [door(1, 1.0)] if i < 2 else [])
                  for i in range(3) for j in range(3))
    spec = Spec("grid", rooms=rooms)
    b = build_geometry(spec)
    assert len(b.walls) == 8                      # four lines each way
    union = unary_union(piece_polygons(b, 2.2))   # above the doors
    assert_matches_ideal(union, ideal_band(spec))
    free = shapely.box(-1, -1, 10, 10).difference(union.buffer(0.0005))
    assert len(free.geoms) == 10                  # nine rooms and the outside


# ------------------------------------------------------------------------------------------------ openings
def test_openings_split_walls_like_the_editor():
    spec = Spec("o", rooms=(rect_room("r", 0, 0, 5, 4, [door(0, 1.0), window(2, 2.0)]),))
    b = build_geometry(spec)
    south, north = b.walls[0], b.walls[2]
    e = T / 2
    assert [c for p in south.pieces for c in (p.s0, p.s1, p.z0, p.z1)] == pytest.approx(
        [0, 1 + e, 0, 2.5, 1 + e, 1.9 + e, 2.0, 2.5, 1.9 + e, 5 + 2 * e, 0, 2.5])
    assert [c for p in north.pieces for c in (p.s0, p.s1, p.z0, p.z1)] == pytest.approx(
        [0, 2 + e, 0, 2.5, 2 + e, 2.8 + e, 0, 0.5, 2 + e, 2.8 + e, 1.3, 2.5, 2.8 + e, 5 + 2 * e, 0, 2.5])
    assert [(o.type, o.s0, o.z1) for o in north.openings] == [("window", pytest.approx(2 + e), pytest.approx(1.3))]


def test_full_height_door_has_no_lintel():
    b = build_geometry(Spec("o", rooms=(rect_room("r", 0, 0, 5, 4, [door(0, 1.0, height=2.5)]),)))
    assert [(p.z0, p.z1) for p in b.walls[0].pieces] == [(0, 2.5), (0, 2.5)]


def test_shared_wall_door_listed_by_both_rooms_counts_once():
    spec = Spec("d", rooms=(rect_room("a", 0, 0, 4, 3, [door(1, 1.0)]),
                            rect_room("b", 4, 0, 7, 3, [door(3, 3 - 1.0 - 0.9)])))  # b's wall 3 runs downwards
    (shared,) = [w for w in build_geometry(spec).walls if w.start[0] == w.end[0] == 4]
    assert len(shared.openings) == 1 and shared.rooms == ("a", "b")


def spec_error(spec) -> SpecError:
    with pytest.raises(SpecError) as info:
        build_geometry(spec)
    return info.value


def test_overlapping_openings_on_a_shared_wall_name_the_line():
    spec = Spec("d", source="plan.yaml", rooms=(
        rect_room("a", 0, 0, 4, 3, [door(1, 1.0, line=7)]),
        rect_room("b", 4, 0, 7, 3, [window(3, 1.0, line=12)])))
    err = spec_error(spec)
    assert err.line == 12 and str(err).startswith("plan.yaml:12: ")
    assert "overlaps the door" in str(err) and "line 7" in str(err)


def test_opening_across_a_t_junction_is_refused():
    spec = Spec("t", source="plan.yaml", rooms=(
        rect_room("big", 0, 0, 6, 6, [door(1, 2.5, line=4)]), rect_room("small", 6, 3, 9, 5)))
    err = spec_error(spec)
    assert err.line == 4 and "runs into room 'small'" in str(err)


def test_opening_into_a_corner_is_refused():
    err = spec_error(Spec("c", rooms=(rect_room("r", 0, 0, 4, 3, [door(0, 3.1 - 0.02, line=9)]),)))
    assert err.line == 9 and "runs into" in str(err)


def test_opening_past_the_end_of_its_wall_is_refused():
    err = spec_error(Spec("c", rooms=(rect_room("r", 0, 0, 4, 3, [door(1, 2.5, line=3)]),)))
    assert err.line == 3 and re.search(r"does not fit on room 'r' wall 1, which is 3 m long", str(err))


def test_shared_wall_of_two_thicknesses_is_refused():
    thick = WallStyle(thickness=0.3)
    err = spec_error(Spec("c", rooms=(rect_room("a", 0, 0, 4, 3, line=2),
                                      rect_room("b", 4, 0, 7, 3, style=thick, line=5))))
    assert err.line == 5 and "share a wall" in str(err)


def test_obstacle_names_must_be_unique_across_the_world():
    err = spec_error(Spec("house", obstacles=(Obstacle("sphere", (0, 0), radius=0.2, name="ground_plane", line=8),)))
    assert err.line == 8 and err.message == "obstacle name 'ground_plane' is already used by the ground plane"
    err = spec_error(Spec("house", obstacles=(Obstacle("sphere", (0, 0), radius=0.2, name="house", line=3),)))
    assert err.line == 3 and err.message.endswith("is already used by the building")
    # an unnamed obstacle gets obstacle_N (N from 0); a name written elsewhere may take it
    err = spec_error(Spec("house", obstacles=(Obstacle("sphere", (0, 0), radius=0.2, name="obstacle_1", line=4),
                                              Obstacle("sphere", (2, 0), radius=0.2, line=5))))
    assert err.line == 5 and err.message == ("obstacle 2 has no name, and the one it gets, 'obstacle_1', is already "
                                             "used by the obstacle on line 4")


def test_bounds_cover_obstacles_and_builds_repeat_exactly():
    spec = Spec("b", rooms=(rect_room("r", 0, 0, 4, 3),),
                obstacles=(Obstacle("box", (6, 1), yaw=math.pi / 4, size=(1, 1, 1)),
                           Obstacle("cylinder", (-2, 5), radius=0.5, height=1)))
    b = build_geometry(spec)
    assert b.origin == pytest.approx((2, 1.5))
    assert b.bounds == pytest.approx((-2.5, -T / 2, 6 + math.sqrt(0.5), 5.5))
    assert build_geometry(spec) == b
