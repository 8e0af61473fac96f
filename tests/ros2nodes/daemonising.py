#!/usr/bin/env python3
"""An rclpy node that leaves a daemon behind (double fork, setsid, SIGTERM, SIGINT and SIGHUP ignored), its pid
written to the file named by parameter ``pids`` (read from the command line: the daemon comes before rclpy starts);
then it publishes a Twist at 10 Hz."""
import os
import signal
import sys
import time

import rclpy
from geometry_msgs.msg import Twist


def daemon() -> int:
    read, write = os.pipe()
    if os.fork() == 0:
        os.setsid()
        pid = os.fork()
        if pid:
            os.write(write, str(pid).encode())
            os._exit(0)
        for sig in (signal.SIGTERM, signal.SIGINT, signal.SIGHUP):
            signal.signal(sig, signal.SIG_IGN)
        while True:
            time.sleep(1)
    os.close(write)
    pid = int(os.read(read, 64))
    os.wait()
    return pid


def main():
    target = next(a.split(":=", 1)[1] for a in sys.argv if a.startswith(("pids:=", "_pids:=")))
    with open(target, 'w') as handle:
        handle.write(str(daemon()))
    rclpy.init()
    node = rclpy.create_node('daemonising')
    pub = node.create_publisher(Twist, 'cmd_vel', 10)
    msg = Twist()
    msg.angular.z = 0.5
    node.create_timer(0.1, lambda: pub.publish(msg))
    try:
        rclpy.spin(node)
    except KeyboardInterrupt:
        pass


if __name__ == '__main__':
    main()
