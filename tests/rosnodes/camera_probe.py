#!/usr/bin/env python3
"""Test probe for the simulated camera, written as a student would: images through cv_bridge as BGR, the JPEG
of the compressed topic through cv2.imdecode. Prints one JSON line; saves the last picture and a JPEG-decoded
one taken at the same time.

    camera_probe.py SECONDS OUT.npz [NS] [compressed]

listens to NS/camera/rgb/image_raw, NS/camera/rgb/camera_info (and NS/camera/rgb/image_raw/compressed when
asked), /tf_static and NS/odom; counts SECONDS of simulated time of pictures (after half a second of them) and
reports the image rate from the header stamps, the fields of the first messages, the static transforms and the
robot's pose.
"""

import json
import statistics
import sys
import time

import cv2
import numpy as np
import rospy
from cv_bridge import CvBridge
from nav_msgs.msg import Odometry
from sensor_msgs.msg import CameraInfo, CompressedImage, Image
from tf2_msgs.msg import TFMessage


WARM_UP = 0.5   # s of simulated time after the first picture before counting (connections settling)


def topic(ns, name):
    return ns.rstrip("/") + "/" + name if ns not in ("", "/") else "/" + name


def keep(pictures, stamp, picture):
    """The last few pictures by stamp."""
    pictures[stamp] = picture
    for old in sorted(pictures)[:-10]:
        del pictures[old]


def main(seconds, out, ns="/", compressed=False):
    bridge = CvBridge()
    got = {"stamps": [], "raw": {}, "jpeg": {}, "static": [], "odom": None}

    def on_image(msg):
        picture = bridge.imgmsg_to_cv2(msg, "bgr8")
        stamp = msg.header.stamp.to_sec()
        got["first"] = got.get("first", stamp)
        if stamp >= got["first"] + WARM_UP:
            got["stamps"].append(stamp)
        got.setdefault("image", {"encoding": msg.encoding, "width": msg.width, "height": msg.height,
                                 "step": msg.step, "frame": msg.header.frame_id, "shape": list(picture.shape)})
        keep(got["raw"], stamp, picture)

    def on_info(msg):
        got.setdefault("info", {"K": list(msg.K), "P": list(msg.P), "R": list(msg.R), "D": list(msg.D),
                                "model": msg.distortion_model, "width": msg.width, "height": msg.height,
                                "frame": msg.header.frame_id})
        got["info_count"] = got.get("info_count", 0) + 1

    def on_jpeg(msg):
        picture = cv2.imdecode(np.frombuffer(msg.data, np.uint8), cv2.IMREAD_COLOR)
        got.setdefault("format", msg.format)
        keep(got["jpeg"], msg.header.stamp.to_sec(), picture)

    def on_static(msg):
        for t in msg.transforms:
            tr, q = t.transform.translation, t.transform.rotation
            got["static"].append([t.header.frame_id, t.child_frame_id, [tr.x, tr.y, tr.z], [q.x, q.y, q.z, q.w]])

    def on_odom(msg):
        p, q = msg.pose.pose.position, msg.pose.pose.orientation
        got["odom"] = [[p.x, p.y, p.z], [q.x, q.y, q.z, q.w]]

    rospy.Subscriber(topic(ns, "camera/rgb/image_raw"), Image, on_image, queue_size=100, buff_size=2 ** 26)
    rospy.Subscriber(topic(ns, "camera/rgb/camera_info"), CameraInfo, on_info, queue_size=100)
    if compressed:
        rospy.Subscriber(topic(ns, "camera/rgb/image_raw/compressed"), CompressedImage, on_jpeg, queue_size=100,
                         buff_size=2 ** 24)
    rospy.Subscriber("/tf_static", TFMessage, on_static, queue_size=10)
    rospy.Subscriber(topic(ns, "odom"), Odometry, on_odom, queue_size=10)
    deadline = time.time() + 60
    while not got["stamps"] and time.time() < deadline:
        time.sleep(0.01)
    end = rospy.Time.now().to_sec() + seconds
    while rospy.Time.now().to_sec() < end and time.time() < deadline:
        time.sleep(0.01)
    time.sleep(0.3)
    stamps = got["stamps"]
    both = sorted(set(got["raw"]) & set(got["jpeg"]))
    last = max(got["raw"]) if got["raw"] else None
    np.savez(out, image=got["raw"][last] if last is not None else np.zeros(0),
             raw=got["raw"][both[-1]] if both else np.zeros(0), jpeg=got["jpeg"][both[-1]] if both else np.zeros(0))
    gaps = [b - a for a, b in zip(stamps, stamps[1:])]   # the publisher's period: the median gap, whatever is dropped
    rate = 1.0 / statistics.median(gaps) if len(gaps) > 1 and statistics.median(gaps) > 0 else None
    print(json.dumps({"count": len(stamps), "rate": rate, "image": got.get("image"), "info": got.get("info"),
                      "info_count": got.get("info_count", 0), "format": got.get("format"),
                      "gaps": sorted(set(round((b - a) * 240) for a, b in zip(stamps, stamps[1:]))),
                      "static": got["static"], "odom": got["odom"], "last_stamp": last,
                      "topics": sorted(t for t, _ in rospy.get_published_topics())}))


if __name__ == "__main__":
    rospy.init_node("camera_probe", anonymous=True, disable_signals=True)
    main(float(sys.argv[1]), sys.argv[2], sys.argv[3] if len(sys.argv) > 3 else "/", "compressed" in sys.argv[4:])
    rospy.signal_shutdown("done")
