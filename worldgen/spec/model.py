"""The floorplan spec's model: validated, immutable dataclasses, and the defaults, limits and keys a spec is read
against.

Coordinates are metres in the world frame. A room's ``rect`` or ``polygon`` gives the walls' centre-lines, as the
Building Editor draws them; wall ``i`` runs from vertex ``i`` to vertex ``i+1``; an opening's ``offset`` is the
distance along the wall's centre-line from vertex ``i`` to the opening's near edge.

A spec file is read into these by :func:`worldgen.spec.load.load_spec`.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Literal, Tuple

from ..core.materials import STOCK_NAMES
from ..core.resources import ROBOT_MODELS   # what a spec's robot may be

Point = Tuple[float, float]

DEFAULT_THICKNESS = 0.15   # Building Editor default
DEFAULT_HEIGHT = 2.5       # Building Editor default (level height)
DEFAULT_MATERIAL = "Gazebo/Grey"
DOOR_HEIGHT = 2.0
WINDOW_HEIGHT = 0.8
WINDOW_SILL = 0.5
SPEC_SUFFIXES = (".yaml", ".yml", ".json", ".txt")   # the file names a spec has (a .txt is an ASCII grid)


@dataclass(frozen=True)
class Material:
    """A Gazebo material script name (``Gazebo/Grey``) or an RGBA colour (0–1 each); exactly one is set."""

    script: str | None = DEFAULT_MATERIAL
    rgba: tuple[float, float, float, float] | None = None


@dataclass(frozen=True)
class WallStyle:
    thickness: float = DEFAULT_THICKNESS
    height: float = DEFAULT_HEIGHT
    material: Material = field(default_factory=Material)


@dataclass(frozen=True)
class Opening:
    """A door or window cut into wall ``wall`` of its room (or of its segment)."""

    type: Literal["door", "window"]
    wall: int
    offset: float
    width: float
    height: float
    sill: float = 0.0   # 0 for doors
    line: int | None = None


@dataclass(frozen=True)
class Room:
    name: str
    vertices: tuple[Point, ...]      # centre-line polygon, as written (either winding)
    style: WallStyle
    openings: tuple[Opening, ...] = ()
    line: int | None = None


@dataclass(frozen=True)
class Segment:
    """A free-standing straight wall (``segments:`` in the spec; ASCII grids become these)."""

    start: Point
    end: Point
    style: WallStyle
    openings: tuple[Opening, ...] = ()   # ``wall`` is always 0
    line: int | None = None


@dataclass(frozen=True)
class Obstacle:
    shape: Literal["box", "cylinder", "sphere"]
    at: Point
    yaw: float = 0.0
    size: tuple[float, float, float] | None = None   # box: x, y, z
    radius: float | None = None                        # cylinder, sphere
    height: float | None = None                        # cylinder
    material: Material = field(default_factory=Material)
    name: str | None = None
    line: int | None = None


@dataclass(frozen=True)
class RobotPose:
    model: str = "burger"
    at: Point = (0.0, 0.0)
    yaw: float = 0.0
    line: int | None = None


@dataclass(frozen=True)
class FloorLine:
    """A line of tape on the floor (``lines:``): a polyline through ``points``, ``width`` wide, a loop when
    ``closed`` (the last point joined back to the first). A camera sees it; the robot and its LiDAR do not."""

    points: tuple[Point, ...]
    width: float
    color: Material
    closed: bool = False
    name: str | None = None
    line: int | None = None


@dataclass(frozen=True)
class FloorPatch:
    """A coloured patch on the floor (``patches:``): a ``rect`` (``size`` turned by ``yaw`` about its ``center``)
    or a ``disc`` (``radius``)."""

    shape: Literal["rect", "disc"]
    center: Point
    color: Material
    size: tuple[float, float] | None = None   # rect: along x, along y before the yaw
    yaw: float = 0.0
    radius: float | None = None               # disc
    name: str | None = None
    line: int | None = None


@dataclass(frozen=True)
class Spec:
    name: str
    style: WallStyle = field(default_factory=WallStyle)
    rooms: tuple[Room, ...] = ()
    segments: tuple[Segment, ...] = ()
    obstacles: tuple[Obstacle, ...] = ()
    robot: RobotPose | None = None
    source: str | None = None     # the file it came from, for messages
    lines: tuple[FloorLine, ...] = ()
    patches: tuple[FloorPatch, ...] = ()


# ------------------------------------------------------------------------------------------ limits and keys
LIMIT = 1000.0        # metres: no size or coordinate may exceed it (a typo in units, most likely)
MIN_SIZE = 0.001      # metres: anything thinner is a typo too, and breaks the simulators
NAME_MAX = 64
DOOR_WIDTH = 0.9
WINDOW_WIDTH = 0.8
DEFAULT_CELL = 0.5
SHAPES = ("box", "cylinder", "sphere")
OPENING_TYPES = ("door", "window")
EPS = 1e-9            # metres: lengths closer than this are equal (an opening that just fits)
LINE_WIDTH = 0.05     # metres: a line's width unless it gives one (floor-marking tape)
MAX_LINE_WIDTH = 1.0  # metres: anything wider is an area: a patch
MAX_MARKINGS = 500    # lines and patches in one spec
MAX_LINE_POINTS = 5000   # points of all its lines together (each becomes a box and a disc in the world)
MARKINGS_MODEL = "floor_markings"   # the world's model holding the lines and patches, a link each
PATCH_SHAPES = ("rect", "disc")

TOP_KEYS = ("name", "walls", "rooms", "segments", "grid", "obstacles", "robot", "map", "lines", "patches")
WALL_KEYS = ("thickness", "height", "material")
ROOM_KEYS = ("name", "rect", "polygon", "walls", "openings")
RECT_KEYS = ("center", "size")
OPENING_KEYS = ("type", "wall", "offset", "width", "height", "sill")
SEGMENT_KEYS = ("from", "to", "walls", "openings")
SHAPE_KEYS = {"box": ("size",), "cylinder": ("radius", "height"), "sphere": ("radius",)}
OBSTACLE_KEYS = ("shape", "name", "at", "yaw", "size", "radius", "height", "material")
ROBOT_KEYS = ("model", "at", "yaw")
GRID_KEYS = ("cell", "rows", "origin", "height", "material")
MATERIAL_KEYS = ("script", "rgba")
LINE_KEYS = ("name", "points", "width", "color", "closed")
PATCH_KEYS = ("name", "rect", "disc", "color")
PATCH_RECT_KEYS = ("center", "size", "yaw")
DISC_KEYS = ("center", "radius")

# How each required key is written, for "add …" hints.
KEY_EXAMPLES = {
    "name": "name: my_world", "center": "center: [0, 0]", "size": "size: [5, 5]", "type": "type: door",
    "wall": "wall: 0", "from": "from: [0, 0]", "to": "to: [3, 0]", "shape": "shape: box", "radius": "radius: 0.2",
    "height": "height: 0.5", "points": "points: [[0, 0], [2, 0], [2, 1]]", "color": "color: Gazebo/Yellow",
    "rows": "rows: |  (then the grid lines, indented)",
}

# Gazebo's stock material scripts (media/materials/scripts/gazebo.material, :mod:`worldgen.core.materials`), for
# "did you mean" only: other script names are accepted as written, since a world may bring its own.
GAZEBO_MATERIALS = STOCK_NAMES
