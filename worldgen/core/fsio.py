"""Writing files all-or-nothing: every target is checked first, each file goes through a temporary file and
``os.replace``, so an error or a crash never leaves a half-written file behind."""

from __future__ import annotations

import os
import shutil
import tempfile
from pathlib import Path
from typing import Mapping, Union

from .errors import InputError, OutputExistsError

FileData = Union[str, bytes]


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
    for target in targets:   # os.replace cannot put a file over a folder, and would fail half-way through
        if target.is_dir():
            raise InputError(f"{target} is a folder", hint="remove it, or choose another output with -o")
    staged: list[tuple[Path, Path]] = []
    try:
        for key, data in files.items():
            target = Path(key)
            target.parent.mkdir(parents=True, exist_ok=True)
            fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".tmp", dir=target.parent)
            staged.append((Path(tmp), target))
            with os.fdopen(fd, "wb") as fh:
                fh.write(_as_bytes(data))
            os.chmod(tmp, 0o755 if str(key) in executable else 0o644)
    except BaseException as err:
        for tmp, _ in staged:
            tmp.unlink(missing_ok=True)
        if isinstance(err, OSError):   # a folder that cannot be made or written to: the user's to fix
            raise _unwritable(err, target) from None
        raise
    for tmp, target in staged:
        os.replace(tmp, target)
    return targets


def _unwritable(err: OSError, target: Path) -> InputError:
    return InputError(f"cannot write {err.filename or target}: {err.strerror}",
                      hint="check that the output folder can be created and written to")


def write_file(path: str | Path, data: FileData, *, force: bool = False) -> Path:
    """Write one file atomically; see :func:`write_files`."""
    return write_files({path: data}, force=force)[0]


def write_tree(root: str | Path, files: Mapping[str, FileData], *, force: bool = False,
               executable: frozenset[str] | set[str] = frozenset()) -> Path:
    """Create the folder ``root`` holding ``files`` (relative path → data), all or nothing.

    The tree is built in a temporary sibling folder and renamed into place, so a failure leaves no partial
    folder. An existing ``root`` (folder, file or link) is refused unless ``force``, in which case it is replaced.
    """
    root = Path(root)
    check_free([root], force)
    try:
        root.parent.mkdir(parents=True, exist_ok=True)
        staging = Path(tempfile.mkdtemp(prefix=f".{root.name}.", dir=root.parent))
    except OSError as err:   # a parent that is a file, or a folder we may not write to
        raise _unwritable(err, root) from None
    try:
        for rel, data in files.items():
            p = staging / rel
            p.parent.mkdir(parents=True, exist_ok=True)
            p.write_bytes(_as_bytes(data))
            p.chmod(0o755 if rel in executable else 0o644)
        staging.chmod(0o755)
        if root.is_dir() and not root.is_symlink():
            shutil.rmtree(root)
        elif root.exists() or root.is_symlink():
            root.unlink()
        os.replace(staging, root)
    except BaseException as err:
        shutil.rmtree(staging, ignore_errors=True)
        if isinstance(err, OSError):
            raise _unwritable(err, root) from None
        raise
    return root
