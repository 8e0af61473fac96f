"""A robot's cameras, read from its URDF's ``<gazebo reference="LINK"><sensor type="camera"|"depth">`` blocks the
way Gazebo's sensor and gazebo_ros's camera plugins read them (``libgazebo_ros_camera``, and the RGB image of
``libgazebo_ros_openni_kinect`` and ``libgazebo_ros_depth_camera``, which share ``GazeboRosCameraUtils``).

What a node sees follows from these numbers alone:

- topics: ``<robot namespace>/<cameraName>/<imageTopicName>`` (default ``image_raw``) and
  ``…/<cameraInfoTopicName>`` (default ``camera_info``); a name starting with ``/`` is absolute. The Waffle Pi's
  ``cameraName`` is ``camera`` and its topics ``rgb/image_raw`` and ``rgb/camera_info``: ``/camera/rgb/image_raw``.
- K: focal length ``f = width / (2 tan(hfov / 2))`` (the plugin's ``focalLength`` when not 0), and the principal
  point ``cx = (width + 1) / 2``, ``cy = (height + 1) / 2`` (its ``Cx``/``Cy`` when not 0) — the plugin's own
  formula, half a pixel right of and below the middle of the image in ROS's pixel-centre coordinates. P is K with
  ``P[3] = −f · hackBaseline`` (P[2] is ``cx`` too: the plugin never uses its ``CxPrime`` there). Distortion is
  plumb_bob with the plugin's k1, k2, t1, t2, k3 (all 0 on the TurtleBot3s).
- the image encoding from the sensor's ``<format>`` as the plugin maps it (``R8G8B8`` → ``rgb8``; a format it does
  not know → ``bgr8``, as it falls back).
- the rate: the plugin's ``updateRate`` (the sensor's ``<update_rate>`` when that is lower; 30 Hz when neither
  says).

A camera sensor without a gazebo_ros plugin publishes nothing on ROS, so it is not listed.
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from dataclasses import dataclass

from ..core.numbers import floats

# Gazebo's <format> names → sensor_msgs/image_encodings, as GazeboRosCameraUtils::Init maps them.
ENCODINGS = {"L8": "mono8", "L_INT8": "mono8", "L16": "mono16", "L_INT16": "mono16", "R8G8B8": "rgb8",
             "RGB_INT8": "rgb8", "B8G8R8": "bgr8", "BGR_INT8": "bgr8", "R16G16B16": "rgb16", "RGB_INT16": "rgb16",
             "BAYER_RGGB8": "bayer_rggb8", "BAYER_BGGR8": "bayer_bggr8", "BAYER_GBRG8": "bayer_gbrg8",
             "BAYER_GRBG8": "bayer_grbg8"}
FALLBACK_ENCODING = "bgr8"      # the plugin's choice for a format it does not know
FALLBACK_RATE = 30.0            # Hz, when neither the plugin nor the sensor gives one
CAMERA_PLUGINS = ("gazebo_ros_camera", "gazebo_ros_openni_kinect", "gazebo_ros_depth_camera")


@dataclass(frozen=True)
class CameraParams:
    """One camera sensor and its gazebo_ros plugin (see the module docstring). ``link`` is the ``<gazebo
    reference>`` the sensor is on; the image looks along that frame's +x (``pose`` is the sensor's ``<pose>`` in
    it), with +z up."""

    link: str
    sensor: str                 # the sensor's name
    kind: str                   # camera | depth
    hfov: float                 # rad
    width: int
    height: int
    format: str                 # Gazebo's <format>
    near: float
    far: float
    update_rate: float          # Hz, what the plugin publishes at
    camera_name: str
    image_topic: str
    info_topic: str
    frame_name: str
    hack_baseline: float = 0.0
    focal_length: float = 0.0   # 0: from hfov and width
    cx_given: float = 0.0       # 0: (width + 1) / 2
    cy_given: float = 0.0       # 0: (height + 1) / 2
    distortion: tuple[float, float, float, float, float] = (0.0, 0.0, 0.0, 0.0, 0.0)   # k1 k2 t1 t2 k3
    pose: tuple[float, float, float, float, float, float] = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    plugin: str = ""

    @property
    def fx(self) -> float:
        return self.focal_length or self.width / (2.0 * math.tan(self.hfov / 2.0))

    @property
    def cx(self) -> float:
        return self.cx_given or (self.width + 1.0) / 2.0

    @property
    def cy(self) -> float:
        return self.cy_given or (self.height + 1.0) / 2.0

    @property
    def K(self) -> tuple[float, ...]:   # noqa: N802  (sensor_msgs/CameraInfo's name)
        f = self.fx
        return (f, 0.0, self.cx, 0.0, f, self.cy, 0.0, 0.0, 1.0)

    @property
    def P(self) -> tuple[float, ...]:   # noqa: N802
        f = self.fx
        return (f, 0.0, self.cx, -f * self.hack_baseline, 0.0, f, self.cy, 0.0, 0.0, 0.0, 1.0, 0.0)

    @property
    def encoding(self) -> str:
        return ENCODINGS.get(self.format.strip().upper(), FALLBACK_ENCODING)


def camera_topic(ns: str, camera_name: str, name: str) -> str:
    """A camera topic as the plugin's node handle resolves it: ``ns/camera_name/name``, or ``name`` when absolute."""
    if name.startswith("/"):
        return "/" + name.strip("/")
    parts = [p.strip("/") for p in (ns, camera_name, name)]
    return "/" + "/".join(p for p in parts if p)


def read_cameras(gazebo: list[ET.Element]) -> tuple[CameraParams, ...]:
    """Every camera (and depth camera) sensor with a gazebo_ros camera plugin among a URDF's ``<gazebo>`` blocks."""
    found = []
    for block in gazebo:
        link = block.get("reference")
        for sensor in block.findall("sensor"):
            if not link or sensor.get("type") not in ("camera", "depth"):
                continue
            plugin = next((p for p in sensor.findall("plugin")
                           if any(name in p.get("filename", "") for name in CAMERA_PLUGINS)), None)
            if plugin is not None:
                found.append(_camera(link, sensor, plugin))
    return tuple(found)


def _camera(link: str, sensor: ET.Element, plugin: ET.Element) -> CameraParams:
    camera = sensor.find("camera")
    image = camera.find("image") if camera is not None else None
    clip = camera.find("clip") if camera is not None else None
    sensor_rate = _num(sensor, "update_rate", 0.0)
    plugin_rate = _num(plugin, "updateRate", 0.0)
    rates = [r for r in (sensor_rate, plugin_rate) if r > 0]
    return CameraParams(
        link=link, sensor=sensor.get("name", ""), kind=sensor.get("type", "camera"),
        hfov=_num(camera, "horizontal_fov", 1.047), width=int(_num(image, "width", 320)),
        height=int(_num(image, "height", 240)), format=_text(image, "format", "R8G8B8"),
        near=_num(clip, "near", 0.1), far=_num(clip, "far", 100.0),
        update_rate=min(rates) if rates else FALLBACK_RATE,
        camera_name=_text(plugin, "cameraName", ""), image_topic=_text(plugin, "imageTopicName", "image_raw"),
        info_topic=_text(plugin, "cameraInfoTopicName", "camera_info"),
        frame_name=_text(plugin, "frameName", "world"), hack_baseline=_num(plugin, "hackBaseline", 0.0),
        focal_length=_num(plugin, "focalLength", 0.0), cx_given=_num(plugin, "Cx", 0.0),
        cy_given=_num(plugin, "Cy", 0.0),
        distortion=tuple(_num(plugin, k, 0.0) for k in ("distortionK1", "distortionK2", "distortionT1",
                                                         "distortionT2", "distortionK3")),
        pose=floats(sensor.findtext("pose"), 6), plugin=plugin.get("filename", ""))


def _text(elem: ET.Element | None, path: str, default: str) -> str:
    text = elem.findtext(path) if elem is not None else None
    return text.strip() if text is not None and text.strip() else default


def _num(elem: ET.Element | None, path: str, default: float) -> float:
    """The number at ``path`` under ``elem``; of two, the first, as Gazebo's ``sdf::Element::Get`` takes it
    (upstream's Waffle plugin block gives ``hackBaseline`` twice, 0.07 then 0)."""
    text = elem.findtext(path) if elem is not None else None
    try:
        value = float(text) if text is not None and text.strip() else default
    except ValueError:
        return default
    return value if math.isfinite(value) else default
