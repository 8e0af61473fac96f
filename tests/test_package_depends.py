"""A world built or a launch file written into a package gives its package.xml the exec_depends that launch file
needs (a package scaffolded without --world has none of Gazebo's): added on lines of their own after its last
dependency, the rest of the file as it was, all or nothing with the other files written."""

from __future__ import annotations

import pytest
from conftest import REPO, CliRunner

from worldgen.cli import main
from worldgen.core.errors import OutputExistsError
from worldgen.core.fsio import write_files
from worldgen.packages.world_files import launch_depends, launch_depends_update

SPEC = REPO / "examples" / "enclosed_room.yaml"
FORMAT_1 = """<?xml version="1.0"?>
<package>
  <name>old_lab</name>
  <version>0.1.0</version>
  <description>an old lab</description>
  <maintainer email="ta@example.com">TA</maintainer>
  <license>BSD</license>
  <buildtool_depend>catkin</buildtool_depend>
  <build_depend>rospy</build_depend>   <!-- kept as it is -->
  <run_depend>rospy</run_depend>
  <run_depend>xacro</run_depend>
</package>
"""


def cli(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def test_a_format_1_package_gets_run_depends_and_keeps_every_other_byte(tmp_path):
    pkg = tmp_path / "old_lab"
    pkg.mkdir()
    (pkg / "package.xml").write_text(FORMAT_1)
    [(path, text)] = launch_depends_update(pkg, "noetic").items()
    added = [line for line in text.splitlines() if line not in FORMAT_1.splitlines()]
    assert added == ["  <run_depend>gazebo_ros</run_depend>", "  <run_depend>turtlebot3_description</run_depend>"]
    assert [line for line in text.splitlines() if line not in added] == FORMAT_1.splitlines()
    assert text.index("<run_depend>xacro") < text.index("<run_depend>gazebo_ros")   # after its last dependency


@pytest.mark.parametrize("ros", ["noetic", "humble", "jazzy"])
def test_build_into_a_bare_scaffold_adds_them_once(tmp_path, ros):
    assert cli("scaffold", "lab", "rospy" if ros == "noetic" else "rclpy", "--ros", ros, "-p", tmp_path).exit_code == 0
    pkg = tmp_path / "lab"
    done = cli("build", SPEC, "--ros", ros, "--package", pkg)
    assert done.exit_code == 0, done.output
    [said] = [line for line in done.stdout.splitlines() if line.startswith("updated")]
    assert said == f"updated {pkg / 'package.xml'}: exec_depend {', '.join(launch_depends(ros))} (what its launch " \
                   "file starts)"
    assert launch_depends_update(pkg, ros) == {}
    again = cli("build", SPEC, "--ros", ros, "--package", pkg, "--force")
    assert again.exit_code == 0 and "updated" not in again.stdout   # nothing missing: package.xml left alone


def test_a_refused_build_leaves_package_xml_as_it_was(tmp_path):
    assert cli("scaffold", "lab", "rospy", "-p", tmp_path).exit_code == 0
    pkg = tmp_path / "lab"
    (pkg / "worlds").mkdir(exist_ok=True)
    (pkg / "worlds" / "enclosed_room.world").write_text("mine")   # the world build would write: refused
    before = (pkg / "package.xml").read_bytes()
    done = cli("build", SPEC, "--package", pkg)
    assert done.exit_code == 2 and (pkg / "package.xml").read_bytes() == before
    assert (pkg / "worlds" / "enclosed_room.world").read_text() == "mine"


def test_write_files_updates_in_place_and_refuses_the_rest(tmp_path):
    kept, new = tmp_path / "package.xml", tmp_path / "launch" / "a.launch"
    kept.write_text("old")
    assert write_files({new: "launch", kept: "new"}, update={kept}) == [new, kept]
    assert kept.read_text() == "new" and new.read_text() == "launch"
    with pytest.raises(OutputExistsError):   # the launch file exists now: nothing written, the update neither
        write_files({new: "again", kept: "newer"}, update={kept})
    assert kept.read_text() == "new" and new.read_text() == "launch"
