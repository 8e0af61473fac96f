"""One robot's camera on ROS 1: the three topics of :class:`~worldgen.interface.camera.CameraIO` as rospy
publishers (queue 2, as the plugin advertises them), each fed only while some node subscribes to it (the JPEG is
encoded only for a compressed subscriber).

=====================================  ===========================  ============================================
topic (Waffle Pi, global namespace)    type                         what
=====================================  ===========================  ============================================
``/camera/rgb/image_raw``              sensor_msgs/Image            rgb8, 640 × 480, step 1920, frame
                                                                    ``camera_rgb_optical_frame``
``/camera/rgb/camera_info``            sensor_msgs/CameraInfo       plumb_bob, D zeros, K and P from the field of
                                                                    view
``/camera/rgb/image_raw/compressed``   sensor_msgs/CompressedImage  image_transport's JPEG (quality 80),
                                                                    format ``rgb8; jpeg compressed bgr8``
=====================================  ===========================  ============================================
"""

from __future__ import annotations

from ..interface.camera import CameraIO
from ..interface.topics import camera_topics
from .messages import fill, message_class


class CameraTopics:
    """The publishers of one camera of one robot (see the module docstring)."""

    def __init__(self, rospy, io: CameraIO):
        self.rospy, self.io = rospy, io
        table = camera_topics("noetic", io.image_topic, io.info_topic)
        names = {"image": io.image_topic, "info": io.info_topic, "compressed": io.image_topic + "/compressed"}
        self.pubs = {key: rospy.Publisher(names[key], message_class(t.type), queue_size=t.qos.depth)
                     for key, t in table.items()}
        self.every = io.every

    @property
    def frames(self) -> int:
        return self.io.frames

    def close(self) -> None:
        for publisher in self.pubs.values():
            publisher.unregister()

    def wanted(self) -> list[str]:
        """The topics some node subscribes to now."""
        return [name for name, publisher in self.pubs.items() if publisher.get_num_connections() > 0]

    def publish(self, session, t: float) -> bool:
        """Take and send a picture when some node wants one; True when one was sent."""
        wanted = self.wanted()
        if not wanted:
            return False
        rgb = self.io.picture(session)
        makers = {"image": lambda: self.io.image(rgb, t), "info": lambda: self.io.info(t),
                  "compressed": lambda: self.io.compressed(rgb, t)}
        for key in ("image", "info", "compressed"):
            if key in wanted:
                publisher = self.pubs[key]
                publisher.publish(fill(publisher.data_class(), makers[key](), self.rospy))
        return True
