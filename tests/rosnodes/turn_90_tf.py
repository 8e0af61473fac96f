#!/usr/bin/env python3
"""Student style: turn 90 degrees to the left by odometry, the yaw from tf.transformations.euler_from_quaternion,
slowing down near the end, then stop."""
import math

import rospy
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from tf.transformations import euler_from_quaternion


class Turner:
    def __init__(self):
        rospy.init_node("turn_90")
        self.start = None
        self.done = False
        self.pub = rospy.Publisher("cmd_vel", Twist, queue_size=10)
        rospy.Subscriber("odom", Odometry, self.on_odom)

    def on_odom(self, msg):
        q = msg.pose.pose.orientation
        _, _, yaw = euler_from_quaternion([q.x, q.y, q.z, q.w])
        if self.start is None:
            self.start = yaw
        turned = math.atan2(math.sin(yaw - self.start), math.cos(yaw - self.start))
        remaining = math.pi / 2 - turned
        twist = Twist()
        if not self.done and remaining > 0.01:
            twist.angular.z = max(0.1, min(0.5, 1.5 * remaining))
        else:
            self.done = True
        self.pub.publish(twist)


if __name__ == "__main__":
    Turner()
    rospy.spin()
