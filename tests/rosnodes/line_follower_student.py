#!/usr/bin/env python3
"""Student style: follow the yellow tape with the camera. Mask the tape's colour in HSV, keep a band of rows
near the bottom of the image, steer on the offset of the mask's centroid (cv2.moments) from the middle."""
import cv2
import cv_bridge
import numpy as np
import rospy
from geometry_msgs.msg import Twist
from sensor_msgs.msg import Image

LOWER = np.array([20, 80, 80])     # yellow in OpenCV's HSV (hue 0-180)
UPPER = np.array([40, 255, 255])


class Follower:
    def __init__(self):
        rospy.init_node("follower")
        self.bridge = cv_bridge.CvBridge()
        self.pub = rospy.Publisher("cmd_vel", Twist, queue_size=1)
        self.sub = rospy.Subscriber("camera/rgb/image_raw", Image, self.image_callback)

    def image_callback(self, msg):
        image = self.bridge.imgmsg_to_cv2(msg, desired_encoding="bgr8")
        hsv = cv2.cvtColor(image, cv2.COLOR_BGR2HSV)
        mask = cv2.inRange(hsv, LOWER, UPPER)
        h, w, d = image.shape
        top = int(0.6 * h)
        mask[0:top, 0:w] = 0
        M = cv2.moments(mask)
        twist = Twist()
        if M["m00"] > 0:
            cx = int(M["m10"] / M["m00"])
            err = cx - w / 2
            twist.linear.x = 0.12
            twist.angular.z = -float(err) / 250
        else:
            twist.angular.z = 0.4
        self.pub.publish(twist)


if __name__ == "__main__":
    Follower()
    rospy.spin()
