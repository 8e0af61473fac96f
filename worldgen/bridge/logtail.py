"""A child's output kept bounded, however much it prints: its first lines (:data:`HEAD` bytes) and its last
:data:`TAIL` bytes.

The child writes straight into its log file (no copy through worldgen, so a node that prints fast is not slowed by
us). Reading the log (:func:`read_kept`) reads the head and the tail only, with one line between them saying how
much was left out, so worldgen's memory stays bounded; and while the child runs, the keeper
(:mod:`.keeper`) frees the disk blocks between head and tail (:func:`trim`: the file keeps its length, the middle
becomes a hole) where the file system can punch holes (ext4, xfs, btrfs, tmpfs), so the disk stays bounded too.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path

HEAD = 64 * 1024          # the first lines kept
TAIL = 1024 * 1024        # the last bytes kept
BLOCK = 4096
TRIM_AT = 4 * 1024 * 1024  # bytes past head and tail before the middle is freed on disk


@dataclass(frozen=True)
class Kept:
    """What is kept of one output: the text (with a line marking the cut), how many bytes the process wrote, and
    how many of them were left out."""

    text: str
    written: int
    cut: int


def amount(size: int) -> str:
    """``size`` bytes as a person reads it: 512 bytes, 64 KB, 398.2 MB, 1.3 GB (decimal units)."""
    if size < 1000:
        return f"{size} bytes"
    for unit, scale in (("KB", 1e3), ("MB", 1e6), ("GB", 1e9)):
        if size < scale * 1000 or unit == "GB":
            value = size / scale
            return f"{value:.0f} {unit}" if value >= 100 else f"{value:.1f} {unit}"
    raise AssertionError("unreachable")


def read_kept(path: Path | str, head: int = HEAD, tail: int = TAIL) -> Kept:
    """The kept part of the log at ``path`` (never more than ``head + tail`` bytes read); an unreadable or missing
    log is empty."""
    try:
        with open(path, "rb") as handle:
            size = os.fstat(handle.fileno()).st_size
            if size <= head + tail:
                data = handle.read(head + tail)
                return Kept(_text(data), len(data), 0)
            first = handle.read(head)
            handle.seek(size - tail)
            last = handle.read(tail)
    except OSError:
        return Kept("", 0, 0)
    if b"\n" in first:                      # whole lines on both sides of the cut
        first = first[:first.rfind(b"\n") + 1]
    newline = last.find(b"\n")
    if 0 <= newline < len(last) - 1:
        last = last[newline + 1:]
    cut = size - len(first) - len(last)
    marker = f"[worldgen: {amount(cut)} of this output left out here; the first and the last lines are kept]\n"
    return Kept(_text(first) + marker + _text(last), size, cut)


def _text(data: bytes) -> str:
    return data.decode("utf-8", errors="replace")


def _punch():
    """libc's fallocate, or None (not Linux, no libc)."""
    try:
        import ctypes

        libc = ctypes.CDLL(None, use_errno=True)
        call = getattr(libc, "fallocate64", None) or libc.fallocate
    except (OSError, AttributeError):
        return None
    call.argtypes = [ctypes.c_int, ctypes.c_int, ctypes.c_int64, ctypes.c_int64]
    call.restype = ctypes.c_int
    return call


FALLOC_FL_KEEP_SIZE = 0x01
FALLOC_FL_PUNCH_HOLE = 0x02
_FALLOCATE = _punch()


def trim(fd: int, done: int, head: int = HEAD, tail: int = TAIL) -> int:
    """Free on disk the part of the open log ``fd`` between its head and its tail that is not freed yet (``done``:
    where the last trim ended; 0 at first). Returns the new ``done``, or -1 when the file system cannot (then the
    caller stops trying: only the disk is not bounded, reading still is)."""
    if _FALLOCATE is None:
        return -1
    try:
        size = os.fstat(fd).st_size
    except OSError:
        return done
    start = max(done, -(-head // BLOCK) * BLOCK)
    end = (size - tail) // BLOCK * BLOCK
    if end - start < TRIM_AT:
        return done
    if _FALLOCATE(fd, FALLOC_FL_PUNCH_HOLE | FALLOC_FL_KEEP_SIZE, start, end - start) != 0:
        return -1
    return end
