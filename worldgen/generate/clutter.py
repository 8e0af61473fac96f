"""``clutter``: one room with boxes and cylinders standing about at a density, every gap between them either
closed or passable.

Shapes are dropped at random (boxes turned any way, cylinders, and now and then a row of two or three crates
standing flush against each other, whose joints are closed) until they cover ``density`` of the floor or no more
fit. A shape is kept only when it is at least ``gap`` (the robot's width and 0.2 m, unless given) from every other
shape and from the walls, and at least the robot's turning clearance from the spawn. So every gap in the room is
either none at all (a crate row's joints) or one the robot drives through, and the free floor is one piece: the
shapes, each grown by half a gap, neither touch one another nor the walls, so they are islands in it. The robot
starts at a random place, facing something 1 to 3.3 m ahead.
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import Dict, List, Sequence, Tuple

from ..spec.model import Material, Obstacle, RobotPose, Room, Spec, WallStyle
from .options import ClutterOptions
from .rng import Rng
from .robot import RobotSpace
from .shapes import Point, Rect, box_outline, convex_apart, convex_circle_distance, dist, edges_of, facing
from .trig import PI

THICKNESS = 0.15
GRAIN = 0.05
SLACK = 0.002          # m: kept beyond every gap, for the rounding of what is written
AHEAD = (1.0, 3.3)
HEADINGS = tuple(k * PI / 4 for k in range(-3, 5))
MISSES = 40           # drops that do not fit, one after another, before the room counts as full
ROW_CHANCE = 0.2       # a drop is a row of crates this often
BOX_COLOUR = Material("Gazebo/Wood")
CYLINDER_COLOUR = Material("Gazebo/Blue")


class Shape:
    """A dropped shape: boxes (centre, size, yaw; a row of crates has two or three, flush) or one disc, its
    bounding circle (``reach``) and a circle inside it (``inner``) round ``centre``. Its outlines are worked out
    only when a cheaper test cannot tell whether it fits."""

    def __init__(self, centre: Point, reach: float, inner: float, area: float, height: float,
                 boxes: Tuple = (), radius: float = 0.0):
        self.centre, self.reach, self.inner, self.area, self.height = centre, reach, inner, area, height
        self.boxes, self.radius = boxes, radius
        self._outlines: Tuple = ()

    @property
    def outlines(self) -> Tuple[Tuple[Point, ...], ...]:
        if self.boxes and not self._outlines:
            self._outlines = tuple(tuple(box_outline(c, size, yaw)) for c, size, yaw in self.boxes)
        return self._outlines

    @property
    def discs(self) -> Tuple[Tuple[Point, float], ...]:
        return ((self.centre, self.radius),) if self.radius else ()

    def obstacles(self, index: int) -> List[Obstacle]:
        if self.radius:
            return [Obstacle("cylinder", self.centre, radius=self.radius, height=self.height,
                             material=CYLINDER_COLOUR, name=f"cylinder_{index}")]
        names = [f"box_{index}"] if len(self.boxes) == 1 else [f"crates_{index}_{c}" for c in "abc"]
        return [Obstacle("box", c, yaw=yaw, size=(size[0], size[1], self.height), material=BOX_COLOUR, name=n)
                for (c, size, yaw), n in zip(self.boxes, names)]


def resolve(options: ClutterOptions, space: RobotSpace) -> ClutterOptions:
    from ..core.errors import InputError

    gap = options.gap if options.gap is not None else space.passage
    if gap < space.passage:
        raise InputError(f"--gap {gap:g} is too narrow for the {space.model}, which is {space.width:g} m wide",
                         hint=f"give --gap at least {space.passage:g}, or leave it out")
    w, h = (round(round(v / GRAIN) * GRAIN, 3) for v in options.size)
    if min(w, h) < THICKNESS + 2 * space.clearance + 0.2:
        raise InputError(f"--size {w:g}x{h:g} leaves the {space.model} no room to turn",
                         hint=f"make both sides at least {THICKNESS + 2 * space.clearance + 0.2:.2f} m")
    return replace(options, size=(w, h), gap=gap)


def _apart(a: Shape, b: Shape, gap: float) -> bool:
    """Whether every part of ``a`` is at least ``gap`` from every part of ``b``."""
    for p in a.outlines:
        if not (all(convex_apart(p, q, gap) for q in b.outlines) and
                all(convex_circle_distance(p, c, r) >= gap for c, r in b.discs)):
            return False
    for c, r in a.discs:
        if not (all(convex_circle_distance(q, c, r) >= gap for q in b.outlines) and
                all(dist(c, d) - r - s >= gap for d, s in b.discs)):
            return False
    return True


def _pick(rng: Rng, low: float, count: int, grain: float) -> float:
    """One of ``low``, ``low + grain``, … (``count`` values), to the millimetre."""
    return round(low + grain * rng.below(count), 3)


def _drop(area: Rect, shapes: str, rng: Rng) -> Shape:
    """One random shape whose centre lies in ``area``."""
    kind = shapes if shapes != "mixed" else ("row" if rng.chance(ROW_CHANCE) else rng.choice(("box", "cylinder")))
    if shapes == "box" and rng.chance(ROW_CHANCE):
        kind = "row"
    cx, cy = round(rng.uniform(area.x0, area.x1), 2), round(rng.uniform(area.y0, area.y1), 2)
    height = _pick(rng, 0.3, 15, 0.05)                 # 0.3 … 1.0 m
    if kind == "cylinder":
        r = _pick(rng, 0.1, 26, 0.01)                  # 0.1 … 0.35 m
        return Shape((cx, cy), r, r, PI * r * r, height, radius=r)
    if kind == "box":
        size = (_pick(rng, 0.2, 13, 0.05), _pick(rng, 0.2, 13, 0.05))   # 0.2 … 0.8 m
        yaw = round(rng.uniform(0, PI), 4)
        return Shape((cx, cy), dist(size, (0.0, 0.0)) / 2, min(size) / 2, size[0] * size[1], height,
                     (((cx, cy), size, yaw),))
    # a row of crates, flush along x or y: every joint closed
    count, deep = rng.between(2, 3), _pick(rng, 0.3, 5, 0.05)   # 0.3 … 0.5 m deep
    lengths = [_pick(rng, 0.3, 7, 0.05) for _ in range(count)]   # 0.3 … 0.6 m long
    along_x = rng.chance(0.5)
    total, at = sum(lengths), -sum(lengths) / 2
    boxes = []
    for length in lengths:
        mid = round(at + length / 2, 3)
        centre = (round(cx + mid, 3), cy) if along_x else (cx, round(cy + mid, 3))
        boxes.append((centre, (length, deep) if along_x else (deep, length), 0.0))
        at += length
    return Shape((cx, cy), dist((total, deep), (0.0, 0.0)) / 2, deep / 2, total * deep, height, tuple(boxes))


def _inside(shape: Shape, room: Rect) -> bool:
    (x, y), r = shape.centre, shape.reach
    if room.x0 <= x - r and x + r <= room.x1 and room.y0 <= y - r and y + r <= room.y1:
        return True
    points = [p for o in shape.outlines for p in o]
    for (x, y), r in shape.discs:
        points += [(x - r, y - r), (x + r, y + r)]
    return all(room.x0 <= x <= room.x1 and room.y0 <= y <= room.y1 for x, y in points)


class _Placed:
    """The shapes placed so far, in square buckets by centre, so a new shape is tested against its neighbours
    only: placing n shapes takes time linear in n, not quadratic, in a room of any size."""

    BUCKET = 2.0   # m

    def __init__(self):
        self.shapes: List[Shape] = []
        self._buckets: Dict[Tuple[int, int], List[Shape]] = {}
        self._reach = 0.0   # the largest reach placed

    def _key(self, p: Point) -> Tuple[int, int]:
        return math.floor(p[0] / self.BUCKET), math.floor(p[1] / self.BUCKET)

    def add(self, shape: Shape) -> None:
        self.shapes.append(shape)
        self._buckets.setdefault(self._key(shape.centre), []).append(shape)
        self._reach = max(self._reach, shape.reach)

    def fits(self, shape: Shape, gap: float) -> bool:
        """Whether ``shape`` is at least ``gap`` from every shape placed (only those whose reach could come that
        near are looked at)."""
        (i, j), k = self._key(shape.centre), math.ceil((shape.reach + self._reach + gap + SLACK) / self.BUCKET)
        for di in range(-k, k + 1):
            for dj in range(-k, k + 1):
                for other in self._buckets.get((i + di, j + dj), ()):
                    apart = dist(shape.centre, other.centre)
                    if apart - shape.reach - other.reach >= gap + SLACK:
                        continue
                    if apart - shape.inner - other.inner < gap + SLACK:
                        return False   # their inner discs alone are too close
                    if not _apart(shape, other, gap + SLACK):
                        return False
        return True


def _clear_of(shape: Shape, spawn: Point, clearance: float) -> bool:
    if dist(shape.centre, spawn) - shape.reach >= clearance + SLACK:
        return True
    return (all(convex_circle_distance(o, spawn, 0.0) >= clearance + SLACK for o in shape.outlines) and
            all(dist(c, spawn) - r >= clearance + SLACK for c, r in shape.discs))


def make(name: str, options: ClutterOptions, space: RobotSpace, rng: Rng) -> Tuple[Spec, str]:
    w, h = options.size
    x0, y0 = round(-w / 2, 3), round(-h / 2, 3)
    room = Rect(x0, y0, round(x0 + w, 3), round(y0 + h, 3))
    floor = room.shrunk(THICKNESS / 2)
    margin = space.clearance + 0.1
    spawn = (round(rng.uniform(floor.x0 + margin, floor.x1 - margin), 2),
             round(rng.uniform(floor.y0 + margin, floor.y1 - margin), 2))
    allowed = floor.shrunk(options.gap + SLACK)
    target = options.density * floor.area
    placed = _Placed()
    covered, misses = 0.0, 0
    while covered < target and misses < MISSES and allowed.width > 0 and allowed.height > 0:
        shape = _drop(allowed, options.shapes, rng)
        if _inside(shape, allowed) and _clear_of(shape, spawn, space.clearance) and \
                placed.fits(shape, options.gap):
            placed.add(shape)
            covered += shape.area
            misses = 0
        else:
            misses += 1
    segments = [e for s in placed.shapes for o in s.outlines for e in edges_of(o)]
    segments += _disc_edges(placed.shapes) + edges_of(floor.corners())
    yaw, _ = facing(spawn, HEADINGS, space.width / 2 + 0.05, segments, *AHEAD, rng)
    style = WallStyle(THICKNESS, options.wall_height, Material())
    obstacles = tuple(ob for i, s in enumerate(placed.shapes) for ob in s.obstacles(i))
    spec = Spec(name=name, style=style, rooms=(Room("room", tuple(room.corners()), style),), obstacles=obstacles,
                robot=RobotPose(options.robot, spawn, round(yaw, 4)))
    share = covered / floor.area
    return spec, (f"a {w:g} x {h:g} m room with {len(obstacles)} obstacles covering {share:.0%} of its floor, "
                  f"every gap closed or at least {options.gap:g} m")


def _disc_edges(placed: Sequence[Shape]) -> list:
    """Each disc as the square around it, for the heading's rays (which then stop a little short of the disc)."""
    edges = []
    for s in placed:
        for (x, y), r in s.discs:
            edges += edges_of([(x - r, y - r), (x + r, y - r), (x + r, y + r), (x - r, y + r)])
    return edges

