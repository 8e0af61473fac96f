"""Where students' rclpy nodes get their Python: ``$WORLDGEN_ROS2_PYTHON``, else the ``python3`` on PATH (after
``source /opt/ros/humble/setup.bash``, or in a venv with PyPI's Jazzy wheels activated), else the checkout's
``.venv-ros2`` (what ``.ci/ros2-peer`` makes) — the first that imports rclpy. worldgen itself needs no ROS 2: it
speaks DDS through cyclonedds (``pip install 'worldgen[ros2]'``), checked by :func:`require_cyclonedds`."""

from __future__ import annotations

import functools
import os
import shutil
import sys
from pathlib import Path

from ..core.errors import InputError
from ..runtime.interpreters import imports

ENV_PYTHON = "WORLDGEN_ROS2_PYTHON"
PEER_VENV = Path(__file__).resolve().parents[2] / ".venv-ros2"


def install_hint(stack: str) -> str:
    return (f"source /opt/ros/{stack}/setup.bash (apt install ros-{stack}-rclpy), or "
            f"pip install 'ros-jazzy-rclpy[fastrtps]' ros-jazzy-geometry-msgs ros-jazzy-sensor-msgs in a venv "
            f"and activate it, or set {ENV_PYTHON}")


@functools.lru_cache(maxsize=None)
def imports_rclpy(python: str) -> bool:
    """Asked once a process, and kept on disk while the interpreter and rclpy stay (:mod:`worldgen.runtime.
    interpreters`)."""
    return imports(python, "rclpy", timeout=60)


def candidates() -> list[tuple[str, str]]:
    """(python, where it came from) in the order they are tried."""
    chosen = os.environ.get(ENV_PYTHON)
    if chosen:
        return [(chosen, f"${ENV_PYTHON}")]
    found = []
    on_path = shutil.which("python3")
    if on_path:
        found.append((on_path, "python3 on PATH"))
    peer = PEER_VENV / "bin" / "python"
    if peer.exists():
        found.append((str(peer), str(PEER_VENV)))
    return found


def node_python(stack: str) -> str:
    """The interpreter for students' rclpy nodes (see the module docstring); InputError naming what was tried and
    what to install when none imports rclpy."""
    tried = []
    for python, where in candidates():
        if os.access(python, os.X_OK) and imports_rclpy(python):
            return python
        tried.append(f"{python} ({where})")
    raise InputError(f"rclpy (ROS 2's Python client) is not importable by {', '.join(tried) or 'any python3'}",
                     hint=install_hint(stack))


def doctor_python() -> str:
    """The Python ``worldgen doctor --ros`` checks: the one that runs nodes, or when none imports rclpy, the first
    that would be tried (so that its report shows rclpy missing)."""
    for python, _ in candidates():
        if os.access(python, os.X_OK) and imports_rclpy(python):
            return python
    return next((p for p, _ in candidates() if os.access(p, os.X_OK)), sys.executable)


def require_cyclonedds() -> None:
    """InputError naming the extra when this Python cannot speak DDS."""
    try:
        import cyclonedds  # noqa: F401  (whether it imports is the question)
    except ImportError:
        version = f"{sys.version_info[0]}.{sys.version_info[1]}"
        raise InputError(f"worldgen's ROS 2 side needs cyclonedds, which this Python ({version}) does not have",
                         hint="pip install 'worldgen[ros2]' (Python 3.10 to 3.13)") from None
