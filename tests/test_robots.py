"""Our TurtleBot3 descriptions match the reference numbers (mass, wheel separation, LiDAR height), in the URDF and
once loaded in pybullet; xacro's $(find) resolves through ROS_PACKAGE_PATH; bad input is an InputError."""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET

import pytest

from worldgen.core.errors import InputError
from worldgen.robots import absolute_mesh_paths, find_package, robot_urdf
from worldgen.robots.profile import link_frames, robot_profile

# Reference (turtlebot3_description, noetic): URDF mass sum, wheel centre separation, base_scan above the floor,
# the diff-drive plugin's separation, and the link/joint counts.
REFERENCE = {
    "burger": {"mass": 1.0017, "separation": 0.160, "lidar_z": 0.182, "plugin_sep": 0.160, "links": 7, "joints": 6},
    "waffle": {"mass": 1.5539, "separation": 0.288, "lidar_z": 0.132, "plugin_sep": 0.287, "links": 13, "joints": 12},
    "waffle_pi": {"mass": 1.5539, "separation": 0.288, "lidar_z": 0.132, "plugin_sep": 0.287, "links": 11,
                  "joints": 10},
}
MODELS = sorted(REFERENCE)


def close(value: float, expected: float, rel: float = 0.02) -> bool:
    return abs(value - expected) <= rel * abs(expected)


@pytest.fixture(scope="module", params=MODELS)
def described(request):
    urdf = robot_urdf(request.param)
    return request.param, urdf, ET.fromstring(urdf), robot_profile(urdf)


def test_urdf_structure_and_numbers(described):
    model, _, root, profile = described
    ref = REFERENCE[model]
    assert root.get("name") == f"turtlebot3_{model}"
    assert (len(root.findall("link")), len(root.findall("joint"))) == (ref["links"], ref["joints"])
    mass = sum(float(link.find("inertial/mass").get("value")) for link in root.findall("link"))
    assert close(mass, ref["mass"]), mass
    frames = link_frames(profile.joints, profile.root_link)
    left, right = frames["wheel_left_link"][0], frames["wheel_right_link"][0]
    assert close(math.dist(left, right), ref["separation"])
    assert left[2] == pytest.approx(0.033, abs=1e-9) and right[2] == pytest.approx(0.033, abs=1e-9)
    assert close(frames["base_scan"][0][2], ref["lidar_z"])
    assert frames["imu_link"][0][2] == pytest.approx(0.078, abs=1e-9)


def test_every_link_has_an_explicit_inertial(described):
    """pybullet gives a link without <inertial> 1 kg; frame links carry a tiny one instead."""
    _, _, root, _ = described
    for link in root.findall("link"):
        assert link.find("inertial/mass") is not None, link.get("name")
    frames = [link for link in root.findall("link") if link.find("collision") is None]
    assert frames and all(float(link.find("inertial/mass").get("value")) < 1e-4 for link in frames)


def test_no_meshes_and_primitive_collisions(described):
    _, urdf, root, _ = described
    assert "<mesh" not in urdf and "package://" not in urdf
    kinds = {g.tag for g in root.iter("geometry") for g in g}
    assert kinds <= {"box", "cylinder"}


def test_gazebo_blocks_give_the_plugin_and_sensor_numbers(described):
    model, _, _, profile = described
    drive, lidar = profile.drive, profile.lidar
    assert drive.from_plugin and (drive.left_joint, drive.right_joint) == ("wheel_left_joint", "wheel_right_joint")
    assert drive.wheel_separation == pytest.approx(REFERENCE[model]["plugin_sep"])
    assert drive.wheel_radius == pytest.approx(0.033)
    assert (drive.acceleration, drive.torque, drive.update_rate) == (1.0, 10.0, 30.0)
    assert lidar.from_sensor and lidar.link == "base_scan"
    assert (lidar.samples, lidar.range_min, lidar.range_max, lidar.resolution) == (360, 0.12, 3.5, 0.015)
    assert lidar.angle_increment == pytest.approx(6.28319 / 359)
    assert (lidar.noise_stddev, lidar.update_rate) == (0.01, 5.0)
    casters = [n for n in profile.links if n.startswith("caster")]
    assert len(casters) == (1 if model == "burger" else 2)
    for link in ["wheel_left_link", "wheel_right_link", *casters]:
        assert profile.friction[link] == 0.1
    assert profile.base_frame == profile.root_link == "base_footprint"


def test_waffle_camera_frames():
    frames = link_frames(robot_profile(robot_urdf("waffle")).joints, "base_link")
    assert frames["camera_rgb_frame"][0] == pytest.approx((0.069, -0.047, 0.107), abs=1e-9)
    assert frames["camera_depth_frame"][0] == pytest.approx((0.069, -0.037, 0.107), abs=1e-9)
    pi = link_frames(robot_profile(robot_urdf("waffle_pi")).joints, "base_link")
    assert pi["camera_rgb_frame"][0] == pytest.approx((0.076, 0.0, 0.093), abs=1e-9)
    assert "camera_depth_frame" not in pi


@pytest.mark.parametrize("model", MODELS)
def test_in_pybullet_mass_wheels_and_lidar_height(model):
    import pybullet as pb

    from worldgen.sim.behaviours import settle
    from worldgen.sim.session import Session

    ref = REFERENCE[model]
    with Session(None, model, (1.0, -2.0, 0.7)) as session:
        total = sum(pb.getDynamicsInfo(session.robot, i, physicsClientId=session.client)[0]
                    for i in session.link_name)
        assert close(total, ref["mass"])
        rest = settle(session, 0.5)
        assert rest.upright and abs(rest.z) < 0.003 and rest.drift < 0.002
        left = session.link_pose("wheel_left_link")[0]
        right = session.link_pose("wheel_right_link")[0]
        assert close(math.dist(left, right), ref["separation"])
        assert left[2] == pytest.approx(0.033, abs=0.002)
        assert close(session.link_pose("base_scan")[0][2], ref["lidar_z"])
        assert session.odometry().yaw == pytest.approx(0.7, abs=0.01)


def test_user_xacro_finds_its_package_through_ros_package_path(tmp_path, monkeypatch):
    pkg = tmp_path / "ws" / "src" / "mypkg"
    (pkg / "urdf").mkdir(parents=True)
    (pkg / "package.xml").write_text("<package format='2'><name>mypkg</name><version>0.0.1</version></package>")
    (pkg / "urdf" / "parts.xacro").write_text(
        "<robot xmlns:xacro='http://www.ros.org/wiki/xacro'>"
        "<xacro:macro name='block' params='name size'><link name='${name}'><inertial><mass value='2.5'/>"
        "<inertia ixx='0.01' ixy='0' ixz='0' iyy='0.01' iyz='0' izz='0.01'/></inertial>"
        "<collision><geometry><box size='${size} ${size} ${size}'/></geometry></collision></link></xacro:macro>"
        "</robot>")
    robot = tmp_path / "elsewhere" / "bot.urdf.xacro"
    robot.parent.mkdir()
    robot.write_text(
        "<robot name='bot' xmlns:xacro='http://www.ros.org/wiki/xacro'>"
        "<xacro:arg name='edge' default='0.1'/>"
        "<xacro:include filename='$(find mypkg)/urdf/parts.xacro'/>"
        "<xacro:block name='base' size='$(arg edge)'/></robot>")
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(tmp_path / "ws" / "src"))
    root = ET.fromstring(robot_urdf(robot, mappings={"edge": "0.25"}))
    assert root.find("link/collision/geometry/box").get("size") == "0.25 0.25 0.25"
    assert find_package("mypkg") == pkg
    assert find_package("worldgen_turtlebot3").name == "worldgen_turtlebot3"   # ours, always on the path
    import xacro.substitution_args as sa
    assert sa._eval_find.__module__ == "xacro.substitution_args"               # the patch is undone


def test_missing_package_says_where_it_looked(tmp_path, monkeypatch):
    robot = tmp_path / "bot.urdf.xacro"
    robot.write_text("<robot name='b' xmlns:xacro='http://www.ros.org/wiki/xacro'>"
                     "<xacro:include filename='$(find no_such_pkg)/x.xacro'/></robot>")
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(tmp_path))
    with pytest.raises(InputError) as err:
        robot_urdf(robot)
    assert "no_such_pkg" in str(err.value) and "ROS_PACKAGE_PATH" in str(err.value)
    assert str(robot) in str(err.value)


@pytest.mark.parametrize("robot, words", [("tank", "unknown robot"), ("/no/such/robot.urdf.xacro", "not found")])
def test_bad_robot_names(robot, words):
    with pytest.raises(InputError, match=words):
        robot_urdf(robot)


def test_broken_xacro_and_urdf(tmp_path):
    bad = tmp_path / "bad.urdf.xacro"
    bad.write_text("<robot name='b' xmlns:xacro='http://www.ros.org/wiki/xacro'><xacro:nope/></robot>")
    with pytest.raises(InputError, match="xacro failed"):
        robot_urdf(bad)
    broken = tmp_path / "broken.urdf"
    broken.write_text("<robot name='b'><link name='a'></robot>")
    with pytest.raises(InputError, match="cannot read"):
        robot_urdf(broken)
    itself = tmp_path / "itself.urdf.xacro"
    itself.write_text("<robot name='b' xmlns:xacro='http://www.ros.org/wiki/xacro'>"
                      "<xacro:include filename='itself.urdf.xacro'/></robot>")
    with pytest.raises(InputError, match="xacro recursed without end"):
        robot_urdf(itself)


def test_package_uris_become_absolute_paths(tmp_path, monkeypatch):
    (tmp_path / "desc").mkdir()
    (tmp_path / "desc" / "package.xml").write_text("<package><name>desc</name></package>")
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(tmp_path))
    text = absolute_mesh_paths('<mesh filename="package://desc/meshes/a.stl"/><mesh filename="file:///m/b.stl"/>')
    assert text == f'<mesh filename="{tmp_path}/desc/meshes/a.stl"/><mesh filename="/m/b.stl"/>'
    with pytest.raises(InputError, match="not on ROS_PACKAGE_PATH"):
        absolute_mesh_paths('<mesh filename="package://other/a.stl"/>')


def test_user_urdf_with_package_meshes_loads_in_pybullet(tmp_path, monkeypatch):
    """A description like the real turtlebot3_description: package:// meshes (a collision mesh that exists, a
    visual mesh that does not — visuals are not loaded), wheels found by joint name, no Gazebo blocks."""
    import trimesh

    from worldgen.sim.session import Session

    pkg = tmp_path / "my_description"
    (pkg / "meshes").mkdir(parents=True)
    (pkg / "package.xml").write_text("<package format='2'><name>my_description</name></package>")
    trimesh.creation.box((0.2, 0.2, 0.1)).export(pkg / "meshes" / "body.stl")
    inertial = ("<inertial><mass value='{m}'/><inertia ixx='1e-3' ixy='0' ixz='0' iyy='1e-3' iyz='0' izz='1e-3'/>"
                "</inertial>")
    wheel = ("<joint name='wheel_{s}_joint' type='continuous'><parent link='base'/><child link='wheel_{s}'/>"
             "<origin xyz='0 {y} 0.05' rpy='-1.5708 0 0'/><axis xyz='0 0 1'/></joint>"
             "<link name='wheel_{s}'><collision><geometry><cylinder radius='0.05' length='0.02'/></geometry>"
             "</collision>" + inertial.format(m=0.05) + "</link>")
    urdf = tmp_path / "robot.urdf"
    urdf.write_text(
        "<robot name='mybot'><link name='footprint'/><joint name='fix' type='fixed'><parent link='footprint'/>"
        "<child link='base'/></joint><link name='base'>"
        "<visual><geometry><mesh filename='package://my_description/meshes/missing.dae'/></geometry></visual>"
        "<collision><origin xyz='0 0 0.1'/><geometry><mesh filename='package://my_description/meshes/body.stl'/>"
        "</geometry></collision>" + inertial.format(m=1.5) + "</link>"
        + wheel.format(s="left", y=0.13) + wheel.format(s="right", y=-0.13) + "</robot>")
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(tmp_path))
    with Session(None, urdf) as session:
        import pybullet as pb
        masses = [pb.getDynamicsInfo(session.robot, i, physicsClientId=session.client)[0] for i in session.link_name]
        assert sum(masses) == pytest.approx(1.6, abs=1e-4)   # the frame link without <inertial> adds nothing
        drive = session.profile.drive
        assert not drive.from_plugin
        assert drive.wheel_separation == pytest.approx(0.26) and drive.wheel_radius == pytest.approx(0.05)
        assert session.lidar is None
        session.run(0.3)
        assert session.odometry().z == pytest.approx(0.0, abs=0.01)   # on its wheels, not fallen through
        session.cmd_vel(0.2)
        session.run(1.0)
        assert session.odometry().x > 0.1
