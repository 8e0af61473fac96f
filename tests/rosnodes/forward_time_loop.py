#!/usr/bin/env python3
"""Student style: pace with time.time() (wall clock), drive forward for 3 s, then stop."""
import time

import rospy
from geometry_msgs.msg import Twist

rospy.init_node("forward")
pub = rospy.Publisher("/cmd_vel", Twist, queue_size=1)
time.sleep(0.5)   # "wait for the publisher to connect"
move = Twist()
move.linear.x = 0.1
start = time.time()
while time.time() - start < 3.0 and not rospy.is_shutdown():
    pub.publish(move)
    time.sleep(0.1)
pub.publish(Twist())
rospy.spin()
