#!/usr/bin/env python3
"""Deliberately wrong for spin: turns for 3 s of ROS time, then stops."""
import rospy
from geometry_msgs.msg import Twist

rospy.init_node("spin_briefly")
pub = rospy.Publisher("cmd_vel", Twist, queue_size=10)
twist = Twist()
twist.angular.z = 1.0
rate = rospy.Rate(10)
end = None
while not rospy.is_shutdown():
    now = rospy.get_time()
    if end is None and now > 0:
        end = now + 3.0
    if end is not None and now > end:
        twist.angular.z = 0.0
    pub.publish(twist)
    rate.sleep()
