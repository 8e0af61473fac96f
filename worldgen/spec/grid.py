"""ASCII grids: a maze or floorplan typed as text becomes straight walls.

Characters: ``#`` wall, ``.`` or space free floor, ``R`` the robot facing +x (or ``>`` ``^`` ``<`` ``v`` for a
heading of 0, π/2, π, −π/2). Row 0 is the top line; the grid's bottom-left corner sits at ``origin`` (default
(0, 0)), so the cell in row ``r`` and column ``c`` of an ``H``-row grid has its centre at
``(ox + (c + ½)·cell, oy + (H − r − ½)·cell)``: the picture is the top-down view, +x to the right, +y up.

Walls: a maximal horizontal run of two or more ``#`` can become one wall along the row's centre, from the first
to the last cell centre, one cell thick. A wall's box reaches half its thickness beyond its end points (the way
corners close), so the box covers the run's cells exactly. Vertical runs likewise. The runs are taken longest
first (rows before columns on a tie), and a run whose cells all lie in runs taken already adds nothing and is
dropped: a block two or more cells thick becomes a few walls along its longer side (a 3-cell-thick wall 200 cells
long is 3 walls, not 200), which keeps a scanned map (:mod:`worldgen.spec.maps`) to a sane number of boxes.
A lone ``#`` (no ``#`` left, right, above or below it) has no run to belong to; it becomes a square post.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Sequence, Tuple

from ..core.errors import SpecError

Point = Tuple[float, float]

WALL = "#"
FREE = frozenset(". ")
ROBOT_HEADINGS = {"R": 0.0, ">": 0.0, "^": math.pi / 2, "<": math.pi, "v": -math.pi / 2}
POST_PREFIX = "grid_post_"   # a lone cell's post is the obstacle named grid_post_ROW_COLUMN (from 1)
LEGEND = "use # for a wall, . or space for free floor, R or > ^ < v for the robot and its heading"
MAX_CELLS = 64_000_000   # cells of one grid (as many as a map may have pixels)
MAX_PIECES = 50_000      # walls and posts one grid may become


@dataclass(frozen=True)
class GridPlan:
    """What a grid holds, in metres: wall centre-lines (start, end), lone-cell posts, the robot's pose."""

    walls: tuple[tuple[Point, Point], ...]
    posts: tuple[tuple[int, int, Point], ...]   # (row, column, centre) of each lone '#'
    robot: tuple[Point, float] | None             # (x, y), yaw
    rows: int
    columns: int


def plan_grid(rows: Sequence[str], cell: float, origin: Point = (0.0, 0.0), *, source: str | None = None,
              row_lines: Sequence[int | None] | None = None, max_pieces: int | None = MAX_PIECES) -> GridPlan:
    """Turn grid rows (top row first) into walls, posts and the robot pose.

    ``row_lines`` gives each row's line in ``source`` so that a bad character is reported where it is.
    Raises SpecError for an unknown character, a second robot, a grid without any wall, or one that makes more
    than ``max_pieces`` walls and posts (None: no limit; the caller checks).
    """
    def line_of(r: int) -> int | None:
        return row_lines[r] if row_lines is not None and r < len(row_lines) else None

    width = max((len(row) for row in rows), default=0)
    if width * len(rows) > MAX_CELLS:
        raise SpecError(f"the grid has {width} × {len(rows)} cells, more than the {MAX_CELLS:,} worldgen reads",
                        path=source, line=line_of(0), hint="use a coarser cell (see Limits in the README)")
    grid = [row.ljust(width) for row in rows]
    height = len(grid)
    if max_pieces is not None:
        _refuse_lone_cells(grid, max_pieces, source, line_of(0))
    ox, oy = origin

    def centre(r: int, c: int) -> Point:
        return (round(ox + (c + 0.5) * cell, 9), round(oy + (height - r - 0.5) * cell, 9))

    robot = None
    for r, row in enumerate(grid):
        for c, ch in enumerate(row):
            if ch == WALL or ch in FREE:
                continue
            if ch in ROBOT_HEADINGS:
                if robot is not None:
                    raise SpecError(f"the grid places the robot twice (row {r + 1}, column {c + 1})",
                                    path=source, line=line_of(r), hint="keep one R, >, ^, < or v in the grid")
                robot = (centre(r, c), ROBOT_HEADINGS[ch])
                continue
            shown = "a tab" if ch == "\t" else repr(ch)
            raise SpecError(f"the grid has {shown} in row {r + 1}, column {c + 1}",
                            path=source, line=line_of(r), hint=LEGEND)

    is_wall = [[ch == WALL for ch in row] for row in grid]
    if not any(any(row) for row in is_wall):
        raise SpecError("the grid has no walls", path=source, line=line_of(0), hint=LEGEND)

    # (length, 0 for a row or 1 for a column, its index, first and last cell along it)
    runs = [(c1 - c0, 0, r, c0, c1) for r in range(height) for c0, c1 in _runs(is_wall[r])]
    runs += [(r1 - r0, 1, c, r0, r1) for c in range(width)
             for r0, r1 in _runs([is_wall[r][c] for r in range(height)])]
    covered = [[False] * width for _ in range(height)]
    taken = []
    for run in sorted(runs, key=lambda run: (-run[0], run[1:])):
        _, vertical, k, a, b = run
        cells = [(i, k) if vertical else (k, i) for i in range(a, b + 1)]
        if all(covered[r][c] for r, c in cells):
            continue
        for r, c in cells:
            covered[r][c] = True
        taken.append(run[1:])
    walls = [(centre(b, k), centre(a, k)) if vertical else (centre(k, a), centre(k, b))   # columns bottom to top
             for vertical, k, a, b in sorted(taken)]                                     # rows first, top down

    posts = tuple((r, c, centre(r, c)) for r in range(height) for c in range(width)
                  if is_wall[r][c] and not _has_wall_neighbour(is_wall, r, c))
    if max_pieces is not None and len(walls) + len(posts) > max_pieces:
        raise SpecError(f"the grid makes {len(walls) + len(posts):,} walls and posts, more than the {max_pieces:,} "
                        "worldgen builds from one grid", path=source, line=line_of(0),
                        hint="join the lone # cells into walls, or use a coarser cell (see Limits in the README)")
    return GridPlan(tuple(walls), posts, robot, height, width)


def _refuse_lone_cells(grid: Sequence[str], max_pieces: int, source: str | None, line: int | None) -> None:
    """SpecError at once when the lone ``#`` cells alone (each a post) are more than ``max_pieces``."""
    if len(grid) * len(grid[0] if grid else "") <= max_pieces:
        return
    import numpy as np

    cells = np.array([np.frombuffer(row.encode("utf-32-le"), dtype=np.uint32) for row in grid]) == ord(WALL)
    padded = np.pad(cells, 1)
    lone = int((cells & ~(padded[:-2, 1:-1] | padded[2:, 1:-1] | padded[1:-1, :-2] | padded[1:-1, 2:])).sum())
    if lone > max_pieces:
        raise SpecError(f"the grid makes {lone:,} posts (lone # cells) at least, more than the {max_pieces:,} walls "
                        "and posts worldgen builds from one grid", path=source, line=line,
                        hint="join the lone # cells into walls, or use a coarser cell (see Limits in the README)")


def _runs(cells: Sequence[bool]) -> list[tuple[int, int]]:
    """Index ranges (first, last) of the maximal runs of True at least two long."""
    runs, start = [], None
    for i, on in enumerate([*cells, False]):
        if on and start is None:
            start = i
        elif not on and start is not None:
            if i - start >= 2:
                runs.append((start, i - 1))
            start = None
    return runs


def _has_wall_neighbour(is_wall: list[list[bool]], r: int, c: int) -> bool:
    for dr, dc in ((0, 1), (0, -1), (1, 0), (-1, 0)):
        rr, cc = r + dr, c + dc
        if 0 <= rr < len(is_wall) and 0 <= cc < len(is_wall[rr]) and is_wall[rr][cc]:
            return True
    return False
