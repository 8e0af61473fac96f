"""The README's `worldgen sim` / `worldgen run` section: its grading line over a class's ``submissions/`` folder runs
as written, in a folder holding the examples and a made submissions folder, with a fresh HOME and a free master port.
The section's other lines run in tests/test_readme.py with every ```sh block of the README (which leaves out only
the lines over ``submissions/``, a folder no reader has)."""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from xml.etree import ElementTree

from bridgetools import NODES, REPO, need_ros
from rosstubs import free_port

README = (REPO / "README.md").read_text(encoding="utf-8")
SECTION = README.split("## Running your own nodes without Gazebo", 1)[1].split("\n## ", 1)[0]
BLOCKS = re.findall(r"```sh\n(.*?)```", SECTION, flags=re.S)


def test_the_section_has_the_workflow_and_the_grading_command():
    text = "\n".join(BLOCKS)
    assert "worldgen sim " in text and "worldgen run submissions/ --task stop-at-wall -j 2 --junit grades.xml" in text


def test_the_grading_line_runs_as_written(tmp_path):
    need_ros()
    work, home, bin_dir = tmp_path / "work", tmp_path / "home", tmp_path / "bin"
    for folder in (work, home, bin_dir):
        folder.mkdir()
    shutil.copytree(REPO / "examples", work / "examples")
    for name, node in (("ada", "stop_at_wall_numpy.py"), ("bob", "drive_into_wall.py")):
        scripts = work / "submissions" / name / "scripts"
        scripts.mkdir(parents=True)
        (work / "submissions" / name / "package.xml").write_text(
            f"<package format='2'><name>{name}</name><version>0.0.0</version><description>d</description>"
            "<maintainer email='a@example.com'>a</maintainer><license>BSD</license></package>")
        shutil.copy(NODES / node, scripts / "stop_at_wall.py")
    (bin_dir / "worldgen").write_text(f'#!/bin/sh\nexec "{sys.executable}" -m worldgen "$@"\n')
    (bin_dir / "worldgen").chmod(0o755)
    env = {k: v for k, v in os.environ.items() if not k.startswith("ROS_") and k != "PWD"}
    env.update(HOME=str(home), PATH=f"{bin_dir}{os.pathsep}{env['PATH']}", PYTHONPATH=str(REPO),
               ROS_MASTER_URI=f"http://127.0.0.1:{free_port()}", ROS_HOME=str(home / ".ros"), MPLBACKEND="Agg")
    lines = [ln for block in BLOCKS for ln in block.splitlines() if "submissions/" in ln]
    assert lines
    for line in lines:   # ada's node stops at the wall, bob's drives into it: exit 1
        line = line.replace("stop-at-wall", "stop-at-wall --rate max")
        proc = subprocess.run(["bash", "-c", line], cwd=work, env=env, capture_output=True, text=True, timeout=300)
        assert proc.returncode == 1, (line, proc.stderr[-3000:], proc.stdout[-2000:])
        assert "Traceback" not in proc.stderr
    cases = {(case.get("classname"), case.get("name")): [child.tag for child in case]
             for case in ElementTree.parse(work / "grades.xml").iter("testcase")}
    assert cases == {("submissions/ada", "node"): [], ("submissions/ada", "stop-at-wall"): [],
                     ("submissions/bob", "node"): [], ("submissions/bob", "stop-at-wall"): ["failure"]}, cases
