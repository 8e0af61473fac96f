"""What would break in a ROS 2 (ament) package: the files colcon needs to build it and the folders it must
install for ``ros2 launch`` and ``get_package_share_directory`` to find its launch files and worlds.

- **ament_python** (``<build_type>ament_python</build_type>``): ``setup.py`` (read statically with
  :mod:`.pystatic`, never run: ``name``, ``data_files``, ``entry_points``), ``setup.cfg`` (where ``ros2 run``
  finds the executables), ``resource/NAME`` (the ament index marker) installed to
  ``share/ament_index/resource_index/packages``, ``package.xml`` and every file of ``launch/`` and ``worlds/``
  installed under ``share/NAME``.
- **ament_cmake**: ``CMakeLists.txt`` with ``project(NAME)``, ``find_package(ament_cmake REQUIRED)``,
  ``ament_package()`` and ``install(DIRECTORY launch worlds … DESTINATION share/${PROJECT_NAME})``.

:func:`installed_source` answers the other way round, for the launch reader: which file of the package a path
under ``share/NAME`` comes from.
"""

from __future__ import annotations

import configparser
import glob as globbing
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable, List, Optional, Set, Tuple

from ..core.errors import WorldFileError
from ..core.packages import MANIFEST
from .build_files import check_project, cmake_text, file_text
from .pystatic import parse_python, read_module
from .pyvalues import Call, Ctx, Unknown, first_unknown, not_run

SHARED = ("launch", "worlds", "models")   # the folders a class package's launch files and worlds live in
Add = Callable[..., None]   # add(check, severity, message, where=None, fix=None)


class GlobPattern(str):
    """A ``glob(PATTERN)`` in setup.py: the files it matches are the package's own, matched when checked."""


@dataclass
class SetupInfo:
    """What a setup.py gives setuptools, as far as it can be read: the name, ``data_files`` as (destination,
    sources) pairs, the ``console_scripts`` names, and why anything could not be read (line, reason)."""

    name: object = None
    data_files: List[Tuple[object, list]] = field(default_factory=list)
    scripts: Set[str] = field(default_factory=set)
    unreadable: List[Tuple[Optional[int], str]] = field(default_factory=list)
    found: bool = False


def read_setup(setup_py: Path) -> SetupInfo:
    """setup.py read statically: the keyword arguments of its ``setup(...)`` call."""
    info = SetupInfo()

    def setup(ctx: Ctx, call: Call):
        info.found = True
        info.name = call.kwargs.get("name")
        _data_files(info, call.kwargs.get("data_files"), call.line)
        _entry_points(info, call.kwargs.get("entry_points"), call.line)
        scripts = call.kwargs.get("scripts")   # installed where setup.cfg puts scripts: lib/NAME
        if isinstance(scripts, (list, tuple)):
            info.scripts.update(Path(p).name for p in scripts if isinstance(p, str))
        return None

    def skipped(ctx: Ctx, kind: str, node, frame, reason) -> None:   # a loop may add to data_files
        info.unreadable.append((getattr(node, "lineno", None), f"{not_run(kind, node)} is not run here"))

    calls = {"setup": setup, "glob": lambda ctx, call: [GlobPattern(call.arg(0, "pathname"))]
             if isinstance(call.arg(0, "pathname"), str) else Unknown("glob() of a pattern that cannot be known",
                                                                        call.line)}
    try:
        read_module(Ctx(setup_py, {}, calls, on_skip=skipped), parse_python(setup_py, "setup.py"))
    except RecursionError:   # every nesting is bounded; this is the backstop for their product
        raise WorldFileError("setup.py nests too deeply to read", path=setup_py, hint="simplify it") from None
    return info


def _data_files(info: SetupInfo, given, line: int | None) -> None:
    if given is None:
        return
    if not isinstance(given, (list, tuple)):
        info.unreadable.append((line, f"data_files: {given.reason if isinstance(given, Unknown) else 'not a list'}"))
        return
    for entry in given:
        if isinstance(entry, (list, tuple)) and len(entry) == 2 and isinstance(entry[1], (list, tuple)):
            unknown = first_unknown([entry[0], *entry[1]])
            if unknown is not None:
                info.unreadable.append((unknown.line or line, f"a data_files entry: {unknown.reason}"))
            info.data_files.append((entry[0], list(entry[1])))
        else:
            reason = entry.reason if isinstance(entry, Unknown) else "not a (destination, [files]) pair"
            info.unreadable.append((getattr(entry, "line", None) or line, f"a data_files entry: {reason}"))


def _entry_points(info: SetupInfo, given, line: int | None) -> None:
    scripts = given.get("console_scripts") if isinstance(given, dict) else None
    if isinstance(given, Unknown) or isinstance(scripts, Unknown):
        info.unreadable.append((line, f"entry_points: {(given if isinstance(given, Unknown) else scripts).reason}"))
        return
    for item in scripts if isinstance(scripts, (list, tuple)) else []:
        if isinstance(item, str) and "=" in item:
            info.scripts.add(item.split("=", 1)[0].strip())


def _sources(pkg_dir: Path, sources: list) -> List[Path]:
    """The package's files a data_files entry installs (globs matched in the package folder, sorted)."""
    found: List[Path] = []
    for source in sources:
        if isinstance(source, GlobPattern):
            found += sorted(Path(p) for p in globbing.glob(str(pkg_dir / source)) if Path(p).is_file())
        elif isinstance(source, str):
            found.append(pkg_dir / source)
    return found


def _destination(dest) -> Optional[str]:
    return str(dest).strip().strip("/") if isinstance(dest, str) else None


def installed_source(pkg_dir: Path, relative: Path) -> Optional[Path]:
    """The file of the ament_python package ``pkg_dir`` that its setup.py installs as ``share/NAME/relative``
    (None when it installs none there, or setup.py cannot be read)."""
    from ..core.packages import manifest_name

    setup_py = pkg_dir / "setup.py"
    name = manifest_name(pkg_dir / MANIFEST)
    if not setup_py.is_file() or not name:
        return None
    try:
        info = read_setup(setup_py)
    except WorldFileError:
        return None
    want = f"share/{name}/{relative.parent.as_posix()}".rstrip("/.")
    for dest, sources in info.data_files:
        if _destination(dest) == want:
            for source in _sources(pkg_dir, sources):
                if source.name == relative.name and source.is_file():
                    return source
    return None


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
    installed = {}
    for dest, sources in info.data_files:
        where = _destination(dest)
        if where is not None:
            installed.setdefault(where, []).extend(p.resolve() for p in _sources(pkg_dir, sources))
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
