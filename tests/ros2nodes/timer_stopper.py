#!/usr/bin/env python3
"""A student-style rclpy stop-at-wall node: a 10 Hz timer, /scan with the default reliable QoS (depth 10), Twist or
TwistStamped (parameter ``stamped``), the front distance as the nearest beam within ±10° of index 0."""
import math

import rclpy
from geometry_msgs.msg import Twist, TwistStamped
from rclpy.node import Node
from sensor_msgs.msg import LaserScan


class Stopper(Node):
    def __init__(self):
        super().__init__('timer_stopper')
        self.stamped = self.declare_parameter('stamped', True).value
        self.target = self.declare_parameter('target', 0.5).value
        self.pub = self.create_publisher(TwistStamped if self.stamped else Twist, 'cmd_vel', 10)
        self.create_subscription(LaserScan, 'scan', self.on_scan, 10)
        self.front = None
        self.create_timer(0.1, self.tick)

    def on_scan(self, msg):
        near = [r for i, r in enumerate(msg.ranges) if (i <= 10 or i >= len(msg.ranges) - 10) and math.isfinite(r)
                and r > msg.range_min]
        self.front = min(near) if near else math.inf

    def tick(self):
        speed = 0.0 if self.front is None else max(0.0, min(0.2, 0.8 * (self.front - self.target)))
        if self.stamped:
            msg = TwistStamped()
            msg.header.stamp = self.get_clock().now().to_msg()
            msg.twist.linear.x = speed
        else:
            msg = Twist()
            msg.linear.x = speed
        self.pub.publish(msg)


def main():
    rclpy.init()
    rclpy.spin(Stopper())


if __name__ == '__main__':
    main()
