#!/usr/bin/env python3
"""Student style: stop at the wall with numpy: the ranges as an array, no return (inf) as nan, np.nanmin of the
beams ahead, a P law on the distance left."""
import numpy as np
import rospy
from geometry_msgs.msg import Twist
from sensor_msgs.msg import LaserScan

TARGET = 0.5


def on_scan(msg):
    ranges = np.array(msg.ranges)
    ranges[np.isinf(ranges)] = np.nan
    ahead = np.concatenate((ranges[:10], ranges[-10:]))
    twist = Twist()
    if np.all(np.isnan(ahead)):
        twist.linear.x = 0.15
    else:
        error = np.nanmin(ahead) - TARGET
        if abs(error) > 0.01:
            twist.linear.x = float(np.clip(0.6 * error, -0.1, 0.15))
    pub.publish(twist)


rospy.init_node("stop_at_wall_numpy")
pub = rospy.Publisher("cmd_vel", Twist, queue_size=10)
rospy.Subscriber("scan", LaserScan, on_scan)
rospy.spin()
