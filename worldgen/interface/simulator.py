"""What every simulator process (ROS 1's :mod:`worldgen.ros1.node`, ROS 2's :mod:`worldgen.ros2.node`) makes of its
config before its transport has a say: the session with its robots (:func:`open_session`, :func:`session_robots`),
the robot graded among several (:func:`graded_of`), the person a person-follow run moves round its loop
(:class:`Person`), and the trace written whole at the end (:func:`write_trace`)."""

from __future__ import annotations

import json
import math
import os

from ..core.scene import Scene
from ..robots import robot_urdf
from ..robots.profile import robot_profile
from ..sim.session import Session

NO_TIMING = {"sim_time_s": 0.0, "wall_time_s": 0.0, "real_time_factor": None, "interrupted": True}   # never ran


def model_name(robot: str | None) -> str:
    """The model name a robot gets in Gazebo's lists: ``turtlebot3_burger`` as the class's launch files spawn it."""
    robot = robot or "burger"
    return f"turtlebot3_{robot}" if robot in ("burger", "waffle", "waffle_pi") else "turtlebot3"


def open_session(config: dict) -> Session:
    """The config's scene with its first robot, the OpenGL context made when any robot has a camera (WorldgenError
    naming what to install when it cannot be, before anything joins a ROS graph)."""
    first = (config.get("robots") or [{}])[0]
    session = Session(Scene.load(config["scene_file"]), first.get("robot") or config.get("robot") or "burger",
                      tuple(first.get("spawn") or config["spawn"]), no_hit=config.get("no_hit", "inf"),
                      seed=config.get("seed", 0), mappings=first.get("mappings"),
                      name=first.get("name") or model_name(config.get("robot")))
    if session.main.profile.cameras or any(
            robot_profile(robot_urdf(e.get("robot") or "burger", e.get("mappings"))).cameras
            for e in (config.get("robots") or [{}])[1:]):
        session.open_cameras()
    return session


def session_robots(session: Session, config: dict) -> list:
    """Each robot of the config with its entry (name, ns, robot, spawn, tf_prefix, mappings): the session's first
    robot for the first entry, the others added to the session."""
    found = []
    for i, entry in enumerate(config.get("robots") or [{}]):
        robot = session.robots[0] if i == 0 else session.add_robot(
            entry.get("robot") or "burger", entry["spawn"], name=entry.get("name") or f"robot_{i}",
            mappings=entry.get("mappings"))
        if i == 0 and entry.get("name"):
            robot.name = entry["name"]
        found.append((robot, entry))
    return found


def graded_of(robots: list, which):
    """The robot (anything with ``ns`` and ``robot``) named by ``which``, its namespace with or without slashes or
    its model name; the first when none is."""
    return next((r for r in robots if which in (r.ns, r.ns.strip("/"), r.robot.name)), robots[0])


class Person:
    """The person of a person-follow run: a body the session moves round the config's loop at a walking speed, and
    the path it took (``[t, x, y]`` rows of the trace)."""

    def __init__(self, session: Session, loop: dict):
        self.loop = loop
        self.path: list = []
        self.body = session.add_mover(loop["radius"], loop["height"], "person", self.xy(0.0))

    def xy(self, t: float) -> tuple[float, float]:
        p = self.loop
        angle = p["phase"] + p["speed"] * t / p["loop_radius"]
        return (p["centre"][0] + p["loop_radius"] * math.cos(angle), p["centre"][1] + p["loop_radius"] * math.sin(angle))

    def record(self, t: float) -> None:
        self.path.append([t, *self.xy(t)])


def person_of(session: Session, config: dict) -> Person | None:
    return Person(session, config["person"]) if config.get("person") else None


def write_trace(path: str, data: dict) -> None:
    """``data`` as JSON at ``path``, whole or not at all (a run takes the file's presence as the run's end)."""
    tmp = f"{path}.part"
    with open(tmp, "w", encoding="utf-8") as fh:
        json.dump(data, fh)
    os.replace(tmp, path)
