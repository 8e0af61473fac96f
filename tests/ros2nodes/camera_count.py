#!/usr/bin/env python3
"""Counts the camera's pictures (reliable, depth 10) and writes what came to the file named by parameter ``out``:
count, the distinct stamps, the size, encoding and frame of the first picture."""
import json
import time

import rclpy
from rclpy.node import Node
from sensor_msgs.msg import CameraInfo, Image


class Count(Node):
    def __init__(self):
        super().__init__('camera_count')
        self.out = self.declare_parameter('out', '/tmp/camera.json').value
        self.seen = {'count': 0, 'stamps': [], 'info': 0}
        self.create_subscription(Image, 'camera/image_raw', self.on_image, 10)
        self.create_subscription(CameraInfo, 'camera/camera_info', self.on_info, 10)

    def on_image(self, msg):
        self.seen['count'] += 1
        self.seen['stamps'].append(msg.header.stamp.sec + msg.header.stamp.nanosec * 1e-9)
        if 'first' not in self.seen:
            self.seen['first'] = {'width': msg.width, 'height': msg.height, 'encoding': msg.encoding,
                                  'frame': msg.header.frame_id, 'bytes': len(msg.data)}

    def on_info(self, msg):
        self.seen['info'] += 1
        self.seen['k'] = list(msg.k)

    def dump(self):
        with open(self.out, 'w') as fh:
            json.dump(self.seen, fh)


def main():
    rclpy.init()
    node = Count()
    last = 0.0
    try:
        while rclpy.ok():
            rclpy.spin_once(node, timeout_sec=0.02)
            if time.monotonic() - last > 0.5:
                node.dump()
                last = time.monotonic()
    except BaseException:   # noqa: B036 (Ctrl-C or SIGTERM at the end of the run: write what came)
        node.dump()


if __name__ == '__main__':
    main()
