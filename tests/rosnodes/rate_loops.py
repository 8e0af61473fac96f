#!/usr/bin/env python3
"""Loops paced by simulated time, as students pace theirs: rospy.Rate(10) (publishing cmd_vel: the node drives),
rospy.Rate(30) and rospy.sleep(0.25), each in a thread of its own. For each wake-up, the file named by ``out:=FILE``
gets, as it happens, a line ``LOOP DEADLINE WOKE`` (nanoseconds of simulated time: when the loop asked to wake,
and the rospy time it read on waking).

Every /clock message goes to ``FILE.clock``, written by a second node forked first: one with no simulated time of
its own, so that its subscription gets every message (rospy's own /clock subscription keeps only the latest of those
waiting, and a second subscription in the same process shares its connection)."""
import os
import sys
import threading

import rospy
from geometry_msgs.msg import Twist
from rosgraph_msgs.msg import Clock

args = dict(a.split(":=", 1) for a in sys.argv[1:] if ":=" in a)

subscribed, tell = os.pipe()
if os.fork() == 0:
    clock_file = open(args["out"] + ".clock", "w", buffering=1)
    rospy.init_node("clock_recorder", disable_rostime=True)
    rospy.Subscriber("/clock", Clock, lambda msg: clock_file.write(f"{msg.clock.to_nsec()}\n"))
    os.write(tell, b"x")
    rospy.spin()
    os._exit(0)
os.read(subscribed, 1)   # the recorder has joined first (a run counts one node a process before it starts)

out = open(args["out"], "w", buffering=1)
lock = threading.Lock()


def write(line):
    with lock:
        out.write(line + "\n")


def rate_loop(hz, each=None):
    rate = rospy.Rate(hz)
    while not rospy.is_shutdown():
        if each is not None:
            each()
        rate.sleep()
        write(f"rate{hz} {rate.last_time.to_nsec()} {rospy.get_rostime().to_nsec()}")


def sleep_loop(seconds):
    while not rospy.is_shutdown():
        deadline = rospy.get_rostime() + rospy.Duration.from_sec(seconds)
        rospy.sleep(seconds)
        write(f"sleep{seconds:g} {deadline.to_nsec()} {rospy.get_rostime().to_nsec()}")


rospy.init_node("rate_loops")
pub = rospy.Publisher("cmd_vel", Twist, queue_size=10)
twist = Twist()
twist.angular.z = 0.5
threading.Thread(target=rate_loop, args=(30,), daemon=True).start()
threading.Thread(target=sleep_loop, args=(0.25,), daemon=True).start()
rate_loop(10, lambda: pub.publish(twist))
