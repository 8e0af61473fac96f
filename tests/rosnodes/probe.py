#!/usr/bin/env python3
"""Test probe for `worldgen sim`: listens to what the simulator publishes, or drives it, and prints one JSON line.

    probe.py topics SECONDS        message counts, rates (from header stamps, simulated time: one over the median
                                   gap, the publisher's period, whatever a loaded machine drops) and first messages
    probe.py drive V W SECONDS     cmd_vel (V, W) for SECONDS of simulated time, then stop; odometry before/after
    probe.py reset                 drive 1 s, call /gazebo/reset_world, report the pose after
"""

import json
import math
import statistics
import sys
import time

import rospy
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import Imu, JointState, LaserScan
from std_srvs.srv import Empty
from tf2_msgs.msg import TFMessage

TOPICS = {"/clock": Clock, "/scan": LaserScan, "/odom": Odometry, "/tf": TFMessage, "/tf_static": TFMessage,
          "/joint_states": JointState, "/imu": Imu}


def yaw_of(q):
    return math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z))


def wait_for_time():
    deadline = time.time() + 20
    while rospy.Time.now().to_sec() == 0 and time.time() < deadline:
        time.sleep(0.01)


def topics(seconds):
    seen = {name: [] for name in TOPICS}
    arrivals = {name: [] for name in TOPICS}
    first = {}
    started = time.time()
    first_scan_wall = []

    def keep(name):
        def callback(msg):
            arrivals[name].append(time.time())
            if name == "/clock":
                seen[name].append(msg.clock.to_sec())
            elif name in ("/tf", "/tf_static"):
                seen[name].append(msg.transforms[0].header.stamp.to_sec())
                if name == "/tf_static" or name not in first:
                    first.setdefault(name, [])
                    first[name] += [[t.header.frame_id, t.child_frame_id] for t in msg.transforms]
            else:
                seen[name].append(msg.header.stamp.to_sec())
                if name == "/scan" and not first_scan_wall:
                    first_scan_wall.append(time.time() - started)
                if name not in first:
                    first[name] = describe(name, msg)
        return callback

    for name, cls in TOPICS.items():
        rospy.Subscriber(name, cls, keep(name), queue_size=1000)
    wait_for_time()
    end = rospy.Time.now().to_sec() + seconds
    deadline = time.time() + 60
    while rospy.Time.now().to_sec() < end and time.time() < deadline:
        time.sleep(0.01)
    rates = {}
    for name, stamps in seen.items():
        gaps = [b - a for a, b in zip(stamps, stamps[1:])]
        if len(gaps) > 1 and statistics.median(gaps) > 0:
            rates[name] = 1.0 / statistics.median(gaps)
    counts = {name: len(s) for name, s in seen.items()}
    wall_rates = {name: (len(a) - 1) / (a[-1] - a[0]) for name, a in arrivals.items() if len(a) > 2 and a[-1] > a[0]}
    print(json.dumps({"rates": rates, "wall_rates": wall_rates, "counts": counts, "first": first,
                      "use_sim_time": rospy.get_param("/use_sim_time", None),
                      "first_scan_wall_s": first_scan_wall[0] if first_scan_wall else None}))


def describe(name, msg):
    if name == "/scan":
        return {"frame": msg.header.frame_id, "angle_min": msg.angle_min, "angle_max": msg.angle_max,
                "angle_increment": msg.angle_increment, "range_min": msg.range_min, "range_max": msg.range_max,
                "n": len(msg.ranges), "front": msg.ranges[0], "ranges": list(msg.ranges)}
    if name == "/odom":
        return {"frame": msg.header.frame_id, "child": msg.child_frame_id, "x": msg.pose.pose.position.x,
                "y": msg.pose.pose.position.y, "yaw": yaw_of(msg.pose.pose.orientation)}
    if name == "/joint_states":
        return {"name": list(msg.name), "position": list(msg.position), "velocity": list(msg.velocity)}
    if name == "/imu":
        return {"frame": msg.header.frame_id, "az": msg.linear_acceleration.z, "wz": msg.angular_velocity.z,
                "qw": msg.orientation.w}
    return {}


class Odom:
    def __init__(self):
        self.last = None
        self.turned = 0.0
        rospy.Subscriber("/odom", Odometry, self.on_odom, queue_size=100)

    def on_odom(self, msg):
        pose = (msg.pose.pose.position.x, msg.pose.pose.position.y, yaw_of(msg.pose.pose.orientation))
        if self.last is not None:
            self.turned += math.atan2(math.sin(pose[2] - self.last[2]), math.cos(pose[2] - self.last[2]))
        self.last = pose

    def wait(self):
        deadline = time.time() + 20
        while self.last is None and time.time() < deadline:
            time.sleep(0.01)
        return self.last


def drive(v, w, seconds):
    odom = Odom()
    pub = rospy.Publisher("/cmd_vel", Twist, queue_size=10)
    wait_for_time()
    start = odom.wait()
    deadline = time.time() + 20
    while pub.get_num_connections() == 0 and time.time() < deadline:
        time.sleep(0.01)
    twist = Twist()
    twist.linear.x, twist.angular.z = v, w
    turned0 = odom.turned
    rate = rospy.Rate(20)
    end = rospy.Time.now() + rospy.Duration(seconds)
    while rospy.Time.now() < end:
        pub.publish(twist)
        rate.sleep()
    pub.publish(Twist())
    rospy.sleep(1.0)
    final = odom.last
    print(json.dumps({"start": start, "end": final, "distance": math.hypot(final[0] - start[0], final[1] - start[1]),
                      "turned": odom.turned - turned0}))


def reset():
    odom = Odom()
    pub = rospy.Publisher("/cmd_vel", Twist, queue_size=10)
    wait_for_time()
    start = odom.wait()
    while pub.get_num_connections() == 0:
        time.sleep(0.01)
    twist = Twist()
    twist.linear.x, twist.angular.z = 0.2, 0.5
    for _ in range(20):
        pub.publish(twist)
        rospy.sleep(0.1)
    moved = odom.last
    rospy.wait_for_service("/gazebo/reset_world", timeout=10)
    rospy.ServiceProxy("/gazebo/reset_world", Empty)()
    rospy.sleep(0.5)
    rospy.wait_for_service("/gazebo/reset_simulation", timeout=10)
    rospy.ServiceProxy("/gazebo/reset_simulation", Empty)()
    rospy.sleep(0.5)
    print(json.dumps({"start": start, "moved": moved, "after": odom.last}))


if __name__ == "__main__":
    rospy.init_node("probe", disable_signals=True)
    mode, args = sys.argv[1], [float(a) for a in sys.argv[2:]]
    {"topics": topics, "drive": drive, "reset": reset}[mode](*args)
    rospy.signal_shutdown("done")
