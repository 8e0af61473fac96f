"""pybullet imported without its greeting: the first ``import pybullet`` of a process prints ``pybullet build time:
…`` on the process's stderr, which a simulator process that shares its terminal (``worldgen sim``) would show the
student. :func:`import_pybullet` imports it with stderr pointed at /dev/null for that moment."""

from __future__ import annotations

import os
import sys


def import_pybullet():
    """pybullet, imported (once) with file descriptor 2 silenced for the import."""
    if "pybullet" in sys.modules:
        return sys.modules["pybullet"]
    sys.stderr.flush()
    saved = os.dup(2)
    try:
        with open(os.devnull, "w") as null:
            os.dup2(null.fileno(), 2)
            import pybullet
    finally:
        os.dup2(saved, 2)
        os.close(saved)
    return pybullet
