"""``spawn_sdf_model`` and ``spawn_urdf_model``: a model's XML from a request → bodies in the running simulation.

An SDF model (``<sdf><model>`` or a bare ``<model>``) is read by worldgen's SDF reader, so boxes, cylinders,
spheres and meshes (``model://`` and file URIs found as for worlds) appear in the physics and in every LiDAR; a
model that is not ``<static>`` moves under physics with its links' mass. A URDF robot with a differential drive
(a TurtleBot3's ``robot_description``) becomes another simulated robot, its topics in the request's
``robot_namespace``. Answers are Gazebo's own: ``(success, status_message)``.
"""

from __future__ import annotations

import dataclasses
import math
import xml.etree.ElementTree as ET

from ..core import poses
from ..core.errors import WorldgenError
from ..sim.models import matrix_of
from .pose_msgs import pose7

OK = "SpawnModel: Successfully spawned entity"


def spawn_model(bridge, req, kind: str) -> tuple[bool, str]:
    """Spawn ``req`` (a gazebo_msgs/SpawnModel request) into ``bridge``'s simulation."""
    api, name = bridge.api, req.model_name
    if not name:
        return False, "SpawnModel: Failure - model name is empty"
    if name in api.names():
        return False, f"SpawnModel: Failure - entity [{name}] already exists."
    try:
        root = ET.fromstring(req.model_xml)
    except ET.ParseError as err:
        return False, f"SpawnModel: Failure - model format is not valid XML ({err})"
    frame = matrix_of(pose7(req.initial_pose))
    if req.reference_frame not in ("", "world", "map", "/map"):
        ref = api.entity_pose(req.reference_frame)
        if ref is None:
            return False, f"SpawnModel: Failure - reference frame [{req.reference_frame}] not found"
        frame = matrix_of(ref[0]) @ frame
    if root.tag == "robot":
        return _spawn_robot(bridge, name, req.model_xml, frame, req.robot_namespace)
    if root.tag not in ("sdf", "model"):
        return False, f"SpawnModel: Failure - <{root.tag}> is neither SDF nor URDF"
    return _spawn_sdf(bridge, name, req.model_xml, frame)


def _spawn_sdf(bridge, name: str, text: str, frame) -> tuple[bool, str]:
    from ..sdf.reader import read_world_text

    if not text.lstrip().startswith("<sdf") and not text.lstrip().startswith("<?xml"):
        text = f'<sdf version="1.6">{text}</sdf>'
    try:
        scene = read_world_text(text)
    except WorldgenError as err:
        return False, f"SpawnModel: Failure - the SDF cannot be read: {err}"
    shapes = [s for s in scene.shapes if s.kind != "plane"]
    if not scene.models:
        return False, "SpawnModel: Failure - the SDF holds no <model>"
    own = scene.model_poses.get(scene.models[0])
    model_frame = matrix_of(own) if own is not None else poses.IDENTITY
    inverse = poses.inverse(model_frame)

    def local(shape):
        t = inverse @ poses.transform(shape.position, poses.quat_matrix(*shape.orientation))
        return dataclasses.replace(shape, position=tuple(float(v) for v in t[:3, 3]),
                                   orientation=poses.matrix_quat(t[:3, :3]),
                                   model=name + shape.model[len(scene.models[0]):])

    static = all(s.static for s in shapes)
    visuals = [local(v) for v in scene.visuals] if scene.visuals else None   # None: a camera draws the collisions
    bridge.session.models.spawn(name, [local(s) for s in shapes], frame @ model_frame, static, sdf_mass(text),
                                visuals=visuals)
    return True, OK


def _spawn_robot(bridge, name: str, urdf: str, frame, namespace: str) -> tuple[bool, str]:
    from ..robots.profile import robot_profile

    try:
        profile = robot_profile(urdf)
    except (WorldgenError, ET.ParseError, ValueError) as err:
        return False, f"SpawnModel: Failure - the URDF cannot be read: {err}"
    if profile.drive is None:
        return False, ("SpawnModel: Failure - worldgen simulates URDF models with a differential drive only "
                       "(a TurtleBot3); spawn other objects as SDF with spawn_sdf_model")
    yaw = math.atan2(frame[1, 0], frame[0, 0])
    ns = "/" + namespace.strip("/") if namespace.strip("/") else f"/{name}"
    try:
        bridge.add_robot(name, urdf=urdf, spawn=(float(frame[0, 3]), float(frame[1, 3]), yaw), ns=ns,
                         z=float(frame[2, 3]))
    except WorldgenError as err:
        return False, f"SpawnModel: Failure - {err}"
    return True, OK


def sdf_mass(text: str) -> float:
    """The model's mass: its links' ``<inertial><mass>`` added up (SDF's default 1 kg for a link without)."""
    try:
        root = ET.fromstring(text)
    except ET.ParseError:
        return 1.0
    total = 0.0
    for link in root.iter("link"):
        mass = link.findtext("inertial/mass")
        try:
            total += float(mass) if mass is not None else 1.0
        except ValueError:
            total += 1.0
    return total if total > 0 and math.isfinite(total) else 1.0
