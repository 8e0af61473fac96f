#!/usr/bin/env python3
"""A student-style rclpy node paced by time.sleep: spin_once in a loop, /scan with qos_profile_sensor_data, Twist."""
import math
import time

import rclpy
from geometry_msgs.msg import Twist
from rclpy.qos import qos_profile_sensor_data
from sensor_msgs.msg import LaserScan

front = [None]


def on_scan(msg):
    ahead = [r for r in msg.ranges[:10] + msg.ranges[-10:] if math.isfinite(r) and r > 0]
    front[0] = min(ahead) if ahead else math.inf


def main():
    rclpy.init()
    node = rclpy.create_node('sleep_loop_stopper')
    pub = node.create_publisher(Twist, 'cmd_vel', 10)
    node.create_subscription(LaserScan, 'scan', on_scan, qos_profile_sensor_data)
    while rclpy.ok():
        rclpy.spin_once(node, timeout_sec=0.05)
        msg = Twist()
        if front[0] is not None and front[0] > 0.5:
            msg.linear.x = 0.15
        pub.publish(msg)
        time.sleep(0.05)


if __name__ == '__main__':
    main()
