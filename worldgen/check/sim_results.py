"""What ``worldgen validate``'s simulator child measured, as typed records: the child
(:mod:`worldgen.check.sim_job`) builds a :class:`SimNumbers`, sends :meth:`SimNumbers.to_dict` back as JSON, and
the parent parses it once with :meth:`SimNumbers.from_dict`; :func:`worldgen.check.checks.sim_findings` judges
the record, never a dict by string keys.

A stage that did not run is None (``ran`` lists those that did; ``failed`` says why a check could not run).
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field
from typing import Dict, List, Optional, Tuple


@dataclass(frozen=True)
class Touch:
    """One contact: the world's shape, the robot's link, and when (simulated seconds) it was first touched."""

    shape: str
    link: str
    time: float


@dataclass(frozen=True)
class Settled:
    """The robot after standing still: its height, how far it slid, how far it tipped."""

    time: float
    z: float
    moved: float
    tilt_deg: float
    contact_points: Tuple[Touch, ...] = ()


@dataclass(frozen=True)
class Scanned:
    """One 360-beam scan from the spawn, the true ranges (no noise): how many beams hit nothing within
    ``range_max`` and what such a beam reads, the nearest and farthest hits, and whether nothing is straight
    ahead."""

    beams: int
    no_hit: int
    range_max: float = 3.5
    no_hit_reading: Optional[float] = None
    no_hit_bearings_deg: Tuple[float, ...] = ()
    nearest: Optional[float] = None
    nearest_bearing_deg: Optional[float] = None
    farthest: Optional[float] = None
    front_no_hit: bool = False
    ranges_sample: Tuple[float, ...] = ()


@dataclass(frozen=True)
class Spun:
    """Spinning in place: the most the base frame drifted, how far it turned (rad), what it touched."""

    drift: float
    turned: float
    touched: Tuple[str, ...] = ()
    contact_points: Tuple[Touch, ...] = ()


@dataclass(frozen=True)
class Stopped:
    """Driving to the wall ahead: where it ended (None: no wall in range), what it touched, how long it took;
    ``no_wall`` when no wall was within ``range`` in any direction (not tried)."""

    distance: Optional[float] = None
    touched: Tuple[str, ...] = ()
    contact_points: Tuple[Touch, ...] = ()
    time: Optional[float] = None
    start_distance: Optional[float] = None
    turned_to_face: bool = False
    overshoot: Optional[float] = None
    heading_deg: Optional[float] = None
    no_wall: bool = False
    range: float = 3.5


@dataclass(frozen=True)
class SimNumbers:
    """Everything the simulated checks measured in one world."""

    ran: Tuple[str, ...] = ()
    failed: Dict[str, str] = field(default_factory=dict)   # check → why it could not run
    settle: Optional[Settled] = None
    lidar: Optional[Scanned] = None
    spin: Optional[Spun] = None
    stop: Optional[Stopped] = None
    sim_seconds: Optional[float] = None
    wall_seconds: Optional[float] = None

    def to_dict(self) -> dict:
        """JSON-able values (what the child sends)."""
        return asdict(self)

    @classmethod
    def from_dict(cls, data: dict) -> "SimNumbers":
        """The record :meth:`to_dict` gave; a part missing from ``data`` is None, a field missing from a part
        takes its default. A key no record has is a TypeError (the child and the parent disagree)."""
        parts = {"settle": Settled, "lidar": Scanned, "spin": Spun, "stop": Stopped}
        values = {k: v for k, v in data.items() if k not in parts}
        for name, record in parts.items():
            part = data.get(name)
            values[name] = None if part is None else _record(record, part)
        values["ran"] = tuple(values.get("ran", ()))
        return cls(**values)


def _record(record, data: dict):
    """``record(**data)`` with lists as tuples and contact points as :class:`Touch` records."""
    values = {key: tuple(value) if isinstance(value, list) else value for key, value in data.items()}
    if "contact_points" in values:
        values["contact_points"] = tuple(Touch(**c) for c in values["contact_points"])
    return record(**values)


def touches(contacts: List[dict], at_most: int = 3) -> Tuple[Touch, ...]:
    """The first ``at_most`` of a session's contacts as :class:`Touch` records."""
    return tuple(Touch(c["shape"], c["link"], c["time"]) for c in contacts[:at_most])
