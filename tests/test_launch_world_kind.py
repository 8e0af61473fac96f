"""``worldgen launch`` checks that its WORLD is for the simulator the target starts: Jazzy's Gazebo Sim needs a
world naming the systems a TurtleBot3 uses (a Gazebo Classic world there has no sensors), and Gazebo Classic
(Noetic, Humble) cannot load a Gazebo Sim world's systems."""

from __future__ import annotations

from pathlib import Path

import pytest
from conftest import CliRunner
from lxml import etree

from worldgen.cli import main
from worldgen.launch.targets import gz_sim_systems

ROOM = Path(__file__).resolve().parent.parent / "examples" / "enclosed_room.yaml"


@pytest.fixture(scope="module")
def worlds(tmp_path_factory):
    out = tmp_path_factory.mktemp("worlds")
    runner = CliRunner()
    for ros, folder in (("noetic", "classic"), ("jazzy", "gz")):
        done = runner.invoke(main, ["build", str(ROOM), "--ros", ros, "-o", str(out / folder)])
        assert done.exit_code == 0, done.output
    gz = (out / "gz" / "enclosed_room.sdf").read_text()
    root = etree.fromstring(gz.encode())
    world = root.find("world")
    for plugin in world.findall("plugin"):
        if "sensors" in plugin.get("filename"):
            world.remove(plugin)
    (out / "gz" / "no_sensors.sdf").write_bytes(etree.tostring(root))
    return out


def launch(worlds: Path, world: str, ros: str, tmp_path: Path):
    return CliRunner().invoke(main, ["launch", str(worlds / world), "--ros", ros, "--package", "lab", "-o",
                                     str(tmp_path / "out")])


@pytest.mark.parametrize("world, ros", [("classic/enclosed_room.world", "noetic"),
                                        ("classic/enclosed_room.world", "humble"),
                                        ("gz/enclosed_room.sdf", "jazzy")])
def test_a_world_for_its_simulator_is_launched(worlds, tmp_path, world, ros):
    done = launch(worlds, world, ros, tmp_path)
    assert done.exit_code == 0, done.output


@pytest.mark.parametrize("world, ros, words", [
    ("classic/enclosed_room.world", "jazzy", "is a Gazebo Classic world"),
    ("gz/enclosed_room.sdf", "humble", "is a Gazebo Sim world"),
    ("gz/enclosed_room.sdf", "noetic", "starts Gazebo Classic"),
    ("gz/no_sensors.sdf", "jazzy", "without the sensors system"),
])
def test_a_world_for_the_other_simulator_is_refused(worlds, tmp_path, world, ros, words):
    done = launch(worlds, world, ros, tmp_path)
    assert done.exit_code == 2
    (line,) = done.stderr.splitlines()
    assert words in line and "--ros jazzy" in line
    assert not (tmp_path / "out").exists()


def test_systems_are_known_by_library_or_class_of_any_release():
    world = etree.fromstring(
        "<world><plugin filename='libignition-gazebo6-sensors-system.so' name='x'/>"
        "<plugin filename='whatever' name='gz::sim::systems::UserCommands'/>"
        "<plugin filename='gz-sim8-physics-system' name='p'/>"
        "<plugin filename='libgazebo_ros_state.so' name='gazebo_ros_state'/></world>")
    assert gz_sim_systems(world) == {"sensors", "usercommands", "physics"}
