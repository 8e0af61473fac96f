"""Input files read with a size cap: only regular files, at most :data:`MAX_INPUT_BYTES`.

A FIFO would block the read (or its opening) forever, ``/dev/zero`` never ends, and a file of gigabytes would be
parsed into many times its size in memory; all of them are refused at once, with a line that says so.
"""

from __future__ import annotations

import os
import stat
from pathlib import Path
from typing import Type

from .errors import InputError, WorldFileError, WorldgenError

MAX_INPUT_BYTES = 64 * 2 ** 20   # worlds, model files, launch files, meshes, URDF: the largest read
MAX_SPEC_BYTES = 4 * 2 ** 20     # floorplan specs and map_server YAML: hand-written text


def _mib(n: int) -> str:
    return f"{n / 2 ** 20:.0f} MiB" if n >= 2 ** 20 else f"{n} bytes"


def check_regular(path: str | Path, error: Type[WorldgenError] = WorldFileError, what: str = "file") -> None:
    """Refuse ``path`` when it exists but is not a regular file (a FIFO, a device, a socket); no open, no read."""
    try:
        mode = os.stat(path).st_mode
    except OSError:
        return   # missing or unreadable: the caller's own read says so
    if not stat.S_ISREG(mode) and not stat.S_ISDIR(mode):
        raise error(f"the {what} is not a regular file (a pipe, device or socket)", path=path,
                    hint="save it to a file and give that file's path")


def read_capped(path: str | Path, limit: int = MAX_INPUT_BYTES, error: Type[WorldgenError] = WorldFileError,
                what: str = "file") -> bytes:
    """The bytes of the regular file ``path``; ``error`` (one line) for a pipe, a device or a file over
    ``limit`` bytes. OSError (missing, no permission, a folder) is left to the caller."""
    fd = os.open(str(path), os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))   # a FIFO must not block the open
    try:
        info = os.fstat(fd)
        if stat.S_ISDIR(info.st_mode):
            raise IsADirectoryError(21, "Is a directory", str(path))
        if not stat.S_ISREG(info.st_mode):
            raise error(f"the {what} is not a regular file (a pipe, device or socket)", path=path,
                        hint="save it to a file and give that file's path")
        too_big = error(f"the {what} is larger than {_mib(limit)}, the most worldgen reads", path=path,
                        hint=f"split it or trim it under {_mib(limit)} (see Limits in the README)")
        if info.st_size > limit:
            raise too_big
        chunks, total = [], 0
        while True:
            chunk = os.read(fd, min(1 << 20, limit + 1 - total))
            if not chunk:
                break
            chunks.append(chunk)
            total += len(chunk)
            if total > limit:   # it grew while being read
                raise too_big
        return b"".join(chunks)
    finally:
        os.close(fd)


def read_text_capped(path: str | Path, limit: int = MAX_SPEC_BYTES, error: Type[WorldgenError] = WorldFileError,
                     what: str = "file") -> str:
    """:func:`read_capped` decoded as UTF-8 with newlines made ``\\n`` (as ``Path.read_text`` reads them);
    UnicodeDecodeError is left to the caller."""
    text = read_capped(path, limit, error, what).decode("utf-8")
    return text.replace("\r\n", "\n").replace("\r", "\n")


# files worldgen writes or a package holds that no command reads as its world: what each is, and what to do
NOT_READ = {
    ".py": ("a Python file (a node, or setup.py)",
            "run a node with worldgen run WORLD NODE.py; validate the package that holds it"),
    ".html": ("a page (worldgen view, drive, run and validate --html write these)", "open it in a web browser"),
    ".htm": ("a page", "open it in a web browser"),
    **{suffix: ("a picture", "give the world or spec it shows") for suffix in (".png", ".jpg", ".jpeg", ".svg")},
    ".pgm": ("a map image", "give the map's .yaml (map_server's), which names this image"),
    ".csv": ("a table (drive --csv, run --csv)", "give the world or spec it was made in"),
}


def refuse_unread(path: str | Path, wanted: str, error: Type[WorldgenError] = InputError) -> None:
    """``error`` when ``path`` is, by its suffix, a file no command reads as its world (:data:`NOT_READ`): what it
    is, not ``wanted`` ("a world or spec" …), and what to do instead."""
    suffix = Path(path).suffix.lower()
    if suffix in NOT_READ:
        what, hint = NOT_READ[suffix]
        raise error(f"is {what}, not {wanted}", path=path, hint=hint)
