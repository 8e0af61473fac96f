#!/usr/bin/env python3
"""Student style: a spin node with a stray import an IDE added (from tkinter import *), never used."""
from tkinter import *

import rospy
from geometry_msgs.msg import Twist

rospy.init_node("spin_tk")
pub = rospy.Publisher("cmd_vel", Twist, queue_size=10)
twist = Twist()
twist.angular.z = 1.0
rate = rospy.Rate(10)
while not rospy.is_shutdown():
    pub.publish(twist)
    rate.sleep()
