"""What the simulated TurtleBot3 publishes on each stack, against the upstream plugin that fills it there: the rows
of the README's fidelity table that no live transport test shows on its own (the live ones:
tests/test_bridge_sim.py for ROS 1, tests/test_ros2_live.py for ROS 2). Transport-free: the robot interface's
message contents (:class:`worldgen.interface.robot.RobotIO`) over a real pybullet session.
"""

from __future__ import annotations

import itertools
import math
import re

import pytest
from conftest import REPO

from worldgen.interface.robot import ODOM_COV, PLUGINS, RobotIO
from worldgen.sim.behaviours import settle
from worldgen.sim.session import Session

SPAWN = (1.0, 2.0, math.pi / 2)


@pytest.fixture(scope="module")
def at_rest():
    """A Burger settled at ``SPAWN`` on an empty floor."""
    with Session(None, "burger", SPAWN) as session:
        settle(session, 0.5)
        yield session


def messages(session, stack: str) -> dict:
    io = RobotIO(session.main, plugins=PLUGINS[stack], model="burger")
    out = io.drive(session.t, odom=True, tf=True, joint_states=True)
    io.imu(session.time_step, session.t)
    session.run(session.time_step)
    out["imu"] = io.imu(session.time_step, session.t)
    return out


def test_odometry_covariances_per_stack(at_rest):
    """gazebo_ros_diff_drive (ROS 1) fills the pose's covariance and leaves the twist's zero; ROS 2's copies the
    pose's into the twist; Gazebo Sim's DiffDrive (Jazzy) leaves both zero."""
    noetic, humble, jazzy = (messages(at_rest, s)["odom"] for s in ("noetic", "humble", "jazzy"))
    assert noetic["pose"]["covariance"] == ODOM_COV and noetic["twist"]["covariance"] == [0.0] * 36
    assert humble["pose"]["covariance"] == ODOM_COV and humble["twist"]["covariance"] == ODOM_COV
    assert jazzy["pose"]["covariance"] == [0.0] * 36 and jazzy["twist"]["covariance"] == [0.0] * 36


def test_odometry_pose_per_stack(at_rest):
    """Gazebo Classic's plugin reports the true pose in the world (odometrySource world); Gazebo Sim's counts
    from the spawn pose (the robot starts at 0, 0, heading 0)."""
    noetic, jazzy = (messages(at_rest, s)["odom"]["pose"]["pose"] for s in ("noetic", "jazzy"))
    assert (noetic["position"]["x"], noetic["position"]["y"]) == pytest.approx(SPAWN[:2], abs=0.01)
    assert 2 * math.atan2(noetic["orientation"]["z"], noetic["orientation"]["w"]) == pytest.approx(SPAWN[2], abs=0.01)
    assert (jazzy["position"]["x"], jazzy["position"]["y"], jazzy["position"]["z"]) == pytest.approx((0, 0, 0),
                                                                                                     abs=0.01)
    assert abs(jazzy["orientation"]["z"]) < 0.01


def test_joint_states_per_stack(at_rest):
    """ROS 1's diff drive: positions only; ROS 2's gazebo_ros_joint_state_publisher: positions and velocities;
    Gazebo Sim's JointStatePublisher: efforts as well."""
    noetic, humble, jazzy = (messages(at_rest, s)["joint_states"] for s in ("noetic", "humble", "jazzy"))
    assert noetic["name"] == ["wheel_left_joint", "wheel_right_joint"]
    assert (len(noetic["position"]), noetic["velocity"], noetic["effort"]) == (2, [], [])
    assert (len(humble["velocity"]), humble["effort"]) == (2, [])
    assert (len(jazzy["velocity"]), jazzy["effort"]) == (2, [0.0, 0.0])


def test_the_imu_at_rest_per_stack(at_rest):
    """Noetic's TurtleBot3 IMU is the model plugin libgazebo_ros_imu (velocity differenced: about 0 at rest, no
    gravity, covariances 0); Humble's and Jazzy's are IMU sensors (gravity: +9.8 up, the xacro's noise as
    covariances), Jazzy's framed by Gazebo Sim's scoped name."""
    noetic, humble, jazzy = (messages(at_rest, s)["imu"] for s in ("noetic", "humble", "jazzy"))
    assert noetic["header"]["frame_id"] == humble["header"]["frame_id"] == "imu_link"
    assert jazzy["header"]["frame_id"] == "burger/imu_link/tb3_imu"
    assert abs(noetic["linear_acceleration"]["z"]) < 0.2
    assert humble["linear_acceleration"]["z"] == pytest.approx(9.8, abs=0.2)
    assert jazzy["linear_acceleration"]["z"] == pytest.approx(9.8, abs=0.2)
    assert noetic["angular_velocity_covariance"] == [0.0] * 9
    assert humble["angular_velocity_covariance"][::4] == [4e-8] * 3
    assert humble["linear_acceleration_covariance"][::4] == [2.89e-4] * 3


FIDELITY = re.compile(r"^\| (?P<quantity>[^|]+) \|(?:[^|]*\|){3} (?P<tests>[^|]+) \|$")


def fidelity_rows() -> list[tuple[str, list[str]]]:
    """The README's fidelity table: each row's quantity and the tests it names (``FILE::NAME``)."""
    text = (REPO / "README.md").read_text(encoding="utf-8")
    after = text.split("### Fidelity", 1)[1].split("\n| quantity |", 1)[1].splitlines()
    rows = [FIDELITY.match(line) for line in itertools.takewhile(lambda line: line.startswith("|"), after[2:])]
    assert all(rows), "a row of the fidelity table does not have five cells"
    return [(m["quantity"], re.findall(r"`(test_\w+\.py)::(\w+)`", m["tests"])) for m in rows]


def test_every_row_of_the_fidelity_table_names_a_test_that_exists():
    rows = fidelity_rows()
    assert len(rows) >= 12
    for quantity, tests in rows:
        assert tests, f"{quantity}: no test named"
        for path, name in tests:
            source = (REPO / "tests" / path).read_text(encoding="utf-8")
            assert re.search(rf"^def {name}\(", source, re.M), f"{quantity}: {path}::{name} is not a test"
