#!/usr/bin/env python3
"""Turns by publishing geometry_msgs/TwistStamped on /cmd_vel, which the ROS 1 TurtleBot3 does not take."""
import rospy
from geometry_msgs.msg import TwistStamped
rospy.init_node("stamped")
pub = rospy.Publisher("/cmd_vel", TwistStamped, queue_size=1)
r = rospy.Rate(10)
while not rospy.is_shutdown():
    t = TwistStamped(); t.twist.angular.z = 1.0; pub.publish(t); r.sleep()
