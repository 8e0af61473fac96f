"""The simulated camera without ROS: the sensor's numbers as gazebo_ros's camera plugin reads them, and pictures
drawn on the CPU (moderngl on EGL, Mesa's llvmpipe) whose geometry is the pinhole model of the published K:
a red box covers the columns its corners project to, a floor marking lies where it projects, other robots and
spawned models show, and no OpenGL means one line naming what to install."""

from __future__ import annotations

import math
import os

import numpy as np
import pytest

from worldgen.core.errors import InputError
from worldgen.core.scene import Scene, Shape
from worldgen.robots import robot_urdf
from worldgen.robots.cameras import camera_topic, read_cameras
from worldgen.robots.profile import robot_profile

PI_HFOV = 1.085595
RED, BLUE, GREEN = (1.0, 0.0, 0.0, 1.0), (0.0, 0.0, 1.0, 1.0), (0.0, 0.8, 0.0, 1.0)


def need_gl() -> None:
    """Skip without an OpenGL context (fail under CI, which installs Mesa's EGL)."""
    from worldgen.sim.camera import open_context

    try:
        open_context().release()
    except InputError as err:
        if os.environ.get("CI"):
            pytest.fail(str(err))
        pytest.skip(str(err))


# -- the sensor's numbers ------------------------------------------------------------------------------------------

def test_waffle_pi_camera_is_the_plugins():
    (cam,) = robot_profile(robot_urdf("waffle_pi")).cameras
    assert (cam.link, cam.kind, cam.width, cam.height, cam.encoding) == ("camera_rgb_frame", "camera", 640, 480, "rgb8")
    assert (cam.hfov, cam.near, cam.far, cam.update_rate) == (PI_HFOV, 0.03, 100.0, 30.0)
    assert camera_topic("/", cam.camera_name, cam.image_topic) == "/camera/rgb/image_raw"
    assert camera_topic("/", cam.camera_name, cam.info_topic) == "/camera/rgb/camera_info"
    assert cam.frame_name == "camera_rgb_optical_frame"
    f = 640 / (2 * math.tan(PI_HFOV / 2))
    assert cam.K == pytest.approx((f, 0, 320.5, 0, f, 240.5, 0, 0, 1))
    assert cam.P == pytest.approx((f, 0, 320.5, -f * 0.07, 0, f, 240.5, 0, 0, 0, 1, 0))
    assert cam.distortion == (0, 0, 0, 0, 0)


def test_waffle_r200_colour_image_and_burger_without_camera():
    (cam,) = robot_profile(robot_urdf("waffle")).cameras
    assert (cam.kind, cam.width, cam.height, cam.hfov, cam.encoding) == ("depth", 1920, 1080, 1.3439, "rgb8")
    assert camera_topic("/", cam.camera_name, cam.image_topic) == "/camera/rgb/image_raw"
    assert robot_profile(robot_urdf("burger")).cameras == ()


def _sensor(plugin: str, image_format: str = "R8G8B8", extra: str = "") -> list:
    import xml.etree.ElementTree as ET

    text = (f'<gazebo reference="cam"><sensor type="camera" name="c"><camera><horizontal_fov>1.0</horizontal_fov>'
            f'<image><width>64</width><height>48</height><format>{image_format}</format></image></camera>'
            f'{plugin}{extra}</sensor></gazebo>')
    return [ET.fromstring(text)]


def test_plugin_defaults_namespaces_and_formats():
    plain = '<plugin name="p" filename="libgazebo_ros_camera.so"/>'
    (cam,) = read_cameras(_sensor(plain))
    assert camera_topic("/", cam.camera_name, cam.image_topic) == "/image_raw"
    assert camera_topic("/tb3_1", "camera", "rgb/image_raw") == "/tb3_1/camera/rgb/image_raw"
    assert camera_topic("/tb3_1", "camera", "/top/image") == "/top/image"
    assert cam.update_rate == 30.0 and cam.K[2] == 32.5 and cam.K[5] == 24.5
    formats = {f: read_cameras(_sensor(plain, f))[0].encoding for f in ("B8G8R8", "L8", "XYZ")}
    assert formats == {"B8G8R8": "bgr8", "L8": "mono8", "XYZ": "bgr8"}   # an unknown format: the plugin's bgr8
    rated = read_cameras(_sensor('<plugin name="p" filename="libgazebo_ros_camera.so"><updateRate>30</updateRate>'
                                 '<hackBaseline>0.07</hackBaseline><hackBaseline>0</hackBaseline></plugin>',
                                 extra="<update_rate>10</update_rate>"))[0]
    assert rated.update_rate == 10.0 and rated.hack_baseline == 0.07   # the slower; the first of two, as SDF
    assert read_cameras(_sensor("")) == ()   # no gazebo_ros plugin: nothing on ROS


def test_encodings():
    from worldgen.sim.camera import encoded

    rgb = np.arange(2 * 2 * 3, dtype=np.uint8).reshape(2, 2, 3)
    assert encoded(rgb, "bgr8") == (rgb[:, :, ::-1].tobytes(), 6)
    mono, step = encoded(np.full((1, 1, 3), [255, 0, 0], np.uint8), "mono8")
    assert (mono, step) == (bytes([76]), 1)
    bayer, _ = encoded(rgb, "bayer_rggb8")
    assert list(bayer) == [rgb[0, 0, 0], rgb[0, 1, 1], rgb[1, 0, 1], rgb[1, 1, 2]]
    assert encoded(np.full((1, 1, 3), 255, np.uint8), "rgb16") == (b"\xff" * 6, 6)


# -- pictures ----------------------------------------------------------------------------------------------------

def _scene(*visuals: Shape, collisions: bool = True) -> Scene:
    shapes = [Shape(s.kind, s.position, s.orientation, size=s.size, radius=s.radius, length=s.length,
                    model=s.model) for s in visuals if s.kind != "plane"] if collisions else []
    return Scene(source=None, shapes=shapes, visuals=list(visuals), models=sorted({s.model for s in visuals}))


def _red_mask(img: np.ndarray) -> np.ndarray:
    r, g, b = (img[:, :, i].astype(int) for i in range(3))
    return (r > g + 40) & (r > b + 40)


def _covered(mask: np.ndarray):
    cols, rows = np.where(mask.any(axis=0))[0], np.where(mask.any(axis=1))[0]
    return (int(cols.min()), int(cols.max()), int(rows.min()), int(rows.max())) if len(cols) else None


def _expected(session, corners) -> tuple[float, float, float, float]:
    """The pixel span the pinhole model of the camera's K gives for ``corners`` (first covered column = ceil of
    the left edge, as a pixel is drawn when its centre is inside)."""
    from worldgen.sim.camera import intrinsics, project
    from worldgen.sim.camera_scene import sensor_pose

    cam = session.main.profile.cameras[0]
    uv, z = project(corners, sensor_pose(session.main, cam), intrinsics(cam.fx, cam.fx, cam.cx, cam.cy))
    assert (z > 0).all()
    return (math.ceil(uv[:, 0].min()), math.floor(uv[:, 0].max()), math.ceil(uv[:, 1].min()),
            math.floor(uv[:, 1].max()))


def _box_corners(centre, size) -> np.ndarray:
    c, h = np.asarray(centre, float), np.asarray(size, float) / 2
    return np.array([c + h * [sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)])


@pytest.fixture(scope="module")
def red_box_session():
    need_gl()
    from worldgen.sim.session import Session

    box = Shape("box", (1.2, 0.1, 0.15), (0.0, 0.0, math.sin(0.2), math.cos(0.2)), size=(0.2, 0.3, 0.3),
                model="red_box", color=RED)
    marking = Shape("box", (0.8, -0.25, -0.0005), size=(0.3, 0.05, 0.001), model="marking", color=BLUE)   # top at 0
    with Session(_scene(box, marking), "waffle_pi", (0.0, 0.0, 0.0)) as session:
        session.run(0.3)
        yield session, box, marking


def test_red_box_covers_the_pixels_its_corners_project_to(red_box_session):
    from worldgen.core import poses

    session, box, _ = red_box_session
    img = session.camera_image(session.main, session.main.profile.cameras[0])
    assert img.shape == (480, 640, 3) and img.dtype == np.uint8
    rotation = poses.quat_matrix(*box.orientation)
    corners = _box_corners((0, 0, 0), box.size) @ rotation.T + box.position
    got, want = _covered(_red_mask(img)), _expected(session, corners)
    assert np.abs(np.subtract(got, want)).max() <= 1, (got, want)
    assert np.abs(img[5, 320].astype(int) - 178.5).max() <= 1      # Gazebo's grey background above the horizon
    floor = img[470, 320]
    assert floor[0] == floor[1] == floor[2] and floor[0] > 150      # the grey ground plane, lit by the sun


def test_a_marking_flush_with_the_floor_shows_where_it_projects_and_does_not_flicker(red_box_session):
    session, _, marking = red_box_session
    img = session.camera_image(session.main, session.main.profile.cameras[0])
    blue = (img[:, :, 2].astype(int) > img[:, :, 0] + 40) & (img[:, :, 2].astype(int) > img[:, :, 1] + 40)
    top = _box_corners(marking.position, marking.size)[[1, 3, 7, 5]]   # the top face, in order around it
    got, want = _covered(blue), _expected(session, top)
    assert np.abs(np.subtract(got, want)).max() <= 1, (got, want)
    from worldgen.sim.camera import intrinsics, project
    from worldgen.sim.camera_scene import sensor_pose

    cam = session.main.profile.cameras[0]
    uv, _ = project(top, sensor_pose(session.main, cam), intrinsics(cam.fx, cam.fx, cam.cx, cam.cy))
    u, v = uv[:, 0], uv[:, 1]
    area = abs(np.dot(u, np.roll(v, 1)) - np.dot(v, np.roll(u, 1))) / 2
    assert blue.sum() == pytest.approx(area, rel=0.1)   # the whole quadrilateral, not a z-fight's speckles


def test_spawned_moved_and_deleted_models_and_other_robots_show(red_box_session):
    from worldgen.core import poses

    session, _, _ = red_box_session
    cam = session.main.profile.cameras[0]
    green = Shape("cylinder", (0.0, 0.0, 0.2), radius=0.1, length=0.4, color=GREEN, model="can")
    session.models.spawn("can", [Shape("cylinder", (0.0, 0.0, 0.2), radius=0.1, length=0.4, model="can")],
                         poses.transform((1.0, -0.5, 0.0)), static=True, visuals=[green])

    def green_columns():
        img = session.camera_image(session.main, cam)
        mask = (img[:, :, 1].astype(int) > img[:, :, 0] + 40) & (img[:, :, 1].astype(int) > img[:, :, 2] + 40)
        return _covered(mask)

    right = green_columns()
    assert right is not None and right[0] > 320                      # y = −0.5: right of the middle
    session.models.set_pose("can", poses.transform((1.0, 0.45, 0.0)))
    left = green_columns()
    assert left is not None and left[1] < 320
    session.models.delete("can")
    assert green_columns() is None
    other = session.add_robot("burger", (0.9, -0.3, math.pi), name="other")
    try:
        img = session.camera_image(session.main, cam)
        dark = (img.max(axis=2) < 90) & (img.min(axis=2) == img.max(axis=2))
        base = _box_corners((0.9 + 0.032, -0.3, 0.01 + 0.08 / 2), (0.14, 0.14, 0.08))
        want = _expected(session, base)
        cols = np.where(dark[want[2]:want[3] + 1].any(axis=0))[0]
        assert want[0] - 20 <= cols.min() and cols.max() <= want[1] + 20 and len(cols) > 30
    finally:
        session.remove_robot(other)


def test_a_scene_without_visuals_draws_its_collision_shapes_grey():
    need_gl()
    from worldgen.sim.session import Session

    box = Shape("box", (1.0, 0.0, 0.25), size=(0.3, 0.3, 0.5), model="crate")
    scene = Scene(source=None, shapes=[box], models=["crate"])
    with Session(scene, "waffle_pi") as session:
        img = session.camera_image(session.main, session.main.profile.cameras[0])
        corners = _box_corners(box.position, box.size)
        want = _expected(session, corners)
        row = img[(want[2] + want[3]) // 2]
        inside, outside = row[(want[0] + want[1]) // 2], row[5]
        assert inside[0] == inside[1] == inside[2] and abs(int(inside[0]) - int(outside[0])) > 20


def test_without_opengl_one_line_names_the_packages(monkeypatch):
    import sys
    import types

    def no_egl(**kwargs):
        raise Exception("libEGL.so.1: cannot open shared object file\nmore")   # what glcontext raises

    monkeypatch.setitem(sys.modules, "moderngl", types.SimpleNamespace(create_standalone_context=no_egl))
    from worldgen.sim.camera import open_context

    with pytest.raises(InputError) as err:
        open_context()
    text = str(err.value)
    assert "\n" not in text and "libegl1 libegl-mesa0 libgl1-mesa-dri" in text and "--robot burger" in text
    assert "libEGL.so.1" in text
    monkeypatch.setitem(sys.modules, "moderngl", None)   # not installed
    with pytest.raises(InputError, match="pip install moderngl"):
        open_context()


def test_a_model_spawned_from_sdf_shows_in_its_material_colour(red_box_session):
    """What spawn_sdf_model does (the SDF reader's visuals, placed at the request's pose): a green can, then gone."""
    from types import SimpleNamespace as Msg

    from worldgen.ros1.spawner import OK, spawn_model

    session, _, _ = red_box_session
    sdf = ("<sdf version='1.6'><model name='can'><static>true</static><link name='l'>"
           "<collision name='c'><geometry><cylinder><radius>0.1</radius><length>0.4</length></cylinder></geometry>"
           "</collision><visual name='v'><geometry><cylinder><radius>0.1</radius><length>0.4</length></cylinder>"
           "</geometry><material><diffuse>0 0.8 0 1</diffuse><ambient>0 0.8 0 1</ambient></material></visual>"
           "</link></model></sdf>")
    pose = Msg(position=Msg(x=1.0, y=-0.4, z=0.2), orientation=Msg(x=0.0, y=0.0, z=0.0, w=1.0))
    bridge = Msg(session=session, api=Msg(names=session.models.names))
    request = Msg(model_name="green_can", model_xml=sdf, initial_pose=pose, reference_frame="", robot_namespace="")
    assert spawn_model(bridge, request, "sdf") == (True, OK)
    try:
        img = session.camera_image(session.main, session.main.profile.cameras[0]).astype(int)
        green = (img[:, :, 1] > img[:, :, 0] + 40) & (img[:, :, 1] > img[:, :, 2] + 40)
        corners = _box_corners((1.0, -0.4, 0.2), (0.2, 0.2, 0.4))
        want = _expected(session, corners)
        got = _covered(green)
        assert got is not None and want[0] - 2 <= got[0] and got[1] <= want[1] + 2 and got[3] <= want[3] + 1
    finally:
        session.models.delete("green_can")
