#!/usr/bin/env python3
"""Deliberately wrong: drives straight ahead forever (never stops, never turns)."""
import rospy
from geometry_msgs.msg import Twist

rospy.init_node("into_the_wall")
pub = rospy.Publisher("cmd_vel", Twist, queue_size=10)
twist = Twist()
twist.linear.x = 0.2
rate = rospy.Rate(5)
while not rospy.is_shutdown():
    pub.publish(twist)
    rate.sleep()
