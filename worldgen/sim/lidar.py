"""A planar LiDAR like Gazebo's ray sensor (TurtleBot3's LDS-01: 360 beams, 0.12–3.5 m, 5 Hz).

Beam i points at ``min_angle + i·(max_angle − min_angle)/(samples − 1)`` counter-clockwise from the sensor's +x,
as Gazebo spaces them (so with 0…6.28319 the first and last beams overlap). Rays start at ``range_min`` as
Gazebo's do, so the robot's own housing is never seen, and they skip the robot's bodies altogether. A range is
the true distance plus optional Gaussian noise, clipped to the range, as Gazebo Classic's ``RaySensor`` makes it
(``MultiRayShape::GetRange`` is ``range_min`` plus the ray's length; the ``<range><resolution>`` is read but
never applied, so readings are not quantised); beams that hit nothing read ``inf`` (Gazebo) or ``0.0`` (the real
robot's driver), by option.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field

import numpy as np
import pybullet as pb

from ..robots.profile import LidarParams
from .scene_loader import SCENE_GROUP

NO_HIT = {"inf": math.inf, "zero": 0.0}
# Threads each scan's rays are cast on: the same ranges as on one (each ray is cast alone), in two thirds of the
# time (0.53 → 0.34 ms a scan of 360 beams). pybullet keeps the pool's thread until the client disconnects, so a
# process still holding a session that has scanned runs two threads (and forks no server: see sim.forkserver).
RAY_THREADS = 2


@dataclass
class Scan:
    """One revolution, shaped like sensor_msgs/LaserScan plus what a picture or a check needs.

    ``ranges`` are what the sensor reports (noise, no-hit value); ``true_ranges`` are the exact
    distances (``inf`` for no hit); ``hits`` the world (x, y, z) of each beam's end (beams × 3), a hit where
    ``true_ranges`` is finite (:attr:`points`: None for no hit); ``origin`` is the sensor's world (x, y, z, yaw);
    ``time`` the simulated time of the scan.
    """

    angle_min: float
    angle_max: float
    angle_increment: float
    range_min: float
    range_max: float
    ranges: list[float]
    true_ranges: list[float]
    hits: np.ndarray = field(compare=False)
    origin: tuple[float, float, float, float]
    time: float = 0.0
    frame_id: str = "base_scan"
    # the ranges as arrays (:meth:`array`), kept by the cast that made them; not a field ``replace`` would copy
    arrays: dict = field(default_factory=dict, init=False, repr=False, compare=False)

    @property
    def angles(self) -> list[float]:
        return [self.angle_min + i * self.angle_increment for i in range(len(self.ranges))]

    @property
    def points(self) -> list[tuple[float, float, float] | None]:
        """The world (x, y, z) of each beam's hit, None for a beam that hit nothing."""
        return [tuple(p) if math.isfinite(r) else None for p, r in zip(self.hits.tolist(), self.true_ranges)]

    def array(self, true: bool = False) -> np.ndarray:
        """``ranges`` (``true``: ``true_ranges``) as a read-only array."""
        key = "true" if true else "measured"
        if key not in self.arrays:
            values = np.array(self.true_ranges if true else self.ranges, float)
            values.setflags(write=False)
            self.arrays[key] = values
        return self.arrays[key]

    def to_dict(self) -> dict:
        return {"angle_min": self.angle_min, "angle_max": self.angle_max, "angle_increment": self.angle_increment,
                "range_min": self.range_min, "range_max": self.range_max, "ranges": list(self.ranges),
                "frame_id": self.frame_id, "time": self.time, "origin": list(self.origin),
                "points": [list(p) if p is not None else None for p in self.points]}


@functools.lru_cache(maxsize=32)
def beam_directions(params: LidarParams) -> np.ndarray:
    """Unit vectors (samples × 3) of the beams in the sensor frame (made once per sensor: read-only)."""
    angles = params.min_angle + np.arange(params.samples) * params.angle_increment
    directions = np.stack([np.cos(angles), np.sin(angles), np.zeros_like(angles)], axis=1)
    directions.setflags(write=False)
    return directions


def cast_scan(client: int, params: LidarParams, position, orientation, *, no_hit: str = "inf",
              rng: np.random.Generator | None = None, time: float = 0.0, mask: int = SCENE_GROUP) -> Scan:
    """Cast one scan from the sensor pose (world ``position``, quaternion ``orientation``).

    ``rng`` adds the sensor's Gaussian noise (None: no noise); ``mask`` is the collision mask the
    rays see (the scene alone by default; a robot's own LiDAR also sees the other robots).
    """
    if no_hit not in NO_HIT:
        raise ValueError(f"no_hit must be one of {sorted(NO_HIT)}, not {no_hit!r}")
    rot = np.array(pb.getMatrixFromQuaternion(orientation), float).reshape(3, 3)
    dirs = beam_directions(params) @ rot.T
    origin = np.asarray(position, float)
    starts = origin + dirs * params.range_min
    ends = origin + dirs * params.range_max
    results = pb.rayTestBatch(starts, ends, collisionFilterMask=mask, numThreads=RAY_THREADS,
                              physicsClientId=client)
    span = params.range_max - params.range_min
    hit = np.fromiter([r[0] >= 0 for r in results], bool, len(results))           # a body was hit
    fractions = np.fromiter([r[2] for r in results], float, len(results))         # where along the ray
    true = np.where(hit, params.range_min + fractions * span, np.inf)
    measured = true.copy()
    if rng is not None and params.noise_stddev > 0:
        measured[hit] += rng.normal(params.noise_mean, params.noise_stddev, int(hit.sum()))
    measured[hit] = np.clip(measured[hit], params.range_min, params.range_max)
    measured[~hit] = NO_HIT[no_hit]
    yaw = math.atan2(rot[1, 0], rot[0, 0])
    true.setflags(write=False)
    measured.setflags(write=False)
    scan = Scan(angle_min=params.min_angle, angle_max=params.min_angle + (params.samples - 1) * params.angle_increment,
                angle_increment=params.angle_increment, range_min=params.range_min, range_max=params.range_max,
                ranges=measured.tolist(), true_ranges=true.tolist(), hits=starts + (ends - starts) * fractions[:, None],
                origin=(float(origin[0]), float(origin[1]), float(origin[2]), yaw), time=time, frame_id=params.link)
    scan.arrays.update(true=true, measured=measured)
    return scan


def front_distance(scan: Scan, half_angle: float = math.radians(10), *, true: bool = False) -> float | None:
    """The nearest reading within ±``half_angle`` of straight ahead (the sensor's +x), ignoring no-hit beams
    (``inf`` or 0) — what a student's stop-at-wall node computes. ``true`` uses the exact distances. None when
    every beam there reads no hit."""
    values = scan.array(true)
    ahead = values[_ahead(scan.angle_min, scan.angle_increment, len(values), half_angle)]
    ahead = ahead[np.isfinite(ahead) & (ahead > 0.0)]
    return float(ahead.min()) if ahead.size else None


@functools.lru_cache(maxsize=64)
def _ahead(angle_min: float, angle_increment: float, count: int, half_angle: float) -> np.ndarray:
    """Which of ``count`` beams point within ±``half_angle`` of straight ahead (read-only)."""
    angles = np.remainder(angle_min + np.arange(count) * angle_increment + math.pi, math.tau) - math.pi
    mask = np.abs(angles) <= half_angle + 1e-9
    mask.setflags(write=False)
    return mask


def lidar_info(params: LidarParams) -> dict:
    """The beam layout a recorded scan's ranges need (:func:`scan_row`): ``angle_min``, ``angle_increment``
    (rad; beam i at ``angle_min + i·angle_increment`` CCW from the sensor's +x), ``range_min``, ``range_max`` (m)
    and ``count``, the number of beams."""
    return {"angle_min": params.min_angle, "angle_increment": params.angle_increment,
            "range_min": params.range_min, "range_max": params.range_max, "count": params.samples}


def scan_row(scan: Scan) -> list:
    """One scan, compact, for a replay: ``[ox, oy, yaw, [mm, …]]`` — the sensor's world position (m, 4 decimals)
    and heading (rad, 4 decimals), and each beam's reported range (noise included) in whole millimetres, -1 for a
    beam that hit nothing (whether it reads ``inf`` or 0)."""
    hit = np.isfinite(scan.array(true=True))
    mm = np.where(hit, np.rint(scan.array() * 1000.0), -1.0).astype(int)
    x, y, _, yaw = scan.origin
    return [round(x, 4), round(y, 4), round(yaw, 4), mm.tolist()]
