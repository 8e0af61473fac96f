"""A headless pybullet session that behaves like a TurtleBot3 in Gazebo: the world's shapes as static bodies,
our robot description on the floor at the spawn pose, the diff-drive plugin's wheel commands, ground-truth
odometry, the LDS-01 LiDAR, and contact queries.

Always a DIRECT client of its own (every call passes ``physicsClientId``), closed by :meth:`Session.close` or
the ``with`` block. pybullet writes warnings to the C-level stdout and can crash the process on bad input, so
programs run sessions through :func:`worldgen.sim.process.run_isolated`.

Gazebo's TurtleBot3 worlds step ODE at 1 ms with 150 iterations; here the step is 1/240 s with 10 solver
iterations (see ``DEFAULT_TIME_STEP``), which keeps the wheel contacts stable and the session far faster than
real time. Friction follows Gazebo's: each robot link gets the μ of its ``<gazebo>`` block (wheels and casters
0.1) and every other surface 1.0; Bullet multiplies the two, Gazebo takes the smaller, which agree here.
"""

from __future__ import annotations

import math
import os
import tempfile
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pybullet as pb

from ..core.errors import InputError
from ..robots.description import absolute_mesh_paths, robot_file, robot_urdf
from ..robots.profile import LidarParams, RobotProfile, robot_profile
from ..core.scene import Scene
from .drive import DiffDrive
from .lidar import Scan, cast_scan
from .scene_loader import ROBOT_GROUP, ROBOT_MASK, SCENE_GROUP, SCENE_MASK, SceneBodies, load_scene

GRAVITY = -9.8                  # Gazebo's default
DEFAULT_TIME_STEP = 1.0 / 240   # s; a whole number of steps per 30 Hz drive update and per 5 Hz scan
DEFAULT_SOLVER_ITERATIONS = 10
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


class Session:
    """One robot in one scene. ``spawn`` is (x, y) or (x, y, yaw) of the base frame, on the ground (z = 0)."""

    def __init__(self, scene: Scene | None = None, robot: str | Path = "burger", spawn=(0.0, 0.0, 0.0), *,
                 mappings: dict[str, str] | None = None, time_step: float = DEFAULT_TIME_STEP,
                 solver_iterations: int = DEFAULT_SOLVER_ITERATIONS, no_hit: str = "inf", noise: bool = True,
                 seed: int = 0, add_ground: bool = True, urdf: str | None = None):
        self.time_step = time_step
        self.no_hit = no_hit
        self.rng = np.random.default_rng(seed) if noise else None
        self.touches = TouchLog()
        self._steps = 0
        source = robot_file(robot)
        self.urdf = urdf if urdf is not None else robot_urdf(robot, mappings)
        self.profile: RobotProfile = robot_profile(self.urdf, source=str(source))
        if self.profile.drive is None:
            raise InputError("the robot has no differential drive: no libgazebo_ros_diff_drive plugin and no "
                             "joints named wheel_left_joint/wheel_right_joint", path=source,
                             hint="use a TurtleBot3 model or add the diff-drive plugin block to the URDF")
        self.drive = DiffDrive(self.profile.drive)
        self._update_every = max(1, round(1.0 / (self.profile.drive.update_rate * time_step)))
        self.client = pb.connect(pb.DIRECT)
        try:
            pb.setGravity(0, 0, GRAVITY, physicsClientId=self.client)
            pb.setPhysicsEngineParameter(fixedTimeStep=time_step, numSolverIterations=solver_iterations,
                                         numSubSteps=0, physicsClientId=self.client)
            self.bodies: SceneBodies = load_scene(self.client, scene or Scene(source=None), add_ground=add_ground)
            self.robot = self._load_robot(source, spawn)
        except BaseException:
            self.close()
            raise

    # -- setup -----------------------------------------------------------------------------------------------

    def _load_robot(self, source: Path, spawn) -> int:
        x, y, yaw = _spawn_pose(spawn)
        text = _collision_urdf(self.urdf, source)
        fd, path = tempfile.mkstemp(prefix="worldgen_robot_", suffix=".urdf")
        try:
            with os.fdopen(fd, "w", encoding="utf-8") as fh:
                fh.write(text)
            try:
                # Inertias as written (not recomputed from the shapes), and true cylinders for the wheels:
                # pybullet otherwise turns them into polygonal hulls that bump along at low speed.
                robot = pb.loadURDF(path, [x, y, 0.0], pb.getQuaternionFromEuler([0, 0, yaw]),
                                    flags=pb.URDF_USE_INERTIA_FROM_FILE | pb.URDF_USE_IMPLICIT_CYLINDER,
                                    physicsClientId=self.client)
            except pb.error as err:
                raise InputError(f"pybullet cannot load the robot description ({err})", path=source,
                                 hint="check that every collision mesh file exists") from None
        finally:
            os.unlink(path)
        # pybullet numbers each joint as its child link; the root link is -1
        self.link_index = {pb.getBodyInfo(robot, physicsClientId=self.client)[0].decode(): -1}
        joint_index, movable = {}, []
        for j in range(pb.getNumJoints(robot, physicsClientId=self.client)):
            info = pb.getJointInfo(robot, j, physicsClientId=self.client)
            self.link_index[info[12].decode()] = j
            joint_index[info[1].decode()] = j
            if info[2] != pb.JOINT_FIXED:
                movable.append(j)
        self.link_name = {i: n for n, i in self.link_index.items()}
        # Damping is per multibody (and, passed with a link index, pybullet drops the whole call): Gazebo has none.
        pb.changeDynamics(robot, -1, linearDamping=0.0, angularDamping=0.0, physicsClientId=self.client)
        for index, name in self.link_name.items():
            pb.changeDynamics(robot, index, lateralFriction=self.profile.friction.get(name, 1.0),
                              physicsClientId=self.client)
            pb.setCollisionFilterGroupMask(robot, index, ROBOT_GROUP, ROBOT_MASK, physicsClientId=self.client)
        drive = self.profile.drive
        self.wheels = (joint_index[drive.left_joint], joint_index[drive.right_joint])
        for j in movable:  # joints without a controller turn freely, as in Gazebo
            pb.setJointMotorControl2(robot, j, pb.VELOCITY_CONTROL, targetVelocity=0.0,
                                     force=drive.torque if j in self.wheels else 0.0, physicsClientId=self.client)
        lidar = self.profile.lidar
        self.lidar: LidarParams | None = lidar if lidar is not None and lidar.link in self.link_index else None
        self.base_index = self.link_index.get(self.profile.base_frame, -1)
        self.spawn = (x, y, yaw)
        self._initial_base = pb.getBasePositionAndOrientation(robot, physicsClientId=self.client)
        return robot

    def add_mover(self, radius: float, height: float, label: str, position=(0.0, 0.0)) -> int:
        """A static upright cylinder (a person, say) that :meth:`move_body` moves: the LiDAR sees it, contacts
        name it ``label``. Returns its body id."""
        from ..core.scene import Shape

        sid = pb.createCollisionShape(pb.GEOM_CYLINDER, radius=radius, height=height, physicsClientId=self.client)
        body = pb.createMultiBody(baseMass=0, baseCollisionShapeIndex=sid,
                                  basePosition=[position[0], position[1], height / 2], physicsClientId=self.client)
        pb.setCollisionFilterGroupMask(body, -1, SCENE_GROUP, SCENE_MASK, physicsClientId=self.client)
        self.bodies.shapes[body] = [Shape("cylinder", (position[0], position[1], height / 2), radius=radius,
                                          length=height, model=label)]
        return body

    def move_body(self, body: int, x: float, y: float) -> None:
        """Put a body made by :meth:`add_mover` at (x, y) on the floor."""
        z = pb.getBasePositionAndOrientation(body, physicsClientId=self.client)[0][2]
        pb.resetBasePositionAndOrientation(body, [x, y, z], [0, 0, 0, 1], physicsClientId=self.client)
        shape = self.bodies.shapes[body][0]
        shape.position = (x, y, z)

    def reset_robot(self) -> None:
        """Put the robot back at its spawn pose, at rest, wheels at angle 0 and the command at zero (what
        Gazebo's reset_world does to a model); simulated time keeps running."""
        position, orientation = self._initial_base
        pb.resetBasePositionAndOrientation(self.robot, position, orientation, physicsClientId=self.client)
        pb.resetBaseVelocity(self.robot, [0, 0, 0], [0, 0, 0], physicsClientId=self.client)
        for j in range(pb.getNumJoints(self.robot, physicsClientId=self.client)):
            pb.resetJointState(self.robot, j, 0.0, 0.0, physicsClientId=self.client)
        self.drive.command = (0.0, 0.0)
        self.drive.ramped = [0.0, 0.0]

    # -- time ------------------------------------------------------------------------------------------------

    def cmd_vel(self, v: float, omega: float = 0.0) -> None:
        """Publish a velocity command (m/s forward, rad/s CCW); it holds until the next one."""
        self.drive.command = (float(v), float(omega))

    def start_exercise(self) -> None:
        """Forget the contacts logged so far and restart the drive plugin's ramp from the wheels' measured speeds,
        so that an exercise neither reports a previous one's touches nor inherits the stale ramp state it left
        (see :mod:`.drive`). Behaviours call this at their start."""
        self.touches = TouchLog()
        self.drive.ramped = list(self.wheel_rim_speeds())

    def run(self, seconds: float) -> None:
        """Advance the simulation by ``seconds`` (whole steps), updating the drive at its rate from the wheels'
        measured speeds and logging every contact with the scene at each drive update."""
        for _ in range(max(0, round(seconds / self.time_step))):
            if self._steps % self._update_every == 0:
                left, right = self.drive.update(self._update_every * self.time_step, self.wheel_rim_speeds())
                for joint, speed in zip(self.wheels, (left, right)):
                    pb.setJointMotorControl2(self.robot, joint, pb.VELOCITY_CONTROL, targetVelocity=speed,
                                             force=self.drive.params.torque, physicsClientId=self.client)
                self.touches.add(self.t, self.contacts())
            pb.stepSimulation(physicsClientId=self.client)
            self._steps += 1

    # -- state -----------------------------------------------------------------------------------------------

    @property
    def t(self) -> float:
        """Simulated seconds since the session started."""
        return self._steps * self.time_step

    def link_pose(self, link: str | int):
        """World position and quaternion (x, y, z, w) of a robot link's frame (name or index; -1 = root)."""
        index = self.link_index[link] if isinstance(link, str) else link
        if index == -1:
            com_pos, com_orn = pb.getBasePositionAndOrientation(self.robot, physicsClientId=self.client)
            local_pos, local_orn = pb.getDynamicsInfo(self.robot, -1, physicsClientId=self.client)[3:5]
            inv_pos, inv_orn = pb.invertTransform(local_pos, local_orn)
            return pb.multiplyTransforms(com_pos, com_orn, inv_pos, inv_orn)
        state = pb.getLinkState(self.robot, index, computeForwardKinematics=True, physicsClientId=self.client)
        return state[4], state[5]

    def wheel_rim_speeds(self) -> tuple[float, float]:
        """The drive wheels' measured rim speeds (left, right) in m/s: joint speed × the drive's wheel radius."""
        states = pb.getJointStates(self.robot, self.wheels, physicsClientId=self.client)
        return states[0][1] * self.drive.params.wheel_radius, states[1][1] * self.drive.params.wheel_radius

    def wheel_states(self) -> tuple[tuple[float, float], tuple[float, float]]:
        """The drive wheels' joint angles (rad) and speeds (rad/s): ((left, right), (left, right))."""
        states = pb.getJointStates(self.robot, self.wheels, physicsClientId=self.client)
        return (states[0][0], states[1][0]), (states[0][1], states[1][1])

    def base_velocity(self) -> tuple[tuple[float, float, float], tuple[float, float, float]]:
        """World-frame linear (m/s) and angular (rad/s) velocity of the base frame."""
        if self.base_index == -1:
            lin, ang = pb.getBaseVelocity(self.robot, physicsClientId=self.client)
        else:
            state = pb.getLinkState(self.robot, self.base_index, computeLinkVelocity=True,
                                    physicsClientId=self.client)
            lin, ang = state[6], state[7]
        return tuple(lin), tuple(ang)

    def clearance(self, within: float = 1.0) -> float:
        """The smallest distance between the robot and any scene body but the ground (``within`` when nothing
        is closer than that)."""
        nearest = within
        for body in self.bodies.obstacle_bodies:
            for pt in pb.getClosestPoints(self.robot, body, within, physicsClientId=self.client):
                nearest = min(nearest, pt[8])
        return nearest

    def odometry(self) -> Odometry:
        (x, y, z), quat = self.link_pose(self.base_index)
        roll, pitch, yaw = pb.getEulerFromQuaternion(quat)
        lin, ang = self.base_velocity()
        v = lin[0] * math.cos(yaw) + lin[1] * math.sin(yaw)
        return Odometry(self.t, x, y, z, roll, pitch, yaw, v, ang[2])

    def scan(self, noise: bool = True) -> Scan:
        """One LiDAR scan from the sensor's current pose (``noise`` False: quantised exact ranges)."""
        if self.lidar is None:
            raise InputError("the robot has no LiDAR (no ray sensor block and no base_scan link)",
                             hint="use a TurtleBot3 model or add a <sensor type=\"ray\"> block")
        pos, orn = self.link_pose(self.lidar.link)
        px, py, pz, rr, rp, ry = self.lidar.pose
        pos, orn = pb.multiplyTransforms(pos, orn, [px, py, pz], pb.getQuaternionFromEuler([rr, rp, ry]))
        return cast_scan(self.client, self.lidar, pos, orn, no_hit=self.no_hit,
                         rng=self.rng if noise else None, time=self.t)

    def contacts(self, touch_distance: float = TOUCH_DISTANCE) -> list[Contact]:
        """What the robot touches other than the ground: one entry per (link, shape), deepest point first."""
        found: dict[tuple[str, str], Contact] = {}
        planes = self.bodies.planes
        for pt in pb.getContactPoints(bodyA=self.robot, physicsClientId=self.client):
            body, dist = pt[2], pt[8]
            if body == self.robot or body in planes or dist > touch_distance:
                continue
            contact = Contact(self.link_name.get(pt[3], str(pt[3])), self.bodies.label(body, pt[6]), dist,
                              tuple(pt[6]))
            key = (contact.link, contact.shape)
            if key not in found or dist < found[key].distance:
                found[key] = contact
        return sorted(found.values(), key=lambda c: (c.distance, c.link, c.shape))

    # -- teardown --------------------------------------------------------------------------------------------

    def close(self) -> None:
        client, self.client = getattr(self, "client", None), None
        if client is not None and pb.isConnected(physicsClientId=client):
            pb.disconnect(physicsClientId=client)

    def __enter__(self) -> Session:
        return self

    def __exit__(self, *exc) -> None:
        self.close()


def _spawn_pose(spawn) -> tuple[float, float, float]:
    values = [float(v) for v in spawn]
    if len(values) not in (2, 3) or not all(math.isfinite(v) for v in values):
        raise InputError(f"spawn pose must be x, y or x, y, yaw (finite numbers), not {spawn!r}")
    return values[0], values[1], values[2] if len(values) == 3 else 0.0


def _collision_urdf(urdf: str, source: Path) -> str:
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
