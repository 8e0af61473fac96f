"""The floorplan spec: a YAML/JSON (or ASCII-grid) file read into validated, immutable dataclasses.

Coordinates are metres in the world frame. A room's ``rect`` or ``polygon`` gives the walls' centre-lines, as the
Building Editor draws them; wall ``i`` runs from vertex ``i`` to vertex ``i+1``; an opening's ``offset`` is the
distance along the wall's centre-line from vertex ``i`` to the opening's near edge.

Parsing (``load_spec``) lives below the dataclasses; every error is a :class:`~worldgen.errors.SpecError` naming
the file and line.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Literal

Point = tuple[float, float]

DEFAULT_THICKNESS = 0.15   # Building Editor default
DEFAULT_HEIGHT = 2.5       # Building Editor default (level height)
DEFAULT_MATERIAL = "Gazebo/Grey"
DOOR_HEIGHT = 2.0
WINDOW_HEIGHT = 0.8
WINDOW_SILL = 0.5
ROBOT_MODELS = ("burger", "waffle", "waffle_pi")


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
class Spec:
    name: str
    style: WallStyle = field(default_factory=WallStyle)
    rooms: tuple[Room, ...] = ()
    segments: tuple[Segment, ...] = ()
    obstacles: tuple[Obstacle, ...] = ()
    robot: RobotPose | None = None
    source: str | None = None     # the file it came from, for messages
