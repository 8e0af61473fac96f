"""ASCII grids: walls where the '#' are, exactly, in metres."""

from __future__ import annotations

import math

import pytest
import shapely

from worldgen.core.errors import SpecError
from worldgen.spec.grid import plan_grid
from worldgen.spec.load import parse_spec

MAZE3 = ["#####",
         "#R..#",
         "#####"]


def test_three_line_maze_in_numbers():
    plan = plan_grid(MAZE3, 0.5)
    assert (plan.rows, plan.columns) == (3, 5)
    # Row 0 is the top: its centre-line is at y = (3 - 0.5) * 0.5; the grid's bottom-left corner is (0, 0).
    assert sorted(plan.walls) == sorted([
        ((0.25, 1.25), (2.25, 1.25)),   # top row
        ((0.25, 0.25), (2.25, 0.25)),   # bottom row
        ((0.25, 0.25), (0.25, 1.25)),   # left column, bottom to top
        ((2.25, 0.25), (2.25, 1.25)),   # right column
    ])
    assert plan.posts == ()
    assert plan.robot == ((0.75, 0.75), 0.0)


def _wall_boxes(walls, thickness):
    """The footprint of each wall's box: its centre-line reaching thickness/2 beyond both ends."""
    boxes = []
    for (x0, y0), (x1, y1) in walls:
        line = shapely.LineString([(x0, y0), (x1, y1)])
        boxes.append(line.buffer(thickness / 2, cap_style="square"))
    return boxes


def _cells(rows, cell, char="#"):
    h = len(rows)
    return [shapely.box(c * cell, (h - r - 1) * cell, (c + 1) * cell, (h - r) * cell)
            for r, row in enumerate(rows) for c, ch in enumerate(row) if ch == char]


@pytest.mark.parametrize("rows", [
    MAZE3,
    ["##########",
     "#R   #   #",
     "#  ###   #",
     "#    # # #",
     "#### #   #",
     "#      # #",
     "##########"],
    ["#  #", " ## ", "#  #", "####", "####"],     # lone cells, a thick block, a T
])
def test_wall_boxes_cover_the_wall_cells_exactly(rows):
    cell = 0.4
    plan = plan_grid(rows, cell)
    built = _wall_boxes(plan.walls, cell) + [shapely.box(x - cell / 2, y - cell / 2, x + cell / 2, y + cell / 2)
                                            for _, _, (x, y) in plan.posts]
    drawn = shapely.union_all(_cells(rows, cell))
    covered = shapely.union_all(built)
    assert covered.symmetric_difference(drawn).area < 1e-9
    # no wall is a zero-length segment (the geometry module refuses those)
    assert all(math.dist(a, b) >= cell - 1e-9 for a, b in plan.walls)


def test_lone_cell_is_a_post_and_thick_block_has_no_vertical_walls():
    plan = plan_grid(["#...", "....", "####", "####"], 1.0)
    assert plan.posts == ((0, 0, (0.5, 3.5)),)
    assert sorted(plan.walls) == [((0.5, 0.5), (3.5, 0.5)), ((0.5, 1.5), (3.5, 1.5))]


def test_thick_blocks_become_walls_along_their_longer_side():
    # a block 3 cells wide and 6 tall: 3 walls up it, not 6 across it
    plan = plan_grid(["###"] * 6, 1.0)
    assert sorted(plan.walls) == [((0.5, 0.5), (0.5, 5.5)), ((1.5, 0.5), (1.5, 5.5)), ((2.5, 0.5), (2.5, 5.5))]
    # an L with arms two cells thick: two walls along each arm, the corner square in both
    plan = plan_grid(["##....", "##....", "##....", "######", "######"], 1.0)
    assert sorted(plan.walls) == sorted([((0.5, 0.5), (0.5, 4.5)), ((1.5, 0.5), (1.5, 4.5)),
                                         ((0.5, 0.5), (5.5, 0.5)), ((0.5, 1.5), (5.5, 1.5))])


def test_origin_shifts_everything_and_headings_set_yaw():
    for mark, yaw in (("R", 0.0), (">", 0.0), ("^", math.pi / 2), ("<", math.pi), ("v", -math.pi / 2)):
        plan = plan_grid(["###", f"#{mark}#", "###"], 1.0, origin=(10.0, -5.0))
        assert plan.robot == ((11.5, -3.5), yaw)
        assert ((10.5, -2.5), (12.5, -2.5)) in plan.walls


def test_short_rows_are_padded_with_free_cells():
    plan = plan_grid(["###", "#", "###"], 1.0)
    assert plan.columns == 3
    assert ((0.5, 0.5), (0.5, 2.5)) in plan.walls
    assert ((2.5, 0.5), (2.5, 2.5)) not in plan.walls


@pytest.mark.parametrize("rows, words, line", [
    (["###", "#x#", "###"], ["'x'", "row 2, column 2"], 11),
    (["###", "#\t#", "###"], ["a tab", "row 2"], 11),
    (["#R#", "#R#"], ["robot twice", "row 2"], 11),
    (["...", ". ."], ["no walls"], 10),
])
def test_grid_errors_name_the_row_and_line(rows, words, line):
    with pytest.raises(SpecError) as err:
        plan_grid(rows, 0.5, source="m.yaml", row_lines=list(range(10, 10 + len(rows))))
    text = str(err.value)
    assert text.startswith(f"m.yaml:{line}: ")
    for word in words:
        assert word in text


SPEC = """\
name: maze
walls: {height: 0.5, material: Gazebo/Wood}
robot: {model: waffle}
grid:
  cell: 0.25
  rows: |
    ######
    #>   #
    #  # #
    #    #
    ######
"""


def test_grid_in_a_spec_becomes_segments_with_the_cell_as_thickness():
    spec = parse_spec(SPEC, "maze.yaml")
    assert spec.rooms == ()
    assert {s.style.thickness for s in spec.segments} == {0.25}
    assert {s.style.height for s in spec.segments} == {0.5}
    assert {s.style.material.script for s in spec.segments} == {"Gazebo/Wood"}
    # the lone '#' in row 3 (line 9) is a cell-sized post, as tall as the walls
    (post,) = spec.obstacles
    assert (post.shape, post.at, post.size, post.name, post.line) == (
        "box", (0.875, 0.625), (0.25, 0.25, 0.5), "grid_post_3_4", 9)
    assert (spec.robot.model, spec.robot.at, spec.robot.yaw) == ("waffle", (0.375, 0.875), 0.0)


def test_grid_height_overrides_walls_and_rows_may_be_a_list():
    spec = parse_spec('name: m\ngrid: {cell: 1, height: 1.2, origin: [-2, -1], rows: ["###", "# #", "###"]}\n')
    assert {s.style.height for s in spec.segments} == {1.2}
    assert ((-1.5, -0.5), (0.5, -0.5)) in [(s.start, s.end) for s in spec.segments]


def test_grid_error_lines_point_into_the_block():
    with pytest.raises(SpecError) as err:
        parse_spec(SPEC.replace("#  # #", "#  * #"), "maze.yaml")
    assert str(err.value).startswith("maze.yaml:9: the grid has '*' in row 3, column 4")


def test_txt_grid_file(tmp_path):
    from worldgen.spec.load import load_spec

    path = tmp_path / "small-maze.txt"
    path.write_text("####\n#^ #\n####\n")
    spec = load_spec(path)
    assert spec.name == "small_maze"
    assert {s.style.thickness for s in spec.segments} == {0.5}
    assert spec.robot.at == (0.75, 0.75) and spec.robot.yaw == pytest.approx(math.pi / 2)
