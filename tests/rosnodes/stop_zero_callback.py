#!/usr/bin/env python3
"""Student style: publish from the scan callback; reads the real robot's 0 for no return (and inf, Gazebo's)."""
import rospy
from geometry_msgs.msg import Twist
from sensor_msgs.msg import LaserScan


class Stopper(object):
    def __init__(self):
        rospy.init_node("stop_at_wall_student")
        self.pub = rospy.Publisher("cmd_vel", Twist, queue_size=10)
        rospy.Subscriber("scan", LaserScan, self.process_scan)

    def process_scan(self, data):
        ahead = [r for r in data.ranges[:15] + data.ranges[-15:] if r != 0.0 and r != float("inf")]
        twist = Twist()
        if not ahead or min(ahead) > 0.5:
            twist.linear.x = 0.15 if not ahead or min(ahead) > 0.8 else 0.5 * (min(ahead) - 0.5) + 0.02
        self.pub.publish(twist)

    def run(self):
        rospy.spin()


if __name__ == "__main__":
    Stopper().run()
