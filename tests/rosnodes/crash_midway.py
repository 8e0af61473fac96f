#!/usr/bin/env python3
"""Spins for two simulated seconds, then raises: an uncaught exception part-way through a run."""
import rospy
from geometry_msgs.msg import Twist

rospy.init_node("crash_midway")
pub = rospy.Publisher("cmd_vel", Twist, queue_size=1)
rospy.sleep(0.5)
turn = Twist()
turn.angular.z = 1.0
pub.publish(turn)
rospy.sleep(1.5)
raise ValueError("the ranges were empty")
