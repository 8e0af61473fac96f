#!/usr/bin/env python3
"""Student style: follow the wall on the right at 0.4 m, P control on the nearest beam's distance and bearing."""
import math

import rospy
from geometry_msgs.msg import Twist
from sensor_msgs.msg import LaserScan

TARGET = 0.4


class WallFollower(object):
    def __init__(self):
        rospy.init_node("wall_follower")
        self.pub = rospy.Publisher("cmd_vel", Twist, queue_size=10)
        self.sub = rospy.Subscriber("scan", LaserScan, self.process_scan)

    def process_scan(self, data):
        best, best_angle = None, 0.0
        for i, r in enumerate(data.ranges):
            if math.isinf(r) or math.isnan(r) or r < data.range_min:
                continue
            if best is None or r < best:
                best, best_angle = r, data.angle_min + i * data.angle_increment
        twist = Twist()
        if best is None or best > TARGET + 0.5:
            twist.linear.x = 0.15          # find a wall
        else:
            bearing = math.atan2(math.sin(best_angle), math.cos(best_angle))
            front = min([r for r in data.ranges[:20] + data.ranges[-20:] if not math.isinf(r)] or [9.0])
            twist.linear.x = 0.12 if front > TARGET + 0.15 else 0.03
            twist.angular.z = 1.5 * (bearing + math.pi / 2) - 2.0 * (best - TARGET)
        self.pub.publish(twist)

    def run(self):
        rospy.spin()


if __name__ == "__main__":
    WallFollower().run()
