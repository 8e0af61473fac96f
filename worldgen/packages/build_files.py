"""What the catkin and the ament package checks both read in a package's build files: a file's text, read safely,
and the ``project()`` call of a CMakeLists.txt."""

from __future__ import annotations

import re
from pathlib import Path
from typing import Callable

from ..core.errors import WorldgenError
from ..core.inputs import read_capped


def file_text(path: Path) -> str:
    """A file's text (capped, never a pipe or device; empty when it cannot be read)."""
    try:
        return read_capped(path).decode("utf-8", "replace")
    except (OSError, WorldgenError):
        return ""


def cmake_text(cmake: Path) -> str:
    """A CMakeLists.txt's text without its comments."""
    return re.sub(r"#[^\n]*", "", file_text(cmake))


def check_project(text: str, name: str, cmake: Path, add: Callable, check: str) -> None:
    """An error finding (``check``) when the CMakeLists.txt ``text`` has no ``project()`` call, or one that does
    not name the package ``name``."""
    project = re.search(r"\bproject\s*\(\s*([^\s)]+)", text, re.IGNORECASE)
    if not project:
        add(check, "error", "CMakeLists.txt has no project() call", cmake, f"add project({name})")
    elif project.group(1) != name:
        add(check, "error", f"project({project.group(1)}) does not match the package name {name}", cmake,
            f"write project({name})")
