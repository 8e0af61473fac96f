"""A built world put into a ROS package (``worldgen build --package``): the world file and its launch file, and
for Jazzy the bridge's parameter file, placed in the package folder, for catkin (roslaunch XML) and ament (launch.py)
packages alike; and the package's ``package.xml`` given the exec_depends that launch file needs when it lacks them
(:func:`launch_depends_update`: a package scaffolded without ``--world`` has none of Gazebo's), so that what worldgen
writes into a package validates with nothing to say about it."""

from __future__ import annotations

import re
from pathlib import Path
from typing import Iterable, Sequence

from ..core.safexml import parse_file
from ..launch.writer_py import world_package_files
from ..launch.writer_xml import check_package_ref, default_launch_name, launch_xml, package_name_of
from .ament import LAUNCH_DEPENDS
from .catkin import GAZEBO_DEPENDS


def package_world_files(pkg_dir: str | Path, world_name: str, world_text: str, spawn: Sequence[float],
                        ros: str = "noetic", model: str = "optenv", cmd_vel: str | None = None) -> dict[Path, str]:
    """The files that put a built world into the package folder ``pkg_dir`` (path → text, for
    :func:`worldgen.core.fsio.write_files`): for ``noetic`` ``worlds/NAME.world`` and
    ``launch/turtlebot3_in_NAME.launch``; for ROS 2 those of :func:`worldgen.launch.writer_py.world_package_files`.
    Raises InputError for a package folder whose name cannot name a ROS package."""
    pkg_dir = Path(pkg_dir)
    package = check_package_ref(package_name_of(pkg_dir))
    if ros == "noetic":
        world_file = f"{world_name}.world"
        launch_name = default_launch_name(world_file)
        files = {f"worlds/{world_file}": world_text,
                 f"launch/{launch_name}": launch_xml(world_file, package, model, spawn, launch_name=launch_name)}
    else:
        files = world_package_files(world_name, world_text, package, ros, spawn, model, cmd_vel)
    return {pkg_dir / rel: text for rel, text in files.items()}


# the tags that name a package a launch file may use (catkin_pkg counts build, buildtool and exec depends)
DEPEND_TAGS = ("depend", "exec_depend", "run_depend", "build_depend", "build_export_depend", "buildtool_depend")
_DEPEND_LINE = re.compile(r"^([ \t]*)<(%s)\b[^>]*>[^<]*</\2>[ \t]*$" % "|".join(DEPEND_TAGS), re.MULTILINE)
_TAIL = re.compile(r"^[ \t]*<(export|/package)\b", re.MULTILINE)


def launch_depends(ros: str) -> tuple[str, ...]:
    """The packages the launch file worldgen writes for ``ros`` starts (its exec_depends)."""
    return GAZEBO_DEPENDS if ros == "noetic" else LAUNCH_DEPENDS[ros]


def launch_depends_update(pkg_dir: str | Path, ros: str, also: Iterable[str] = ()) -> dict[Path, str]:
    """``{PKG/package.xml: its text with an exec_depend (format 1: run_depend) added for each package the launch
    file uses (:func:`launch_depends`, and ``also``: the packages of its extra nodes) that it does not name yet}``,
    each on a line of its own after its last dependency, the rest of the file byte for byte; ``{}`` when nothing is
    missing, or when there is no package.xml that parses (validate says what is wrong with it)."""
    manifest = Path(pkg_dir) / "package.xml"
    root = parse_file(manifest)
    if root is None or not manifest.is_file():
        return {}
    own = (root.findtext("name") or "").strip()
    named = {(el.text or "").strip() for tag in DEPEND_TAGS for el in root.iterfind(tag)}
    missing = [d for d in dict.fromkeys([*launch_depends(ros), *sorted(also)]) if d not in named and d != own]
    if not missing:
        return {}
    text = manifest.read_text(encoding="utf-8")
    tag = "run_depend" if root.get("format", "1").strip() == "1" else "exec_depend"
    lines = [m for m in _DEPEND_LINE.finditer(text)]
    if lines:
        at, indent = lines[-1].end(), lines[-1].group(1)
        added = "".join(f"\n{indent}<{tag}>{d}</{tag}>" for d in missing)
    else:   # no dependency yet: before <export> (or </package>)
        tail = _TAIL.search(text)
        if tail is None:
            return {}
        at, added = tail.start(), "".join(f"  <{tag}>{d}</{tag}>\n" for d in missing)
    return {manifest: text[:at] + added + text[at:]}


def update_notes(updated: dict[Path, str]) -> dict[Path, str]:
    """The line a command prints for each package.xml of :func:`launch_depends_update` it writes."""
    return {path: f"updated {path}: exec_depend {', '.join(added_depends(path, text))} (what its launch file "
                  "starts)" for path, text in updated.items()}


def added_depends(manifest: Path, text: str) -> list[str]:
    """The packages ``text`` (a new package.xml) exec_depends (run_depends) on that the file at ``manifest`` does
    not name yet, in order."""
    old = manifest.read_text(encoding="utf-8") if manifest.is_file() else ""
    names = re.compile(r"<(?:exec|run)_depend>\s*([^<\s]+)\s*</")
    return [d for d in names.findall(text) if d not in set(names.findall(old))]
