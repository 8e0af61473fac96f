"""Reading an ASCII grid into a spec: a spec's ``grid:`` block (cell, rows, origin, wall height and material), or a
whole ``.txt`` file as a spec. The grid itself is planned into walls, posts and the robot by
:func:`worldgen.spec.grid.plan_grid`."""

from __future__ import annotations

from . import values
from .grid import POST_PREFIX, plan_grid
from .messages import describe, metres, suggest_name
from .model import DEFAULT_CELL, GRID_KEYS, LIMIT, Obstacle, RobotPose, Segment, Spec, WallStyle
from .nodes import Node
from .values import Source


def read_grid(src: Source, node: Node, base: WallStyle) -> tuple[list[Segment], list[Obstacle], tuple | None]:
    keys = values.mapping(src, node, "grid", GRID_KEYS, required=("rows",))
    cell = values.length(src, keys["cell"], "grid cell") if "cell" in keys else DEFAULT_CELL
    origin = values.point(src, keys["origin"], "grid origin") if "origin" in keys else (0.0, 0.0)
    height = values.length(src, keys["height"], "grid height") if "height" in keys else base.height
    material = values.material(src, keys["material"], "grid material") if "material" in keys else base.material
    rows_node = keys["rows"]
    value = rows_node.value
    if isinstance(value, str):
        if rows_node.style == ">":
            src.fail("grid rows are folded into one line by '>'", rows_node.line,
                     hint="write rows: | for a literal block, so that each line stays a row")
        rows = value.split("\n")
        if rows and rows[-1] == "":
            rows.pop()
        if rows_node.style == "|":   # a literal block: row i is i + 1 lines below 'rows: |'
            row_lines = [rows_node.line + 1 + i for i in range(len(rows))]
        else:                        # one quoted text: every row is on its line
            row_lines = [rows_node.line] * len(rows)
    elif isinstance(value, list):
        for i, row in enumerate(value):
            if not isinstance(row.value, str):
                src.fail(f"grid row {i + 1} must be a line of text, not {describe(row.value)}", row.line,
                         hint='quote each row, e.g. - "#####" (an unquoted # starts a comment), or write '
                              "rows: | and the grid below it")
        rows, row_lines = [r.value for r in value], [r.line for r in value]
    else:
        src.fail(f"grid rows must be text lines, not {describe(value)}", rows_node.line,
                 hint="write rows: | and the grid below it, one line per row")
    return grid_parts(src, rows, row_lines, cell, origin, WallStyle(cell, height, material), rows_node.line)


def grid_parts(src: Source, rows, row_lines, cell, origin, style, line):
    columns = max((len(r) for r in rows), default=0)
    if not rows or not columns:
        src.fail("the grid is empty", line, hint="draw walls with #, one character per cell")
    extent = [origin[0], origin[1], origin[0] + columns * cell, origin[1] + len(rows) * cell]
    if max(abs(v) for v in extent) > LIMIT:
        src.fail(f"the grid reaches farther than {LIMIT:g} m from the origin ({len(rows)} rows × {columns} "
                 f"columns of {metres(cell)} m)", line, hint="use a smaller cell, in metres, or a smaller grid")
    plan = plan_grid(rows, cell, origin, source=src.path, row_lines=row_lines)
    segments = [Segment(start=a, end=b, style=style, line=line) for a, b in plan.walls]
    posts = [Obstacle(shape="box", at=at, size=(cell, cell, style.height), material=style.material,
                      name=f"{POST_PREFIX}{r + 1}_{c + 1}", line=row_lines[r]) for r, c, at in plan.posts]
    return segments, posts, plan.robot


def read_grid_file(src: Source, text: str, stem: str) -> Spec:
    """A plain ``.txt`` grid: the whole file is the grid, with the default cell and walls."""
    rows = text.split("\n")
    if rows and rows[-1] == "":
        rows.pop()
    rows = [r.rstrip("\r") for r in rows]
    name = suggest_name(stem)
    segments, posts, robot = grid_parts(src, rows, list(range(1, len(rows) + 1)), DEFAULT_CELL, (0.0, 0.0),
                                        WallStyle(thickness=DEFAULT_CELL), 1)
    pose = RobotPose(at=robot[0], yaw=robot[1], line=1) if robot else None
    return Spec(name=name, segments=tuple(segments), obstacles=tuple(posts), robot=pose, source=src.path)
