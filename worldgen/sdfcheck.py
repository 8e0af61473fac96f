"""libsdformat's own check of a world or model file, where the library is installed.

libsdformat exports ``cmdCheck(path)``, the function behind ``ign sdf -k``: it parses the file as Gazebo would,
converts it to the library's newest SDF version, checks names, poses and frames, prints what is wrong to stderr
and returns 0 or -1. It is called through ctypes in a child process, so that its messages (written by C code
straight to the file descriptors) can be captured and a crash in the library cannot take the caller down.
``model://`` includes are resolved through ``SDF_PATH``, which the child inherits.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

LIBRARIES = ("libsdformat12.so.12", "libsdformat12.so", "libsdformat13.so.13", "libsdformat14.so.14")
_ABSENT = 3     # the child's exit code when no library with cmdCheck loads
_COLOUR = re.compile(r"\x1b\[[0-9;]*m")

_CHILD = f"""
import ctypes, sys
for name in {LIBRARIES!r}:
    try:
        check = ctypes.CDLL(name).cmdCheck
    except (OSError, AttributeError):
        continue
    check.argtypes = [ctypes.c_char_p]
    check.restype = ctypes.c_int
    sys.exit(0 if check(sys.argv[1].encode()) == 0 else 1)
sys.exit({_ABSENT})
"""


def sdformat_check(path: str | Path, *, timeout: float = 300.0) -> tuple[bool, str] | None:
    """``(valid, messages)`` from libsdformat's check of ``path``, or None when the library is not installed.

    ``messages`` is what the library printed (stdout and stderr, without colour codes). A crash or a timeout
    counts as not valid, with the reason in ``messages``.
    """
    cmd = [sys.executable, "-c", _CHILD, os.fspath(Path(path).resolve())]
    try:
        done = subprocess.run(cmd, capture_output=True, text=True, errors="replace", timeout=timeout)
    except subprocess.TimeoutExpired:
        return False, f"libsdformat did not finish checking {path} within {timeout:g} s"
    if done.returncode == _ABSENT:
        return None
    messages = _COLOUR.sub("", "\n".join(p.strip() for p in (done.stdout, done.stderr) if p.strip()))
    if done.returncode < 0:
        return False, f"libsdformat crashed (signal {-done.returncode}) checking {path}\n{messages}".strip()
    return done.returncode == 0, messages
