"""ros_gz_sim's ``gz_args`` holds gz sim's options and the world in one string (``['-r -s -v2 ', world]``): the
world read from it is the world alone, whether its package is found or not."""

from __future__ import annotations

from pathlib import Path

import pytest

from worldgen.launch.reader import read_launch

LAUNCH = """import os
from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import IncludeLaunchDescription
from launch.launch_description_sources import PythonLaunchDescriptionSource


def generate_launch_description():
    world = os.path.join(get_package_share_directory('{package}'), 'worlds', 'room.sdf')
    ros_gz_sim = get_package_share_directory('ros_gz_sim')
    return LaunchDescription([
        IncludeLaunchDescription(
            PythonLaunchDescriptionSource(os.path.join(ros_gz_sim, 'launch', 'gz_sim.launch.py')),
            launch_arguments={{'gz_args': {gz_args}, 'on_exit_shutdown': 'true'}}.items()),
    ])
"""


@pytest.mark.parametrize("gz_args", ["['-r -s -v2 ', world]", "'-r -s -v 4 ' + world", "['-s', ' ', world, ' -v2']",
                                     "world"])
def test_the_world_apart_from_the_flags_when_its_package_is_not_found(tmp_path, gz_args):
    launch = tmp_path / "sim.launch.py"
    launch.write_text(LAUNCH.format(package="nowhere_pkg", gz_args=gz_args))
    info = read_launch(launch, ros_package_path=[], environ={})
    assert info.world_ref == "‹nowhere_pkg›/worlds/room.sdf"
    assert info.package == "nowhere_pkg" and info.world_path is None
    assert [f.message for f in info.findings] == ["gz_sim.launch.py's gz_args: package 'nowhere_pkg' not found"]


def test_the_world_apart_from_the_flags_when_its_package_is_found(tmp_path):
    package = tmp_path / "src" / "lab"
    (package / "worlds").mkdir(parents=True)
    (package / "package.xml").write_text("<package format='3'><name>lab</name><version>0.0.1</version>"
                                         "<description>d</description><maintainer email='a@b.c'>a</maintainer>"
                                         "<license>BSD</license></package>\n")
    (package / "worlds" / "room.sdf").write_text("<sdf version='1.8'><world name='w'/></sdf>\n")
    launch = package / "sim.launch.py"
    launch.write_text(LAUNCH.format(package="lab", gz_args="['-r -s -v2 ', world]"))
    info = read_launch(launch, ros_package_path=[str(tmp_path / "src")], environ={})
    assert Path(info.world_path).resolve() == (package / "worlds" / "room.sdf").resolve()
    assert info.package == "lab"
