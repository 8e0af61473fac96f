"""The rclpy side of tests/test_ros2_dds.py: a real ROS 2 node (run by the peer's Python) that listens to or talks on
one topic and reports, as JSON lines on stdout, what it received and what rclpy's graph says.

    dds_side.py listen TOPIC TYPE [--best-effort] [--count N] [--node NAME]...   (exits when done)
    dds_side.py talk TOPIC TYPE                                                   (until terminated)

TYPE is ``string`` (std_msgs/String) or ``scan`` (sensor_msgs/LaserScan). ``listen`` waits (15 s at most) for N
messages and for every ``--node`` to show in ``get_node_names_and_namespaces()``, then prints
``{"graph": {"nodes": [[name, ns]…], "publishers": [{node, namespace, type, hash, gid}…]}}`` (also after a
timeout) and stays (30 s at most) until terminated, so that the other side can look at it."""

import argparse
import json
import math
import signal
import sys
import time

import rclpy
from rclpy.qos import QoSProfile, qos_profile_sensor_data
from sensor_msgs.msg import LaserScan
from std_msgs.msg import String

TYPES = {"string": String, "scan": LaserScan}


def say(obj) -> None:
    print(json.dumps(obj), flush=True)


def as_dict(msg) -> dict:
    if isinstance(msg, String):
        return {"data": msg.data}
    return {"frame_id": msg.header.frame_id, "stamp": [msg.header.stamp.sec, msg.header.stamp.nanosec],
            "angle_min": msg.angle_min, "angle_increment": msg.angle_increment,
            "ranges": ["inf" if math.isinf(r) else r for r in msg.ranges], "intensities": list(msg.intensities)}


def scan(i: int) -> LaserScan:
    msg = LaserScan()
    msg.header.frame_id = "base_scan"
    msg.header.stamp.sec, msg.header.stamp.nanosec = i, 250_000_000
    msg.angle_min, msg.angle_max, msg.angle_increment = 0.0, 6.2657, 0.0174533
    msg.range_min, msg.range_max = 0.12, 3.5
    msg.ranges = [float("inf") if k % 7 == 0 else 0.5 + k / 100 for k in range(360)]
    msg.intensities = [float(k % 3) for k in range(360)]
    return msg


def graph(node, topic: str) -> dict:
    pubs = [{"node": i.node_name, "namespace": i.node_namespace, "type": i.topic_type,
             "hash": str(getattr(i, "topic_type_hash", "")), "gid": bytes(i.endpoint_gid).hex()[:32]}
            for i in node.get_publishers_info_by_topic(topic)]
    return {"nodes": sorted(node.get_node_names_and_namespaces()), "publishers": pubs}


def listen(args) -> int:
    node = rclpy.create_node("listener")
    got = []
    qos = qos_profile_sensor_data if args.best_effort else QoSProfile(depth=10)
    node.create_subscription(TYPES[args.type], args.topic, lambda m: got.append(as_dict(m)), qos)
    wanted = {tuple(n.rsplit("/", 1)) for n in args.node}
    wanted = {(ns or "/", name) for ns, name in wanted}
    deadline = time.monotonic() + 15.0
    while time.monotonic() < deadline:
        rclpy.spin_once(node, timeout_sec=0.05)
        seen = {(name_ns[1], name_ns[0]) for name_ns in node.get_node_names_and_namespaces()}
        if len(got) >= args.count and wanted <= seen:
            break
    for msg in got[:args.count]:
        say({"msg": msg})
    done = time.monotonic() < deadline
    say({"graph": graph(node, args.topic)})
    end = time.monotonic() + 30.0     # then stay, for the other side to look at this node, until terminated
    while time.monotonic() < end:
        rclpy.spin_once(node, timeout_sec=0.1)
    return 0 if done else 1


def talk(args) -> int:
    node = rclpy.create_node("talker")
    pub = node.create_publisher(TYPES[args.type], args.topic, 10)
    i = 0
    while True:
        pub.publish(String(data=f"from rclpy {i}") if args.type == "string" else scan(i))
        i += 1
        rclpy.spin_once(node, timeout_sec=0.05)


def main() -> int:
    parser = argparse.ArgumentParser()
    parser.add_argument("mode", choices=["listen", "talk"])
    parser.add_argument("topic")
    parser.add_argument("type", choices=sorted(TYPES))
    parser.add_argument("--best-effort", action="store_true")
    parser.add_argument("--count", type=int, default=3)
    parser.add_argument("--node", action="append", default=[])
    args = parser.parse_args()
    # Ended by SIGTERM (the test's end): exit at once, rclpy's own handlers off (they would shut the context down
    # under a publish in progress)
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(0))
    rclpy.init(signal_handler_options=rclpy.signals.SignalHandlerOptions.NO)
    try:
        return listen(args) if args.mode == "listen" else talk(args)
    except KeyboardInterrupt:
        return 0
    finally:
        if rclpy.ok():
            rclpy.shutdown()


if __name__ == "__main__":
    sys.exit(main())
