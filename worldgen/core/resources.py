"""Where the package's data lives, in a checkout and in an installed wheel alike, and the templates' renderer.

The wheel carries the top-level ``templates/`` and ``examples/`` folders as ``worldgen/templates`` and
``worldgen/examples`` (see pyproject.toml); in a checkout or an editable install they are found beside the
package.
"""

from __future__ import annotations

import os
from pathlib import Path

PACKAGE_DIR = Path(__file__).resolve().parent.parent   # the worldgen package
ENV_CACHE = "WORLDGEN_CACHE"   # where worldgen keeps what it made once (processed robots, generated types)
ROBOT_MODELS = ("burger", "waffle", "waffle_pi")   # the TurtleBot3 models robots_dir() describes


def _data_dir(name: str) -> Path:
    for candidate in (PACKAGE_DIR / name, PACKAGE_DIR.parent / name):
        if candidate.is_dir():
            return candidate
    raise FileNotFoundError(f"worldgen's {name} folder is missing from this installation")


def templates_dir() -> Path:
    """The Jinja2 templates (``templates/``)."""
    return _data_dir("templates")


def examples_dir() -> Path:
    """The example floorplan specs (``examples/``); the course builds its world from one of them."""
    return _data_dir("examples")


def robots_dir() -> Path:
    """The folder of our TurtleBot3 descriptions (a ROS package folder: package.xml + urdf/)."""
    return PACKAGE_DIR / "robots" / "worldgen_turtlebot3"


def cache_dir() -> Path:
    """Where worldgen keeps what it made and may reuse: ``WORLDGEN_CACHE``, else ``$XDG_CACHE_HOME/worldgen``,
    else ``~/.cache/worldgen`` (not created here)."""
    if os.environ.get(ENV_CACHE):
        return Path(os.environ[ENV_CACHE])
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return Path(base) / "worldgen"


def render_template(template: str, **context) -> str:
    """Render ``templates/TEMPLATE`` (Jinja2) with ``context``. XML and HTML templates (``*.xml.j2``,
    ``*.launch.j2``, ``*.html.j2``) escape their values; undefined names are errors, so a template and its caller cannot drift apart silently."""
    import jinja2

    env = _JINJA.get("env")
    if env is None:
        env = jinja2.Environment(
            loader=jinja2.FileSystemLoader(str(templates_dir())),
            autoescape=jinja2.select_autoescape(enabled_extensions=("xml.j2", "launch.j2", "html.j2"),
                                                default_for_string=False),
            undefined=jinja2.StrictUndefined, keep_trailing_newline=True, trim_blocks=True, lstrip_blocks=True)
        _JINJA["env"] = env
    return env.get_template(template).render(**context)


_JINJA: dict[str, object] = {}
