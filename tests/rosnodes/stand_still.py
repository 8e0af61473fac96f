#!/usr/bin/env python3
"""Deliberately wrong for person-follow: publishes a zero Twist and never moves."""
import rospy
from geometry_msgs.msg import Twist

rospy.init_node("stand_still")
pub = rospy.Publisher("cmd_vel", Twist, queue_size=10)
rate = rospy.Rate(5)
while not rospy.is_shutdown():
    pub.publish(Twist())
    rate.sleep()
