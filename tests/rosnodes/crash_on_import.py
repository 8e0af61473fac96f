#!/usr/bin/env python3
import rospy
from geometry_msgs.msg import Twistt   # a typo students make
