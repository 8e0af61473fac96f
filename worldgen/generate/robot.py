"""What the chosen TurtleBot3 needs from a generated world: its width (for doors and gaps) and the circle its
corners sweep when it turns in place (for cells, corridors and the spawn), as ``validate`` measures them
(:func:`worldgen.robots.body.robot_body`), rounded up to the millimetre so that every machine sizes alike."""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

DEFAULT_ROBOT = "waffle_pi"   # the widest TurtleBot3 (with the Waffle): a world it fits, the Burger fits too
PASS_MARGIN = 0.2    # m: a door or a gap is at least the robot's width plus this (10 cm each side)
TURN_MARGIN = 0.1    # m: a spawn keeps this much more than the turning radius from walls and obstacles


@dataclass(frozen=True)
class RobotSpace:
    """The room a robot needs, in metres: ``width`` across its body, ``turn`` the radius its corners sweep
    turning in place; ``camera`` whether it has one (the Waffles)."""

    model: str
    width: float
    turn: float
    camera: bool

    @property
    def passage(self) -> float:
        """The narrowest door or gap a generated world has: the width plus :data:`PASS_MARGIN`."""
        return round(self.width + PASS_MARGIN, 3)

    @property
    def clearance(self) -> float:
        """How far a spawn keeps from walls and obstacles: the turning radius plus :data:`TURN_MARGIN`."""
        return round(self.turn + TURN_MARGIN, 3)


def _up(value: float) -> float:
    return math.ceil(round(value * 1000, 6)) / 1000


@lru_cache(maxsize=4)
def robot_space(model: str) -> RobotSpace:
    """The :class:`RobotSpace` of a TurtleBot3 model name."""
    from ..robots import robot_urdf
    from ..robots.body import robot_body
    from ..robots.profile import robot_profile

    body = robot_body(model)
    camera = bool(robot_profile(robot_urdf(model)).cameras)
    return RobotSpace(model, _up(body.width), _up(body.turn_radius), camera)
