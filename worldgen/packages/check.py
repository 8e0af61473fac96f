"""What would break in a catkin or ament package: its manifest, build files, scripts and launch files.

:func:`check_package` reads every launch file of the package (roslaunch XML and ROS 2 Python launch files) with
:func:`worldgen.launch.reader.read_launch` and turns what it cannot resolve into findings, beside the checks of
package.xml (with catkin_pkg when it is installed), the scripts' executable bits, and the build files: a catkin
package's CMakeLists.txt here, an ament package's (setup.py, setup.cfg, resource marker, or CMakeLists.txt with
ament_package()) in :mod:`.check_ament`.
"""

from __future__ import annotations

import os
import re
from dataclasses import dataclass
from pathlib import Path
from typing import Mapping, Optional, Sequence, Set

from ..core.errors import WorldFileError, WorldgenError
from ..core.inputs import read_capped
from ..core.safexml import parse_bytes
from ..core.findings import Finding
from .check_ament import check_ament
from .build_files import check_project, cmake_text, file_text
from ..launch.reader import PYTHON_LAUNCH_SUFFIXES, package_index, read_launch
from ..core.packages import build_type, manifest_name
from ..spec.model import ROBOT_MODELS


def package_launch_files(pkg_dir: str | Path) -> list[Path]:
    """Every launch file of a package (``*.launch``, ``*.launch.xml``, ROS 2's ``*.launch.py`` and
    ``*_launch.py``), sorted; hidden folders and nested packages are skipped."""
    pkg_dir = Path(pkg_dir)
    found: list[Path] = []
    for dirpath, dirnames, filenames in os.walk(pkg_dir):
        here = Path(dirpath)
        if here != pkg_dir and "package.xml" in filenames:
            dirnames.clear()
            continue
        dirnames[:] = sorted(d for d in dirnames if not d.startswith("."))
        found += [here / f for f in filenames if f.endswith((".launch", ".launch.xml") + PYTHON_LAUNCH_SUFFIXES)]
    return sorted(found)


def check_package(pkg_dir: str | Path, *, ros_package_path: Sequence[str | Path] | None = None,
                  environ: Mapping[str, str] | None = None, launch_rows: bool = False) -> list[Finding]:
    """What would break in the catkin or ament package at ``pkg_dir``: package.xml that catkin_pkg cannot parse
    (or a name catkin rejects), a catkin CMakeLists.txt without ``project(NAME)``/``catkin_package()`` or not
    installing its launch/worlds/models folders (an ament package's build files: :mod:`.check_ament`), scripts
    without their executable bit, launch files that do not parse, name a world file that does not exist, an
    unknown robot model or a node the package does not have, and missing exec_depends on the packages the launch
    files use. With ``launch_rows`` the caller reports each launch file's read on a row of its own (``worldgen
    validate``): what that row says — the read's findings, a file that does not parse, a world that is not
    there — is left out here, so that one cause is said once."""
    pkg_dir = Path(pkg_dir)
    findings: list[Finding] = []

    def add(check, severity, message, where=None, fix=None):
        findings.append(Finding(check, severity, message, where=str(where) if where else None, fix=fix))

    manifest = pkg_dir / "package.xml"
    if not manifest.is_file():
        add("package-xml", "error", "no package.xml: this folder is not a ROS package", pkg_dir,
            "create it with 'worldgen scaffold NAME' or catkin_create_pkg (ROS 2: ros2 pkg create)")
        return findings
    name, depends = _read_manifest(manifest, add)
    kind = build_type(pkg_dir)
    executables: set[str] | None = None
    if kind == "catkin" and re.search(r"<buildtool_depend>\s*ament_", file_text(manifest)):
        add("package-xml", "warning", "package.xml depends on ament but declares no <build_type>: colcon builds "
            "it as a catkin package", manifest, "add <export><build_type>ament_cmake</build_type></export> (or "
            "ament_python)")
    if kind != "catkin":
        executables = check_ament(pkg_dir, name, kind, add)
    elif not (pkg_dir / "CMakeLists.txt").is_file():
        add("cmake", "error", "no CMakeLists.txt", pkg_dir, "every catkin package needs one (see catkin_create_pkg)")
    else:
        _check_cmake(pkg_dir / "CMakeLists.txt", name, pkg_dir, add)
    scripts = pkg_dir / "scripts"
    if scripts.is_dir():
        for script in sorted(p for p in scripts.rglob("*") if p.is_file() and not p.name.startswith(".")):
            if not os.access(script, os.X_OK):
                add("script-executable", "error", "script is not executable: rosrun and roslaunch cannot start it",
                    script, f"chmod +x {script}")
            elif script.suffix == ".py" and not _head(script).startswith(b"#!"):
                add("script-executable", "error", "Python script has no #! line", script,
                    "start it with #!/usr/bin/env python3")
    used: set[str] = set()
    package = _Package(name, pkg_dir, kind, executables, launch_rows)
    for launch in package_launch_files(pkg_dir):
        _check_launch(launch, package, used, add, ros_package_path, environ)
    if depends is not None:
        for dep in sorted(used - depends - {name}):
            add("package-depends", "warning", f"launch files use the package {dep} but package.xml does not "
                f"exec_depend on it", manifest, f"add <exec_depend>{dep}</exec_depend>")
    return findings


def _read_manifest(manifest: Path, add) -> tuple[str, set[str] | None]:
    try:
        from catkin_pkg.package import parse_package
    except ImportError:   # catkin_pkg is a test dependency; without it, the XML and the name only
        try:
            parse_bytes(read_capped(manifest), manifest, what="package.xml")
        except (OSError, WorldgenError) as err:
            line = getattr(err, "line", None)
            add("package-xml", "error", getattr(err, "message", None) or f"package.xml cannot be read: {err}",
                f"{manifest}:{line}" if line else manifest, getattr(err, "hint", None) or "fix package.xml")
            return manifest.parent.name, None
        name = manifest_name(manifest)
        if not name:
            add("package-xml", "error", "package.xml has no <name>", manifest,
                "name the package: <name>my_package</name> (as catkin_create_pkg writes it)")
        return name or manifest.parent.name, None
    warnings: list[str] = []
    try:
        package = parse_package(str(manifest), warnings=warnings)
    except Exception as err:   # InvalidPackage, ValueError, and plain Exceptions on bad XML
        add("package-xml", "error", f"catkin_pkg cannot parse package.xml: {' '.join(str(err).split())}",
            manifest, "fix package.xml (compare with one made by 'worldgen scaffold')")
        return manifest_name(manifest) or manifest.parent.name, None
    for warning in warnings:
        add("package-xml", "warning", warning, manifest, None)
    deps = {d.name for d in package.exec_depends + package.build_depends + package.buildtool_depends}
    return package.name, deps


def _check_cmake(cmake: Path, name: str, pkg_dir: Path, add) -> None:
    text = cmake_text(cmake)
    check_project(text, name, cmake, add, "cmake")
    if not re.search(r"\bcatkin_(package|metapackage)\s*\(", text):
        add("cmake", "error", "CMakeLists.txt never calls catkin_package()", cmake, "add catkin_package()")
    installed = set()
    for match in re.finditer(r"\binstall\s*\(\s*DIRECTORY([^)]*)\)", text, re.IGNORECASE):
        words = match.group(1).split()
        installed.update(w.rstrip("/") for w in words[:words.index("DESTINATION")] if "DESTINATION" in words)
    for folder in ("launch", "worlds", "models"):
        if (pkg_dir / folder).is_dir() and any((pkg_dir / folder).iterdir()) and folder not in installed:
            add("cmake-install", "warning", f"{folder}/ is not installed: 'catkin_make install' leaves it out",
                cmake, f"add install(DIRECTORY {folder} DESTINATION ${{CATKIN_PACKAGE_SHARE_DESTINATION}})")


@dataclass(frozen=True)
class _Package:
    """The package whose launch files are checked: its name, folder, build type and (ament) the executables
    its build files install (None: not known)."""

    name: str
    folder: Path
    kind: str = "catkin"
    executables: Optional[Set[str]] = None
    launch_rows: bool = False   # each launch file's read is reported on its own row: not repeated here


def _check_launch(launch: Path, package: _Package, used: set[str], add, ros_package_path, environ) -> None:
    name, pkg_dir, kind, executables = package.name, package.folder, package.kind, package.executables
    try:
        info = read_launch(launch, ros_package_path=ros_package_path, environ=environ or {})
    except WorldFileError as err:
        if not package.launch_rows:
            add("launch-parse", "error", err.message, f"{err.path}:{err.line}" if err.line else err.path, err.hint)
        return
    for finding in () if package.launch_rows else info.findings:
        if finding.severity in ("error", "warning"):
            add(finding.check, finding.severity, finding.message, finding.where, finding.fix)
    if not package.launch_rows:
        _check_world(info, launch, name, add)
    known = set(ROBOT_MODELS)
    models = {r.robot for r in info.robots if r.robot} | ({info.model} if info.model else set())
    for model in sorted(models - known):
        add("launch-model", "error", f"unknown TurtleBot3 model {model!r}", launch,
            f"use one of {', '.join(sorted(known))}")
    index = package_index(launch, ros_package_path)   # (crawled only when a name is looked up)
    for node in info.nodes:
        if node.package != name:
            near = index.misspelt(node.package)
            if near is not None:   # (not depended on either: the exec_depend to add is the right name's)
                add("launch-node", "error", f"node {node.full_name}: no package {node.package!r} is found; did you "
                    f"mean {near!r}?", f"{launch}:{node.line}", f"write pkg=\"{near}\" (or the package's own name)")
                continue
        used.add(node.package)
        if node.package == name and kind != "catkin":
            if executables is not None and node.type not in executables:
                add("launch-node", "error", f"node {node.full_name}: {node.package} installs no executable "
                    f"{node.type!r}", f"{launch}:{node.line}", "add it to setup.py's console_scripts (ament_python) "
                    "or install it in CMakeLists.txt (ament_cmake), or fix executable=")
        elif node.package == name:
            exe = next((p for p in pkg_dir.rglob(node.type) if p.is_file()), None)
            if exe is None:
                add("launch-node", "error", f"node {node.full_name}: {node.package}/{node.type} is not in the package",
                    f"{launch}:{node.line}", f"add scripts/{node.type} or fix type=")
            elif not os.access(exe, os.X_OK):
                add("launch-node", "error", f"node {node.full_name}: {exe} is not executable",
                    f"{launch}:{node.line}", f"chmod +x {exe}")
    text = file_text(launch)
    named = set(re.findall(r"\$\(find\s+([^)\s]+)\)", text))
    named.update(re.findall(r"\b(?:get_package_share_directory|FindPackageShare)\(\s*(?:package\s*=\s*)?"
                            r"['\"]([A-Za-z0-9_]+)['\"]", text))
    # a misspelt one is said where it is used (the launch file's row), not as a depend to add
    used.update(other for other in named if other == name or index.misspelt(other) is None)


def _check_world(info, launch: Path, name: str, add) -> None:
    """A launch file's world: a file that is not there, or a world in its own package that does not resolve."""
    if info.world_path is not None and not info.world_path.is_file():
        add("launch-world", "error", f"the world file {info.world_path} does not exist", launch,
            "build it (worldgen build SPEC --package DIR) or fix the world's path")
    elif info.world_path is None and info.package == name and info.world_ref:
        add("launch-world", "error", f"the world {info.world_ref} cannot be resolved", launch,
            "fix the world's path")


def _head(path: Path) -> bytes:
    """The first two bytes of a file (empty when it cannot be read)."""
    try:
        with open(path, "rb") as handle:
            return handle.read(2)
    except OSError:
        return b""
