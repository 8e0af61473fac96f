"""The model tree the reader builds before it places anything (so that ``<state>`` can override poses first)."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import List, Optional, Tuple

import numpy as np

from ..core import poses
from ..core.materials import STOCK_COLORS


@dataclass
class Collision:
    name: str
    pose: np.ndarray  # in the link frame
    shape: dict       # Shape keyword arguments for the geometry (kind, size, radius, …)


@dataclass
class Visual:
    name: str
    pose: np.ndarray  # in the link frame
    shape: dict       # Shape keyword arguments, as for a collision
    color: Optional[Tuple[float, float, float, float]] = None   # from its <material>; None when not known


@dataclass
class Link:
    name: str
    pose: np.ndarray  # in the model frame
    collisions: List[Collision] = field(default_factory=list)
    world: Optional[np.ndarray] = None  # from <state>: world frame
    visuals: List[Visual] = field(default_factory=list)
    bare: Optional[str] = None   # where a link with <visual>s but no <collision> is (the emitter judges it)
    tall: bool = False           # whether one of those visuals stands 5 cm or more (or is of unknown height)
    unread: int = 0              # visuals whose geometry could not be read (none, unsupported, mesh not found)


@dataclass
class Model:
    name: str
    pose: np.ndarray  # in the parent frame (world or parent model)
    static: bool
    where: str
    links: List[Link] = field(default_factory=list)
    models: List[Model] = field(default_factory=list)
    world: Optional[np.ndarray] = None  # from <state>: world frame


GROUND_SIZE = 100.0                    # m: the stock ground plane's visual is 100 m square …
GROUND_COLOR = STOCK_COLORS["Gazebo/Grey"]   # … and Gazebo/Grey


def ground_plane(name: str, where: str) -> Model:
    """A stand-in for Gazebo's stock ground_plane model: a static plane through z = 0, seen as a grey square."""
    link = Link("link", poses.IDENTITY, [Collision("collision", poses.IDENTITY,
                                                    {"kind": "plane", "normal": (0.0, 0.0, 1.0)})])
    link.visuals.append(Visual("visual", poses.IDENTITY, {"kind": "plane", "normal": (0.0, 0.0, 1.0),
                                                          "size": (GROUND_SIZE, GROUND_SIZE, 0.0)}, GROUND_COLOR))
    return Model(name, poses.IDENTITY, True, where, links=[link])
