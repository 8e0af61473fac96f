"""The Waffle Pi's camera through ROS, as a student's node sees it: `worldgen sim --robot waffle_pi` publishes
/camera/rgb/image_raw (rgb8, 640 × 480, 30 Hz of simulated time), /camera/rgb/camera_info (Gazebo's K and P) and
the JPEG of image_raw/compressed; a red box 1 m ahead and a marking on the floor land where camera_info's K, the
tf frames and the odometry put them; other robots' cameras are in their namespaces, and a Burger has none.

Real rosmaster, real rospy nodes under Debian's python with cv_bridge and OpenCV (tests/rosnodes/camera_probe.py).
"""

from __future__ import annotations

import json
import math
import signal
import subprocess
import sys
import time

import numpy as np
import pytest

from bridgetools import NODES, REPO, ROOM, no_leftovers, need_ros, ros_env, wait_master, worldgen
from rosstubs import SYSTEM_PYTHON, need_module, start_roscore, stop_process

RED_BOX = {"centre": (1.0, 0.05, 0.15), "size": (0.2, 0.3, 0.3), "yaw": 0.3}
MARKING = {"centre": (0.7, -0.2, 0.0005), "size": (0.4, 0.04, 0.001)}
FRAMES = ("base_footprint", "base_link", "camera_link", "camera_rgb_frame", "camera_rgb_optical_frame")


def need_camera() -> None:
    need_ros()
    for module in ("cv_bridge", "cv2", "sensor_msgs.msg"):
        need_module(module)
    from test_camera import need_gl

    need_gl()


def camera_probe(env, out, seconds=3.0, ns="/", compressed=False) -> dict:
    args = [SYSTEM_PYTHON, str(NODES / "camera_probe.py"), str(seconds), str(out), ns]
    proc = subprocess.run(args + (["compressed"] if compressed else []), env=env, capture_output=True, text=True,
                          timeout=120)
    assert proc.returncode == 0, proc.stderr[-3000:]
    return json.loads(proc.stdout.strip().splitlines()[-1])


@pytest.fixture(scope="module")
def waffle_pi_sim(tmp_path_factory):
    """`worldgen sim` on the class room with a Waffle Pi, at 2x real time."""
    need_camera()
    tmp = tmp_path_factory.mktemp("camera")
    env = ros_env(tmp)
    proc = worldgen(["sim", str(ROOM), "--robot", "waffle_pi", "--rate", "2"], env)
    wait_master(env, proc)
    yield env, tmp
    proc.send_signal(signal.SIGINT)
    out, err = proc.communicate(timeout=30)
    assert proc.returncode == 0, err
    assert "Traceback" not in err
    no_leftovers(env)


def test_image_camera_info_and_compressed_as_gazebos_plugin(waffle_pi_sim):
    env, tmp = waffle_pi_sim
    got = camera_probe(env, tmp / "pi.npz", compressed=True)
    assert got["rate"] == pytest.approx(30.0, rel=0.05)
    assert got["gaps"][0] == 8 and all(g % 8 == 0 for g in got["gaps"])   # every 8th 1/240 s step
    assert got["image"] == {"encoding": "rgb8", "width": 640, "height": 480, "step": 1920,
                            "frame": "camera_rgb_optical_frame", "shape": [480, 640, 3]}
    f = 640 / (2 * math.tan(1.085595 / 2))
    info = got["info"]
    assert info["K"] == pytest.approx([f, 0, 320.5, 0, f, 240.5, 0, 0, 1])
    assert info["P"] == pytest.approx([f, 0, 320.5, -0.07 * f, 0, f, 240.5, 0, 0, 0, 1, 0])
    assert info["R"] == [1, 0, 0, 0, 1, 0, 0, 0, 1] and info["D"] == [0, 0, 0, 0, 0]
    assert (info["model"], info["width"], info["height"], info["frame"]) == ("plumb_bob", 640, 480,
                                                                             "camera_rgb_optical_frame")
    assert got["info_count"] >= got["count"] - 2
    static = {(p, c) for p, c, _, _ in got["static"]}
    assert set(zip(FRAMES, FRAMES[1:])) <= static
    assert got["format"] == "rgb8; jpeg compressed bgr8"
    saved = np.load(tmp / "pi.npz")
    raw, jpeg = saved["raw"].astype(int), saved["jpeg"].astype(int)
    assert raw.shape == jpeg.shape == (480, 640, 3)
    assert np.abs(raw - jpeg).mean() < 2.0 and np.percentile(np.abs(raw - jpeg), 99) < 12
    picture = saved["image"]
    wall, floor = picture[100, 320], picture[400, 320]   # the wall 2.4 m ahead above the horizon, the floor below
    assert wall[0] == wall[1] == wall[2] and floor[0] == floor[1] == floor[2] and int(floor[0]) - int(wall[0]) > 40


# -- a hand-made scene: the Waffle Pi facing a red box, a marking on the floor, two more robots behind ------------

@pytest.fixture(scope="module")
def scene_sim(tmp_path_factory):
    need_camera()
    from worldgen.core.scene import Scene, Shape
    from worldgen.ros1.gazebo_types import gazebo_msgs_path
    from worldgen.ros1.master import node_names
    from worldgen.bridge.world import World, write_config

    tmp = tmp_path_factory.mktemp("camera_scene")
    yaw = RED_BOX["yaw"]
    red = Shape("box", RED_BOX["centre"], (0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2)), size=RED_BOX["size"],
                model="red_box", color=(1.0, 0.0, 0.0, 1.0))
    marking = Shape("box", MARKING["centre"], size=MARKING["size"], model="tape", color=(0.0, 0.0, 1.0, 1.0))
    plane = Shape("plane", (0.0, 0.0, 0.0), normal=(0.0, 0.0, 1.0), model="ground_plane")
    collision = Shape("box", red.position, red.orientation, size=red.size, model="red_box")
    scene = Scene(source=None, shapes=[plane, collision], visuals=[plane, red, marking],
                  models=["ground_plane", "red_box", "tape"], model_poses={})
    robots = [{"name": "turtlebot3_waffle_pi", "ns": "/", "robot": "waffle_pi", "spawn": [0.0, 0.0, 0.0]},
              {"name": "tb3_1", "ns": "/tb3_1", "robot": "burger", "spawn": [-1.5, -1.0, 0.0]},
              {"name": "tb3_2", "ns": "/tb3_2", "robot": "waffle_pi", "spawn": [-1.5, 1.0, 0.0]}]
    robots = [dict(r, tf_prefix=None, mappings=None) for r in robots]
    world = World(tmp / "hand_made", scene, "waffle_pi", "test", (0.0, 0.0, 0.0), "test", robots)
    config = write_config(tmp, world, rate=2.0, duration=None, no_hit="inf", trace=None, set_sim_time=True,
                          gazebo_msgs=gazebo_msgs_path())
    core, env = start_roscore(tmp)
    env = dict(env, PYTHONPATH=str(REPO))
    node = subprocess.Popen([sys.executable, "-m", "worldgen.ros1", str(config)], env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        deadline = time.monotonic() + 30
        while "/gazebo" not in node_names(env["ROS_MASTER_URI"]) and time.monotonic() < deadline:
            assert node.poll() is None, node.communicate()[1]
            time.sleep(0.05)
        yield env, tmp
    finally:
        node.send_signal(signal.SIGTERM)
        _, err = node.communicate(timeout=30)
        stop_process(core)
        assert "Traceback" not in err, err


def _camera_pose(got: dict) -> np.ndarray:
    """World pose of camera_rgb_optical_frame from the odometry and the static transforms, as a node computes it
    with tf (Gazebo's odom frame is the world frame at spawn)."""
    from worldgen.core import poses

    links = {c: (xyz, q) for p, c, xyz, q in got["static"] if c in FRAMES}
    (x, y, z), q = got["odom"]
    t = poses.transform((x, y, z), poses.quat_matrix(*q))
    for child in FRAMES[1:]:
        xyz, quat = links[child]
        t = t @ poses.transform(xyz, poses.quat_matrix(*quat))
    return t


def _pixels(corners, pose: np.ndarray, k) -> tuple[float, float, float, float]:
    """The span of pixels the pinhole model gives (first covered column = ceil of the left edge)."""
    optical = (np.asarray(corners, float) - pose[:3, 3]) @ pose[:3, :3]
    k = np.asarray(k, float).reshape(3, 3)
    u = k[0, 0] * optical[:, 0] / optical[:, 2] + k[0, 2]
    v = k[1, 1] * optical[:, 1] / optical[:, 2] + k[1, 2]
    assert (optical[:, 2] > 0).all()
    return math.ceil(u.min()), math.floor(u.max()), math.ceil(v.min()), math.floor(v.max())


def _corners(centre, size, yaw=0.0) -> np.ndarray:
    h = np.asarray(size, float) / 2
    c, s = math.cos(yaw), math.sin(yaw)
    rot = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])
    return np.array([rot @ (h * [a, b, d]) + centre for a in (-1, 1) for b in (-1, 1) for d in (-1, 1)])


def _span(mask: np.ndarray):
    cols, rows = np.where(mask.any(axis=0))[0], np.where(mask.any(axis=1))[0]
    return int(cols.min()), int(cols.max()), int(rows.min()), int(rows.max())


def test_red_box_and_floor_marking_land_where_k_and_tf_project_them(scene_sim):
    env, tmp = scene_sim
    got = camera_probe(env, tmp / "scene.npz", seconds=1.0)
    picture = np.load(tmp / "scene.npz")["image"].astype(int)   # BGR, from cv_bridge
    b, g, r = picture[:, :, 0], picture[:, :, 1], picture[:, :, 2]
    pose, k = _camera_pose(got), got["info"]["K"]
    red = _span((r > g + 40) & (r > b + 40))
    want = _pixels(_corners(RED_BOX["centre"], RED_BOX["size"], RED_BOX["yaw"]), pose, k)
    assert np.abs(np.subtract(red, want)).max() <= 2, (red, want)
    blue = _span((b > r + 40) & (b > g + 40))
    top = _corners(MARKING["centre"], MARKING["size"])[1::2]
    want = _pixels(top, pose, k)
    assert np.abs(np.subtract(blue, want)).max() <= 2, (blue, want)


def test_every_robot_with_a_camera_has_it_in_its_namespace_and_a_burger_has_none(scene_sim):
    env, tmp = scene_sim
    got = camera_probe(env, tmp / "tb3_2.npz", seconds=0.5, ns="/tb3_2")
    assert got["count"] >= 10 and got["image"]["frame"] == "tb3_2/camera_rgb_optical_frame"
    assert got["info"]["frame"] == "tb3_2/camera_rgb_optical_frame"
    picture = np.load(tmp / "tb3_2.npz")["image"]
    assert picture.shape == (480, 640, 3)
    topics = got["topics"]
    assert {"/camera/rgb/image_raw", "/camera/rgb/camera_info", "/camera/rgb/image_raw/compressed",
            "/tb3_2/camera/rgb/image_raw"} <= set(topics)
    assert not [t for t in topics if t.startswith("/tb3_1/camera")] and "/tb3_1/scan" in topics


def test_without_opengl_a_camera_robot_is_one_line_and_a_burger_runs(tmp_path):
    need_ros()
    env = dict(ros_env(tmp_path), __EGL_VENDOR_LIBRARY_FILENAMES=str(tmp_path / "no_such_vendor.json"))
    probe = subprocess.run([sys.executable, "-c", "from worldgen.sim.camera import open_context; open_context()"],
                           env=env, capture_output=True, text=True)
    if probe.returncode == 0:
        pytest.skip("this EGL does not read __EGL_VENDOR_LIBRARY_FILENAMES: no way to take OpenGL away here")
    proc = worldgen(["sim", str(ROOM), "--robot", "waffle_pi", "--duration", "1"], env)
    _, err = proc.communicate(timeout=60)
    lines = err.strip().splitlines()
    assert proc.returncode == 2 and len(lines) == 1, err
    assert lines[0].startswith("worldgen: error: no OpenGL context for the simulated camera")
    assert "sudo apt-get install libegl1 libegl-mesa0 libgl1-mesa-dri" in lines[0] and "--robot burger" in lines[0]
    proc = worldgen(["sim", str(ROOM), "--duration", "1", "--rate", "max"], env)
    _, err = proc.communicate(timeout=60)
    assert proc.returncode == 0, err
    no_leftovers(env)


def test_a_student_line_follower_keeps_what_its_camera_sees_on_the_tape(tmp_path):
    """The class's line-following lab end to end: the student's HSV-mask node (tests/rosnodes/
    line_follower_student.py) on examples/line_track.yaml steers by every picture; the floor point its camera
    looks at (0.30 m ahead, where the bottom image row meets the floor) stays on the tape, round the first bend."""
    import csv

    import shapely
    import yaml

    need_camera()
    spec = yaml.safe_load((REPO / "examples" / "line_track.yaml").read_text())
    points = spec["lines"][0]["points"]
    tape = shapely.LineString(points + points[:1])
    out = tmp_path / "follow.csv"
    proc = worldgen(["run", str(REPO / "examples" / "line_track.yaml"), str(NODES / "line_follower_student.py"),
                     "--rate", "2", "--duration", "15", "--csv", str(out)], ros_env(tmp_path))
    _, err = proc.communicate(timeout=180)
    assert out.is_file(), err
    rows = [(float(r["x"]), float(r["y"]), float(r["yaw"])) for r in csv.DictReader(out.open())]
    ahead = np.array([tape.distance(shapely.Point(x + 0.30 * math.cos(yaw), y + 0.30 * math.sin(yaw)))
                      for x, y, yaw in rows])
    assert len(rows) >= 15 * 30 and (ahead <= 0.05).mean() > 0.95 and np.median(ahead) < 0.03
    x, y, _ = rows[-1]
    assert x > 1.0 and y > -0.6   # past the first bend, heading up the right side
