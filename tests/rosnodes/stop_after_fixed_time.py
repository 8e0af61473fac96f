#!/usr/bin/env python3
"""Deliberately over-tuned: a stop-at-wall "solution" that never looks at the LiDAR. It drives at 0.2 m/s for
exactly as long as the class's room needs (from the middle of the 5 m room to 0.5 m before its wall: 1.925 m,
9.625 s of simulated time) and then stops. It passes in that room and almost nowhere else."""
import rospy
from geometry_msgs.msg import Twist

rospy.init_node("stop_after_fixed_time")
pub = rospy.Publisher("cmd_vel", Twist, queue_size=10)
rate = rospy.Rate(10)
while not rospy.is_shutdown() and rospy.get_time() == 0:
    rate.sleep()   # wait for the simulated clock
start = rospy.get_time()
while not rospy.is_shutdown():
    twist = Twist()
    if rospy.get_time() - start < 1.925 / 0.2:
        twist.linear.x = 0.2
    pub.publish(twist)
    rate.sleep()
