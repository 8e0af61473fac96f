#!/usr/bin/env python3
"""A node that will not stop when asked: SIGTERM, SIGINT and SIGHUP ignored (rospy's handlers off); it spins."""
import signal

import rospy
from geometry_msgs.msg import Twist

rospy.init_node("stubborn", disable_signals=True)
for sig in (signal.SIGTERM, signal.SIGINT, signal.SIGHUP):
    signal.signal(sig, signal.SIG_IGN)
pub = rospy.Publisher("cmd_vel", Twist, queue_size=10)
twist = Twist()
twist.angular.z = 1.0
rate = rospy.Rate(10)
while True:
    pub.publish(twist)
    rate.sleep()
