"""Geometry: a spec's rooms and segments become straight walls, each a set of boxes.

``build_geometry(spec)`` joins corners (no gap, no spike, whatever the angle), writes a wall shared by two rooms
once, and splits a wall around its openings the way the Building Editor does (pieces beside an opening, a lintel
above it, a sill below a window). Everything here is plain numbers; writers turn it into files.

How a plan becomes walls (all distances in metres, along wall centre-lines), one module per step, over
:mod:`.vectors`:

1. Merging (:mod:`.runs`). Every room edge and segment is an *edge*. Edges on one straight line (within ``EPS``) are
   projected onto that line; edges that overlap, or touch end to end with the same style, merge into one wall. So a
   wall two rooms share is written once, a big room's side stays one wall when a small room shares part of it, and a
   straight line of rooms' sides is one wall, as a person would draw it in the Building Editor.
2. Joining (:mod:`.joins`). Wall ends that meet are *nodes*. A free end reaches ``thickness/2`` past its point (the
   editor's way: a wall drawn 5 m between centre points is a 5.15 m box). The end of a wall meeting another wall's
   middle (a T-junction) reaches the far face of that wall. Two ends that a room draws as its corner (or, where no
   room does, the two on either side of a gap of 180° or more) reach the point where their outer faces meet
   (``(t/2)·tan(φ/2)`` for a turn of φ), which closes the corner exactly; where that would poke out (a corner
   sharper than 90°) each wall stops where it still lies inside the other, and thin *filler* boxes along the outer
   faces cover the mitre's spike, so the union of all boxes stays within ``JOIN_TOLERANCE`` of the ideal mitred band
   and nothing pokes out of it. Other ends (a Y of three walls, say) stop at the point, which already closes it.
3. Openings (:mod:`.openings`). Openings are placed on their merged wall and split it into pieces; an opening that
   runs into another wall (a corner, a T-junction, a crossing) or overlaps another opening is a SpecError naming its
   spec line.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..core.errors import SpecError
from ..spec.model import MARKINGS_MODEL, FloorLine, FloorPatch, Material, Obstacle, Point, RobotPose, Spec
from .joins import join_corners
from .openings import Piece, PlacedOpening, place_holes, split_pieces
from .runs import Run, fail, merge_edges, spec_edges
from .vectors import CellGrid, add, bbox, overlap, rectangle, unit

_CLEAR = 1e-4           # an opening may touch another wall's box but not cut into it by more than this


@dataclass(frozen=True)
class Wall:
    """A straight wall. ``start``/``end`` are the ends of its boxes' centre-line (joins included), so its length
    is the box length of an unsplit wall. A ``filler`` is a thin box that fills the tip of a corner sharper than
    90° (no openings, one piece)."""

    index: int
    start: Point
    end: Point
    thickness: float
    height: float
    material: Material
    pieces: tuple[Piece, ...]
    openings: tuple[PlacedOpening, ...] = ()
    rooms: tuple[str, ...] = ()
    filler: bool = False

    @property
    def length(self) -> float:
        return math.dist(self.start, self.end)

    @property
    def yaw(self) -> float:
        return math.atan2(self.end[1] - self.start[1], self.end[0] - self.start[0])

    def footprint(self) -> tuple[Point, Point, Point, Point]:
        """The four corners of the wall's box seen from above (counter-clockwise from start-right)."""
        return rectangle(self.start, self.end, self.thickness)


@dataclass(frozen=True)
class Building:
    name: str
    walls: tuple[Wall, ...]
    obstacles: tuple[Obstacle, ...]
    robot: RobotPose | None
    origin: Point          # the bounding-box centre of the walls: the model pose, as the Building Editor writes it
    bounds: tuple[float, float, float, float]   # xmin, ymin, xmax, ymax of everything built
    lines: tuple[FloorLine, ...] = ()            # floor markings, as the spec gives them (see :mod:`.tape`)
    patches: tuple[FloorPatch, ...] = ()


# ------------------------------------------------------------------------------------------------- public
def build_geometry(spec: Spec) -> Building:
    """The walls (boxes), obstacles and robot pose of ``spec``; raises SpecError for what only geometry can tell
    (openings overlapping on a shared wall or running into another wall, shared walls of different thickness)."""
    runs = merge_edges(spec_edges(spec), spec)
    for run in runs:
        place_holes(run, spec)
    fillers = join_corners(runs, spec)
    walls = [_wall(i, run) for i, run in enumerate(runs)]
    walls += [Wall(len(walls) + i, f.start, f.end, f.thickness, f.height, f.material,
                   (Piece(0.0, math.dist(f.start, f.end), 0.0, f.height),), rooms=f.rooms, filler=True)
              for i, f in enumerate(fillers)]
    _check_clearance(walls, runs, spec)
    if spec.name == "ground_plane" and walls:
        fail(spec, "the world cannot be named 'ground_plane': its building model would clash with the ground",
             None, "choose another name")
    marked = bool(spec.lines or spec.patches)
    if spec.name == MARKINGS_MODEL and walls and marked:
        fail(spec, f"the world cannot be named '{MARKINGS_MODEL}': its building model would clash with the model "
             "of its lines and patches", None, "choose another name")
    obstacle_names(spec.obstacles, spec.name, spec=spec, markings=marked)

    wall_points = [c for w in walls for c in w.footprint()]
    if wall_points:
        wx0, wy0, wx1, wy1 = bbox(wall_points)
        origin = ((wx0 + wx1) / 2, (wy0 + wy1) / 2)
    else:
        origin = (0.0, 0.0)
    everything = wall_points + [c for o in spec.obstacles for c in obstacle_footprint(o)] + marking_extent(spec)
    bounds = bbox(everything) if everything else (0.0, 0.0, 0.0, 0.0)
    return Building(spec.name, tuple(walls), spec.obstacles, spec.robot, origin, bounds, spec.lines, spec.patches)


def obstacle_names(obstacles, building_name: str, *, spec: Spec | None = None, markings: bool = False) -> list[str]:
    """Each obstacle's model name: its own, or ``obstacle_N`` (N its place in the spec, from 0). Raises
    SpecError when two models of the world would share a name (``markings``: the world has a model of floor
    markings too)."""
    names = [o.name or f"obstacle_{i}" for i, o in enumerate(obstacles)]
    taken = {building_name: "the building", "ground_plane": "the ground plane"}
    if markings:
        taken[MARKINGS_MODEL] = "the floor markings"
    for i, (o, name) in enumerate(zip(obstacles, names)):
        if name in taken:
            what = (f"obstacle name '{name}'" if o.name else
                    f"obstacle {i + 1} has no name, and the one it gets, '{name}',")
            raise SpecError(f"{what} is already used by {taken[name]}", path=spec.source if spec else None,
                            line=o.line, hint="give every obstacle its own name")
        taken[name] = f"the obstacle on line {o.line}" if o.line else "another obstacle"
    return names


def obstacle_footprint(o: Obstacle) -> list[Point]:
    """Points whose bounding box is the obstacle's footprint (a box's corners, a round shape's extremes)."""
    x, y = o.at
    if o.shape == "box" and o.size is not None:
        c, s = math.cos(o.yaw), math.sin(o.yaw)
        hx, hy = o.size[0] / 2, o.size[1] / 2
        return [(x + c * a - s * b, y + s * a + c * b) for a, b in ((-hx, -hy), (hx, -hy), (hx, hy), (-hx, hy))]
    r = o.radius or 0.0
    return [(x - r, y - r), (x + r, y + r)]


def marking_extent(spec: Spec) -> list[Point]:
    """Points whose bounding box holds the spec's lines and patches (each grown by its half width or reach)."""
    points = []
    for line in spec.lines:
        h = line.width / 2
        points += [(x + dx, y + dy) for x, y in line.points for dx, dy in ((-h, -h), (h, h))]
    for p in spec.patches:
        r = p.radius if p.shape == "disc" else math.hypot(*p.size) / 2
        points += [(p.center[0] - r, p.center[1] - r), (p.center[0] + r, p.center[1] + r)]
    return points


# ---------------------------------------------------------------------------------------------- the walls
def _wall(index: int, run: Run) -> Wall:
    start = run.at(run.u0 - run.e0)
    end = run.at(run.u1 + run.e1)
    length = run.u1 - run.u0 + run.e0 + run.e1
    height = run.style.height
    shift = run.e0 - run.u0
    openings = tuple(PlacedOpening(h.opening.type, h.u0 + shift, h.u1 + shift, h.z0, h.z1) for h in run.holes)
    rooms = tuple(dict.fromkeys(e.room for e in sorted(run.edges, key=lambda e: e.order) if e.room))
    return Wall(index, start, end, run.style.thickness, height, run.style.material,
                split_pieces(length, height, openings), openings, rooms)


def _check_clearance(walls: list[Wall], runs: list[Run], spec: Spec) -> None:
    """An opening must not run into another wall's box (a corner, a T-junction, a crossing)."""
    if not any(w.openings for w in walls):
        return
    extent = bbox([c for w in walls for c in w.footprint()])
    grid = CellGrid(max(1.0, (extent[2] - extent[0] + extent[3] - extent[1]) / 128))
    for w in walls:
        grid.add(w.index, bbox(w.footprint()))
    for w, run in zip(walls, runs):
        d = unit(w.start, w.end)
        for op, hole in zip(w.openings, run.holes):
            a = add(w.start, d, op.s0 + _CLEAR)
            b = add(w.start, d, op.s1 - _CLEAR)
            rect = rectangle(a, b, w.thickness - 2 * _CLEAR)
            for k in grid.near(bbox(rect)):
                other = walls[k]
                if k != w.index and overlap(rect, other.footprint()):
                    what = runs[k].label if k < len(runs) else "a corner filler"
                    fail(spec, f"the {op.type} on {hole.edge.label} runs into {what}", hole.opening.line,
                         "move the opening along its wall so that it clears the walls meeting it")
