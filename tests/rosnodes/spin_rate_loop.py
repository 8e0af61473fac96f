#!/usr/bin/env python3
"""Student style: a rospy.Rate loop publishing the same Twist (spin in place)."""
import rospy
from geometry_msgs.msg import Twist

rospy.init_node("spinner")
pub = rospy.Publisher("cmd_vel", Twist, queue_size=10)
twist = Twist()
twist.angular.z = 1.0
rate = rospy.Rate(10)
while not rospy.is_shutdown():
    pub.publish(twist)
    rate.sleep()
