"""xacro's output kept on disk (worldgen.robots.cache): the same text as processing, reused by the next process
without importing xacro, and made again when anything it was made from changes (an included file, an
environment variable it read, the mappings); a cache folder that cannot be written changes nothing."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

from worldgen.robots import robot_urdf
from worldgen.robots.description import _process_xacro, robot_file

REPO = Path(__file__).resolve().parent.parent

ROBOT = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="$(optenv LAB_ROBOT_NAME labbot)">
  <xacro:include filename="parts.xacro"/>
  <xacro:arg name="width" default="0.1"/>
  <link name="base_link"><collision><geometry><box size="$(arg width) 0.1 0.1"/></geometry></collision></link>
  <xacro:wheel name="left"/>
</robot>
"""
PARTS = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="wheel" params="name">
    <link name="wheel_${name}_link"><collision><geometry><cylinder radius="RADIUS" length="0.02"/></geometry>
    </collision></link>
  </xacro:macro>
</robot>
"""


def write_robot(folder: Path, radius: str = "0.033") -> Path:
    (folder / "parts.xacro").write_text(PARTS.replace("RADIUS", radius))
    path = folder / "labbot.urdf.xacro"
    path.write_text(ROBOT)
    return path


def entries(cache: Path) -> list[Path]:
    return sorted((cache / "robots").glob("*.json"))


def test_a_kept_description_is_the_processed_one_and_the_next_process_skips_xacro(tmp_path):
    env = dict(os.environ, WORLDGEN_CACHE=str(tmp_path / "cache"), PYTHONPATH=str(REPO))
    code = ("import sys; from worldgen.robots import robot_urdf; text = robot_urdf('waffle_pi'); "
            "print(len(text), 'xacro' in sys.modules)")
    first = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env)
    second = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env)
    length = len(_process_xacro(robot_file("waffle_pi"), {}))
    assert first.stdout.split() == [str(length), "True"], first.stderr
    assert second.stdout.split() == [str(length), "False"], second.stderr   # read back, xacro never imported
    assert len(entries(tmp_path / "cache")) == 1


def test_a_change_to_what_it_was_made_from_makes_it_again(tmp_path, monkeypatch):
    monkeypatch.setenv("WORLDGEN_CACHE", str(tmp_path / "cache"))
    monkeypatch.delenv("LAB_ROBOT_NAME", raising=False)
    path = write_robot(tmp_path)
    first = robot_urdf(path)
    assert 'name="labbot"' in first and 'radius="0.033"' in first
    assert robot_urdf(path) == first and len(entries(tmp_path / "cache")) == 1
    write_robot(tmp_path, radius="0.05")        # an included file changed (size too: mtime alone may not)
    assert 'radius="0.05"' in robot_urdf(path)
    monkeypatch.setenv("LAB_ROBOT_NAME", "other")   # an environment variable it read
    assert 'name="other"' in robot_urdf(path)
    assert 'size="0.3 0.1 0.1"' in robot_urdf(path, {"width": "0.3"})   # other mappings: an entry of their own
    assert robot_urdf(path) == _process_xacro(path, {})
    assert len(entries(tmp_path / "cache")) == 2


def test_a_cache_folder_that_cannot_be_written_changes_nothing(tmp_path, monkeypatch):
    blocked = tmp_path / "file"
    blocked.write_text("not a folder")
    monkeypatch.setenv("WORLDGEN_CACHE", str(blocked / "cache"))
    path = write_robot(tmp_path)
    assert robot_urdf(path) == _process_xacro(path, {})


def test_a_damaged_entry_is_made_again(tmp_path, monkeypatch):
    monkeypatch.setenv("WORLDGEN_CACHE", str(tmp_path / "cache"))
    path = write_robot(tmp_path)
    text = robot_urdf(path)
    [entry] = entries(tmp_path / "cache")
    entry.write_text('{"format": 1, "files": {}, "env": {}, "packages": {}, "urdf"')
    assert robot_urdf(path) == text
