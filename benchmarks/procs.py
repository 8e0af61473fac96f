"""What the benchmarks read of running processes: a process's CPU time, and the simulator node of one run."""

from __future__ import annotations

import os
from pathlib import Path


def cpu_seconds(pid: int) -> float:
    """User plus system CPU time of process ``pid`` so far (Linux /proc)."""
    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def simulator_pid(marker: bytes) -> int | None:
    """The simulator node (``python -m worldgen.ros1``) whose environment holds ``marker``
    (``NAME=value``), if one runs."""
    for entry in Path("/proc").iterdir():
        try:
            if entry.name.isdigit() and b"-m\0worldgen.ros1\0" in (entry / "cmdline").read_bytes() and \
                    marker in (entry / "environ").read_bytes():
                return int(entry.name)
        except OSError:
            continue
    return None
