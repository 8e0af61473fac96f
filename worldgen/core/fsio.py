"""Writing outputs so that a failure, a kill or a second writer never leaves a mix.

* One file: written to a temporary file beside the target (``.NAME.worldgen-tmp-PID-XXXX``), then put in place
  with one call: without ``force`` by ``renameat2(RENAME_NOREPLACE)`` or ``os.link`` (both fail when anything, even
  a dangling symbolic link, is at the target, so of two writers exactly one wins); with ``force`` by ``os.replace``
  (a symbolic link at the target is itself replaced, its target is not touched).
* Several files (``build --model-dir``, ``build --package``): every temporary file is written first, then a journal
  ``.NAME.worldgen-journal-PID`` listing the moves is renamed into place — the commit point — and the moves follow.
  Before the commit nothing is in place; a kill during the moves (microseconds) leaves the journal, which the next
  run writing there completes, so the result is the old set or the new set.
* A folder (``scaffold``, ``course``): built as ``.NAME.worldgen-staging-PID`` beside it, then renamed in; an existing
  folder (with ``force``) is swapped with it in one ``renameat2(RENAME_EXCHANGE)`` where Linux offers it (else moved
  aside as ``.NAME.worldgen-old-PID`` first, and restored by the next run if the kill came in between).
* Every write first sweeps the folders it writes to for these names left by a run that was killed (its PID is
  gone, or the file is older than :data:`STALE_SECONDS`). Folders made for the output are removed again on failure.
"""

from __future__ import annotations

import errno
import json
import os
import re
import shutil
import sys
import tempfile
import time
from pathlib import Path
from typing import Iterable, List, Mapping, Tuple, Union

from .errors import InputError, OutputExistsError

FileData = Union[str, bytes]
STALE_SECONDS = 15 * 60   # a worldgen run holds its staging for well under a second; older ones are leftovers
_LEFTOVER = re.compile(r"^\.(?P<name>.+)\.worldgen-(?P<kind>tmp|journal|staging|old)-(?P<pid>\d+)(?:-[A-Za-z0-9_]*)?$")
_RENAME_NOREPLACE, _RENAME_EXCHANGE = 1, 2
_LIBC: dict = {}
_FORCE_HINT = "pass --force to overwrite it, or give another name"


def _as_bytes(data: FileData) -> bytes:
    if isinstance(data, bytes):
        return data
    try:
        return data.encode("utf-8")
    except UnicodeEncodeError:   # a command-line value holding bytes that are not UTF-8 (surrogate escapes)
        raise InputError("a value to be written holds bytes that are not UTF-8 text",
                         hint="check the command's values for characters from a non-UTF-8 file name or locale") \
            from None


def _exists(p: str | Path) -> bool:
    return os.path.lexists(p)   # a dangling symbolic link counts: writing there would follow it


def check_free(paths, force: bool) -> None:
    """Raise OutputExistsError naming the first path that exists (a dangling symbolic link too), unless ``force``."""
    if force:
        return
    for p in paths:
        if _exists(p):
            raise _exists_error(p)


def _exists_error(p) -> OutputExistsError:
    what = "is a symbolic link" if os.path.islink(p) else "exists"
    return OutputExistsError(f"{p} {what}", path=None, hint=_FORCE_HINT)


def _unwritable(err: OSError, target: Path) -> InputError:
    full = err.errno in (errno.ENOSPC, getattr(errno, "EDQUOT", errno.ENOSPC), errno.EFBIG)
    return InputError(f"cannot write {err.filename or target}: {err.strerror}",
                      hint="free some space there, or choose another output" if full else
                      "check that the output folder can be created and written to")


# ------------------------------------------------------------------------------------------ leftovers
def _alive(pid: int) -> bool:
    if pid == os.getpid():
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except (PermissionError, OverflowError):
        return pid > 0
    return True


def _leftovers(folder: Path) -> List[Tuple[Path, str, str]]:
    """(path, kind, name) of every abandoned worldgen staging entry in ``folder``."""
    found = []
    try:
        names = os.listdir(folder)
    except OSError:
        return found
    now = time.time()
    for entry in names:
        m = _LEFTOVER.match(entry)
        if m is None:
            continue
        p = folder / entry
        try:
            age = now - os.lstat(p).st_mtime
        except OSError:
            continue
        if int(m.group("pid")) != os.getpid() and (not _alive(int(m.group("pid"))) or age > STALE_SECONDS):
            found.append((p, m.group("kind"), m.group("name")))
    return found


def sweep(folders: Iterable[str | Path]) -> None:
    """Finish or remove what killed worldgen runs left in ``folders``: committed journals are completed, then
    staging folders, moved-aside folders and temporary files are removed (a moved-aside folder whose place is
    empty is put back)."""
    entries = [e for f in dict.fromkeys(Path(f) for f in folders) for e in _leftovers(f)]
    order = {"journal": 0, "old": 1, "staging": 2, "tmp": 3}
    for p, kind, name in sorted(entries, key=lambda e: order[e[1]]):
        try:
            if kind == "journal":
                _replay(p)
            elif kind == "old" and not _exists(p.parent / name):
                os.rename(p, p.parent / name)
            else:
                _remove(p)
        except OSError:
            pass   # not ours to fix: the write that follows reports what it meets


def _remove(p: Path) -> None:
    if p.is_dir() and not p.is_symlink():
        shutil.rmtree(p, ignore_errors=True)
    elif _exists(p):
        os.unlink(p)


def _replay(journal: Path) -> None:
    """Complete the moves of a committed journal (those still waiting), then drop it."""
    try:
        plan = json.loads(journal.read_text(encoding="utf-8"))
        moves = [(Path(move[0]), Path(move[1]), len(move) > 2) for move in plan["moves"]]
        force = bool(plan["force"])
    except (OSError, ValueError, KeyError, TypeError, IndexError):
        moves, force = [], False
    for tmp, target, replace in moves:   # replace: a file the run was updating in place
        if _exists(tmp):
            _move(tmp, target, force or replace, replay=True)
    os.unlink(journal)


# ------------------------------------------------------------------------------------------ moves
def _renameat2(src: Path, dst: Path, flags: int) -> bool:
    """Linux's renameat2; False where the system or file system does not offer it."""
    if not sys.platform.startswith("linux"):
        return False
    import ctypes

    fn = _LIBC.get("renameat2", False)
    if fn is False:
        try:
            fn = ctypes.CDLL(None, use_errno=True).renameat2
            fn.argtypes = [ctypes.c_int, ctypes.c_char_p, ctypes.c_int, ctypes.c_char_p, ctypes.c_uint]
        except (AttributeError, OSError):   # a C library older than glibc 2.28
            fn = None
        _LIBC["renameat2"] = fn
    if fn is None:
        return False
    at_fdcwd = -100
    if fn(at_fdcwd, os.fsencode(str(src)), at_fdcwd, os.fsencode(str(dst)), flags) == 0:
        return True
    code = ctypes.get_errno()
    if code in (errno.ENOSYS, errno.EINVAL, errno.EOPNOTSUPP, errno.ENOTSUP):
        return False
    raise OSError(code, os.strerror(code), str(dst))


def _claim(tmp: Path, target: Path) -> None:
    """Move the file ``tmp`` to ``target`` only if nothing is there, atomically: renameat2(RENAME_NOREPLACE), else a
    hard link (then the temporary name is dropped), else — a file system with neither — a check and a rename."""
    try:
        if _renameat2(tmp, target, _RENAME_NOREPLACE):
            return
        os.link(tmp, target, follow_symlinks=False)
    except FileExistsError:
        raise _exists_error(target) from None
    except OSError as err:
        if err.errno not in (errno.EPERM, errno.EOPNOTSUPP, errno.ENOTSUP, errno.EMLINK, errno.EXDEV):
            raise
        if _exists(target):
            raise _exists_error(target) from None
        os.rename(tmp, target)
        return
    os.unlink(tmp)


def _move(tmp: Path, target: Path, force: bool, replay: bool = False) -> None:
    if force:
        os.replace(tmp, target)
    elif replay and (os.lstat(tmp).st_nlink > 1 or _exists(target)):   # linked already (no renameat2 here)
        os.unlink(tmp)
    else:
        _claim(tmp, target)


def _make_folders(folder: Path) -> List[Path]:
    """Create ``folder`` and missing parents; returns the ones made here (deepest last)."""
    missing = []
    p = folder
    while not os.path.lexists(p):   # a file on the way: mkdir below says "Not a directory"
        missing.append(p)
        if p.parent == p:
            break
        p = p.parent
    if not missing and not os.path.isdir(folder):
        raise NotADirectoryError(errno.ENOTDIR, os.strerror(errno.ENOTDIR), str(folder))
    made = []
    for p in reversed(missing):
        try:
            os.mkdir(p)
        except FileExistsError:
            if not os.path.isdir(p):
                raise
            continue
        made.append(p)
    return made


def _remove_folders(made: Iterable[Path]) -> None:
    for p in sorted(set(made), key=lambda q: len(q.parts), reverse=True):
        try:
            os.rmdir(p)
        except OSError:
            pass   # not empty: another writer uses it


def _temp_beside(target: Path, data: bytes, mode: int) -> Path:
    fd, tmp = tempfile.mkstemp(prefix=f".{target.name[:80]}.worldgen-tmp-{os.getpid()}-", dir=target.parent)
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(data)
        os.chmod(tmp, mode)
    except BaseException:
        os.unlink(tmp)
        raise
    return Path(tmp)


# ------------------------------------------------------------------------------------------ files
def check_within(targets: Iterable[Path], root: Path) -> None:
    """InputError when a folder between ``root`` (an output folder, itself taken as given) and one of ``targets``
    is a symbolic link: a writer never writes through a link inside its output, which may lead anywhere."""
    for target in targets:
        try:
            parts = Path(target).parent.relative_to(root).parts
        except ValueError:
            continue
        folder = Path(root)
        for part in parts:
            folder = folder / part
            if folder.is_symlink():
                raise InputError(f"{folder} is a symbolic link (to {os.readlink(folder)}): worldgen does not write "
                                 f"through a link inside {root}", path=target,
                                 hint="replace the link with a folder, or remove it")


def write_files(files: Mapping[str | Path, FileData], *, force: bool = False,
                executable: frozenset[str] | set[str] = frozenset(), within: Path | None = None,
                update: frozenset | set = frozenset()) -> list[Path]:
    """Write every file of ``files`` (path → text or bytes) or none of them (see the module docstring).

    Existing targets (a symbolic link too, dangling or not) are refused unless ``force``; with ``force`` a link
    is replaced, not followed. Paths listed in ``executable`` (as given) get mode 0755, the rest 0644. With
    ``within`` (an output folder such as a package), nothing is written through a symlinked folder inside it
    (:func:`check_within`). Paths in ``update`` are files the command rewrites in place (a package's package.xml
    given the dependencies of the launch file written into it): never refused, put in place after every other
    file, so never taken back. Returns the written paths in the given order.
    """
    targets = [Path(p) for p in files]
    updates = {Path(p) for p in update}
    if within is not None:
        check_within(targets, Path(within))
    sweep(t.parent for t in targets)
    check_free([t for t in targets if t not in updates], force)
    for target in targets:   # a file cannot be put over a folder
        if target.is_dir() and not target.is_symlink():
            raise InputError(f"{target} is a folder", hint="remove it, or choose another output with -o")
    made: list[Path] = []
    staged: list[tuple[Path, Path]] = []
    journal = None
    target = targets[0] if targets else Path(".")
    try:
        for key, data in sorted(files.items(), key=lambda item: Path(item[0]) in updates):   # updates last
            target = Path(key)
            made += _make_folders(target.parent)
            staged.append((_temp_beside(target, _as_bytes(data), 0o755 if str(key) in executable else 0o644),
                           target))
        if len(staged) > 1:
            journal = _commit(staged, force, updates)
        done: list[Path] = []
        for tmp, target in staged:
            try:
                _move(tmp, target, force or target in updates)
            except OutputExistsError:   # another writer took this one first: take back the ones placed
                for mine in done:
                    os.unlink(mine)
                raise
            done.append(target)
        if journal is not None:
            os.unlink(journal)
    except BaseException as err:
        for tmp, _ in staged:
            if _exists(tmp):
                os.unlink(tmp)
        if journal is not None and _exists(journal):
            os.unlink(journal)
        _remove_folders(made)
        if isinstance(err, OSError):   # a folder that cannot be made or written to, a full disk: the user's to fix
            raise _unwritable(err, target) from None
        raise
    return targets


def _commit(staged: list[tuple[Path, Path]], force: bool, updates=frozenset()) -> Path:
    """Write the journal of ``staged`` moves beside the first target; its rename is the commit point. A move
    onto one of ``updates`` replaces what is there (its third field)."""
    first = staged[0][1]
    journal = first.parent / f".{first.name[:80]}.worldgen-journal-{os.getpid()}"
    text = json.dumps({"force": force, "moves": [[os.path.abspath(t), os.path.abspath(p)] + ([True] if p in updates
                                                                                        else []) for t, p in staged]})
    tmp = _temp_beside(first, text.encode("utf-8"), 0o644)
    os.rename(tmp, journal)
    return journal


def write_file(path: str | Path, data: FileData, *, force: bool = False) -> Path:
    """Write one file atomically; see :func:`write_files`."""
    return write_files({path: data}, force=force)[0]


# ------------------------------------------------------------------------------------------ folders
def write_tree(root: str | Path, files: Mapping[str, FileData], *, force: bool = False,
               executable: frozenset[str] | set[str] = frozenset()) -> Path:
    """Create the folder ``root`` holding ``files`` (relative path → data), all or nothing.

    The tree is built in a staging sibling folder and renamed into place, so a failure or a kill leaves the old
    folder or the new one. An existing ``root`` (folder, file or link) is refused unless ``force``, in which case
    it is replaced as a whole (a link itself, not what it points to).
    """
    root = Path(root)
    sweep([root.parent])
    check_free([root], force)
    made: list[Path] = []
    staging = root.parent / f".{root.name}.worldgen-staging-{os.getpid()}"
    try:
        made = _make_folders(root.parent)
        _remove(staging)
        os.mkdir(staging)
        for rel, data in files.items():
            p = staging / rel
            p.parent.mkdir(parents=True, exist_ok=True)
            p.write_bytes(_as_bytes(data))
            p.chmod(0o755 if rel in executable else 0o644)
        staging.chmod(0o755)
        _swap_in(staging, root, force)
    except BaseException as err:
        _remove(staging)
        _remove_folders(made)
        if isinstance(err, OSError):
            raise _unwritable(err, root) from None
        raise
    return root


def _swap_in(staging: Path, root: Path, force: bool) -> None:
    """Put the folder ``staging`` at ``root`` in one step; the old ``root`` (with ``force``) ends up at
    ``staging`` and is removed."""
    if not _exists(root):
        try:
            placed = _renameat2(staging, root, _RENAME_NOREPLACE)
        except FileExistsError:
            placed = False   # another writer got there first
        else:
            if not placed:   # no renameat2: rename fails on anything at root but an empty folder
                try:
                    os.rename(staging, root)
                    placed = True
                except OSError as err:
                    if err.errno not in (errno.EEXIST, errno.ENOTEMPTY, errno.ENOTDIR, errno.EISDIR):
                        raise
        if placed:
            return
    if not force:
        raise _exists_error(root)
    if _renameat2(staging, root, _RENAME_EXCHANGE):
        _remove(staging)
        return
    aside = root.parent / f".{root.name}.worldgen-old-{os.getpid()}"
    os.rename(root, aside)
    os.rename(staging, root)
    _remove(aside)
