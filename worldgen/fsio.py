"""Writing files all-or-nothing: every target is checked first, each file goes through a temporary file and
``os.replace``, so an error or a crash never leaves a half-written file behind."""

from __future__ import annotations

import os
import shutil
import tempfile
from pathlib import Path
from typing import Mapping

from .errors import OutputExistsError

FileData = str | bytes


def _as_bytes(data: FileData) -> bytes:
    return data.encode("utf-8") if isinstance(data, str) else data


def check_free(paths, force: bool) -> None:
    """Raise OutputExistsError naming the first existing path, unless ``force``."""
    if force:
        return
    for p in paths:
        if Path(p).exists():
            raise OutputExistsError(f"{p} exists", path=None,
                                    hint="pass --force to overwrite it, or choose another output with -o")


def write_files(files: Mapping[str | Path, FileData], *, force: bool = False,
                executable: frozenset[str] | set[str] = frozenset()) -> list[Path]:
    """Write every file of ``files`` (path → text or bytes) or none of them.

    Existing targets are refused before anything is written unless ``force``. Paths listed in
    ``executable`` (as given) get mode 0755, the rest 0644. Returns the written paths in the given order.
    """
    targets = [Path(p) for p in files]
    check_free(targets, force)
    staged: list[tuple[Path, Path]] = []
    try:
        for key, data in files.items():
            target = Path(key)
            target.parent.mkdir(parents=True, exist_ok=True)
            fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".tmp", dir=target.parent)
            with os.fdopen(fd, "wb") as fh:
                fh.write(_as_bytes(data))
            os.chmod(tmp, 0o755 if str(key) in executable else 0o644)
            staged.append((Path(tmp), target))
    except BaseException:
        for tmp, _ in staged:
            tmp.unlink(missing_ok=True)
        raise
    for tmp, target in staged:
        os.replace(tmp, target)
    return targets


def write_file(path: str | Path, data: FileData, *, force: bool = False) -> Path:
    """Write one file atomically; see :func:`write_files`."""
    return write_files({path: data}, force=force)[0]


def write_tree(root: str | Path, files: Mapping[str, FileData], *, force: bool = False,
               executable: frozenset[str] | set[str] = frozenset(), dirs: tuple[str, ...] = ()) -> Path:
    """Create the folder ``root`` holding ``files`` (relative path → data) and empty ``dirs``, all or nothing.

    The tree is built in a temporary sibling folder and renamed into place, so a failure leaves no partial
    folder. An existing ``root`` is refused unless ``force``, in which case it is replaced.
    """
    root = Path(root)
    check_free([root], force)
    root.parent.mkdir(parents=True, exist_ok=True)
    staging = Path(tempfile.mkdtemp(prefix=f".{root.name}.", dir=root.parent))
    try:
        for d in dirs:
            (staging / d).mkdir(parents=True, exist_ok=True)
        for rel, data in files.items():
            p = staging / rel
            p.parent.mkdir(parents=True, exist_ok=True)
            p.write_bytes(_as_bytes(data))
            p.chmod(0o755 if rel in executable else 0o644)
        staging.chmod(0o755)
        if root.exists():
            shutil.rmtree(root)
        os.replace(staging, root)
    except BaseException:
        shutil.rmtree(staging, ignore_errors=True)
        raise
    return root
