"""worldgen reads what it writes without noise: every file ``new``, ``generate``, ``build``, ``launch``,
``scaffold`` and ``course`` write, for all three stacks, passes ``validate`` with no warning or info about the
files themselves — also a world built (``build --package``) or a launch file written (``launch``) into a package
scaffolded without ``--world``, whose package.xml is given the launch file's exec_depends. What validate may still say: a ROS package the files use that this machine lacks (the
machine's, not the files'), and figures: the camera's measure of the tape, the share of LiDAR beams a big room's
far corners leave out of range (measures, not faults)."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest
from conftest import CliRunner

from worldgen.cli import main

STACKS = ("noetic", "humble", "jazzy")
MISSING_PACKAGE = re.compile(r"package '(gazebo_ros|turtlebot3_\w+|ros_gz_\w+|xacro|robot_state_publisher)' not "
                             r"found")
FIGURES = re.compile(r"^the Waffle Pi's camera can see \d+ floor marking|^\d+ of \d+ beams see nothing within "
                     r"[\d.]+ m and read inf: only the farthest parts of the room")


def invoke(*argv: str, codes=(0,)) -> str:
    done = CliRunner().invoke(main, list(argv))
    assert done.exit_code in codes, f"{argv}: {done.output}"
    return done.stdout


@pytest.fixture(scope="module")
def written(tmp_path_factory) -> list:
    """Every kind of file worldgen writes, in one folder: the paths to validate."""
    out = tmp_path_factory.mktemp("self")
    specs = out / "specs"
    invoke("new", "room", "-o", str(specs / "room.yaml"))
    invoke("new", "track", "--template", "line-track", "-o", str(specs / "track.yaml"))
    for kind in ("arena", "clutter", "maze", "rooms", "track"):
        invoke("generate", kind, "--seed", "1", "-o", str(specs / "generated"))
    targets = sorted(specs.rglob("*.yaml"))
    for ros in STACKS:
        for spec in (specs / "room.yaml", specs / "track.yaml"):
            extra = () if ros == "jazzy" else ("--model-dir",)
            invoke("build", str(spec), "--ros", ros, "-o", str(out / f"built_{ros}"), *extra)
        invoke("course", "--ros", ros, "--workspace", str(out / f"course_{ros}"))
        invoke("scaffold", f"lab_{ros}", "rospy" if ros == "noetic" else "rclpy", "--ros", ros, "-p",
               str(out / f"packages_{ros}"), "--world", str(specs / "track.yaml"))
        package = out / f"packages_{ros}" / f"lab_{ros}"
        world = package / "worlds" / ("track.sdf" if ros == "jazzy" else "track.world")
        invoke("launch", str(world), "--ros", ros, "--name", "again")
        # packages scaffolded without --world: a world built into one, a world given a launch file in another
        bare = out / f"bare_{ros}"
        for name in ("built", "launched"):
            invoke("scaffold", f"{name}_{ros}", "rospy" if ros == "noetic" else "rclpy", "--ros", ros, "-p", str(bare))
        invoke("build", str(specs / "track.yaml"), "--ros", ros, "--package", str(bare / f"built_{ros}"))
        (bare / f"launched_{ros}" / "worlds").mkdir(exist_ok=True)
        copy = bare / f"launched_{ros}" / "worlds" / world.name
        copy.write_bytes(world.read_bytes())
        invoke("launch", str(copy), "--ros", ros, "--node", "lab_nodes/driver")
        targets += sorted((out / f"built_{ros}").glob("*.*"))
        targets += [out / f"course_{ros}", out / f"packages_{ros}", bare]
    if (out / "built_noetic" / "room" / "model.sdf").is_file():
        targets.append(out / "built_noetic" / "room")
    return targets


def fault(finding: dict) -> bool:
    """Whether a finding is about the files (not the machine's missing packages, not a figure)."""
    message = finding["message"]
    return not (MISSING_PACKAGE.search(message) or FIGURES.search(message))


def test_everything_worldgen_writes_validates_without_a_word(written):
    doc = json.loads(invoke("validate", "--skip-sim", "--format", "json", *map(str, written), codes=(0, 1)))
    assert len(doc["results"]) >= len(written)
    said = [(r["path"], f["severity"], f["check"], f["message"]) for r in doc["results"] for f in r["findings"]
            if fault(f)]
    assert said == []
    assert [r["path"] for r in doc["results"] if not r["ok"]] == []


def test_worldgen_specs_and_worlds_pass_the_simulator_too(written):
    worlds = [p for p in written if p.suffix == ".world" and "built_noetic" in str(p)]
    doc = json.loads(invoke("validate", "--format", "json", *map(str, worlds), codes=(0, 1)))
    said = [(r["path"], f["message"]) for r in doc["results"] for f in r["findings"] if fault(f)]
    assert said == [] and all(r["ok"] for r in doc["results"])
