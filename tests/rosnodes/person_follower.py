#!/usr/bin/env python3
"""Student style: follow the nearest thing within 2 m: turn towards it, keep 0.6 m from it."""
import math

import rospy
from geometry_msgs.msg import Twist
from sensor_msgs.msg import LaserScan


def on_scan(scan):
    nearest = None
    for i, r in enumerate(scan.ranges):
        if scan.range_min <= r <= 2.0 and (nearest is None or r < nearest[0]):
            nearest = (r, scan.angle_min + i * scan.angle_increment)
    twist = Twist()
    if nearest is not None:
        distance, angle = nearest
        angle = math.atan2(math.sin(angle), math.cos(angle))
        twist.angular.z = max(-1.5, min(1.5, 2.0 * angle))
        twist.linear.x = max(-0.1, min(0.22, 0.8 * (distance - 0.6))) if abs(angle) < 0.8 else 0.0
    pub.publish(twist)


rospy.init_node("person_follower")
pub = rospy.Publisher("cmd_vel", Twist, queue_size=10)
rospy.Subscriber("scan", LaserScan, on_scan)
rospy.spin()
