"""Robot descriptions processed once and kept: xacro's output on disk, keyed by what it was made from.

Every command that needs a robot (``validate``'s checks and its simulation, ``drive``, ``run``) turns its xacro
file into URDF text, which costs importing xacro and running it. Here the text is kept in worldgen's cache folder
(:func:`worldgen.core.resources.cache_dir`, ``robots/KEY.json``). KEY is a digest of what names the processing:
the file, its ``name:=value`` mappings, the package search path, worldgen's version, the xacro installed and
the code that processes it. An entry also lists what the processing read, each checked before the entry is used:
every file xacro opened (its size and modification time), every environment variable looked up (``$(env)``,
``$(optenv)``) and every package found (``$(find)``); one that changed means processing again.

A cache folder that cannot be written or read is no error: the text is made again. Entries are written whole
(a temporary file renamed over the entry), so processes running at once never read half of one.
"""

from __future__ import annotations

import hashlib
import importlib.util
import json
import os
import tempfile
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

from .. import __version__
from ..core.resources import cache_dir

FORMAT = 1   # of the entries; a change of what is stored changes it


@dataclass
class Inputs:
    """What one processing read: files (path → [mtime_ns, size], None when missing), environment variables
    (name → value, None when unset) and packages (name → folder)."""

    files: dict[str, list[int] | None] = field(default_factory=dict)
    env: dict[str, str | None] = field(default_factory=dict)
    packages: dict[str, str] = field(default_factory=dict)

    def add_file(self, path: str | Path) -> None:
        self.files[str(path)] = _stamp(path)


def cached_urdf(path: Path, mappings: dict[str, str], search: list[Path], find: Callable[[str], Path],
                make: Callable[[Inputs], str], code: str) -> str:
    """The URDF text of xacro file ``path`` with ``mappings``: the kept one while everything it was made from is
    unchanged (``search``: the package search path; ``find``: how a package is found now; ``code``: the file of
    the code that processes it), else ``make(inputs)``'s, which records in ``inputs`` what it reads, kept for
    next time."""
    entry_file = _entry_file(path, mappings, search, code)
    text = _load(entry_file, find) if entry_file is not None else None
    if text is not None:
        return text
    inputs = Inputs()
    inputs.add_file(path)
    text = make(inputs)
    if entry_file is not None:
        _store(entry_file, text, inputs)
    return text


def _entry_file(path: Path, mappings: dict[str, str], search: list[Path], code: str) -> Path | None:
    try:
        xacro = importlib.util.find_spec("xacro")
    except (ImportError, ValueError):
        return None
    if xacro is None or xacro.origin is None:
        return None
    key = json.dumps({"format": FORMAT, "worldgen": __version__, "file": str(path),
                      "mappings": sorted(mappings.items()), "search": [str(p) for p in search],
                      "xacro": [xacro.origin, _stamp(xacro.origin)],
                      "code": [_stamp(code), _stamp(__file__)]})
    return cache_dir() / "robots" / f"{hashlib.sha256(key.encode('utf-8')).hexdigest()[:24]}.json"


def _load(entry_file: Path, find: Callable[[str], Path]) -> str | None:
    try:
        entry = json.loads(entry_file.read_text(encoding="utf-8"))
        if entry.get("format") != FORMAT:
            return None
        if any(_stamp(name) != stamp for name, stamp in entry["files"].items()):
            return None
        if any(os.environ.get(name) != value for name, value in entry["env"].items()):
            return None
        for name, folder in entry["packages"].items():
            try:
                if str(find(name)) != folder:
                    return None
            except LookupError:
                return None
        return entry["urdf"] if isinstance(entry["urdf"], str) else None
    except (OSError, ValueError, KeyError, TypeError, AttributeError):
        return None


def _store(entry_file: Path, text: str, inputs: Inputs) -> None:
    entry = {"format": FORMAT, "files": inputs.files, "env": inputs.env, "packages": inputs.packages, "urdf": text}
    try:
        entry_file.parent.mkdir(parents=True, exist_ok=True)
        fd, temp = tempfile.mkstemp(prefix=".entry-", dir=entry_file.parent)
        try:
            with os.fdopen(fd, "w", encoding="utf-8") as fh:
                json.dump(entry, fh)
            os.replace(temp, entry_file)
        except BaseException:
            os.unlink(temp)
            raise
    except OSError:   # a read-only or full cache folder: nothing kept
        pass


def _stamp(path: str | Path) -> list[int] | None:
    try:
        st = os.stat(path)
    except OSError:
        return None
    return [st.st_mtime_ns, st.st_size]
