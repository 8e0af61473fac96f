"""What would break in a ROS 2 (ament) package: the files colcon needs to build it and the folders it must
install for ``ros2 launch`` and ``get_package_share_directory`` to find its launch files and worlds.

- **ament_python** (``<build_type>ament_python</build_type>``): ``setup.py`` (read statically with
  :mod:`worldgen.pyread.evaluate`, never run: ``name``, ``data_files``, ``entry_points``), ``setup.cfg`` (where ``ros2 run``
  finds the executables), ``resource/NAME`` (the ament index marker) installed to
  ``share/ament_index/resource_index/packages``, ``package.xml`` and every file of ``launch/`` and ``worlds/``
  installed under ``share/NAME``.
- **ament_cmake**: ``CMakeLists.txt`` with ``project(NAME)``, ``find_package(ament_cmake REQUIRED)``,
  ``ament_package()`` and ``install(DIRECTORY launch worlds … DESTINATION share/${PROJECT_NAME})``.

setup.py is read by :mod:`worldgen.pyread.setup_py`, which also tells the launch reader which file of a package
a path under ``share/NAME`` comes from.
"""

from __future__ import annotations

import configparser
import re
from pathlib import Path
from typing import Callable, Optional, Set

from ..core.errors import WorldFileError
from ..core.packages import MANIFEST
from ..pyread.setup_py import installed_files, read_setup
from .build_files import check_project, cmake_text, file_text

SHARED = ("launch", "worlds", "models")   # the folders a class package's launch files and worlds live in
Add = Callable[..., None]   # add(check, severity, message, where=None, fix=None)


# --------------------------------------------------------------------------------------------------- checks

def check_ament(pkg_dir: Path, name: str, kind: str, add: Add) -> Optional[Set[str]]:
    """The checks of an ament package (see the module docstring), reported through ``add``; the names of the
    executables it installs (``ros2 run NAME EXE``), or None when they cannot be told."""
    if kind == "ament_python":
        return _check_python(pkg_dir, name, add)
    if kind == "ament_cmake":
        return _check_cmake(pkg_dir, name, add)
    add("package-build-type", "info", f"build type {kind}: its build files are not checked here", pkg_dir / MANIFEST)
    return None


def _check_python(pkg_dir: Path, name: str, add: Add) -> Optional[Set[str]]:
    setup_py = pkg_dir / "setup.py"
    _setup_cfg(pkg_dir, name, add)
    marker = pkg_dir / "resource" / name
    if not marker.is_file():
        add("package-resource", "error", f"no resource/{name}: the ament index marker that lets ros2 find the "
            "package", pkg_dir, f"create the empty file resource/{name} and install it (see ros2 pkg create)")
    if not setup_py.is_file():
        add("package-setup", "error", "no setup.py: colcon cannot build an ament_python package without one",
            pkg_dir, "create it as 'ros2 pkg create --build-type ament_python NAME' does")
        return None
    try:
        info = read_setup(setup_py)
    except WorldFileError as err:
        add("package-setup", "error", err.message, f"{err.path}:{err.line}" if err.line else err.path, err.hint)
        return None
    if not info.found:
        add("package-setup", "error", "setup.py never calls setup()", setup_py, "call setuptools.setup(...)")
        return None
    for line, reason in info.unreadable:
        add("package-setup", "info", f"what setup.py installs is not checked: {reason} (worldgen reads it, never "
            "runs it)", f"{setup_py}:{line}" if line else setup_py,
            "list data_files as (destination, [files]) pairs of constants, glob() and os.path.join() to have it "
            "checked")
    if isinstance(info.name, str) and info.name != name:
        add("package-setup", "warning", f"setup.py names the package {info.name!r}, package.xml {name!r}", setup_py,
            f"write name='{name}' (or name=package_name)")
    installed = installed_files(pkg_dir, info)
    info.scripts.update(p.name for p in installed.get(f"lib/{name}", []))
    if not info.unreadable:
        _installs(pkg_dir, name, installed, setup_py, add)
    return None if info.unreadable and not info.scripts else info.scripts


def _installs(pkg_dir: Path, name: str, installed: dict, setup_py: Path, add: Add) -> None:
    """Whether data_files installs the marker, package.xml, and every file of launch/ and worlds/."""
    index = installed.get("share/ament_index/resource_index/packages", [])
    if (pkg_dir / "resource" / name).resolve() not in index:
        add("package-install", "error", f"data_files does not install resource/{name} to share/ament_index/"
            "resource_index/packages: ros2 cannot find the package once built", setup_py,
            f"add ('share/ament_index/resource_index/packages', ['resource/{name}']) to data_files")
    if (pkg_dir / MANIFEST).resolve() not in installed.get(f"share/{name}", []):
        add("package-install", "warning", f"data_files does not install package.xml to share/{name}", setup_py,
            f"add ('share/{name}', ['package.xml']) to data_files")
    for folder in SHARED:
        files = sorted(p for p in (pkg_dir / folder).rglob("*") if p.is_file()) if (pkg_dir / folder).is_dir() else []
        covered = {p for dest, paths in installed.items() if dest.startswith(f"share/{name}") for p in paths}
        missing = [p for p in files if p.resolve() not in covered and not p.name.startswith(".")]
        if missing:
            shown = ", ".join(str(p.relative_to(pkg_dir)) for p in missing[:3]) + \
                (f" and {len(missing) - 3} more" if len(missing) > 3 else "")
            add("package-install", "warning", f"{folder}/ is not installed by data_files ({shown}): after colcon "
                f"build, get_package_share_directory('{name}') has no {folder}/" +
                ("" if folder != "launch" else f" and ros2 launch {name} cannot find them"), setup_py,
                f"add (os.path.join('share', '{name}', '{folder}'), glob('{folder}/*')) to data_files")


def _setup_cfg(pkg_dir: Path, name: str, add: Add) -> None:
    cfg = pkg_dir / "setup.cfg"
    fix = f"write [develop] script_dir=$base/lib/{name} and [install] install_scripts=$base/lib/{name}"
    if not cfg.is_file():
        add("package-setup", "error", "no setup.cfg: ros2 run cannot find the package's executables", pkg_dir, fix)
        return
    parser = configparser.ConfigParser(interpolation=None)
    try:
        parser.read_string(file_text(cfg))
    except configparser.Error as err:
        add("package-setup", "error", f"setup.cfg cannot be read: {' '.join(str(err).split())}", cfg, fix)
        return
    scripts = parser.get("install", "install_scripts", fallback=None) or \
        parser.get("install", "install-scripts", fallback=None)
    if scripts is None or scripts.strip().rstrip("/") != f"$base/lib/{name}":
        add("package-setup", "error", f"setup.cfg does not install scripts to $base/lib/{name}: ros2 run cannot "
            "find the package's executables", cfg, fix)


def _check_cmake(pkg_dir: Path, name: str, add: Add) -> Optional[Set[str]]:
    cmake = pkg_dir / "CMakeLists.txt"
    if not cmake.is_file():
        add("package-cmake", "error", "no CMakeLists.txt: colcon cannot build an ament_cmake package without one",
            pkg_dir, "create it as 'ros2 pkg create --build-type ament_cmake NAME' does")
        return None
    text = cmake_text(cmake)
    check_project(text, name, cmake, add, "package-cmake")
    if not re.search(r"\bfind_package\s*\(\s*ament_cmake\b", text, re.IGNORECASE):
        add("package-cmake", "error", "CMakeLists.txt never finds ament_cmake", cmake,
            "add find_package(ament_cmake REQUIRED)")
    if not re.search(r"\bament_package\s*\(", text, re.IGNORECASE):
        add("package-cmake", "error", "CMakeLists.txt never calls ament_package(): colcon builds it, but ros2 "
            "cannot find the package", cmake, "end CMakeLists.txt with ament_package()")
    installed: Set[str] = set()
    for match in re.finditer(r"\binstall\s*\(\s*DIRECTORY([^)]*)\)", text, re.IGNORECASE):
        parts = match.group(1).split()
        cut = parts.index("DESTINATION") if "DESTINATION" in parts else len(parts)
        if any("share" in p for p in parts[cut + 1:cut + 2]):
            installed.update(p.rstrip("/") for p in parts[:cut])
    for folder in SHARED:
        if (pkg_dir / folder).is_dir() and any((pkg_dir / folder).iterdir()) and folder not in installed:
            add("package-install", "warning", f"{folder}/ is not installed: after colcon build, "
                f"get_package_share_directory('{name}') has no {folder}/", cmake,
                f"add install(DIRECTORY {folder} DESTINATION share/${{PROJECT_NAME}})")
    programs = set(re.findall(r"\badd_executable\s*\(\s*([^\s)]+)", text, re.IGNORECASE))
    for match in re.finditer(r"\binstall\s*\(\s*PROGRAMS([^)]*)\)", text, re.IGNORECASE):
        parts = match.group(1).split()
        programs.update(Path(p).name for p in parts[:parts.index("DESTINATION") if "DESTINATION" in parts else None])
    return programs
