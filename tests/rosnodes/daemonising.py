#!/usr/bin/env python3
"""A node that leaves processes behind, as a careless student's might: two daemons (double fork, setsid), one a
Python process ignoring SIGTERM, SIGINT and SIGHUP, the other `sleep` with its environment cleared (nothing left
to trace it by but its ancestry); their pids go to the file named by ``pids:=FILE``; then it spins."""
import os
import signal
import sys
import time

import rospy
from geometry_msgs.msg import Twist


def daemon(run) -> int:
    """Double fork and setsid; ``run()`` in the grandchild; its pid."""
    read, write = os.pipe()
    if os.fork() == 0:
        os.setsid()
        pid = os.fork()
        if pid:
            os.write(write, str(pid).encode())
            os._exit(0)
        os.close(read)
        os.close(write)
        devnull = os.open(os.devnull, os.O_RDWR)
        for fd in (0, 1, 2):
            os.dup2(devnull, fd)
        run()
        os._exit(0)
    os.close(write)
    pid = int(os.read(read, 64))
    os.wait()
    return pid


def stubborn():
    for sig in (signal.SIGTERM, signal.SIGINT, signal.SIGHUP):
        signal.signal(sig, signal.SIG_IGN)
    while True:
        time.sleep(1)


def hidden():
    os.execve("/bin/sleep", ["sleep", "600"], {})


args = dict(a.split(":=", 1) for a in sys.argv[1:] if ":=" in a)
pids = [daemon(stubborn), daemon(hidden)]
with open(args["pids"], "w") as handle:
    handle.write(" ".join(map(str, pids)))
rospy.init_node("daemonising")
pub = rospy.Publisher("cmd_vel", Twist, queue_size=10)
twist = Twist()
twist.angular.z = 0.5
rate = rospy.Rate(10)
while not rospy.is_shutdown():
    pub.publish(twist)
    rate.sleep()
