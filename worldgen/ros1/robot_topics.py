"""One simulated robot on ROS 1: rospy publishers and the ``cmd_vel`` subscriber for a
:class:`~worldgen.interface.robot.RobotIO`, named, typed and queued as the stack's topic table says
(:func:`worldgen.interface.topics.topics`), and its messages in a rosbag when asked.

Messages are made only for topics some node subscribes to (or the bag records), as the plugins do.
"""

from __future__ import annotations

from ..interface.robot import RobotIO
from ..interface.topics import join, topics
from .messages import fill, message_class, ros_time

STACK = "noetic"


class RobotTopics:
    """The publishers, the ``cmd_vel`` subscriber and the bag of one robot (see the module docstring)."""

    def __init__(self, rospy, io: RobotIO, bag=None):
        self.rospy, self.io, self.ns, self.bag = rospy, io, io.ns, bag
        table = topics(STACK)
        self.pubs = {key: rospy.Publisher(join(io.ns, t.name), message_class(t.type), queue_size=t.qos.depth)
                     for key, t in table.items() if t.direction == "out" and t.per_robot}
        cmd = table["cmd_vel"]
        self.cmd_sub = rospy.Subscriber(join(io.ns, cmd.name), message_class(cmd.type), self.on_cmd_vel,
                                        queue_size=cmd.qos.depth)
        self.cameras: list = []   # its CameraTopics (:mod:`.camera_topics`), which the node adds

    @property
    def robot(self):
        return self.io.robot

    def close(self) -> None:
        for camera in self.cameras:
            camera.close()
        self.cmd_sub.unregister()
        for publisher in self.pubs.values():
            publisher.unregister()

    def on_cmd_vel(self, msg) -> None:   # a rospy thread
        if not self.io.command(msg.linear.x, msg.angular.z):
            return
        if self.bag is not None:
            with self.io.lock:
                if self.bag is not None:
                    self.bag.write(join(self.ns, "cmd_vel"), msg, ros_time(self.rospy, self.io.now))

    def _send(self, key: str, values: dict) -> None:
        msg = fill(self.pubs[key].data_class(), values, self.rospy)
        self.pubs[key].publish(msg)
        if self.bag is not None and key in ("odom", "scan"):
            with self.io.lock:
                if self.bag is not None:
                    self.bag.write(join(self.ns, key), msg, msg.header.stamp)

    def static_transforms(self, t: float) -> list[dict]:
        return self.io.static_transforms(t)

    def publish_drive(self, t: float, tf_pub) -> None:
        """The diff-drive plugin's update: odom, tf and joint_states, and a line of the trace."""
        tf_wanted = tf_pub.get_num_connections() > 0
        out = self.io.drive(t, odom=bool(self.pubs["odom"].get_num_connections() or self.bag is not None), tf=tf_wanted,
                            joint_states=self.pubs["joint_states"].get_num_connections() > 0)
        if "odom" in out:
            self._send("odom", out["odom"])
        if "tf" in out:
            tf_pub.publish(fill(tf_pub.data_class(), {"transforms": out["tf"]}, self.rospy))
        if "joint_states" in out:
            self._send("joint_states", out["joint_states"])

    def publish_imu(self, dt: float, t: float) -> None:
        if not self.pubs["imu"].get_num_connections():
            self.io.imu_unheard()
            return
        self._send("imu", self.io.imu(dt, t))

    def publish_scan(self, session) -> bool:
        """One scan (and a trace line); True when some node listens to it."""
        listened = self.pubs["scan"].get_num_connections() > 0
        self._send("scan", self.io.scan(session))
        return listened
