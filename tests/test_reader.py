"""The world reader on small inline SDF: poses, state, includes, meshes, booleans, sizes and broken files.

Every expected number here was worked out by hand from the SDF text in the test (comments show the arithmetic).
"""

from __future__ import annotations

import math
import os
from pathlib import Path

import numpy as np
import pytest

from worldgen.core.errors import WorldFileError
from worldgen.core import poses
from worldgen.sdf.reader import read_world, read_world_text


@pytest.fixture(autouse=True)
def _no_model_path(monkeypatch):
    """Tests start with no model path from the environment (a developer's GAZEBO_MODEL_PATH must not leak in)."""
    for name in ("GAZEBO_MODEL_PATH", "SDF_PATH", "ROS_PACKAGE_PATH"):
        monkeypatch.delenv(name, raising=False)


def world(body: str, version: str = "1.6") -> str:
    return f"<?xml version='1.0'?>\n<sdf version='{version}'>\n<world name='default'>\n{body}\n</world>\n</sdf>\n"


def box_model(name: str, pose: str = "0 0 0 0 0 0", size: str = "1 1 1", static: str = "1", extra: str = "") -> str:
    return (f"<model name='{name}'><static>{static}</static><pose>{pose}</pose>"
            f"<link name='link'><collision name='c'><geometry><box><size>{size}</size></box></geometry></collision>"
            f"</link>{extra}</model>")


def checks(scene, severity: str | None = None) -> list[str]:
    return [f.check for f in scene.findings if severity is None or f.severity == severity]


def rotation(shape) -> np.ndarray:
    return poses.quat_matrix(*shape.orientation)


# -- poses -------------------------------------------------------------------------------------------------------

def test_nested_model_link_and_collision_poses_compose_with_rotations():
    text = world("""
      <model name='A'><static>1</static><pose>1 2 0 0 0 1.5707963267948966</pose>
        <model name='B'><pose>1 0 0 0 0 0</pose>
          <link name='L'><pose>0 1 0 0 0 0</pose>
            <collision name='c'><pose>0.5 0 0.25 0 0 1.5707963267948966</pose>
              <geometry><box><size>1 2 3</size></box></geometry></collision></link></model></model>""")
    (shape,) = read_world_text(text).shapes
    # A turns 90°: B's (1, 0) → (0, 1) → world (1, 3); L's (0, 1) in B → (-1, 0) → (0, 3);
    # the collision's (0.5, 0) → (0, 0.5) → (0, 3.5); yaws add to 180°.
    assert shape.position == pytest.approx((0.0, 3.5, 0.25), abs=1e-9)
    assert shape.orientation == pytest.approx((0.0, 0.0, 1.0, 0.0), abs=1e-9)
    assert (shape.model, shape.link, shape.name) == ("A::B", "L", "c")
    assert shape.size == (1.0, 2.0, 3.0)


def test_roll_pitch_yaw_are_fixed_axes_like_sdf():
    text = world(box_model("m", pose="0 0 0 1.5707963267948966 0 1.5707963267948966"))
    r = rotation(read_world_text(text).shapes[0])
    # R = Rz(90°)·Rx(90°): local x → Rx keeps it → Rz turns it to +y; local y → Rx lifts it to +z → Rz keeps it.
    assert r @ [1, 0, 0] == pytest.approx([0, 1, 0], abs=1e-9)
    assert r @ [0, 1, 0] == pytest.approx([0, 0, 1], abs=1e-9)


def test_positive_pitch_tips_x_down():
    r = rotation(read_world_text(world(box_model("m", pose="0 0 0 0 1.5707963267948966 0"))).shapes[0])
    assert r @ [1, 0, 0] == pytest.approx([0, 0, -1], abs=1e-9)  # right-handed turn about +y


def test_pose_text_forms_minus_zero_scientific_frame_attribute_and_degrees():
    text = world(box_model("a", pose="-0 3e-01 1E+00 0 -0 0") +
                 "<model name='b'><static>1</static><pose frame=''>2 0 0 0 0 0</pose><link name='l'>"
                 "<collision name='c'><pose degrees='true'>0 0 0 0 0 90</pose><geometry><sphere><radius>0.5</radius>"
                 "</sphere></geometry></collision></link></model>", version="1.9")
    a, b = read_world_text(text).shapes
    assert a.position == pytest.approx((0.0, 0.3, 1.0))
    assert b.position == pytest.approx((2.0, 0.0, 0.0))
    assert rotation(b) @ [1, 0, 0] == pytest.approx([0, 1, 0], abs=1e-9)


def test_relative_to_sibling_link_frame_and_joint():
    text = world("""
      <model name='m'><static>1</static><pose>10 0 0 0 0 0</pose>
        <frame name='corner'><pose>1 1 0 0 0 1.5707963267948966</pose></frame>
        <link name='base'><pose relative_to='corner'>2 0 0 0 0 0</pose>
          <collision name='c'><geometry><box><size>1 1 1</size></box></geometry></collision></link>
        <joint name='j' type='fixed'><pose relative_to='base'>0 0 1 0 0 0</pose>
          <parent>base</parent><child>top</child></joint>
        <link name='top'><pose relative_to='j'>0 0 0 0 0 0</pose>
          <collision name='c'><geometry><box><size>1 1 1</size></box></geometry></collision></link>
      </model>""", version="1.7")
    base, top = read_world_text(text).shapes
    # corner at (1, 1) turned 90°; base 2 m along corner's x = +y → (1, 3) in the model → (11, 3) in the world.
    assert base.position == pytest.approx((11.0, 3.0, 0.0))
    # top sits at joint j, 1 m above base.
    assert top.position == pytest.approx((11.0, 3.0, 1.0))


def test_unknown_relative_to_warns_and_falls_back_to_the_parent():
    text = world("<model name='m'><static>1</static><pose>5 0 0 0 0 0</pose><link name='l'>"
                 "<pose relative_to='nowhere'>1 0 0 0 0 0</pose><collision name='c'><geometry><box><size>1 1 1</size>"
                 "</box></geometry></collision></link></model>", version="1.7")
    scene = read_world_text(text)
    assert scene.shapes[0].position == pytest.approx((6.0, 0.0, 0.0))
    (finding,) = [f for f in scene.findings if f.check == "pose"]
    assert finding.severity == "warning" and "nowhere" in finding.message and finding.where == "<string>:4"


def test_models_and_links_sharing_a_name_each_keep_their_own_pose():
    # Gazebo loads both copies where each one's <pose> puts it; the reader warns about the names but must not
    # stack the second copy on the first.
    text = world(box_model("twin", pose="1 0 0 0 0 0") + box_model("twin", pose="5 0 0 0 0 0")
                 + "<model name='m'><static>1</static>"
                 + "".join(f"<link name='L'><pose>0 {y} 0 0 0 0</pose><collision name='c'><geometry><box/></geometry>"
                           "</collision></link>" for y in (2, 7)) + "</model>")
    scene = read_world_text(text)
    assert [s.position for s in scene.shapes] == [(1.0, 0.0, 0.0), (5.0, 0.0, 0.0), (0.0, 2.0, 0.0), (0.0, 7.0, 0.0)]
    assert sorted(f.check for f in scene.findings) == ["names", "names"]


# -- state -------------------------------------------------------------------------------------------------------

STATE_WORLD = world("""
  <model name='room one'><static>1</static><pose>0 0 0 0 0 0</pose>
    <link name='a'><pose>1 0 0 0 0 0</pose><collision name='c'><pose>0 0 0.5 0 0 0</pose>
      <geometry><box><size>1 1 1</size></box></geometry></collision></link>
    <link name='b'><pose>0 2 0 0 0 0</pose><collision name='c'>
      <geometry><box><size>1 1 1</size></box></geometry></collision></link></model>
  <state world_name='default'>
    <sim_time>1 0</sim_time>
    <model name='room one'><pose>10 0 0 0 0 0</pose><scale>1 1 1</scale>
      <link name='a'><pose>3 4 0 0 0 0</pose><velocity>0 0 0 0 0 0</velocity></link></model>
    <model name='ghost'><pose>1 1 1 0 0 0</pose></model>
    <light name='sun'><pose>0 0 10 0 0 0</pose></light>
  </state>
  <state world_name='default'><model name='room one'><pose>-50 0 0 0 0 0</pose></model></state>""")


def test_first_state_overrides_model_pose_and_its_link_poses_are_world_frame():
    scene = read_world_text(STATE_WORLD)
    a, b = scene.shapes
    assert a.position == pytest.approx((3.0, 4.0, 0.5))   # the state link pose as is, not 10 + 3
    assert b.position == pytest.approx((10.0, 2.0, 0.0))  # no state link pose: follows the state model pose
    assert any(f.check == "state" and "ghost" in f.message and f.severity == "info" for f in scene.findings)
    assert any(f.check == "state" and "first" in f.message for f in scene.findings)


def test_state_can_be_ignored():
    a, b = read_world_text(STATE_WORLD, apply_state=False).shapes
    assert a.position == pytest.approx((1.0, 0.0, 0.5))
    assert b.position == pytest.approx((0.0, 2.0, 0.0))


def test_state_moves_nested_models_in_the_world_frame():
    text = world("""
      <model name='outer'><static>1</static><pose>1 0 0 0 0 0</pose>
        <model name='inner'><pose>1 0 0 0 0 0</pose><link name='l'><collision name='c'>
          <geometry><box><size>1 1 1</size></box></geometry></collision></link></model></model>
      <state world_name='default'><model name='outer'><pose>0 5 0 0 0 0</pose>
        <model name='inner'><pose>7 7 0 0 0 0</pose></model></model></state>""")
    assert read_world_text(text).shapes[0].position == pytest.approx((7.0, 7.0, 0.0))


# -- includes ----------------------------------------------------------------------------------------------------

def make_model(folder: Path, name: str, body: str, *, configs=(("1.6", "model.sdf"),), version="1.6") -> Path:
    """A model folder: model.config naming ``configs`` and the SDF files (the first gets ``body``)."""
    model_dir = folder / name
    model_dir.mkdir(parents=True)
    entries = "".join(f"<sdf version='{v}'>{f}</sdf>" for v, f in configs)
    (model_dir / "model.config").write_text(f"<?xml version='1.0'?><model><name>{name}</name>{entries}</model>")
    for _, file_name in configs:
        (model_dir / file_name).write_text(f"<sdf version='{version}'>{body}</sdf>")
    return model_dir


def test_include_found_on_gazebo_model_path_with_name_pose_and_static_overrides(tmp_path, monkeypatch):
    make_model(tmp_path / "models", "crate", box_model("crate", pose="0 0 0.5 0 0 0", static="0"))
    monkeypatch.setenv("GAZEBO_MODEL_PATH", f"/nonexistent{os.pathsep}{tmp_path / 'models'}")
    text = world("<include><uri>model://crate</uri><name>crate_1</name><pose>4 0 0 0 0 0</pose>"
                 "<static>true</static></include><include><uri>model://crate</uri><name>crate_2</name></include>")
    scene = read_world_text(text)
    one, two = scene.shapes
    assert (one.model, one.position, one.static) == ("crate_1", pytest.approx((4.0, 0.0, 0.0)), True)
    # No include pose: the model's own <pose> stands; no include <static>: the model's own 0.
    assert (two.model, two.position, two.static) == ("crate_2", pytest.approx((0.0, 0.0, 0.5)), False)
    assert scene.models == ["crate_1", "crate_2"]
    assert "include" not in checks(scene)


def test_model_config_picks_the_highest_sdf_version(tmp_path):
    folder = make_model(tmp_path, "tall", box_model("tall", size="1 1 1"),
                        configs=(("1.4", "old.sdf"), ("1.6", "new.sdf")))
    (folder / "new.sdf").write_text(f"<sdf version='1.6'>{box_model('tall', size='1 1 9')}</sdf>")
    scene = read_world_text(world("<include><uri>model://tall</uri></include>"), model_paths=[tmp_path])
    assert scene.shapes[0].size == (1.0, 1.0, 9.0)


def test_explicit_model_paths_come_before_the_environment(tmp_path, monkeypatch):
    make_model(tmp_path / "env", "crate", box_model("crate", size="1 1 1"))
    make_model(tmp_path / "cli", "crate", box_model("crate", size="2 2 2"))
    monkeypatch.setenv("GAZEBO_MODEL_PATH", str(tmp_path / "env"))
    scene = read_world_text(world("<include><uri>model://crate</uri></include>"), model_paths=[tmp_path / "cli"])
    assert scene.shapes[0].size == (2.0, 2.0, 2.0)


def test_include_in_a_model_wrapper_composes_with_the_wrapper_pose_and_static(tmp_path):
    make_model(tmp_path, "house", box_model("house", pose="1 0 0 0 0 0", static="0"))
    text = world("<model name='wrapper'><static>1</static><pose>0 10 0 0 0 1.5707963267948966</pose>"
                 "<include><uri>model://house</uri></include></model>", version="1.8")
    (shape,) = read_world_text(text, model_paths=[tmp_path]).shapes
    # the house's own (1, 0) turned 90° by the wrapper → (0, 1) → (0, 11); the wrapper's static wins.
    assert shape.position == pytest.approx((0.0, 11.0, 0.0))
    assert (shape.model, shape.static) == ("wrapper::house", True)


def test_relative_to_a_frame_inside_an_included_model(tmp_path):
    make_model(tmp_path, "base", "<model name='base'><frame name='dock'><pose>2 0 0 0 0 0</pose></frame></model>")
    text = world("<include><uri>model://base</uri><pose>0 5 0 0 0 0</pose></include>"
                 + box_model("crate").replace("<pose>", "<pose relative_to='base::dock'>"), version="1.7")
    assert read_world_text(text, model_paths=[tmp_path]).shapes[0].position == pytest.approx((2.0, 5.0, 0.0))


def test_include_of_a_sub_model_an_absolute_model_uri_and_a_relative_path(tmp_path):
    make_model(tmp_path / "models" / "arena", "inner", box_model("inner", pose="1 0 0 0 0 0"))
    make_model(tmp_path / "elsewhere", "post", box_model("post", pose="2 0 0 0 0 0"))
    make_model(tmp_path / "worlds" / "local", "gate", box_model("gate", pose="3 0 0 0 0 0"))
    text = world(f"<include><uri>model://arena/inner</uri></include>"
                 f"<include><uri>model://{tmp_path / 'elsewhere' / 'post'}</uri></include>"
                 f"<include><uri>local/gate</uri></include>")
    source = tmp_path / "worlds" / "w.world"
    source.write_text(text)
    scene = read_world(source, model_paths=[tmp_path / "models"])
    assert [s.position[0] for s in scene.shapes] == pytest.approx([1.0, 2.0, 3.0])


def test_include_resolved_through_a_catkin_package_export(tmp_path, monkeypatch):
    package = tmp_path / "ws" / "src" / "class_worlds"
    make_model(package / "models", "pillar", box_model("pillar", size="0.2 0.2 1"))
    (package / "package.xml").write_text(
        "<package format='2'><name>class_worlds</name><export>"
        "<gazebo_ros gazebo_model_path='${prefix}/models'/></export></package>")
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(tmp_path / "ws" / "src"))
    scene = read_world_text(world("<include><uri>model://pillar</uri></include>"))
    assert scene.shapes[0].size == (0.2, 0.2, 1.0)


def test_unresolved_include_warns_with_the_uri_and_the_fix_and_adds_no_walls():
    scene = read_world_text(world("<include><uri>model://ground_plane</uri></include>"
                                  "<include><uri>model://sun</uri></include>"
                                  "<include><uri>model://willowgarage</uri></include>"
                                  "<include><uri>https://fuel.gazebosim.org/1.0/OpenRobotics/models/Sun</uri></include>"
                                  "<include><uri>https://fuel.gazebosim.org/1.0/x/models/Cafe</uri></include>"))
    assert [s.kind for s in scene.shapes] == ["plane"]  # the ground-plane stand-in, nothing else
    assert scene.models == ["ground_plane"]
    warnings = [f for f in scene.findings if f.severity == "warning"]
    assert len(warnings) == 2
    missing, online = warnings
    assert missing.check == "include" and "model://willowgarage" in missing.message
    assert "GAZEBO_MODEL_PATH" in missing.fix and "--model-path" in missing.fix
    assert missing.where == "<string>:4"
    assert online.check == "include" and "Cafe" in online.message and "never downloaded" in online.message


def test_stock_models_found_on_the_model_path_are_read_as_they_are(tmp_path):
    make_model(tmp_path, "sun", "<light name='sun' type='directional'><pose>0 0 10 0 0 0</pose></light>")
    make_model(tmp_path, "ground_plane", "<model name='ground_plane'><static>true</static><link name='link'>"
               "<collision name='collision'><geometry><plane><normal>0 0 1</normal><size>100 100</size></plane>"
               "</geometry></collision></link></model>")
    scene = read_world_text(world("<include><uri>model://sun</uri></include>"
                                  "<include><uri>model://ground_plane</uri></include>"), model_paths=[tmp_path])
    assert [s.kind for s in scene.shapes] == ["plane"] and scene.findings == []


def test_a_broken_included_model_is_an_error_finding_not_a_crash(tmp_path):
    folder = make_model(tmp_path, "broken", box_model("broken"))
    (folder / "model.sdf").write_text("<sdf version='1.6'>\n<model name='broken'>\n<link name='a<b'/></model></sdf>")
    scene = read_world_text(world("<include><uri>model://broken</uri></include>" + box_model("fine")),
                            model_paths=[tmp_path])
    assert [s.model for s in scene.shapes] == ["fine"]
    (error,) = [f for f in scene.findings if f.severity == "error"]
    assert error.check == "include" and "model.sdf:3" in error.message and "not well-formed" in error.message


@pytest.mark.parametrize("uri", ["https://fuel.gazebosim.org/1.0/OpenRobotics/models/Ground Plane",
                                 "https://fuel.gazebosim.org/1.0/OpenRobotics/models/Ground%20Plane/2/",
                                 "https://fuel.ignitionrobotics.org/1.0/openrobotics/models/ground plane/1"])
def test_fuel_ground_plane_is_stood_in_for(uri):
    scene = read_world_text(world(f"<include><uri>{uri}</uri><pose>0 0 -0.5 0 0 0</pose></include>", version="1.8"))
    assert [(s.kind, s.position) for s in scene.shapes] == [("plane", (0.0, 0.0, -0.5))]
    assert [(f.check, f.severity) for f in scene.findings] == [("include", "info")]


# -- meshes ------------------------------------------------------------------------------------------------------

@pytest.fixture()
def stl(tmp_path) -> Path:
    """A 1 × 2 × 3 m box mesh saved as STL in a folder whose name has a space."""
    import trimesh

    folder = tmp_path / "my meshes"
    folder.mkdir()
    path = folder / "block.stl"
    trimesh.creation.box(extents=(1.0, 2.0, 3.0)).export(path)
    return path


def mesh_model(name: str, uri: str, scale: str = "1 1 1", pose: str = "0 0 0 0 0 0") -> str:
    return (f"<model name='{name}'><static>1</static><link name='l'><collision name='c'><pose>{pose}</pose>"
            f"<geometry><mesh><uri>{uri}</uri><scale>{scale}</scale></mesh></geometry></collision></link></model>")


def test_meshes_load_from_absolute_file_and_model_uris_scaled_in_the_shape_frame(stl, tmp_path):
    text = world(mesh_model("abs", str(stl), scale="2 1 0.5", pose="5 0 0 0 0 0")
                 + mesh_model("file", f"file://{stl}", scale="2 1 0.5")
                 + mesh_model("model", "model://my meshes/block.stl"))
    scene = read_world_text(text, model_paths=[tmp_path])
    absolute, file_uri, model_uri = scene.shapes
    assert absolute.kind == "mesh" and absolute.position == pytest.approx((5.0, 0.0, 0.0))
    # extents 1 × 2 × 3 scaled by 2, 1, 0.5 → 2 × 2 × 1.5, still centred on the shape frame
    assert np.ptp(absolute.vertices, axis=0) == pytest.approx([2.0, 2.0, 1.5])
    assert np.ptp(model_uri.vertices, axis=0) == pytest.approx([1.0, 2.0, 3.0])
    assert absolute.faces.dtype.kind == "i" and absolute.faces.shape == (12, 3)
    assert file_uri.vertices is absolute.vertices  # same file and scale: loaded once
    assert "mesh" not in checks(scene)


def test_mesh_in_a_catkin_package_by_model_and_package_uris(stl, tmp_path, monkeypatch):
    package = tmp_path / "ws" / "src" / "q_learning_project"
    (package / "gazebo_custom_meshes").mkdir(parents=True)
    (package / "gazebo_custom_meshes" / "block.stl").write_bytes(stl.read_bytes())
    (package / "package.xml").write_text("<package format='2'><name>q_learning_project</name></package>")
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(tmp_path / "ws" / "src"))
    text = world(mesh_model("a", "model://q_learning_project/gazebo_custom_meshes/block.stl")
                 + mesh_model("b", "package://q_learning_project/gazebo_custom_meshes/block.stl"))
    scene = read_world_text(text)
    assert [s.kind for s in scene.shapes] == ["mesh", "mesh"] and scene.findings == []


def test_mesh_relative_to_the_model_folder(stl, tmp_path):
    source = stl.parent / "here.sdf"
    source.write_text(f"<sdf version='1.6'>{mesh_model('m', 'block.stl')}</sdf>")
    (shape,) = read_world(source).shapes
    assert np.ptp(shape.vertices, axis=0) == pytest.approx([1.0, 2.0, 3.0])


def test_collada_unit_is_applied(tmp_path):
    # one triangle, 100 units on a side, in inches (0.0254 m): Gazebo makes it 2.54 m.
    (tmp_path / "tri.dae").write_text("""<?xml version="1.0"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
 <asset><unit name="inch" meter="0.0254"/><up_axis>Z_UP</up_axis></asset>
 <library_geometries><geometry id="g"><mesh>
  <source id="p"><float_array id="pa" count="9">0 0 0 100 0 0 0 100 0</float_array>
   <technique_common><accessor source="#pa" count="3" stride="3">
    <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/></accessor>
   </technique_common></source>
  <vertices id="v"><input semantic="POSITION" source="#p"/></vertices>
  <triangles count="1"><input semantic="VERTEX" source="#v" offset="0"/><p>0 1 2</p></triangles>
 </mesh></geometry></library_geometries>
 <library_visual_scenes><visual_scene id="s"><node><instance_geometry url="#g"/></node></visual_scene>
 </library_visual_scenes><scene><instance_visual_scene url="#s"/></scene>
</COLLADA>""")
    text = world(mesh_model("m", str(tmp_path / "tri.dae"), scale="0.5 0.5 0.5"))
    (shape,) = read_world_text(text).shapes
    assert shape.vertices.max(axis=0) == pytest.approx([1.27, 1.27, 0.0])  # 100 × 0.0254 × 0.5


def test_missing_mesh_warns_once_per_uri_and_skips_the_shapes():
    text = world(mesh_model("a", "model://nowhere/meshes/wall.dae") + mesh_model("b", "model://nowhere/meshes/wall.dae")
                 + mesh_model("c", "/home/someone/my stuff/wall.stl") + box_model("d"))
    scene = read_world_text(text)
    assert [s.model for s in scene.shapes] == ["d"]
    missing = [f for f in scene.findings if f.check == "mesh"]
    assert len(missing) == 2 and all(f.severity == "warning" for f in missing)
    assert "2 collisions skipped" in missing[0].message and "GAZEBO_MODEL_PATH" in missing[0].fix
    assert "/home/someone/my stuff/wall.stl" in missing[1].message and "author's machine" in missing[1].fix


# -- values, names and checks --------------------------------------------------------------------------------------

@pytest.mark.parametrize("text, expected", [("1", True), ("0", False), ("true", True), ("false", False),
                                            (" true ", True), ("\n  0\n", False), ("TRUE", True)])
def test_static_booleans(text, expected):
    scene = read_world_text(world(box_model("m", static=text)))
    assert scene.shapes[0].static is expected
    assert ("static" in checks(scene)) is (not expected)  # the "robot could push it" note


def test_a_bad_boolean_is_a_warning_and_the_default():
    scene = read_world_text(world(box_model("m", static="yes")))
    assert scene.shapes[0].static is False
    assert any(f.check == "structure" and "'yes'" in f.message for f in scene.findings)


def test_non_positive_sizes_are_errors_naming_the_link():
    text = world(box_model("flat", size="1e-05 1.2e-05 0") + "<model name='c'><static>1</static><link name='post'>"
                 "<collision name='c'><geometry><cylinder><radius>-0.1</radius><length>1</length></cylinder>"
                 "</geometry></collision></link></model>" + box_model("ok"))
    scene = read_world_text(text)
    assert [s.model for s in scene.shapes] == ["ok"]
    errors = [f for f in scene.findings if f.severity == "error"]
    assert [f.check for f in errors] == ["sizes", "sizes"]
    assert "flat/link/c" in errors[0].message and "c/post/c" in errors[1].message


def test_shape_kinds_and_default_sizes():
    text = world("<model name='m'><static>1</static><link name='l'>"
                 "<collision name='s'><geometry><sphere><radius>0.25</radius></sphere></geometry></collision>"
                 "<collision name='y'><geometry><cylinder><radius>0.1</radius><length>0.4</length></cylinder>"
                 "</geometry></collision><collision name='b'><geometry><box/></geometry></collision>"
                 "<collision name='p'><geometry><plane><normal>0 0 2</normal><size>9 9</size></plane></geometry>"
                 "</collision><collision name='h'><geometry><heightmap><uri>x.png</uri></heightmap></geometry>"
                 "</collision></link></model>")
    scene = read_world_text(text)
    sphere, cylinder, box, plane = scene.shapes
    assert (sphere.kind, sphere.radius) == ("sphere", 0.25)
    assert (cylinder.kind, cylinder.radius, cylinder.length) == ("cylinder", 0.1, 0.4)
    assert (box.kind, box.size) == ("box", (1.0, 1.0, 1.0))  # SDF's default box
    assert (plane.kind, plane.normal) == ("plane", (0.0, 0.0, 1.0))
    assert scene.obstacles() == [sphere, cylinder, box]
    assert any(f.check == "geometry" and "heightmap" in f.message for f in scene.findings)


def test_duplicate_model_names_visual_only_links_and_population():
    text = world(box_model("twin") + box_model("twin") +
                 "<model name='ghost'><static>1</static><link name='Wall_1'><visual name='v'><geometry><box>"
                 "<size>4 0.15 2.5</size></box></geometry></visual></link></model>"
                 "<population name='p'><model name='d'/><model_count>5</model_count></population>")
    scene = read_world_text(text)
    names = [f for f in scene.findings if f.check == "names"]
    assert len(names) == 1 and "twin" in names[0].message and names[0].severity == "warning"
    (visual,) = [f for f in scene.findings if f.check == "collision"]
    assert visual.severity == "warning" and "ghost/Wall_1" in visual.message and "drive through" in visual.message
    assert any(f.check == "structure" and "population" in f.message and "5 copies" in f.message
               for f in scene.findings)


def test_gravity_inside_physics_is_reported_for_sdf_1_5_and_later_only():
    body = "<physics type='ode'><gravity>0 0 -9.81</gravity></physics>"
    new = read_world_text(world(body, version="1.5"))
    old = read_world_text(world(body, version="1.4"))
    assert [f.check for f in new.findings] == ["structure"] and "gravity" in new.findings[0].message
    assert old.findings == []


@pytest.mark.parametrize("version", ["1.4", "1.5", "1.6", "1.7", "1.8", "1.9", "1.10", "1.11"])
def test_known_sdf_versions_read_quietly(version):
    scene = read_world_text(world(box_model("m"), version=version))
    assert scene.sdf_version == version and scene.findings == [] and len(scene.shapes) == 1


def test_unknown_sdf_version_is_a_warning():
    scene = read_world_text(world(box_model("m"), version="2.3"))
    assert checks(scene) == ["sdf-version"] and len(scene.shapes) == 1


def test_a_pose_that_is_not_six_numbers_is_a_warning():
    scene = read_world_text(world(box_model("m", pose="1 2 three 0 0 0")))
    assert scene.shapes[0].position == (0.0, 0.0, 0.0)
    assert any(f.check == "structure" and "1 2 three" in f.message for f in scene.findings)


# -- file forms and broken files ----------------------------------------------------------------------------------

def test_messy_but_valid_files_read(tmp_path):
    text = ('\r\n<!-- Software License Agreement (BSD) <code@example.com> -->\r\n'
            '<sdf version="1.6">\r\n  <world name=\'default\'>  \r\n'
            + box_model("m", pose="1 0 0 0 0 0") + '\r\n  </world>\r\n</sdf>   ')
    path = tmp_path / "WORLD_WITHOUT_EXTENSION"
    path.write_bytes(text.encode())
    scene = read_world(path)
    assert scene.world_name == "default" and scene.shapes[0].position == pytest.approx((1.0, 0.0, 0.0))
    assert scene.source == path


def test_model_file_and_model_folder_roots(tmp_path):
    folder = make_model(tmp_path, "blocks", box_model("blocks", pose="2 0 0 0 0 0"))
    by_file = read_world(folder / "model.sdf")
    by_folder = read_world(folder)
    assert by_file.world_name is None and by_file.models == ["blocks"]
    assert by_folder.shapes[0].position == pytest.approx((2.0, 0.0, 0.0))


def test_malformed_xml_raises_with_the_line(tmp_path):
    path = tmp_path / "bad.world"
    path.write_text("<?xml version='1.0'?>\n<sdf version='1.6'>\n<world name='a<b'>\n</world>\n</sdf>\n")
    with pytest.raises(WorldFileError) as caught:
        read_world(path)
    err = caught.value
    assert err.line == 3 and err.path == str(path)
    assert str(err).startswith(f"{path}:3: not well-formed XML: Unescaped '<'")
    assert "fix the tag or attribute there" in str(err)


def test_unclosed_tag_line_counts_leading_blank_lines():
    with pytest.raises(WorldFileError) as caught:
        read_world_text("\n\n<sdf version='1.6'>\n<world name='w'>\n</sdf>\n")
    assert caught.value.line == 5 and "not well-formed" in caught.value.message


@pytest.mark.parametrize("text, words", [("", "empty"), ("not xml at all", "not well-formed"),
                                         ("<robot name='r'/>", "URDF"), ("<launch/>", "roslaunch"),
                                         ("<html/>", "<html>")])
def test_files_that_are_not_sdf_raise(text, words):
    with pytest.raises(WorldFileError, match=words):
        read_world_text(text)


def test_missing_file_raises(tmp_path):
    with pytest.raises(WorldFileError, match="no such file"):
        read_world(tmp_path / "nope.world")


def test_external_entities_are_never_loaded(tmp_path):
    secret = tmp_path / "secret.txt"
    secret.write_text("1")
    text = (f"<!DOCTYPE sdf [<!ENTITY x SYSTEM 'file://{secret}'>]><sdf version='1.6'><world name='w'>"
            "<model name='m'><static>&x;</static><link name='l'><collision name='c'><geometry><box/></geometry>"
            "</collision></link></model></world></sdf>")
    scene = read_world_text(text)
    assert scene.shapes[0].static is False  # "1" from the file would have made it static


def test_a_400_room_building_reads(tmp_path):
    """Scale sanity (timing lives in benchmarks/bench_reader.py): 1600 boxes in one model come out placed."""
    links = "".join(
        f"<link name='Wall_{i}'><pose>{(i // 4) * 5} {(i % 4) * 0.1} 0 0 0 {math.pi / 2 * (i % 2)}</pose>"
        f"<collision name='Wall_{i}_Collision'><pose>0 0 1.25 0 0 0</pose><geometry><box><size>5 0.15 2.5</size>"
        f"</box></geometry></collision></link>" for i in range(1600))
    scene = read_world_text(world(f"<model name='b'><static>1</static>{links}</model>"))
    assert len(scene.shapes) == 1600
    assert scene.shapes[-1].position == pytest.approx((399 * 5, 0.3, 1.25))
