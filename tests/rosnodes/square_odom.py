#!/usr/bin/env python3
"""Student style: drive a 1 m square by odometry: a state machine in a rospy.Rate loop, yaw from the quaternion."""
import math

import rospy
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry


def yaw_from_quaternion(q):
    return math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))


class DriveSquare:
    def __init__(self):
        rospy.init_node("drive_square")
        self.side = rospy.get_param("~side", 1.0)
        self.pose = None
        rospy.Subscriber("/odom", Odometry, self.on_odom)
        self.pub = rospy.Publisher("/cmd_vel", Twist, queue_size=10)

    def on_odom(self, msg):
        p = msg.pose.pose
        self.pose = (p.position.x, p.position.y, yaw_from_quaternion(p.orientation))

    def run(self):
        rate = rospy.Rate(20)
        while self.pose is None and not rospy.is_shutdown():
            rate.sleep()
        for corner in range(4):
            x0, y0, _ = self.pose
            while not rospy.is_shutdown() and math.hypot(self.pose[0] - x0, self.pose[1] - y0) < self.side:
                twist = Twist()
                twist.linear.x = 0.15
                self.pub.publish(twist)
                rate.sleep()
            start_yaw = self.pose[2]
            while not rospy.is_shutdown():
                turned = math.atan2(math.sin(self.pose[2] - start_yaw), math.cos(self.pose[2] - start_yaw))
                if turned >= math.pi / 2 - 0.02:
                    break
                twist = Twist()
                twist.angular.z = 0.5 if turned < math.pi / 2 - 0.2 else 0.15
                self.pub.publish(twist)
                rate.sleep()
        self.pub.publish(Twist())
        rospy.spin()


if __name__ == "__main__":
    DriveSquare().run()
