#!/usr/bin/env python3
"""Subscribes to every topic of the simulated TurtleBot3, once reliable and once best effort, and writes what came
(type, frame ids, count, stamps) as JSON to the file named by parameter ``out`` when it ends."""
import json
import signal
import time

import rclpy
from nav_msgs.msg import Odometry
from rclpy.node import Node
from rclpy.qos import QoSProfile, ReliabilityPolicy, DurabilityPolicy
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import Imu, JointState, LaserScan

TOPICS = {'scan': LaserScan, 'odom': Odometry, 'imu': Imu, 'joint_states': JointState, 'clock': Clock}


class Probe(Node):
    def __init__(self):
        super().__init__('probe')
        self.out = self.declare_parameter('out', '/tmp/probe.json').value
        self.seen = {}
        for name, cls in TOPICS.items():
            for kind, rel in (('reliable', ReliabilityPolicy.RELIABLE), ('best_effort', ReliabilityPolicy.BEST_EFFORT)):
                qos = QoSProfile(depth=10, reliability=rel, durability=DurabilityPolicy.VOLATILE)
                self.create_subscription(cls, name, self.keeper(name, kind), qos)

    def keeper(self, name, kind):
        def keep(msg):
            entry = self.seen.setdefault(f'{name}/{kind}', {'count': 0, 'stamps': [], 'frames': []})
            entry['count'] += 1
            stamp = msg.clock if name == 'clock' else msg.header.stamp
            entry['stamps'].append(stamp.sec + stamp.nanosec * 1e-9)
            frame = getattr(getattr(msg, 'header', None), 'frame_id', None)
            if frame is not None and frame not in entry['frames']:
                entry['frames'].append(frame)
            if name == 'odom' and 'child' not in entry:
                entry['child'] = msg.child_frame_id
            if name == 'scan' and 'ranges' not in entry:
                entry['ranges'] = len(msg.ranges)
        return keep

    def dump(self):
        with open(self.out, 'w') as fh:
            json.dump(self.seen, fh)


def main():
    rclpy.init()
    node = Probe()
    signal.signal(signal.SIGINT, lambda *a: (node.dump(), exit(0)))
    signal.signal(signal.SIGTERM, lambda *a: (node.dump(), exit(0)))
    last = 0.0
    while True:
        rclpy.spin_once(node, timeout_sec=0.05)
        if time.monotonic() - last > 0.5:
            node.dump()
            last = time.monotonic()


if __name__ == '__main__':
    main()
