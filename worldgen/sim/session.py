"""A headless pybullet session that behaves like Gazebo with TurtleBot3s in it: the world's shapes as static
bodies, one or more robots (:mod:`.robot`: our description on the floor at its spawn pose, the diff-drive
plugin's wheel commands, ground-truth odometry, the LDS-01 LiDAR, contacts), and models spawned, moved and
deleted while it runs (:mod:`.models`, what Gazebo's spawn/set/delete services do), and what the robots' cameras
see (:mod:`.camera_scene`, drawn when first asked for). The first robot is *the*
robot: the session's robot attributes and methods (``odometry``, ``scan``, ``cmd_vel`` …) are its.

Always a DIRECT client of its own (every call passes ``physicsClientId``), closed by :meth:`Session.close` or
the ``with`` block. pybullet writes warnings to the C-level stdout and can crash the process on bad input, so
programs run sessions through :func:`worldgen.sim.process.run_isolated`.

Gazebo's TurtleBot3 worlds step ODE at 1 ms with 150 iterations; here the step is 1/240 s with 10 solver
iterations (see ``DEFAULT_TIME_STEP``), which keeps the wheel contacts stable and the session far faster than
real time. Friction follows Gazebo's: each robot link gets the μ of its ``<gazebo>`` block (wheels and casters
0.1) and every other surface 1.0; Bullet multiplies the two, Gazebo takes the smaller, which agree here.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pybullet as pb

from ..core.scene import Scene, Shape
from .lidar import Scan
from .models import WorldModels
from .robot import TOUCH_DISTANCE, Contact, Odometry, Robot, TouchLog
from .scene_loader import MAX_ROBOTS, SCENE_GROUP, SCENE_MASK, SceneBodies, load_scene

GRAVITY = -9.8                  # Gazebo's default
DEFAULT_TIME_STEP = 1.0 / 240   # s; a whole number of steps per 30 Hz drive update and per 5 Hz scan
DEFAULT_SOLVER_ITERATIONS = 10


_SPARE: list[int] = []   # a client connected ahead of time (warm), taken by the next session


def warm() -> None:
    """Connect a pybullet client ahead of time (a third of a session's start): a fork server calls this once,
    and the first session of each fork takes its own copy of it (a fork copies the process's memory)."""
    if not _SPARE:
        _SPARE.append(connect())


def connect() -> int:
    """A DIRECT pybullet client without the software renderer built into pybullet, which turns each body's
    shapes into meshes as the body is made (10 ms for the ground plane and a TurtleBot3) and draws only for
    ``getCameraImage``, which nothing here calls (the cameras are drawn by :mod:`.camera_scene`). The physics
    and the rays are the same without it."""
    client = pb.connect(pb.DIRECT)
    renderer = pb.loadPlugin("tinyRendererPlugin", physicsClientId=client)   # built in: its id
    if renderer >= 0:
        pb.unloadPlugin(renderer, physicsClientId=client)
    return client


class Session:
    """Robots in one scene. ``spawn`` is (x, y) or (x, y, yaw) of the first robot's base frame, on the ground;
    :meth:`add_robot` adds more. ``seed`` seeds the LiDAR's noise (None: no noise, the exact ranges);
    ``no_hit`` is what a beam that hits nothing reads ("inf" as Gazebo, "zero" as the real LDS-01 driver).
    The physics' step and solver iterations are the class's (:data:`DEFAULT_TIME_STEP`); a world always gets
    Gazebo's ground plane."""

    time_step: float = DEFAULT_TIME_STEP
    solver_iterations: int = DEFAULT_SOLVER_ITERATIONS

    def __init__(self, scene: Scene | None = None, robot: str | Path = "burger", spawn=(0.0, 0.0, 0.0), *,
                 mappings: dict[str, str] | None = None, no_hit: str = "inf", seed: int | None = 0,
                 urdf: str | None = None, name: str = "turtlebot3"):
        self.no_hit = no_hit
        self.rng = np.random.default_rng(seed) if seed is not None else None
        self._steps = 0
        self.robots: list[Robot] = []
        self.client = _SPARE.pop() if _SPARE else connect()
        try:
            pb.setGravity(0, 0, GRAVITY, physicsClientId=self.client)
            pb.setPhysicsEngineParameter(fixedTimeStep=self.time_step, numSolverIterations=self.solver_iterations,
                                         numSubSteps=0, physicsClientId=self.client)
            scene = scene or Scene(source=None)
            self.scene = scene
            self.movers: dict[int, Shape] = {}
            self._camera_scene = None
            self.bodies: SceneBodies = load_scene(self.client, scene)
            self.models = WorldModels(self.client, self.bodies, scene)
            self.add_robot(robot, spawn, name=name, mappings=mappings, urdf=urdf)
            self._update_every = max(1, round(1.0 / (self.profile.drive.update_rate * self.time_step)))
        except BaseException:
            self.close()
            raise

    # -- robots ----------------------------------------------------------------------------------------------

    def add_robot(self, robot: str | Path = "burger", spawn=(0.0, 0.0, 0.0), *, name: str = "turtlebot3",
                  mappings: dict[str, str] | None = None, urdf: str | None = None, z: float = 0.0) -> Robot:
        """Another robot in the world (a free collision slot of its own); InputError when it cannot load."""
        used = {r.slot for r in self.robots}
        free = [i for i in range(MAX_ROBOTS) if i not in used]
        if not free:
            from ..core.errors import InputError

            raise InputError(f"at most {MAX_ROBOTS} robots in one simulation")
        added = Robot(self.client, robot, spawn, slot=free[0], name=name, mappings=mappings, urdf=urdf, z=z)
        self.robots.append(added)
        return added

    def remove_robot(self, robot: Robot) -> None:
        robot.remove()
        self.robots.remove(robot)

    @property
    def main(self) -> Robot:
        return self.robots[0]

    # The first robot's parts, as the session's own (one-robot callers).
    robot = property(lambda self: self.main.body)
    profile = property(lambda self: self.main.profile)
    drive = property(lambda self: self.main.drive)
    urdf = property(lambda self: self.main.urdf)
    link_index = property(lambda self: self.main.link_index)
    link_name = property(lambda self: self.main.link_name)
    wheels = property(lambda self: self.main.wheels)
    lidar = property(lambda self: self.main.lidar)
    base_index = property(lambda self: self.main.base_index)
    spawn = property(lambda self: self.main.spawn)

    @property
    def touches(self) -> TouchLog:
        return self.main.touches

    @touches.setter
    def touches(self, log: TouchLog) -> None:
        self.main.touches = log

    # -- bodies that are not robots --------------------------------------------------------------------------

    def add_mover(self, radius: float, height: float, label: str, position=(0.0, 0.0)) -> int:
        """A static upright cylinder (a person, say) that :meth:`move_body` moves: the LiDAR sees it, contacts
        name it ``label``. Returns its body id."""
        sid = pb.createCollisionShape(pb.GEOM_CYLINDER, radius=radius, height=height, physicsClientId=self.client)
        body = pb.createMultiBody(baseMass=0, baseCollisionShapeIndex=sid,
                                  basePosition=[position[0], position[1], height / 2], physicsClientId=self.client)
        pb.setCollisionFilterGroupMask(body, -1, SCENE_GROUP, SCENE_MASK, physicsClientId=self.client)
        self.bodies.shapes[body] = [Shape("cylinder", (position[0], position[1], height / 2), radius=radius,
                                          length=height, model=label)]
        self.movers[body] = self.bodies.shapes[body][0]
        return body

    def move_body(self, body: int, x: float, y: float) -> None:
        """Put a body made by :meth:`add_mover` at (x, y) on the floor."""
        z = pb.getBasePositionAndOrientation(body, physicsClientId=self.client)[0][2]
        pb.resetBasePositionAndOrientation(body, [x, y, z], [0, 0, 0, 1], physicsClientId=self.client)
        shape = self.bodies.shapes[body][0]
        shape.position = (x, y, z)

    def label(self, body: int, point) -> str:
        """What a contact with ``body`` at ``point`` touched: a scene shape's label, or a robot's model name."""
        for other in self.robots:
            if other.body == body:
                return other.name
        return self.bodies.label(body, point)

    # -- time ------------------------------------------------------------------------------------------------

    def cmd_vel(self, v: float, omega: float = 0.0) -> None:
        """Publish a velocity command (m/s forward, rad/s CCW); it holds until the next one."""
        self.main.drive.command = (float(v), float(omega))

    def start_exercise(self) -> None:
        """Forget the contacts logged so far and restart the drive plugin's ramp from the wheels' measured speeds,
        so that an exercise neither reports a previous one's touches nor inherits the stale ramp state it left
        (see :mod:`.drive`). Behaviours call this at their start."""
        self.touches = TouchLog()
        self.drive.ramped = list(self.wheel_rim_speeds())

    def run(self, seconds: float) -> None:
        """Advance the simulation by ``seconds`` (whole steps), updating every robot's drive at its rate from
        the wheels' measured speeds and logging every contact at each drive update."""
        for _ in range(max(0, round(seconds / self.time_step))):
            if self._steps % self._update_every == 0:
                for robot in self.robots:
                    robot.update_drive(self._update_every * self.time_step)
                    robot.touches.add(self.t, self.contacts_of(robot))
            pb.stepSimulation(physicsClientId=self.client)
            self._steps += 1

    # -- state -----------------------------------------------------------------------------------------------

    @property
    def t(self) -> float:
        """Simulated seconds since the session started."""
        return self._steps * self.time_step

    def link_pose(self, link: str | int):
        """World position and quaternion (x, y, z, w) of a robot link's frame (name or index; -1 = root)."""
        return self.main.link_pose(link)

    def wheel_rim_speeds(self) -> tuple[float, float]:
        """The drive wheels' measured rim speeds (left, right) in m/s: joint speed × the drive's wheel radius."""
        return self.main.wheel_rim_speeds()

    def wheel_states(self) -> tuple[tuple[float, float], tuple[float, float]]:
        """The drive wheels' joint angles (rad) and speeds (rad/s): ((left, right), (left, right))."""
        return self.main.wheel_states()

    def base_velocity(self) -> tuple[tuple[float, float, float], tuple[float, float, float]]:
        """World-frame linear (m/s) and angular (rad/s) velocity of the base frame."""
        return self.main.base_velocity()

    def clearance(self, within: float = 1.0) -> float:
        """The smallest distance between the robot and any scene body but the ground, or another robot
        (``within`` when nothing is closer than that)."""
        return self.clearance_of(self.main, within)

    def clearance_of(self, robot: Robot, within: float = 1.0) -> float:
        others = [r.body for r in self.robots if r is not robot]
        return robot.clearance(self.bodies.obstacle_bodies + others, within)

    def odometry(self) -> Odometry:
        return self.main.odometry(self.t)

    def scan(self, noise: bool = True) -> Scan:
        """One LiDAR scan from the sensor's current pose (``noise`` False: the exact ranges)."""
        return self.scan_of(self.main, noise)

    def scan_of(self, robot: Robot, noise: bool = True) -> Scan:
        return robot.scan(self.t, self.no_hit, self.rng if noise else None)

    def contacts(self, touch_distance: float = TOUCH_DISTANCE) -> list[Contact]:
        """What the robot touches other than the ground: one entry per (link, shape), deepest point first."""
        return self.contacts_of(self.main, touch_distance)

    def contacts_of(self, robot: Robot, touch_distance: float = TOUCH_DISTANCE) -> list[Contact]:
        return robot.contacts(self.label, self.bodies.planes, touch_distance)

    # -- cameras ---------------------------------------------------------------------------------------------

    def open_cameras(self):
        """The drawing state of the robots' cameras (:mod:`.camera_scene`), its OpenGL context made now:
        InputError naming the packages to install when it cannot be."""
        if self._camera_scene is None:
            from .camera_scene import CameraScene

            self._camera_scene = CameraScene(self)
        self._camera_scene.open()
        return self._camera_scene

    def camera_image(self, robot: Robot, camera) -> np.ndarray:
        """What ``camera`` (one of ``robot.profile.cameras``) sees now: height × width × 3 uint8 RGB."""
        return self.open_cameras().image(robot, camera)

    # -- teardown --------------------------------------------------------------------------------------------

    def close(self) -> None:
        cameras, self._camera_scene = getattr(self, "_camera_scene", None), None
        if cameras is not None:
            cameras.close()
        client, self.client = getattr(self, "client", None), None
        if client is not None and pb.isConnected(physicsClientId=client):
            pb.disconnect(physicsClientId=client)

    def __enter__(self) -> Session:
        return self

    def __exit__(self, *exc) -> None:
        self.close()
