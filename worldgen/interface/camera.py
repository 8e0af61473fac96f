"""One robot's camera as gazebo_ros's camera plugin (``libgazebo_ros_camera``, or the RGB side of
``libgazebo_ros_openni_kinect``) and image_transport publish it, whatever the transport: the picture
(``sensor_msgs/Image``, the camera's encoding, 640 × 480 rgb8 on the Waffle Pi), its ``camera_info`` (plumb_bob,
D zeros, K and P from the field of view) and the JPEG image_transport's compressed publisher makes of it.

All three are due together at the sensor's rate in simulated time (30 Hz: every 8th 1/240 s step), stamped with the
simulated time the picture was taken, and are made only while some node subscribes to one of them: the plugin
switches its sensor on at the first subscriber to the image or the camera_info and off after the last.
"""

from __future__ import annotations

import io

from ..robots.cameras import CameraParams, camera_topic
from ..sim.camera import encoded
from .robot import header
from .topics import frame

JPEG_QUALITY = 80         # compressed_image_transport's default jpeg_quality
COLOUR = ("rgb8", "bgr8", "rgb16")   # what image_transport compresses as colour (the rest: grey)


class CameraIO:
    """The messages of one camera of one robot, and when they are due."""

    def __init__(self, robot, camera: CameraParams, ns: str, prefix: str, time_step: float):
        self.robot, self.camera = robot, camera
        self.image_topic = camera_topic(ns, camera.camera_name, camera.image_topic)
        self.info_topic = camera_topic(ns, camera.camera_name, camera.info_topic)
        self.frame_id = frame(prefix, camera.frame_name.lstrip("/"))
        self.every = max(1, round(1.0 / (camera.update_rate * time_step)))
        self.frames = 0

    def picture(self, session):
        """Draw the camera's view now (an H × W × 3 uint8 array)."""
        self.frames += 1
        return session.camera_image(self.robot, self.camera)

    def info(self, t: float) -> dict:
        c = self.camera
        return {"header": header(t, self.frame_id), "height": c.height, "width": c.width,
                "distortion_model": "plumb_bob", "d": list(c.distortion), "k": list(c.K),
                "r": [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0], "p": list(c.P)}

    def image(self, rgb, t: float) -> dict:
        data, step = encoded(rgb, self.camera.encoding)
        return {"header": header(t, self.frame_id), "height": self.camera.height, "width": self.camera.width,
                "encoding": self.camera.encoding, "is_bigendian": 0, "step": step, "data": data}

    def compressed(self, rgb, t: float) -> dict:
        """The picture as image_transport's compressed publisher sends it: colour encodings as a BGR JPEG, grey
        ones as a grey JPEG, the format naming both."""
        from PIL import Image as PILImage

        grey = self.camera.encoding not in COLOUR
        picture = PILImage.fromarray(rgb).convert("L") if grey else PILImage.fromarray(rgb)
        buffer = io.BytesIO()
        picture.save(buffer, "JPEG", quality=JPEG_QUALITY)
        return {"header": header(t, self.frame_id),
                "format": f"{self.camera.encoding}; jpeg compressed {'mono8' if grey else 'bgr8'}",
                "data": buffer.getvalue()}
