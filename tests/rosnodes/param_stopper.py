#!/usr/bin/env python3
"""Student style, launched with parameters: drives forward on `velocity` (remapped to cmd_vel in the launch file)
and stops ~target_distance from the wall ahead; its speed comes from a <rosparam> file. Writes every parameter it
can see (what `rosparam get /` shows) to $PARAM_DUMP once it has started."""
import json
import os

import rospy
from geometry_msgs.msg import Twist
from sensor_msgs.msg import LaserScan


def main():
    rospy.init_node("param_stopper")
    target = rospy.get_param("~target_distance")
    speed = rospy.get_param("speeds/cruise")
    pub = rospy.Publisher("velocity", Twist, queue_size=10)

    def on_scan(scan):
        ahead = [r for r in scan.ranges[:10] + scan.ranges[-10:] if 0.0 < r < float("inf")]
        twist = Twist()
        if not ahead or min(ahead) > target:
            twist.linear.x = speed if not ahead or min(ahead) > target + 0.3 else max(0.02, min(ahead) - target)
        pub.publish(twist)

    rospy.Subscriber("scan", LaserScan, on_scan)
    with open(os.environ["PARAM_DUMP"], "w") as out:
        json.dump(rospy.get_param("/"), out)
    rospy.spin()


if __name__ == "__main__":
    main()
