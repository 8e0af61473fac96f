"""Messages that name what was checked: which Python could not import rospy, which PATH held no rosmaster."""

from __future__ import annotations

import pytest

from bridgetools import tag  # noqa: F401 (a fixture)

from worldgen.core.errors import InputError
from worldgen.ros1 import master, rosenv


def test_a_python_named_by_the_override_is_said(monkeypatch):
    monkeypatch.setenv(rosenv.ENV_PYTHON, "/bin/false")
    with pytest.raises(InputError) as caught:
        rosenv.node_python()
    assert "not importable by /bin/false, the Python WORLDGEN_ROS_PYTHON names" in str(caught.value)


def test_rosmaster_off_path_is_found_where_its_package_puts_it(monkeypatch, tmp_path):
    monkeypatch.setenv("PATH", str(tmp_path))
    place = tmp_path / "rosmaster"
    place.write_text("#!/bin/sh\n")
    place.chmod(0o755)
    monkeypatch.setattr(master, "ROSMASTER_PLACES", ("/nonexistent/rosmaster", str(place)))
    assert master.rosmaster_command() == str(place)
    monkeypatch.setattr(master, "ROSMASTER_PLACES", ("/nonexistent/rosmaster",))
    place.unlink()
    with pytest.raises(InputError) as caught:
        master.rosmaster_command()
    assert f"neither on PATH ({tmp_path})" in str(caught.value) and "/nonexistent/rosmaster" in str(caught.value)


def test_a_namespace_typo_names_where_the_robot_is(tag):
    """A node started with __ns:=/tmb3_1 commands a robot that is not there: one finding says so, naming the
    robots' own cmd_vel, instead of only "no message on /cmd_vel"."""
    import json
    import os
    import subprocess
    import sys

    from bridgetools import NODES, REPO, ROOM

    done = subprocess.run([sys.executable, "-m", "worldgen", "run", str(ROOM), str(NODES / "drive_into_wall.py"),
                           "__ns:=/tmb3_1", "--duration", "2", "--rate", "max", "--format", "json"],
                          env=dict(os.environ, PYTHONPATH=str(REPO)), capture_output=True, text=True, timeout=120)
    doc = json.loads(done.stdout)
    said = [f for f in doc["findings"] if "no robot lives in /tmb3_1" in f["message"]]
    assert done.returncode == 1 and len(said) == 1 and "the robots take /cmd_vel" in said[0]["message"]
