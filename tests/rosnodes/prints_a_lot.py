#!/usr/bin/env python3
"""A node that prints ``mb:=N`` megabytes (numbered lines, a first and a last line to find), then spins."""
import sys

import rospy
from geometry_msgs.msg import Twist

args = dict(a.split(":=", 1) for a in sys.argv[1:] if ":=" in a)
print("FIRST LINE", flush=True)
line = "x" * 99 + "\n"
chunk = line * 10000                       # 1 MB
for _ in range(int(args.get("mb", "100"))):
    sys.stdout.write(chunk)
print("LAST LINE", flush=True)
rospy.init_node("printer")
pub = rospy.Publisher("cmd_vel", Twist, queue_size=10)
twist = Twist()
twist.angular.z = 1.0
rate = rospy.Rate(10)
while not rospy.is_shutdown():
    pub.publish(twist)
    rate.sleep()
