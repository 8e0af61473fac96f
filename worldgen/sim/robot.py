"""One robot in a pybullet session: its description loaded as a multibody, its diff-drive plugin, its LiDAR, its
contacts and what it touched.

A :class:`~.session.Session` holds one or more of these (several TurtleBot3s in one world, as a launch file with
``<group ns>`` per robot spawns them). Robot ``i`` has a collision group of its own (:func:`.scene_loader.robot_group`),
so robots collide with each other and the world, each one's LiDAR sees the world and the other robots, and no
LiDAR ever sees its own robot.
"""

from __future__ import annotations

import math
import os
import tempfile
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

import numpy as np
import pybullet as pb

from ..core.errors import InputError
from ..robots.description import absolute_mesh_paths, robot_file, robot_urdf
from ..robots.profile import LidarParams, RobotProfile, robot_profile
from .drive import DiffDrive
from .lidar import Scan, cast_scan
from .scene_loader import ray_mask, robot_group, robot_mask

TOUCH_DISTANCE = 0.001          # m: contact points closer than this count as touching


@dataclass(frozen=True)
class Odometry:
    """Ground-truth pose and twist of the robot's base frame (like the plugin's ``odom`` with source world).
    ``v`` is the forward speed along the heading, ``omega`` the yaw rate."""

    t: float
    x: float
    y: float
    z: float
    roll: float
    pitch: float
    yaw: float
    v: float
    omega: float

    def to_dict(self) -> dict:
        return dict(self.__dict__)


@dataclass(frozen=True)
class Contact:
    """The robot's ``link`` touching (or within ``distance`` of) the scene shape labelled ``shape``."""

    link: str
    shape: str
    distance: float
    position: tuple[float, float, float]

    def to_dict(self) -> dict:
        return {"link": self.link, "shape": self.shape, "distance": self.distance, "position": list(self.position)}


@dataclass
class TouchLog:
    """Every (link, shape) pair that touched since the last reset, with when it first did and how deep."""

    first: dict[tuple[str, str], float] = field(default_factory=dict)
    deepest: dict[tuple[str, str], float] = field(default_factory=dict)

    def add(self, t: float, contacts: list[Contact]) -> None:
        for c in contacts:
            key = (c.link, c.shape)
            self.first.setdefault(key, t)
            self.deepest[key] = min(self.deepest.get(key, c.distance), c.distance)

    def to_list(self) -> list[dict]:
        return [{"link": k[0], "shape": k[1], "time": round(self.first[k], 4), "depth": -self.deepest[k]}
                for k in sorted(self.first, key=lambda k: (self.first[k], k))]


class Robot:
    """A robot description (a TurtleBot3 model name or a URDF/xacro file, or URDF text) on the floor of pybullet
    client ``client`` at ``spawn`` (x, y[, yaw]), in collision slot ``slot``. ``name`` is the model name Gazebo
    would list it under."""

    def __init__(self, client: int, robot: str | Path = "burger", spawn=(0.0, 0.0, 0.0), *, slot: int = 0,
                 name: str = "turtlebot3", mappings: dict[str, str] | None = None, urdf: str | None = None,
                 z: float = 0.0):
        self.client, self.slot, self.name = client, slot, name
        self.touches = TouchLog()
        source = robot_file(robot)
        self.source = source if urdf is None else None   # where relative mesh paths start
        self.urdf = urdf if urdf is not None else robot_urdf(robot, mappings)
        self.profile: RobotProfile = robot_profile(self.urdf, source=str(source))
        if self.profile.drive is None:
            raise InputError("the robot has no differential drive: no libgazebo_ros_diff_drive plugin and no "
                             "joints named wheel_left_joint/wheel_right_joint", path=source,
                             hint="use a TurtleBot3 model or add the diff-drive plugin block to the URDF")
        self.drive = DiffDrive(self.profile.drive)
        self.body = self._load(source, spawn, z)

    def _load(self, source: Path, spawn, z: float) -> int:
        x, y, yaw = spawn_pose(spawn)
        text = collision_urdf(self.urdf, source)
        fd, path = tempfile.mkstemp(prefix="worldgen_robot_", suffix=".urdf")
        try:
            with os.fdopen(fd, "w", encoding="utf-8") as fh:
                fh.write(text)
            try:
                # Inertias as written (not recomputed from the shapes), and true cylinders for the wheels:
                # pybullet otherwise turns them into polygonal hulls that bump along at low speed.
                body = pb.loadURDF(path, [x, y, z], pb.getQuaternionFromEuler([0, 0, yaw]),
                                   flags=pb.URDF_USE_INERTIA_FROM_FILE | pb.URDF_USE_IMPLICIT_CYLINDER,
                                   physicsClientId=self.client)
            except pb.error as err:
                raise InputError(f"pybullet cannot load the robot description ({err})", path=source,
                                 hint="check that every collision mesh file exists") from None
        finally:
            os.unlink(path)
        # pybullet numbers each joint as its child link; the root link is -1
        self.link_index = {pb.getBodyInfo(body, physicsClientId=self.client)[0].decode(): -1}
        joint_index, movable = {}, []
        for j in range(pb.getNumJoints(body, physicsClientId=self.client)):
            info = pb.getJointInfo(body, j, physicsClientId=self.client)
            self.link_index[info[12].decode()] = j
            joint_index[info[1].decode()] = j
            if info[2] != pb.JOINT_FIXED:
                movable.append(j)
        self.link_name = {i: n for n, i in self.link_index.items()}
        # Damping is per multibody (and, passed with a link index, pybullet drops the whole call): Gazebo has none.
        pb.changeDynamics(body, -1, linearDamping=0.0, angularDamping=0.0, physicsClientId=self.client)
        for index, link in self.link_name.items():
            pb.changeDynamics(body, index, lateralFriction=self.profile.friction.get(link, 1.0),
                              physicsClientId=self.client)
            pb.setCollisionFilterGroupMask(body, index, robot_group(self.slot), robot_mask(self.slot),
                                           physicsClientId=self.client)
        drive = self.profile.drive
        self.wheels = (joint_index[drive.left_joint], joint_index[drive.right_joint])
        for j in movable:  # joints without a controller turn freely, as in Gazebo
            pb.setJointMotorControl2(body, j, pb.VELOCITY_CONTROL, targetVelocity=0.0,
                                     force=drive.torque if j in self.wheels else 0.0, physicsClientId=self.client)
        lidar = self.profile.lidar
        self.lidar: LidarParams | None = lidar if lidar is not None and lidar.link in self.link_index else None
        self.base_index = self.link_index.get(self.profile.base_frame, -1)
        self.spawn = (x, y, yaw)
        self.initial_base = pb.getBasePositionAndOrientation(body, physicsClientId=self.client)
        return body

    # -- commands --------------------------------------------------------------------------------------------

    def update_drive(self, dt: float) -> None:
        """One diff-drive plugin update ``dt`` seconds after the last: new wheel motor targets."""
        left, right = self.drive.update(dt, self.wheel_rim_speeds())
        for joint, speed in zip(self.wheels, (left, right)):
            pb.setJointMotorControl2(self.body, joint, pb.VELOCITY_CONTROL, targetVelocity=speed,
                                     force=self.drive.params.torque, physicsClientId=self.client)

    def reset(self) -> None:
        """Back at the spawn pose, at rest, wheels at angle 0 and the command at zero (what Gazebo's
        reset_world does to a model)."""
        position, orientation = self.initial_base
        self.teleport(position, orientation)

    def teleport(self, position, orientation, linear=(0.0, 0.0, 0.0), angular=(0.0, 0.0, 0.0), *,
                 keep_command: bool = False) -> None:
        """Put the root link at ``position``/``orientation`` (world) with the given velocity, wheels at rest (what
        Gazebo's set_model_state does to a model's joints). The drive's command goes to zero unless
        ``keep_command`` (set_model_state leaves the diff-drive plugin's last cmd_vel standing)."""
        pb.resetBasePositionAndOrientation(self.body, list(position), list(orientation),
                                           physicsClientId=self.client)
        pb.resetBaseVelocity(self.body, list(linear), list(angular), physicsClientId=self.client)
        for j in range(pb.getNumJoints(self.body, physicsClientId=self.client)):
            pb.resetJointState(self.body, j, 0.0, 0.0, physicsClientId=self.client)
        if not keep_command:
            self.drive.command = (0.0, 0.0)
        self.drive.ramped = [0.0, 0.0]

    def base_to_root(self, position, orientation):
        """The root link's world pose that puts the base frame at ``position``/``orientation``."""
        if self.base_index == -1:
            local_pos, local_orn = pb.getDynamicsInfo(self.body, -1, physicsClientId=self.client)[3:5]
            return pb.multiplyTransforms(position, orientation, local_pos, local_orn)
        root_pos, root_orn = pb.getBasePositionAndOrientation(self.body, physicsClientId=self.client)
        base_pos, base_orn = self.link_pose(self.base_index)
        inv_pos, inv_orn = pb.invertTransform(base_pos, base_orn)
        rel_pos, rel_orn = pb.multiplyTransforms(inv_pos, inv_orn, root_pos, root_orn)
        return pb.multiplyTransforms(position, orientation, rel_pos, rel_orn)

    # -- state -----------------------------------------------------------------------------------------------

    def link_pose(self, link: str | int):
        """World position and quaternion (x, y, z, w) of a link's frame (name or index; -1 = root)."""
        index = self.link_index[link] if isinstance(link, str) else link
        if index == -1:
            com_pos, com_orn = pb.getBasePositionAndOrientation(self.body, physicsClientId=self.client)
            local_pos, local_orn = pb.getDynamicsInfo(self.body, -1, physicsClientId=self.client)[3:5]
            inv_pos, inv_orn = pb.invertTransform(local_pos, local_orn)
            return pb.multiplyTransforms(com_pos, com_orn, inv_pos, inv_orn)
        state = pb.getLinkState(self.body, index, computeForwardKinematics=True, physicsClientId=self.client)
        return state[4], state[5]

    def link_velocity(self, link: str | int):
        """World linear and angular velocity of a link (name or index; -1 = root)."""
        index = self.link_index[link] if isinstance(link, str) else link
        if index == -1:
            lin, ang = pb.getBaseVelocity(self.body, physicsClientId=self.client)
        else:
            state = pb.getLinkState(self.body, index, computeLinkVelocity=True, physicsClientId=self.client)
            lin, ang = state[6], state[7]
        return tuple(lin), tuple(ang)

    def wheel_rim_speeds(self) -> tuple[float, float]:
        """The drive wheels' measured rim speeds (left, right) in m/s: joint speed × the drive's wheel radius."""
        states = pb.getJointStates(self.body, self.wheels, physicsClientId=self.client)
        return states[0][1] * self.drive.params.wheel_radius, states[1][1] * self.drive.params.wheel_radius

    def wheel_states(self) -> tuple[tuple[float, float], tuple[float, float]]:
        """The drive wheels' joint angles (rad) and speeds (rad/s): ((left, right), (left, right))."""
        states = pb.getJointStates(self.body, self.wheels, physicsClientId=self.client)
        return (states[0][0], states[1][0]), (states[0][1], states[1][1])

    def base_velocity(self) -> tuple[tuple[float, float, float], tuple[float, float, float]]:
        """World-frame linear (m/s) and angular (rad/s) velocity of the base frame."""
        return self.link_velocity(self.base_index)

    def odometry(self, t: float) -> Odometry:
        (x, y, z), quat = self.link_pose(self.base_index)
        roll, pitch, yaw = pb.getEulerFromQuaternion(quat)
        lin, ang = self.base_velocity()
        v = lin[0] * math.cos(yaw) + lin[1] * math.sin(yaw)
        return Odometry(t, x, y, z, roll, pitch, yaw, v, ang[2])

    def scan(self, t: float, no_hit: str, rng: np.random.Generator | None) -> Scan:
        """One LiDAR scan from the sensor's current pose: the world and every other robot, never this one."""
        if self.lidar is None:
            raise InputError("the robot has no LiDAR (no ray sensor block and no base_scan link)",
                             hint="use a TurtleBot3 model or add a <sensor type=\"ray\"> block")
        pos, orn = self.link_pose(self.lidar.link)
        px, py, pz, rr, rp, ry = self.lidar.pose
        pos, orn = pb.multiplyTransforms(pos, orn, [px, py, pz], pb.getQuaternionFromEuler([rr, rp, ry]))
        return cast_scan(self.client, self.lidar, pos, orn, no_hit=no_hit, rng=rng, time=t, mask=ray_mask(self.slot))

    def contacts(self, label: Callable[[int, tuple], str], planes, touch_distance: float = TOUCH_DISTANCE
                 ) -> list[Contact]:
        """What the robot touches other than the ground: one entry per (link, shape), deepest point first;
        ``label(body, point)`` names what was touched."""
        found: dict[tuple[str, str], Contact] = {}
        for pt in pb.getContactPoints(bodyA=self.body, physicsClientId=self.client):
            body, dist = pt[2], pt[8]
            if body == self.body or body in planes or dist > touch_distance:
                continue
            contact = Contact(self.link_name.get(pt[3], str(pt[3])), label(body, pt[6]), dist, tuple(pt[6]))
            key = (contact.link, contact.shape)
            if key not in found or dist < found[key].distance:
                found[key] = contact
        return sorted(found.values(), key=lambda c: (c.distance, c.link, c.shape))

    def clearance(self, bodies, within: float = 1.0) -> float:
        """The smallest distance between the robot and any of ``bodies`` (``within`` when none is closer)."""
        nearest = within
        for body in bodies:
            if body == self.body:
                continue
            for pt in pb.getClosestPoints(self.body, body, within, physicsClientId=self.client):
                nearest = min(nearest, pt[8])
        return nearest

    def remove(self) -> None:
        pb.removeBody(self.body, physicsClientId=self.client)


def spawn_pose(spawn) -> tuple[float, float, float]:
    values = [float(v) for v in spawn]
    if len(values) not in (2, 3) or not all(math.isfinite(v) for v in values):
        raise InputError(f"spawn pose must be x, y or x, y, yaw (finite numbers), not {spawn!r}")
    return values[0], values[1], values[2] if len(values) == 3 else 0.0


def collision_urdf(urdf: str, source: Path) -> str:
    """The URDF as pybullet should load it: no visuals and no <gazebo> blocks (DIRECT mode renders nothing, and
    a missing visual mesh would fail the whole load), mesh paths absolute (package://, file:// and paths
    relative to the description's own folder), and a tiny inertial on every link that has none — pybullet
    would give such a frame link 1 kg, Gazebo drops it (turtlebot3_description's base_footprint, imu_link and
    camera frames have none)."""
    root = ET.fromstring(urdf)
    for gazebo in root.findall("gazebo"):
        root.remove(gazebo)
    for link in root.findall("link"):
        for visual in link.findall("visual"):
            link.remove(visual)
        if link.find("inertial") is None:
            inertial = ET.SubElement(link, "inertial")
            ET.SubElement(inertial, "mass", value="1e-05")
            ET.SubElement(inertial, "inertia", ixx="1e-09", ixy="0", ixz="0", iyy="1e-09", iyz="0", izz="1e-09")
        for mesh in link.iter("mesh"):
            name = absolute_mesh_paths(mesh.get("filename", ""), source)
            if name and not os.path.isabs(name):
                name = str((source.parent / name).resolve())
            mesh.set("filename", name)
    return ET.tostring(root, encoding="unicode")
