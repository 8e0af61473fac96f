"""The model tree the reader builds before it places anything (so that ``<state>`` can override poses first)."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import List, Optional

import numpy as np

from ..core import poses


@dataclass
class Collision:
    name: str
    pose: np.ndarray  # in the link frame
    shape: dict       # Shape keyword arguments for the geometry (kind, size, radius, …)


@dataclass
class Link:
    name: str
    pose: np.ndarray  # in the model frame
    collisions: List[Collision] = field(default_factory=list)
    world: Optional[np.ndarray] = None  # from <state>: world frame


@dataclass
class Model:
    name: str
    pose: np.ndarray  # in the parent frame (world or parent model)
    static: bool
    where: str
    links: List[Link] = field(default_factory=list)
    models: List[Model] = field(default_factory=list)
    world: Optional[np.ndarray] = None  # from <state>: world frame


def ground_plane(name: str, where: str) -> Model:
    """A stand-in for Gazebo's stock ground_plane model: a static plane through z = 0."""
    link = Link("link", poses.IDENTITY, [Collision("collision", poses.IDENTITY,
                                                    {"kind": "plane", "normal": (0.0, 0.0, 1.0)})])
    return Model(name, poses.IDENTITY, True, where, links=[link])
