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


def test_a_velocity_topic_typo_names_the_topic_the_node_used(tag):
    """A node whose commands go to /cmdvel (remapped here as a misspelt name would): a finding names that topic
    and the robot's own, beside "no message on /cmd_vel"; none when the robot is commanded."""
    import json
    import os
    import subprocess
    import sys

    from bridgetools import NODES, REPO, ROOM

    def findings(*node_args):
        done = subprocess.run([sys.executable, "-m", "worldgen", "run", str(ROOM), str(NODES / "drive_into_wall.py"),
                               *node_args, "--duration", "2", "--rate", "max", "--format", "json"],
                              env=dict(os.environ, PYTHONPATH=str(REPO)), capture_output=True, text=True, timeout=120)
        return [f["message"] for f in json.loads(done.stdout)["findings"]]

    said = [m for m in findings("cmd_vel:=/cmdvel") if "/cmdvel" in m]
    assert said == ["a node publishes geometry_msgs/Twist on /cmdvel, which no robot takes: the robots take /cmd_vel"]
    assert not [m for m in findings() if "which no robot takes" in m]
