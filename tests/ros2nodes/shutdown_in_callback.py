#!/usr/bin/env python3
"""A student-style rclpy node that drives ahead and calls rclpy.shutdown() inside its scan callback once the wall is
0.5 m ahead (after a last zero command): its process ends while the run goes on."""
import math

import rclpy
from geometry_msgs.msg import TwistStamped
from rclpy.node import Node
from rclpy.qos import qos_profile_sensor_data
from sensor_msgs.msg import LaserScan


class Once(Node):
    def __init__(self):
        super().__init__('shutdown_in_callback')
        self.pub = self.create_publisher(TwistStamped, 'cmd_vel', 10)
        self.create_subscription(LaserScan, 'scan', self.on_scan, qos_profile_sensor_data)

    def on_scan(self, msg):
        ahead = [r for r in list(msg.ranges[:8]) + list(msg.ranges[-8:]) if math.isfinite(r)]
        cmd = TwistStamped()
        cmd.header.stamp = self.get_clock().now().to_msg()
        if ahead and min(ahead) <= 0.5:
            self.pub.publish(cmd)
            rclpy.shutdown()
            return
        cmd.twist.linear.x = 0.2
        self.pub.publish(cmd)


def main():
    rclpy.init()
    node = Once()
    try:
        rclpy.spin(node)
    except Exception:   # noqa: BLE001  (spin ends with an error once the context is shut down)
        pass


if __name__ == '__main__':
    main()
