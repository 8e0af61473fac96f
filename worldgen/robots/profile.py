"""What a simulator needs to know about a robot, read from its URDF the way Gazebo would read it.

The drive comes from the ``libgazebo_ros_diff_drive`` plugin block (wheel joints, separation, diameter, rim
acceleration, torque, update rate), the LiDAR from the ``<sensor type="ray">`` block on its link, the cameras
from the ``<sensor type="camera"|"depth">`` blocks with a gazebo_ros camera plugin (:mod:`.cameras`), and surface
friction from ``<gazebo reference="link"><mu1>``. So a model behaves in our simulator with the numbers Gazebo
would use — including the real ``turtlebot3_description``, whose plugin says 0.287 m where its wheels are 0.288 m
apart. A URDF without those blocks falls back to its geometry (joints named ``wheel_left_joint`` and
``wheel_right_joint``, the wheel's collision cylinder, a link named ``base_scan``) and TurtleBot3's values.
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field

from ..core.errors import InputError
from ..core.numbers import floats
from .cameras import CameraParams, read_cameras

# TurtleBot3's diff-drive and LDS-01 numbers, used when a URDF has no plugin or sensor block.
FALLBACK_DRIVE = {"acceleration": 1.0, "torque": 10.0, "update_rate": 30.0}
LDS01 = {"samples": 360, "min_angle": 0.0, "max_angle": 6.28319, "range_min": 0.12, "range_max": 3.5,
         "resolution": 0.015, "noise_mean": 0.0, "noise_stddev": 0.01, "update_rate": 5.0}


@dataclass(frozen=True)
class DriveParams:
    """A differential drive as gazebo_ros_diff_drive runs it."""

    left_joint: str
    right_joint: str
    wheel_separation: float
    wheel_radius: float
    acceleration: float   # rim speed ramp, m/s²; 0 = set the speed at once
    torque: float         # joint motor force limit, N·m
    update_rate: float    # Hz
    from_plugin: bool


@dataclass(frozen=True)
class LidarParams:
    """A planar ray sensor; beam i points at ``min_angle + i·(max_angle − min_angle)/(samples − 1)``, CCW."""

    link: str
    samples: int
    min_angle: float
    max_angle: float
    range_min: float
    range_max: float
    resolution: float
    noise_mean: float
    noise_stddev: float
    update_rate: float
    pose: tuple[float, float, float, float, float, float] = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)  # in the link
    from_sensor: bool = True

    @property
    def angle_increment(self) -> float:
        return (self.max_angle - self.min_angle) / (self.samples - 1) if self.samples > 1 else 0.0


@dataclass(frozen=True)
class Joint:
    name: str
    type: str
    parent: str
    child: str
    xyz: tuple[float, float, float]
    rpy: tuple[float, float, float]


@dataclass(frozen=True)
class RobotProfile:
    name: str
    root_link: str
    links: tuple[str, ...]
    joints: tuple[Joint, ...]
    drive: DriveParams | None
    lidar: LidarParams | None
    friction: dict[str, float] = field(default_factory=dict)   # link → μ from its <gazebo> block
    base_frame: str = "base_footprint"
    cameras: tuple[CameraParams, ...] = ()


def origin_of(elem: ET.Element) -> tuple[tuple[float, ...], tuple[float, ...]]:
    """The ``xyz`` and ``rpy`` of an element's ``<origin>`` (zeros where absent), as URDF reads them."""
    origin = elem.find("origin")
    if origin is None:
        return (0.0, 0.0, 0.0), (0.0, 0.0, 0.0)
    return floats(origin.get("xyz"), 3), floats(origin.get("rpy"), 3)


def _num(elem: ET.Element | None, path: str, default: float) -> float:
    text = elem.findtext(path) if elem is not None else None
    try:
        return float(text) if text is not None and text.strip() else default
    except ValueError:
        return default


def robot_profile(urdf: str, source: str | None = None) -> RobotProfile:
    """Read ``urdf`` (text) into a :class:`RobotProfile`. ``source`` names the file in error messages."""
    try:
        root = ET.fromstring(urdf)
    except ET.ParseError as err:
        raise InputError(f"the robot description is not XML: {err}", path=source,
                         hint="fix the URDF or xacro file") from None
    if root.tag != "robot":
        raise InputError(f"the robot description's root element is <{root.tag}>, not <robot>", path=source,
                         hint="give a URDF or .urdf.xacro file")
    links = tuple(link.get("name", "") for link in root.findall("link"))
    joints = tuple(_joint(j) for j in root.findall("joint"))
    children = {j.child for j in joints}
    roots = [name for name in links if name not in children]
    if len(roots) != 1:
        raise InputError(f"the robot description has {len(roots)} root links ({', '.join(roots) or 'none'})",
                         path=source, hint="a URDF must form one tree of links joined by joints")
    gazebo = root.findall("gazebo")
    friction: dict[str, float] = {}
    for block in gazebo:
        ref = block.get("reference")
        if ref and block.find("mu1") is not None:
            friction[ref] = _num(block, "mu1", 1.0)
    plugin = next((p for b in gazebo for p in b.findall("plugin") if "diff_drive" in p.get("filename", "")), None)
    return RobotProfile(
        name=root.get("name", ""), root_link=roots[0], links=links, joints=joints,
        drive=_drive(root, joints, plugin, roots[0]), lidar=_lidar(gazebo, links), friction=friction,
        base_frame=(plugin.findtext("robotBaseFrame") or roots[0]).strip() if plugin is not None else roots[0],
        cameras=read_cameras(gazebo))


def _joint(elem: ET.Element) -> Joint:
    xyz, rpy = origin_of(elem)
    return Joint(name=elem.get("name", ""), type=elem.get("type", ""),
                 parent=elem.find("parent").get("link", "") if elem.find("parent") is not None else "",
                 child=elem.find("child").get("link", "") if elem.find("child") is not None else "",
                 xyz=xyz, rpy=rpy)


def _drive(root: ET.Element, joints: tuple[Joint, ...], plugin: ET.Element | None, base: str) -> DriveParams | None:
    by_name = {j.name: j for j in joints}
    if plugin is not None:
        left = (plugin.findtext("leftJoint") or "").strip()
        right = (plugin.findtext("rightJoint") or "").strip()
        if left in by_name and right in by_name:
            return DriveParams(left, right,
                               wheel_separation=_num(plugin, "wheelSeparation", 0.34),
                               wheel_radius=_num(plugin, "wheelDiameter", 0.15) / 2,
                               acceleration=_num(plugin, "wheelAcceleration", 0.0),
                               torque=_num(plugin, "wheelTorque", 5.0),
                               update_rate=_num(plugin, "updateRate", 100.0), from_plugin=True)
    left, right = by_name.get("wheel_left_joint"), by_name.get("wheel_right_joint")
    if left is None or right is None:
        return None
    frames = link_frames(joints, base)
    (lx, ly, lz), (rx, ry, rz) = frames[left.child][0], frames[right.child][0]
    radius = _wheel_radius(root, left.child)
    if radius is None:
        return None
    return DriveParams(left.name, right.name, wheel_separation=math.dist((lx, ly, lz), (rx, ry, rz)),
                       wheel_radius=radius, from_plugin=False, **FALLBACK_DRIVE)


def _wheel_radius(root: ET.Element, link_name: str) -> float | None:
    for link in root.findall("link"):
        if link.get("name") == link_name:
            for geom in link.findall("collision/geometry/*"):
                if geom.tag in ("cylinder", "sphere") and geom.get("radius"):
                    return float(geom.get("radius"))
    return None


def _lidar(gazebo: list[ET.Element], links: tuple[str, ...]) -> LidarParams | None:
    for block in gazebo:
        for sensor in block.findall("sensor"):
            if sensor.get("type") in ("ray", "gpu_ray") and block.get("reference"):
                ray = sensor.find("ray")
                horizontal = ray.find("scan/horizontal") if ray is not None else None
                rng = ray.find("range") if ray is not None else None
                noise = ray.find("noise") if ray is not None else None
                return LidarParams(
                    link=block.get("reference"),
                    samples=int(_num(horizontal, "samples", 640)),
                    min_angle=_num(horizontal, "min_angle", 0.0), max_angle=_num(horizontal, "max_angle", 0.0),
                    range_min=_num(rng, "min", 0.0), range_max=_num(rng, "max", 10.0),
                    resolution=_num(rng, "resolution", 0.0),
                    noise_mean=_num(noise, "mean", 0.0), noise_stddev=_num(noise, "stddev", 0.0),
                    update_rate=_num(sensor, "update_rate", 0.0),
                    pose=floats(sensor.findtext("pose"), 6))
    if "base_scan" in links:
        return LidarParams(link="base_scan", from_sensor=False, **LDS01)
    return None


def link_frames(joints: tuple[Joint, ...], root: str) -> dict[str, tuple[tuple[float, float, float], object]]:
    """Every link's pose in ``root``'s frame at zero joint positions: link → (xyz, 3×3 rotation matrix)."""
    from ..core.poses import IDENTITY, pose_matrix

    frames = {root: IDENTITY}
    pending = list(joints)
    while pending:
        placed = [j for j in pending if j.parent in frames]
        if not placed:
            break
        for j in placed:
            frames[j.child] = frames[j.parent] @ pose_matrix(*j.xyz, *j.rpy)
            pending.remove(j)
    return {link: (tuple(float(v) for v in t[:3, 3]), t[:3, :3]) for link, t in frames.items()}


