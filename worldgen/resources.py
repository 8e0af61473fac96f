"""Where the package's data lives, in a checkout and in an installed wheel alike.

The wheel carries the top-level ``templates/`` folder as ``worldgen/templates`` (see pyproject.toml); in a
checkout or an editable install it is found beside the package.
"""

from __future__ import annotations

from pathlib import Path

PACKAGE_DIR = Path(__file__).resolve().parent


def templates_dir() -> Path:
    for candidate in (PACKAGE_DIR / "templates", PACKAGE_DIR.parent / "templates"):
        if candidate.is_dir():
            return candidate
    raise FileNotFoundError("worldgen's templates folder is missing from this installation")


def robots_dir() -> Path:
    """The folder of our TurtleBot3 descriptions (a ROS package folder: package.xml + urdf/)."""
    return PACKAGE_DIR / "robots" / "worldgen_turtlebot3"
