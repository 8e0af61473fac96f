"""A robot's outline as the geometric checks and the world generators need it: the convex hull of its collision
shapes seen from above, its width, height, turning radius and LiDAR height, read from our TurtleBot3 descriptions
(or a user's URDF/xacro file). What ``validate`` measures a spawn and a gap against is what ``generate`` sizes
doors, corridors and cells for."""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

from . import robot_urdf
from ..core.boxes import box_corners
from ..core.errors import InputError
from ..core.numbers import floats
from ..core.resources import ROBOT_MODELS
from .profile import link_frames, origin_of, robot_profile


@dataclass(frozen=True)
class RobotBody:
    """A robot's outline as the geometric checks need it, in its base frame (base_footprint, x forward).

    ``footprint`` is the convex hull of every collision shape seen from above; ``width`` its extent across
    (y), ``height`` its top; ``turn_radius`` the farthest footprint point from the base origin (what sweeps
    the floor when it turns in place); ``lidar_height`` the LiDAR origin above the floor (None: no LiDAR).
    """

    name: str
    footprint: tuple[tuple[float, float], ...]
    width: float
    height: float
    turn_radius: float
    lidar_height: float | None


@lru_cache(maxsize=8)
def robot_body(robot: str = "burger") -> RobotBody:
    """The :class:`RobotBody` of a model name or URDF/xacro file (raises InputError for a bad one)."""
    urdf = robot_urdf(robot)
    name = str(robot) if str(robot) in ROBOT_MODELS else Path(str(robot)).name
    try:
        return _body_from_urdf(urdf, robot_profile(urdf, source=str(robot)), name=name)
    except ValueError as err:   # a size, origin or joint value that is not a number
        raise InputError(f"the robot description holds a value that is not a number ({err})", path=str(robot),
                         hint="fix the numbers in the URDF or xacro file (sizes, origins, joints)") from None


def _body_from_urdf(urdf: str, profile, name: str) -> RobotBody:
    import numpy as np
    import shapely

    from ..core.poses import rpy_matrix

    frames = link_frames(profile.joints, profile.root_link)
    points = []
    for link in ET.fromstring(urdf).findall("link"):
        if link.get("name") not in frames:
            continue
        (lx, ly, lz), rows = frames[link.get("name")]
        link_rot, link_pos = np.array(rows), np.array([lx, ly, lz])
        for collision in link.findall("collision"):
            local = _geometry_points(collision.find("geometry"))
            if local is None:
                continue
            xyz, rpy = origin_of(collision)
            in_link = local @ rpy_matrix(*rpy).T + np.array(xyz)
            points.append(in_link @ link_rot.T + link_pos)
    if not points:   # no collision geometry at all: a TurtleBot3 burger's box stands in
        points = [np.array([[x, y, z] for x in (-0.102, 0.038) for y in (-0.089, 0.089) for z in (0.0, 0.19)])]
    cloud = np.vstack(points)
    hull = shapely.MultiPoint(cloud[:, :2]).convex_hull
    ring = tuple((round(float(x), 5), round(float(y), 5)) for x, y in list(hull.exterior.coords)[:-1])
    lidar_height = None
    if profile.lidar is not None and profile.lidar.link in frames:
        lidar_height = frames[profile.lidar.link][0][2] + profile.lidar.pose[2]
    return RobotBody(
        name=name, footprint=ring, width=float(cloud[:, 1].max() - cloud[:, 1].min()),
        height=float(cloud[:, 2].max()), turn_radius=float(np.hypot(cloud[:, 0], cloud[:, 1]).max()),
        lidar_height=lidar_height)


def _geometry_points(geometry):
    """Points whose hull bounds a URDF collision geometry, in its own frame (None for meshes and unknowns)."""
    import numpy as np

    if geometry is None or not len(geometry):
        return None
    shape = geometry[0]
    if shape.tag == "box":
        return box_corners(floats(shape.get("size"), 3))
    if shape.tag == "cylinder":
        r, half = float(shape.get("radius", 0)), float(shape.get("length", 0)) / 2
        a = np.linspace(0, 2 * math.pi, 16, endpoint=False)
        ring = np.column_stack([r * np.cos(a), r * np.sin(a)])
        return np.vstack([np.column_stack([ring, np.full(16, z)]) for z in (-half, half)])
    if shape.tag == "sphere":
        return box_corners([2 * float(shape.get("radius", 0))] * 3)
    return None
