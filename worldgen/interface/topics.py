"""What a TurtleBot3 in Gazebo publishes and takes on each stack, as data: one :class:`Topic` per topic, read by
every transport (the ROS 1 one makes rospy publishers of it, the ROS 2 one DDS writers), so a name, a type, a rate
or a QoS is written down once. The sources of each stack's rows are in the README's topic tables
(``docs/ros2_stacks.md`` holds the ROS 2 ones with the lines they were read from).

Rates are in simulated time and come from the step loop (:mod:`.loop`): the physics step is 1/240 s, the drive
plugins update at 30 Hz, the LiDAR at 5 Hz, the camera at 30 Hz; ``/clock`` and the IMU go out every other step.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Iterable

STACKS = ("noetic", "humble", "jazzy")
ROS2_STACKS = ("humble", "jazzy")


@dataclass(frozen=True)
class Qos:
    """A ROS 2 QoS as rclcpp/rclpy name it (ROS 1 uses ``depth`` as the publisher's queue size and
    ``transient_local`` as ``latch``)."""

    reliable: bool = True
    depth: int = 10
    transient_local: bool = False

    def describe(self) -> str:
        return (f"{'reliable' if self.reliable else 'best effort'}, "
                f"{'transient local' if self.transient_local else 'volatile'}, keep last {self.depth}")


DEFAULT = Qos()                                  # rclcpp::QoS(10) / rclpy's depth 10: what most nodes use
SENSOR_DATA = Qos(reliable=False, depth=5)       # rclcpp::SensorDataQoS / rclpy's qos_profile_sensor_data
LATCHED = Qos(reliable=True, depth=1, transient_local=True)   # robot_state_publisher's /tf_static


@dataclass(frozen=True)
class Topic:
    """One topic: ``key`` names it for the code (``scan``, ``odom`` …), ``name`` is relative to the robot's
    namespace for a robot's own topic (``per_robot``), absolute otherwise; ``type`` in ROS 2's spelling
    (``sensor_msgs/msg/LaserScan``); ``direction`` ``out`` (the simulator publishes) or ``in``; ``rate`` in Hz of
    simulated time (None: on change, or latched once); ``node`` the node that publishes or subscribes it in Gazebo
    (as ``ros2 node list`` / ``rosnode list`` shows it)."""

    key: str
    name: str
    type: str
    direction: str
    rate: float | None
    node: str
    qos: Qos = DEFAULT
    per_robot: bool = True

    def full_name(self, ns: str = "/") -> str:
        return join(ns, self.name) if self.per_robot else self.name


def join(ns: str, name: str) -> str:
    """``ns`` + ``name``: ``/tb3_0/scan``, or ``/scan`` in the global namespace."""
    return f"{ns.rstrip('/')}/{name}" if ns not in ("", "/") else f"/{name}"


def near_topic(name: str, published: Iterable[str]) -> str | None:
    """The topic of ``published`` (the simulator's) that ``name``, a topic nothing publishes, most likely misspells:
    one in the same namespace whose last part is at most a letter or so off (``/scans``: ``/scan``); None when none
    is that near (``/image`` is no ``/imu``, ``/odometry`` no ``/odom``)."""
    import difflib

    space, _, last = name.rpartition("/")
    candidates = {t.rpartition("/")[2].lower(): t for t in sorted(published)
                  if t.rpartition("/")[0] == space and t != "/rosout"}
    close = difflib.get_close_matches(last.lower(), list(candidates), n=1, cutoff=0.8)
    return candidates[close[0]] if close and len(last) >= 2 else None


def frame(prefix: str, name: str) -> str:
    """A frame id with the robot's tf prefix (none for the class's one robot)."""
    return f"{prefix}/{name}" if prefix else name


CLOCK_HZ, DRIVE_HZ, SCAN_HZ, IMU_HZ = 120.0, 30.0, 5.0, 120.0
# The topic (key) a task's node must subscribe to before simulated time starts (besides publishing cmd_vel): the
# tasks judged on what the LiDAR sees. A run waits for it, so that the first scan reaches the node.
TASK_INPUTS = {"stop-at-wall": "scan", "wall-follow": "scan", "person-follow": "scan"}

# ROS 1 Noetic + Gazebo Classic 11: gazebo_ros and turtlebot3_gazebo's plugins (../shared/reference/turtlebot3.md).
_NOETIC = (
    Topic("clock", "/clock", "rosgraph_msgs/msg/Clock", "out", CLOCK_HZ, "/gazebo", Qos(depth=10), False),
    Topic("tf", "/tf", "tf2_msgs/msg/TFMessage", "out", DRIVE_HZ, "/gazebo", Qos(depth=100), False),
    Topic("tf_static", "/tf_static", "tf2_msgs/msg/TFMessage", "out", None, "/robot_state_publisher",
          Qos(depth=10, transient_local=True), False),
    Topic("scan", "scan", "sensor_msgs/msg/LaserScan", "out", SCAN_HZ, "/gazebo", Qos(depth=5)),
    Topic("odom", "odom", "nav_msgs/msg/Odometry", "out", DRIVE_HZ, "/gazebo"),
    Topic("joint_states", "joint_states", "sensor_msgs/msg/JointState", "out", DRIVE_HZ, "/gazebo"),
    Topic("imu", "imu", "sensor_msgs/msg/Imu", "out", IMU_HZ, "/gazebo"),
    Topic("cmd_vel", "cmd_vel", "geometry_msgs/msg/Twist", "in", None, "/gazebo"),
)

# ROS 2 Humble + Gazebo Classic 11: gazebo_ros_pkgs' ros2 plugins in turtlebot3_simulations' humble models. Each
# plugin is a node of its own, named by the plugin's name in the model; QoS and rates as docs/ros2_stacks.md cites.
_HUMBLE = (
    Topic("clock", "/clock", "rosgraph_msgs/msg/Clock", "out", 10.0, "/gazebo", Qos(reliable=False, depth=1), False),
    Topic("tf", "/tf", "tf2_msgs/msg/TFMessage", "out", DRIVE_HZ, "/turtlebot3_diff_drive", Qos(depth=100), False),
    Topic("tf_static", "/tf_static", "tf2_msgs/msg/TFMessage", "out", None, "/robot_state_publisher", LATCHED,
          False),
    Topic("scan", "scan", "sensor_msgs/msg/LaserScan", "out", SCAN_HZ, "/turtlebot3_laserscan", Qos(depth=5)),
    Topic("odom", "odom", "nav_msgs/msg/Odometry", "out", DRIVE_HZ, "/turtlebot3_diff_drive", Qos(depth=1)),
    Topic("joint_states", "joint_states", "sensor_msgs/msg/JointState", "out", DRIVE_HZ,
          "/turtlebot3_joint_state", Qos(depth=1000)),
    Topic("imu", "imu", "sensor_msgs/msg/Imu", "out", IMU_HZ, "/turtlebot3_imu", Qos(depth=5)),
    Topic("cmd_vel", "cmd_vel", "geometry_msgs/msg/Twist", "in", None, "/turtlebot3_diff_drive", Qos(depth=1)),
)

# ROS 2 Jazzy + Gazebo Sim 8: everything crosses ros_gz_bridge (turtlebot3_gazebo's params/*_bridge.yaml), whose
# publishers and subscribers all use reliable, volatile, keep last 10; cmd_vel is TwistStamped.
_JAZZY = (
    Topic("clock", "/clock", "rosgraph_msgs/msg/Clock", "out", CLOCK_HZ, "/ros_gz_bridge", DEFAULT, False),
    Topic("tf", "/tf", "tf2_msgs/msg/TFMessage", "out", DRIVE_HZ, "/ros_gz_bridge", DEFAULT, False),
    Topic("tf_static", "/tf_static", "tf2_msgs/msg/TFMessage", "out", None, "/robot_state_publisher", LATCHED,
          False),
    Topic("scan", "scan", "sensor_msgs/msg/LaserScan", "out", SCAN_HZ, "/ros_gz_bridge", DEFAULT),
    Topic("odom", "odom", "nav_msgs/msg/Odometry", "out", DRIVE_HZ, "/ros_gz_bridge", DEFAULT),
    Topic("joint_states", "joint_states", "sensor_msgs/msg/JointState", "out", DRIVE_HZ, "/ros_gz_bridge",
          DEFAULT),
    Topic("imu", "imu", "sensor_msgs/msg/Imu", "out", IMU_HZ, "/ros_gz_bridge", DEFAULT),
    Topic("cmd_vel", "cmd_vel", "geometry_msgs/msg/TwistStamped", "in", None, "/ros_gz_bridge", DEFAULT),
)

_TABLES = {"noetic": _NOETIC, "humble": _HUMBLE, "jazzy": _JAZZY}


def topics(stack: str) -> dict[str, Topic]:
    """The stack's topics by key (see the module docstring)."""
    return {t.key: t for t in _TABLES[stack]}


def camera_topics(stack: str, image: str, info: str) -> dict[str, Topic]:
    """A camera's topics (``image`` and ``info`` as the stack names them, relative to the robot's namespace): the
    picture, its camera_info and (ROS 1: image_transport's) JPEG, at 30 Hz of simulated time."""
    if stack == "noetic":
        return {"image": Topic("image", image, "sensor_msgs/msg/Image", "out", 30.0, "/gazebo", Qos(depth=2)),
                "info": Topic("info", info, "sensor_msgs/msg/CameraInfo", "out", 30.0, "/gazebo", Qos(depth=2)),
                "compressed": Topic("compressed", image + "/compressed", "sensor_msgs/msg/CompressedImage", "out",
                                    30.0, "/gazebo", Qos(depth=2))}
    image_node, info_node = ("/camera_driver", "/camera_driver") if stack == "humble" else \
        ("/ros_gz_image", "/ros_gz_bridge")
    qos = Qos(depth=5) if stack == "humble" else DEFAULT
    return {"image": Topic("image", image, "sensor_msgs/msg/Image", "out", 30.0, image_node, qos),
            "info": Topic("info", info, "sensor_msgs/msg/CameraInfo", "out", 30.0, info_node, qos)}


def clock_every(stack: str, time_step: float) -> int:
    """Physics steps between two ``/clock`` messages on ``stack``."""
    return max(1, round(1.0 / (topics(stack)["clock"].rate * time_step)))
