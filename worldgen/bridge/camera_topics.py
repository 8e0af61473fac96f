"""One robot's camera on ROS, as gazebo_ros's camera plugin (``libgazebo_ros_camera``, or the RGB side of
``libgazebo_ros_openni_kinect``) and image_transport publish it.

=====================================  ===========================  ============================================
topic (Waffle Pi, global namespace)    type                         what
=====================================  ===========================  ============================================
``/camera/rgb/image_raw``              sensor_msgs/Image            rgb8, 640 × 480, step 1920, frame
                                                                    ``camera_rgb_optical_frame``
``/camera/rgb/camera_info``            sensor_msgs/CameraInfo       plumb_bob, D zeros, K and P from the field of
                                                                    view (:mod:`worldgen.robots.cameras`), R = I
``/camera/rgb/image_raw/compressed``   sensor_msgs/CompressedImage  JPEG (quality 80, image_transport's default),
                                                                    format ``rgb8; jpeg compressed bgr8``
=====================================  ===========================  ============================================

All three go out together at the sensor's rate in simulated time (30 Hz: every 8th 1/240 s step), stamped with the
simulated time the picture was taken, and only while some node subscribes to one of them: the plugin switches its
sensor on at the first subscriber to the image or the camera_info and off after the last, and nothing is drawn
for a robot no node looks through. Each goes only to the topics that have subscribers (the JPEG is encoded only
for a compressed subscriber). A robot in namespace ``ns`` has them under ``ns/``, its frame prefixed as its others.
"""

from __future__ import annotations

import io

from ..robots.cameras import CameraParams, camera_topic
from .robot_topics import frame

JPEG_QUALITY = 80         # compressed_image_transport's default jpeg_quality
QUEUE = 2                 # what the plugin advertises its image topics with
COLOUR = ("rgb8", "bgr8", "rgb16")   # what image_transport compresses as colour (the rest: grey)


class CameraTopics:
    """The publishers of one camera of one robot, and when it is due (see the module docstring)."""

    def __init__(self, rospy, robot, camera: CameraParams, ns: str, prefix: str, time_step: float):
        from sensor_msgs.msg import CameraInfo, CompressedImage, Image

        self.rospy, self.robot, self.camera = rospy, robot, camera
        self.Image, self.CompressedImage = Image, CompressedImage
        image = camera_topic(ns, camera.camera_name, camera.image_topic)
        pub = rospy.Publisher
        self.pubs = {"image": pub(image, Image, queue_size=QUEUE),
                     "info": pub(camera_topic(ns, camera.camera_name, camera.info_topic), CameraInfo, queue_size=QUEUE),
                     "compressed": pub(image + "/compressed", CompressedImage, queue_size=QUEUE)}
        self.frame_id = frame(prefix, camera.frame_name.lstrip("/"))
        self.every = max(1, round(1.0 / (camera.update_rate * time_step)))
        self.info = CameraInfo(height=camera.height, width=camera.width, distortion_model="plumb_bob",
                               D=list(camera.distortion), K=list(camera.K), R=[1.0, 0, 0, 0, 1.0, 0, 0, 0, 1.0],
                               P=list(camera.P))
        self.info.header.frame_id = self.frame_id
        self.frames = 0

    def close(self) -> None:
        for publisher in self.pubs.values():
            publisher.unregister()

    def wanted(self) -> list[str]:
        """The topics some node subscribes to now."""
        return [name for name, publisher in self.pubs.items() if publisher.get_num_connections() > 0]

    def publish(self, session, stamp) -> bool:
        """Take and send a picture when some node wants one; True when one was sent."""
        wanted = self.wanted()
        if not wanted:
            return False
        from ..sim.camera import encoded

        rgb = session.camera_image(self.robot, self.camera)
        self.frames += 1
        if "image" in wanted:
            msg = self.Image(height=self.camera.height, width=self.camera.width, encoding=self.camera.encoding,
                             is_bigendian=0)
            msg.data, msg.step = encoded(rgb, self.camera.encoding)
            msg.header.stamp, msg.header.frame_id = stamp, self.frame_id
            self.pubs["image"].publish(msg)
        if "info" in wanted:
            self.info.header.stamp = stamp
            self.pubs["info"].publish(self.info)
        if "compressed" in wanted:
            self.pubs["compressed"].publish(self.compressed(rgb, stamp))
        return True

    def compressed(self, rgb, stamp):
        """The picture as image_transport's compressed publisher sends it: colour encodings as a BGR JPEG,
        grey ones as a grey JPEG, the format naming both."""
        from PIL import Image as PILImage

        grey = self.camera.encoding not in COLOUR
        picture = PILImage.fromarray(rgb).convert("L") if grey else PILImage.fromarray(rgb)
        buffer = io.BytesIO()
        picture.save(buffer, "JPEG", quality=JPEG_QUALITY)
        msg = self.CompressedImage(format=f"{self.camera.encoding}; jpeg compressed {'mono8' if grey else 'bgr8'}",
                                   data=buffer.getvalue())
        msg.header.stamp, msg.header.frame_id = stamp, self.frame_id
        return msg
