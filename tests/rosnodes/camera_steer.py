#!/usr/bin/env python3
"""Student style: steer by the camera. Every picture through cv_bridge as BGR, the red in it with cv2.inRange, then
turn towards its centre and drive while it is seen; turn on the spot looking for it otherwise."""
import cv2
import numpy as np
import rospy
from cv_bridge import CvBridge
from geometry_msgs.msg import Twist
from sensor_msgs.msg import Image

bridge = CvBridge()


def on_image(msg):
    frame = bridge.imgmsg_to_cv2(msg, "bgr8")
    mask = cv2.inRange(frame, np.array([0, 0, 60]), np.array([50, 50, 255]))
    moments = cv2.moments(mask)
    twist = Twist()
    if moments["m00"] > 0:
        cx = moments["m10"] / moments["m00"]
        twist.angular.z = -0.004 * (cx - msg.width / 2)
        twist.linear.x = 0.1
    else:
        twist.angular.z = 0.5
    pub.publish(twist)


rospy.init_node("camera_steer")
pub = rospy.Publisher("cmd_vel", Twist, queue_size=10)
rospy.Subscriber("camera/rgb/image_raw", Image, on_image, queue_size=1, buff_size=2 ** 24)
rospy.spin()
