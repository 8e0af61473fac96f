"""The reader's visuals: what a camera sees of a world, each visual in the world frame with its colour, from any
world (ours, or one saved by Gazebo), and no noise about markings lying on the floor."""

from __future__ import annotations

import math

import pytest

from worldgen.core.materials import STOCK_COLORS, color_name, script_color
from worldgen.sdf.reader import read_world, read_world_text
from worldgen.spec.model import GAZEBO_MATERIALS

SCRIPT = "<script><uri>file://media/materials/scripts/gazebo.material</uri><name>{}</name></script>"


def visual(name, material="", size="1 0.5 0.2", pose="0 0 0.1 0 0 0", geometry=None):
    geometry = geometry or f"<box><size>{size}</size></box>"
    return (f"<visual name='{name}'><pose>{pose}</pose><geometry>{geometry}</geometry>"
            + (f"<material>{material}</material>" if material else "") + "</visual>")


def model(name, body, pose="0 0 0 0 0 0", collision=True):
    hit = "<collision name='c'><geometry><box><size>1 1 1</size></box></geometry></collision>" if collision else ""
    return f"<model name='{name}'><static>1</static><pose>{pose}</pose><link name='l'>{hit}{body}</link></model>"


def world(body, state=""):
    return f"<sdf version='1.6'><world name='default'>{body}{state}</world></sdf>"


def test_colours_come_from_diffuse_then_script_then_ambient():
    text = world(model("m", "".join([
        visual("diffuse", "<ambient>0 0 1 1</ambient><diffuse>1 0 0 1</diffuse>"),
        visual("ambient", "<ambient>0 0.5 0 1</ambient>"),
        visual("script", SCRIPT.format("Gazebo/Yellow")),
        visual("editor", SCRIPT.format("Gazebo/Wood") + "<ambient>1 1 1 1</ambient>"),   # as the Building Editor saves
        visual("own_script", SCRIPT.format("MyLab/Tape")),
        visual("none"),
        visual("rgb", "<diffuse>0.2 0.4 0.6</diffuse>"),
        visual("see_through", "<diffuse>1 1 1 1</diffuse>").replace("<pose>",
                                                                   "<transparency>0.25</transparency><pose>"),
    ])))
    colours = {v.name: v.color for v in read_world_text(text).visuals}
    assert colours == {"diffuse": (1.0, 0.0, 0.0, 1.0), "ambient": (0.0, 0.5, 0.0, 1.0),
                       "script": (1.0, 1.0, 0.0, 1.0), "editor": STOCK_COLORS["Gazebo/Wood"],
                       "own_script": None, "none": None, "rgb": (0.2, 0.4, 0.6, 1.0),
                       "see_through": (1.0, 1.0, 1.0, 0.75)}


def test_visuals_are_placed_in_the_world_and_moved_by_state():
    body = visual("v", SCRIPT.format("Gazebo/Red"), pose="1 0 0.1 0 0 0")
    state = ("<state world_name='default'><model name='m'><pose>5 5 0 0 0 1.5707963</pose>"
             "<link name='l'><pose>5 5 0 0 0 1.5707963</pose></link></model></state>")
    moved = read_world_text(world(model("m", body, pose="2 0 0 0 0 0"), state))
    (v,) = moved.visuals
    assert v.position == pytest.approx((5.0, 6.0, 0.1), abs=1e-6)   # the link turned 90°: +x becomes +y
    assert v.label == "m/l/v" and v.kind == "box" and v.size == (1.0, 0.5, 0.2) and v.color == (1, 0, 0, 1)
    (c,) = moved.shapes
    assert c.position == pytest.approx((5.0, 5.0, 0.0), abs=1e-6)
    still = read_world_text(world(model("m", body, pose="2 0 0 0 0 0"), state), apply_state=False)
    assert still.visuals[0].position == pytest.approx((3.0, 0.0, 0.1))


def test_nested_included_and_ground_plane_visuals(tmp_path):
    folder = tmp_path / "crate"
    folder.mkdir()
    (folder / "model.config").write_text("<model><name>crate</name><sdf version='1.6'>model.sdf</sdf></model>")
    (folder / "model.sdf").write_text("<sdf version='1.6'>" + model("crate", visual("v", SCRIPT.format(
        "Gazebo/Green"), pose="0 0 0.5 0 0 0")) + "</sdf>")
    text = world("<include><uri>model://ground_plane</uri></include>"
                 "<include><uri>model://crate</uri><pose>1 2 0 0 0 0</pose></include>"
                 "<model name='outer'><pose>0 0 1 0 0 0</pose>"
                 + model("inner", visual("v", "<diffuse>0 0 1 1</diffuse>")) + "</model>")
    scene = read_world_text(text, source=tmp_path / "w.world", model_paths=[tmp_path])
    by_label = {v.label: v for v in scene.visuals}
    ground = by_label["ground_plane/link/visual"]
    assert ground.kind == "plane" and ground.size == (100.0, 100.0, 0.0) and ground.color == STOCK_COLORS["Gazebo/Grey"]
    assert by_label["crate/l/v"].position == pytest.approx((1.0, 2.0, 0.5))
    assert by_label["crate/l/v"].color == (0.0, 1.0, 0.0, 1.0)
    assert by_label["outer::inner/l/v"].position == pytest.approx((0.0, 0.0, 1.1))


def test_a_plane_keeps_its_visual_size_and_unread_kinds_stay_skipped():
    text = world(model("floor", visual("p", SCRIPT.format("Gazebo/White"),
                                       geometry="<plane><normal>0 0 1</normal><size>8 6</size></plane>")
                       + visual("h", geometry="<heightmap><uri>file://x.png</uri></heightmap>")
                       + visual("e", geometry="<empty/>")))
    scene = read_world_text(text)
    assert [(v.name, v.kind, v.size) for v in scene.visuals] == [("p", "plane", (8.0, 6.0, 0.0))]
    assert not [f for f in scene.findings if "heightmap" in f.message]   # a visual's odd kind is no obstacle


def test_a_missing_visual_mesh_is_one_info_and_a_shared_one_is_the_collisions_warning(tmp_path):
    mesh = "<mesh><uri>model://nowhere/m.dae</uri></mesh>"
    only_visual = read_world_text(world(model("m", visual("v", geometry=mesh))), source=tmp_path / "w.world")
    (note,) = [f for f in only_visual.findings if f.check == "mesh"]
    assert note.severity == "info" and "1 visual skipped" in note.message and "camera" in note.message
    both = read_world_text(world(
        "<model name='m'><static>1</static><link name='l'><collision name='c'><geometry>" + mesh +
        "</geometry></collision>" + visual("v", geometry=mesh) + "</link></model>"), source=tmp_path / "w.world")
    (warning,) = [f for f in both.findings if f.check == "mesh"]
    assert warning.severity == "warning" and "1 collision skipped" in warning.message


def test_a_marking_on_the_floor_makes_no_noise_but_a_tall_or_floating_visual_does():
    tape = visual("tape", SCRIPT.format("Gazebo/Yellow"), size="2 0.05 0.001", pose="0 0 0.0005 0 0 0")
    disc = visual("dot", "<diffuse>1 0 0 1</diffuse>", pose="1 0 0.0005 0 0 0",
                  geometry="<cylinder><radius>0.1</radius><length>0.001</length></cylinder>")
    wall = visual("wall", size="4 0.15 2.5", pose="0 0 1.25 0 0 0")
    shelf = visual("shelf", size="1 0.3 0.02", pose="0 0 1 0 0 0")
    scene = read_world_text(world(model("marks", tape + disc, collision=False) + model("ghost", wall, collision=False)
                                  + model("shelf", shelf, collision=False)))
    notes = {f.message.split()[1]: f.severity for f in scene.findings if f.check == "collision"}
    assert notes == {"ghost/l": "warning", "shelf/l": "info"}
    assert [v.name for v in scene.visuals] == ["tape", "dot", "wall", "shelf"]


def test_corpus_walls_are_seen_in_their_colours(corpus):
    scene = read_world(corpus / "worlds" / ("Intro-Robotics-UChicago-Spring-2022__warmup_project__worlds_"
                                            "turtlebot3_in_enclosed_room.world"))
    walls = [v for v in scene.visuals if v.model == "5m_room"]
    assert len(walls) == 4 and all(v.color == STOCK_COLORS["Gazebo/Grey"] for v in walls)
    # each wall's visual stands where its collision does (the <state> moved both)
    for v, c in zip(walls, [s for s in scene.shapes if s.model == "5m_room"]):
        assert v.position == pytest.approx(c.position) and v.size == c.size
    studio = read_world(corpus / "models" / "imkishan96__Build_my_world__Project_1_model_studio_model.sdf")
    colours = {color_name(v.color) for v in studio.visuals}
    assert {"Gazebo/Grey"} <= colours and STOCK_COLORS["Gazebo/Wood"] in {v.color for v in studio.visuals}


def test_the_material_table_is_the_specs_did_you_mean_list():
    assert GAZEBO_MATERIALS == tuple(STOCK_COLORS)
    assert script_color("Gazebo/Yellow") == (1.0, 1.0, 0.0, 1.0) and script_color("MyLab/Tape") is None
    assert all(len(c) == 4 and all(0 <= x <= 1 for x in c) for c in STOCK_COLORS.values())
    assert color_name((1.0, 1.0, 0.0, 1.0)) == "Gazebo/Yellow"
    assert color_name((0.2, 0.3, 0.9, 1)) == "rgb(0.2, 0.3, 0.9)"
    assert math.isclose(STOCK_COLORS["Gazebo/Orange"][1], 0.5088)


def test_a_mesh_that_cannot_load_is_said_once(tmp_path):
    (tmp_path / "bad.stl").write_bytes(b"\0" * 10)
    mesh = "<mesh><uri>bad.stl</uri></mesh>"
    text = world("<model name='m'><static>1</static><link name='l'><collision name='c'><geometry>" + mesh +
                 "</geometry></collision>" + visual("v", geometry=mesh) + "</link></model>"
                 + model("n", visual("w", geometry=mesh), collision=False))
    notes = [f for f in read_world_text(text, source=tmp_path / "w.world").findings if f.check == "mesh"]
    assert [f.severity for f in notes] == ["warning"] and "bad.stl" in notes[0].message
