"""``maze``: a maze on a grid of square cells wide enough for the robot to turn in, perfect (one way between any two
cells) or with a share of its inner walls taken out (loops), closed or with an entrance and an exit.

The maze is carved by a depth-first walk from a random cell (the recursive backtracker, with its own stack); each
inner wall it leaves is then taken out with the chance ``loops``. Its outline is one room, ``maze``; its inner
walls are free-standing segments, one per straight run. With ``exits`` a door in the left wall leads from a closed
one-cell lobby (``entrance``, where the robot starts facing in) and one in the right wall into another (``exit``,
with a green disc on its floor), so the world stays closed, as ``validate`` wants, and still has a way in and a
way out. Without, the robot starts in the cell the walk began in, facing the longest open run.

A cell is the robot's turning circle plus :data:`~worldgen.generate.robot.TURN_MARGIN` on each side plus a wall,
rounded up to 5 cm (0.85 m for a Waffle Pi, 0.6 m for a Burger), so every cell is a place it can turn round in.
"""

from __future__ import annotations

import math
from typing import List, Optional, Set, Tuple

from ..spec.model import Material, FloorPatch, Opening, RobotPose, Room, Segment, Spec, WallStyle
from .options import MazeOptions
from .rng import Rng
from .robot import RobotSpace
from .trig import HALF_PI, PI

THICKNESS = 0.15
GRAIN = 0.05          # m: cells are a multiple of this
DOOR_SLACK = 0.05     # m: a door keeps this far from the walls meeting the outline either side of its cell
MATERIAL = Material("Gazebo/Wood")
GOAL_COLOUR = Material("Gazebo/Green")
Cell = Tuple[int, int]
Wall = Tuple[str, int, int]   # ("v", i, j): between cells (i, j) and (i+1, j); ("h", i, j): (i, j) and (i, j+1)


def resolve(options: MazeOptions, space: RobotSpace) -> MazeOptions:
    """The options with the cell sized for the robot when none is given; InputError for a given cell the robot
    cannot turn round in (a world that would then fail validate: spawned in a wall, touching them as it spins)."""
    from dataclasses import replace

    from ..core.errors import InputError

    least = round(math.ceil((THICKNESS + 2 * space.clearance) / GRAIN - 1e-9) * GRAIN, 3)
    if options.cell is None:
        return replace(options, cell=least)
    if options.cell < least - 1e-9:
        raise InputError(f"--cell {options.cell:g} leaves the {space.model} no room to turn in a cell",
                         hint=f"give --cell at least {least:g}, or leave it out")
    return options


def _carve(cols: int, rows: int, rng: Rng) -> Tuple[Set[Wall], Cell]:
    """The inner walls a depth-first walk from a random cell leaves standing, and that cell."""
    walls: Set[Wall] = {("v", i, j) for i in range(cols - 1) for j in range(rows)}
    walls |= {("h", i, j) for i in range(cols) for j in range(rows - 1)}
    start = (rng.below(cols), rng.below(rows))
    seen, stack = {start}, [start]
    while stack:
        i, j = stack[-1]
        options = [(n, w) for n, w in (((i + 1, j), ("v", i, j)), ((i - 1, j), ("v", i - 1, j)),
                                       ((i, j + 1), ("h", i, j)), ((i, j - 1), ("h", i, j - 1)))
                   if 0 <= n[0] < cols and 0 <= n[1] < rows and n not in seen]
        if not options:
            stack.pop()
            continue
        cell, wall = rng.choice(options)
        walls.discard(wall)
        seen.add(cell)
        stack.append(cell)
    return walls, start


def _runs(walls: Set[Wall], cols: int, rows: int) -> List[Tuple[Tuple[int, int], Tuple[int, int]]]:
    """The walls as straight runs between grid points ((gx, gy) to (gx, gy)), vertical lines first."""
    runs = []
    for kind, lines, span in (("v", cols - 1, rows), ("h", rows - 1, cols)):
        for k in range(lines):
            start = None
            for m in range(span + 1):
                present = m < span and ((kind, k, m) in walls if kind == "v" else (kind, m, k) in walls)
                if present and start is None:
                    start = m
                elif not present and start is not None:
                    runs.append(((k + 1, start), (k + 1, m)) if kind == "v" else ((start, k + 1), (m, k + 1)))
                    start = None
    return runs


def _open_run(walls: Set[Wall], cols: int, rows: int, cell: Cell, step: Tuple[int, int]) -> int:
    """How many cells the robot can drive from ``cell`` in direction ``step`` before a wall."""
    count, (i, j) = 0, cell
    while True:
        ni, nj = i + step[0], j + step[1]
        if not (0 <= ni < cols and 0 <= nj < rows):
            return count
        wall = ("v", min(i, ni), j) if step[1] == 0 else ("h", i, min(j, nj))
        if wall in walls:
            return count
        count, i, j = count + 1, ni, nj


def make(name: str, options: MazeOptions, space: RobotSpace, rng: Rng) -> Tuple[Spec, str]:
    c = options.cell
    cols, rows = max(2, int(options.size[0] / c + 1e-9)), max(2, int(options.size[1] / c + 1e-9))
    walls, start = _carve(cols, rows, rng)
    for wall in sorted(walls):
        if rng.chance(options.loops):
            walls.discard(wall)
    x0, y0 = round(-cols * c / 2, 3), round(-rows * c / 2, 3)

    def at(gx: float, gy: float) -> Tuple[float, float]:
        return (round(x0 + gx * c, 3), round(y0 + gy * c, 3))

    style = WallStyle(THICKNESS, options.wall_height, MATERIAL)
    segments = tuple(Segment(at(*a), at(*b), style) for a, b in _runs(walls, cols, rows))
    door = round(min(0.9, c - THICKNESS - 2 * DOOR_SLACK), 3)
    rooms: List[Room] = []
    patches: Tuple[FloorPatch, ...] = ()
    maze_openings: Tuple[Opening, ...] = ()
    if options.exits:
        enter, leave = rng.below(rows), rng.below(rows)
        side = round((c - door) / 2, 3)
        maze_openings = (   # wall 1 (right) runs up from (x1, y0); wall 3 (left) runs down from (x0, y1)
            Opening("door", 1, round(leave * c + side, 3), door, options.wall_height),
            Opening("door", 3, round((rows - enter - 1) * c + side, 3), door, options.wall_height))
        rooms += [Room("entrance", _square(at(-1, enter), c), style),
                  Room("exit", _square(at(cols, leave), c), style)]
        goal = at(cols + 0.5, leave + 0.5)
        patches = (FloorPatch("disc", goal, GOAL_COLOUR, radius=0.2, name="goal"),)
        spawn, yaw = at(-0.5, enter + 0.5), 0.0
    else:
        steps = {(1, 0): 0.0, (0, 1): HALF_PI, (-1, 0): PI, (0, -1): -HALF_PI}
        best = max(steps, key=lambda s: (_open_run(walls, cols, rows, start, s), -list(steps).index(s)))
        spawn, yaw = at(start[0] + 0.5, start[1] + 0.5), round(steps[best], 4)
    maze = Room("maze", (at(0, 0), at(cols, 0), at(cols, rows), at(0, rows)), style, maze_openings)
    spec = Spec(name=name, style=style, rooms=(maze, *rooms), segments=segments, patches=patches,
                robot=RobotPose(options.robot, spawn, yaw))
    loops = f", {number_share(options.loops)} of its inner walls taken out" if options.loops else ", perfect"
    ends = "an entrance and an exit" if options.exits else "closed"
    return spec, f"a {cols} x {rows} maze of {c:g} m cells{loops}, {ends}"


def shortfall(spec: Spec, options: MazeOptions) -> Optional[str]:
    """What the maze does otherwise than asked (None: nothing): larger than ``--size``, when that holds fewer than
    two cells a side (the least a maze has)."""
    (x0, y0), _, (x1, y1), _ = spec.rooms[0].vertices
    w, h = options.size
    if x1 - x0 <= w + 1e-9 and y1 - y0 <= h + 1e-9:
        return None
    return (f"a {x1 - x0:g} x {y1 - y0:g} m maze, larger than the {w:g} x {h:g} m asked: a maze has at least two "
            f"{options.cell:g} m cells a side; give a larger --size")


def number_share(share: float) -> str:
    return f"{share:.0%}"


def _square(corner: Tuple[float, float], c: float):
    x, y = corner
    return ((x, y), (round(x + c, 3), y), (round(x + c, 3), round(y + c, 3)), (x, round(y + c, 3)))

