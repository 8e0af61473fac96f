"""What an ament_python package's ``setup.py`` gives setuptools, read without running it: the name,
``data_files`` (where each file is installed), the ``console_scripts``; and, the other way round for the launch
reader, which file of the package a path under ``share/NAME`` comes from (:func:`installed_source`)."""

from __future__ import annotations

import glob as globbing
from dataclasses import dataclass, field
from pathlib import Path
from typing import Dict, List, Optional, Set, Tuple

from ..core.errors import WorldFileError
from ..core.packages import MANIFEST, manifest_name
from .evaluate import parse_python, read_module
from .values import Call, Ctx, Unknown, first_unknown, not_run


class GlobPattern(str):
    """A ``glob(PATTERN)`` in setup.py: the files it matches are the package's own, matched when checked."""


@dataclass
class SetupInfo:
    """What a setup.py gives setuptools, as far as it can be read: the name, ``data_files`` as (destination,
    sources) pairs, the ``console_scripts`` names, and why anything could not be read (line, reason)."""

    name: object = None
    data_files: List[Tuple[object, list]] = field(default_factory=list)
    scripts: Set[str] = field(default_factory=set)
    entry_points: Dict[str, str] = field(default_factory=dict)   # console_scripts name -> "module:function"
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
                                                                        call.line),
             "os.path.isfile": _is_file}
    try:
        read_module(Ctx(setup_py, {}, calls, on_skip=skipped, comprehensions=True),
                    parse_python(setup_py, "setup.py"))
    except RecursionError:   # every nesting is bounded; this is the backstop for their product
        raise WorldFileError("setup.py nests too deeply to read", path=setup_py, hint="simplify it") from None
    return info


def _is_file(ctx: Ctx, call: Call):
    """``os.path.isfile(p)`` of a glob's pattern: True, as a pattern stands for the files it matches (directories
    are never installed: see :func:`_sources`); of anything else not followed (it looks at the file system)."""
    if isinstance(call.arg(0, "path"), GlobPattern):
        return True
    return Unknown("os.path.isfile() is not followed (it looks at the file system)", call.line)


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
            name, target = (part.strip() for part in item.split("=", 1))
            info.scripts.add(name)
            info.entry_points[name] = target


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


def installed_files(pkg_dir: Path, info: SetupInfo) -> Dict[str, List[Path]]:
    """Where setup.py installs the package's files: destination folder (``share/NAME``, ``lib/NAME``) → the files
    (resolved), for the destinations that can be read."""
    installed: Dict[str, List[Path]] = {}
    for dest, sources in info.data_files:
        where = _destination(dest)
        if where is not None:
            installed.setdefault(where, []).extend(p.resolve() for p in _sources(pkg_dir, sources))
    return installed


def installed_source(pkg_dir: Path, relative: Path) -> Optional[Path]:
    """The file of the ament_python package ``pkg_dir`` that its setup.py installs as ``share/NAME/relative``
    (None when it installs none there, or setup.py cannot be read)."""
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
