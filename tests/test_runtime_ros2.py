"""What a ROS 2 student is told to install: ROS 2's package names for the stack (apt's ros-DISTRO-…, PyPI's Jazzy
wheels where they exist), in the preflight of `worldgen run --ros` and in `worldgen doctor --ros`."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from worldgen.runtime.naming import Naming

REPO = Path(__file__).resolve().parent.parent


@pytest.mark.parametrize("stack", ["humble", "jazzy"])
def test_ros_packages_are_named_for_the_stack(stack):
    naming = Naming(stack)
    assert naming.package("rclpy") == f"ros-{stack}-rclpy"
    assert naming.package("cv_bridge") == f"ros-{stack}-cv-bridge"
    assert naming.package("turtlebot3_msgs") == f"ros-{stack}-turtlebot3-msgs"
    assert naming.package("cv2") == "python3-opencv"
    wheels = "'ros-jazzy-rclpy[fastrtps]'" in naming.hint("rclpy")
    assert wheels == (stack == "jazzy")        # PyPI has Jazzy's wheels, not Humble's
    assert "pip" not in naming.hint("cv_bridge")   # no wheel of it anywhere
    assert "pip install opencv-python" in naming.hint("cv2")


def test_ros1_naming_is_unchanged():
    assert Naming("noetic").package("tf") == "python3-tf"
    assert Naming("noetic", apt_ros=True).package("tf") == "ros-noetic-tf"


def peer() -> str:
    python = os.environ.get("WORLDGEN_ROS2_PYTHON") or str(REPO / ".venv-ros2" / "bin" / "python")
    if not os.access(python, os.X_OK):
        if os.environ.get("CI"):
            pytest.fail(f"no ROS 2 peer at {python}")
        pytest.skip(f"no ROS 2 peer at {python} (bash .ci/ros2-peer)")
    return python


def test_doctor_and_run_name_ros2_packages_and_start_nothing(tmp_path):
    pytest.importorskip("cyclonedds", reason="the ros2 extra (cyclonedds) is not installed for this Python")
    python = peer()
    node = tmp_path / "follow.py"
    node.write_text("import rclpy\nfrom cv_bridge import CvBridge\nimport numpy\n")
    env = dict(os.environ, WORLDGEN_ROS2_PYTHON=python, PYTHONPATH=str(REPO))
    done = subprocess.run([sys.executable, "-m", "worldgen", "doctor", "--ros", "jazzy", str(node), "--format", "json"],
                          env=env, capture_output=True, text=True, timeout=120)
    doc = json.loads(done.stdout)
    assert done.returncode == 1 and doc["rospy"] is True        # rclpy, the client library, is there
    states = {m["module"]: m["state"] for m in doc["modules"]}
    assert states == {"cv_bridge": "MISSING", "numpy": "ok", "rclpy": "ok"}
    assert doc["packages"] == ["ros-jazzy-cv-bridge"]
    done = subprocess.run([sys.executable, "-m", "worldgen", "run", str(REPO / "examples" / "enclosed_room.yaml"),
                           str(node), "--ros", "humble", "--format", "json"], env=env, capture_output=True, text=True,
                          timeout=120)
    result = json.loads(done.stdout)
    assert done.returncode == 1 and result["metrics"] == {}   # nothing ran
    [finding] = result["findings"]
    assert finding["check"] == "runtime" and finding["where"] == f"{node}:2"
    assert "ros-humble-cv-bridge" in finding["message"] and "apt install ros-humble-cv-bridge" in finding["fix"]
