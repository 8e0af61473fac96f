"""Gazebo Sim worlds (--ros jazzy): the writer's world with Harmonic's systems and colours, nothing else changed;
libsdformat accepts them, worldgen validate gives them the classic world's verdict."""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest
from conftest import EXAMPLES, CliRunner
from lxml import etree

from worldgen.check.sdformat import sdformat_check
from worldgen.cli import main
from worldgen.core.materials import STOCK_COLORS
from worldgen.geometry.building import build_geometry
from worldgen.sdf.gzsim import SYSTEMS, gzsim_world
from worldgen.sdf.writer import world_sdf
from worldgen.spec.load import load_spec

SPECS = sorted(p for p in EXAMPLES.glob("*.yaml"))


def classic_and_gz(spec: Path, version: str = "1.8") -> tuple[str, str]:
    building = build_geometry(load_spec(spec))
    classic = world_sdf(building, version)
    return classic, gzsim_world(classic, version)


def strip_gz(root):
    """The tree less what gzsim_world adds, for comparing with the classic world."""
    world = root.find("world")
    for plugin in world.findall("plugin"):
        world.remove(plugin)
    for material in world.iter("material"):
        for tag in ("ambient", "diffuse", "script"):
            for element in material.findall(tag):
                material.remove(element)
    return etree.tostring(root)


@pytest.mark.parametrize("spec", SPECS, ids=lambda p: p.stem)
def test_only_the_systems_and_colours_change(spec):
    classic, gz = classic_and_gz(spec)
    root = etree.fromstring(gz.encode())
    assert root.get("version") == "1.8"
    world = root.find("world")
    plugins = [(p.get("filename"), p.get("name")) for p in world.findall("plugin")]
    assert plugins == [(library, name) for library, name, _ in SYSTEMS]
    assert [p.tag for p in world][:5] == ["plugin"] * 5
    assert world.find("plugin[@name='gz::sim::systems::Sensors']/render_engine").text == "ogre2"
    assert not list(root.iter("include")) and "fuel" not in gz.lower()   # offline: nothing to download
    assert world.find("model[@name='ground_plane']") is not None and world.find("light[@name='sun']") is not None
    for material in root.iter("material"):   # stock scripts became their colours
        script = material.find("script")
        assert script is None or script.findtext("name") not in STOCK_COLORS
    classic_root = etree.fromstring(classic.encode())
    assert strip_gz(root) == strip_gz(classic_root)   # every wall, obstacle and pose as the writer wrote it
    assert gz == gzsim_world(classic)                 # byte-identical twice


def test_a_stock_material_becomes_its_colour():
    classic, gz = classic_and_gz(EXAMPLES / "enclosed_room.yaml")
    ground = etree.fromstring(gz.encode()).find("world/model[@name='ground_plane']/link/visual/material")
    grey = " ".join(f"{v:g}" for v in STOCK_COLORS["Gazebo/Grey"])
    assert [(e.tag, e.text) for e in ground] == [("ambient", grey), ("diffuse", grey)]


def test_refuses_what_is_not_a_writer_world():
    with pytest.raises(ValueError):
        gzsim_world('<?xml version="1.0"?>\n<sdf version="1.6"><model name="m"/></sdf>\n')
    with pytest.raises(ValueError):
        gzsim_world(classic_and_gz(EXAMPLES / "enclosed_room.yaml")[0], "1.6")


@pytest.fixture(scope="module")
def check():
    probe = Path(__file__).resolve().parent / "conftest.py"
    if sdformat_check(probe) is None:
        if os.environ.get("CI"):
            pytest.fail("libsdformat (libsdformat12.so.12) is missing under CI: install libsdformat-dev")
        pytest.skip("libsdformat is not installed")
    return sdformat_check


@pytest.mark.parametrize("version", ["1.8", "1.9"])
@pytest.mark.parametrize("spec", SPECS, ids=lambda p: p.stem)
def test_libsdformat_accepts_the_gz_world(check, spec, version, tmp_path):
    path = tmp_path / f"{spec.stem}.sdf"
    path.write_text(classic_and_gz(spec, version)[1])
    valid, messages = check(path)
    assert valid, messages


def test_build_writes_it_and_validate_gives_the_classic_verdict(tmp_path):
    runner = CliRunner()
    spec = EXAMPLES / "enclosed_room.yaml"
    for args in (["-o", str(tmp_path / "classic")], ["-o", str(tmp_path / "gz"), "--ros", "jazzy"]):
        result = runner.invoke(main, ["build", str(spec)] + args)
        assert result.exit_code == 0, result.output
    gz = tmp_path / "gz" / "enclosed_room.sdf"
    assert gz.read_text() == classic_and_gz(spec)[1]
    verdicts = []
    for world in (tmp_path / "classic" / "enclosed_room.world", gz):
        result = runner.invoke(main, ["validate", str(world), "--format", "json", "--sdformat"])
        (row,) = json.loads(result.stdout)["results"]
        verdicts.append((result.exit_code, row["ok"], row["checks"], row["spawn"],
                         [(f["check"], f["severity"]) for f in row["findings"]]))
    assert verdicts[0] == verdicts[1] and verdicts[0][:2] == (0, True)


@pytest.mark.parametrize("args, words", [
    (["--model-dir"], "model folder"),
    (["--sdf-version", "1.6"], "writes SDF 1.8 or 1.9"),
])
def test_build_refuses_for_jazzy(tmp_path, args, words):
    result = CliRunner().invoke(main, ["build", str(EXAMPLES / "enclosed_room.yaml"), "-o", str(tmp_path),
                                       "--ros", "jazzy"] + args)
    assert result.exit_code == 2 and words in result.output and not list(tmp_path.iterdir())
