#!/usr/bin/env python3
"""Drives slowly, then exits after ~duration seconds of ROS time (a node a launch file marks required)."""
import rospy
from geometry_msgs.msg import Twist

rospy.init_node("quitter")
pub = rospy.Publisher("cmd_vel", Twist, queue_size=10)
rate = rospy.Rate(10)
while rospy.get_time() == 0 and not rospy.is_shutdown():
    rospy.sleep(0.01)
start = rospy.get_time()
while not rospy.is_shutdown() and rospy.get_time() - start < rospy.get_param("~duration", 2.0):
    twist = Twist()
    twist.angular.z = 0.3
    pub.publish(twist)
    rate.sleep()
