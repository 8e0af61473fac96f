"""The ``catkin_make`` command to tell a user: with a virtualenv's ``python3`` first on PATH, CMake takes that Python,
which has no ``catkin_pkg``, and the build fails; ROS's own Python is then named with
``-DPYTHON_EXECUTABLE=/usr/bin/python3`` (the README's advice, given where it applies)."""

from __future__ import annotations

import os
import shutil
from pathlib import Path

SYSTEM_PYTHON = "/usr/bin/python3"


def catkin_make_command(path: str | None = None) -> str:
    """``catkin_make``, with ``-DPYTHON_EXECUTABLE`` when the ``python3`` first on ``path`` (default PATH) is a
    virtualenv's (a ``pyvenv.cfg`` beside its ``bin/``) and the system's Python is there to name instead."""
    found = shutil.which("python3", path=path)
    in_venv = found is not None and (Path(os.path.abspath(found)).parent.parent / "pyvenv.cfg").is_file()
    if in_venv and os.path.isfile(SYSTEM_PYTHON):
        return f"catkin_make -DPYTHON_EXECUTABLE={SYSTEM_PYTHON}"
    return "catkin_make"
