"""libsdformat's own check passes on what we write, for every SDF version we offer, and on every example.

The library is optional at run time; these tests skip without it, except under CI (env CI set), where a missing
library fails the run instead of silently skipping the check."""

from __future__ import annotations

import math
import os
from pathlib import Path

import pytest

from worldgen.geometry.building import build_geometry
from worldgen.sdf.writer import SDF_VERSIONS, model_sdf, world_sdf
from worldgen.check.sdformat import Message, messages, sdf_path, sdformat_check
from worldgen.spec.model import Material, Obstacle, Opening, Room, Segment, Spec, WallStyle

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


@pytest.fixture(scope="module")
def check():
    """sdformat_check, once the library is known to be there."""
    probe = Path(__file__).resolve().parent / "conftest.py"   # any file: only "is the library there" matters
    if sdformat_check(probe) is None:
        if os.environ.get("CI"):
            pytest.fail("libsdformat (libsdformat12.so.12) is missing under CI: install libsdformat-dev")
        pytest.skip("libsdformat is not installed")
    return sdformat_check


def everything_spec() -> Spec:
    """Rooms sharing walls, a sharp corner (fillers), doors, a window, a segment, obstacles, an RGBA material."""
    green = WallStyle(material=Material(script=None, rgba=(0.2, 0.6, 0.2, 1)))
    return Spec("everything", rooms=(
        Room("a", ((0, 0), (4, 0), (4, 3), (0, 3)), WallStyle(),
             (Opening("door", 1, 1.0, 0.9, 2.0), Opening("window", 2, 1.0, 0.8, 0.8, 0.5))),
        Room("b", ((4, 0), (7, 0), (7, 3), (4, 3)), WallStyle()),
        Room("wedge", ((0, 5), (5, 5), (5 * math.cos(math.pi / 6), 5 + 5 * math.sin(math.pi / 6))), green)),
        segments=(Segment((1, 1), (2, 2), WallStyle(height=1.0)),),
        obstacles=(Obstacle("box", (5, 1), 0.3, (0.4, 0.4, 0.5), name="crate"),
                   Obstacle("cylinder", (6, 2), radius=0.2, height=0.5), Obstacle("sphere", (1, 2.5), radius=0.2)))


@pytest.mark.parametrize("version", SDF_VERSIONS)
def test_every_version_passes_libsdformat(check, version, tmp_path):
    building = build_geometry(everything_spec())
    assert any(w.filler for w in building.walls)
    for name, text in (("w.world", world_sdf(building, version)), ("model.sdf", model_sdf(building, version))):
        path = tmp_path / name
        path.write_text(text)
        valid, messages = check(path)
        assert valid, messages


def test_broken_file_is_reported(check, tmp_path):
    path = tmp_path / "bad.world"
    path.write_text('<sdf version="1.6"><world name="default"><model name="m"><link name="l"><collision name="c">'
                    "<geometry><box><size>1 1</size></box></geometry></collision></link></model></world></sdf>")
    valid, messages = check(path)
    assert not valid and "size" in messages and "\x1b[" not in messages


@pytest.mark.skipif(not list(EXAMPLES.glob("*.yaml")), reason="no examples/ in this checkout")
def test_examples_build_into_valid_worlds(check, tmp_path):
    from worldgen.spec.load import load_spec

    for spec_path in sorted(EXAMPLES.glob("*.yaml")):
        path = tmp_path / f"{spec_path.stem}.world"
        path.write_text(world_sdf(build_geometry(load_spec(spec_path))))
        valid, messages = check(path)
        assert valid, f"{spec_path.name}: {messages}"


def test_missing_library_means_none(monkeypatch, tmp_path):
    import worldgen.check.sdformat as sdfcheck

    monkeypatch.setattr(sdfcheck, "_CHILD", sdfcheck._CHILD.replace("libsdformat", "libno_such_sdformat"))
    path = tmp_path / "w.world"
    path.write_text("<sdf version='1.6'/>")
    assert sdfcheck.sdformat_check(path) is None


def test_stand_ins_for_gazebo_stock_models(check, tmp_path, monkeypatch):
    monkeypatch.delenv("GAZEBO_MODEL_PATH", raising=False)
    monkeypatch.delenv("SDF_PATH", raising=False)
    path = tmp_path / "stock.world"
    path.write_text("<sdf version='1.6'><world name='default'><include><uri>model://ground_plane</uri></include>"
                    "<include><uri>model://sun</uri></include></world></sdf>")
    valid, said = check(path, stubs=False)
    assert not valid and "Unable to find uri[model://ground_plane]" in said and "model://sun" in said
    assert check(path) == (True, "Valid.")


def test_sdf_path_puts_the_stand_ins_last(tmp_path):
    env = {"GAZEBO_MODEL_PATH": "/g1:/g2", "SDF_PATH": "/s1"}
    assert sdf_path([tmp_path], Path("/stubs"), env=env) == f"{tmp_path}:/g1:/g2:/s1:/stubs"
    assert sdf_path((), None, env={}) == ""


# What libsdformat 12 printed for a box of two numbers (abridged; a colon put in the world name, as a quoted
# name may hold one).
ARITY = """Error [Param.cc:399] Unknown error. Unable to set value [1 2 ] for key[size]
Error:   Could not find the 'robot' element in the xml file
         at line 109 in ./urdf_parser/src/model.cpp
Error Code 9: [/sdf/world[@name="w:1"]/model[@name="m"]/link[@name="l"]/collision[@name="c"]/geometry/box/size:\
/tmp/a.world:L6]: Msg: Error reading element <size>
Error Code 9: [/sdf/world[@name="w:1"]/model[@name="m"]/link[@name="l"]/collision[@name="c"]/geometry/box:\
/tmp/a.world:L6]: Msg: Error reading element <box>
Error Code 9: [/sdf/world[@name="w:1"]/model[@name="m"]:/tmp/a.world:L4]: Msg: Error reading element <model>
Error Code 9: [/sdf/world[@name="w:1"]:/tmp/a.world:L3]: Msg: Error reading element <world>
Error Code 9: Msg: Error reading element <sdf>
Error Code 1: Msg: Unable to read file:/tmp/a.world"""

DUPLICATE = """Warning [Model.cc:174] Non-unique name[l] detected 2 times in XML children of model with name[m].
Error Code 2: Msg: link with name[l] already exists.
Error Code 9: Msg: Failed to load a world."""

SHARED = """Error: Non-unique names detected in <link name='l'>
  <collision name='c'>
  </collision>
  <visual name='c'>
  </visual>
</link>"""


def test_messages_keep_the_cause_where_the_cascade_starts():
    assert messages(ARITY) == [Message("error", "Unknown error. Unable to set value [1 2 ] for key[size]",
                                       "/tmp/a.world", 6,
                                       "world[w:1]/model[m]/link[l]/collision[c]/geometry/box/size")]
    assert messages(ARITY)[0].where == "/tmp/a.world:6 (world[w:1]/model[m]/link[l]/collision[c]/geometry/box/size)"


def test_messages_place_a_duplicate_name_by_the_warning_about_it():
    assert messages(DUPLICATE) == [Message("error", "link with name[l] already exists.", element="model m")]


def test_messages_drop_an_xml_dump_and_keep_a_lone_generic_error():
    assert messages(SHARED) == [Message("error", "Non-unique names detected in <link name='l'>")]
    assert messages("Error Code 9: Msg: Failed to load a world.") == [
        Message("error", "Failed to load a world.")]
    assert messages("Valid.") == []
