"""`worldgen run` with a node printing hundreds of megabytes (issue 25: 876 MB peak for a node printing 400 MB):

- worldgen's peak memory: the resident set at its highest (``ru_maxrss`` of RUSAGE_SELF) of a fresh Python running
  the command in-process, for a node printing MB megabytes and for the same node printing nothing (target: within
  100 MB of each other, whatever MB is);
- the node's log on disk (blocks allocated, polled every 50 ms while the run goes): at its largest, while a burst
  outruns the keeper's next trim (every 50 ms, 10 ms while a log grows; target under 100 MB for 400 MB printed at
  once, against all of it without), and at its last reading (target: under 6 MB, head + tail + one trim's slack),
  where the file system punches holes;
- the wall time of both runs, for the record.

    .venv/bin/python benchmarks/bench_run_output.py [MB]      (default 400)

``WORLDGEN_BENCH_PATH`` puts another checkout's worldgen first (to measure an older version the same way).
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
NODE = REPO / "tests" / "rosnodes" / "prints_a_lot.py"
ROOM = REPO / "examples" / "enclosed_room.yaml"

RUNNER = r"""
import resource, sys
from worldgen.cli import main
try:
    main(["run", sys.argv[1], sys.argv[2], "mb:=" + sys.argv[3], "--rate", "max", "--duration", "2",
          "--format", "json"], standalone_mode=False)
finally:
    print("MAXRSS", resource.getrusage(resource.RUSAGE_SELF).ru_maxrss, file=sys.stderr, flush=True)
"""


def largest_log(folder: Path, stop: threading.Event, found: list) -> None:
    """Keep in ``found[0]`` the most disk any node log under ``folder`` took (bytes allocated) until ``stop``."""
    while not stop.is_set():
        for log in folder.glob("*/node_*.log"):
            try:
                found[0] = max(found[0], log.stat().st_blocks * 512)
                found[1] = max(found[1], log.stat().st_size)
                found[2] = log.stat().st_blocks * 512
            except OSError:
                pass
        time.sleep(0.05)


def one_run(mb: int) -> dict:
    with tempfile.TemporaryDirectory(prefix="bench_run_output_") as tmp:
        path = os.pathsep.join(p for p in (os.environ.get("WORLDGEN_BENCH_PATH"), str(REPO)) if p)
        env = dict(os.environ, TMPDIR=tmp, PYTHONPATH=path)
        env.pop("ROS_MASTER_URI", None)
        stop, found = threading.Event(), [0, 0, 0]
        watcher = threading.Thread(target=largest_log, args=(Path(tmp), stop, found))
        watcher.start()
        started = time.monotonic()
        done = subprocess.run([sys.executable, "-c", RUNNER, str(ROOM), str(NODE), str(mb)], env=env, cwd=tmp,
                              stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, timeout=600)
        took = time.monotonic() - started
        stop.set()
        watcher.join()
    rss = [int(line.split()[1]) for line in done.stderr.splitlines() if line.startswith("MAXRSS ")]
    if done.returncode != 0 or not rss:
        raise SystemExit(f"the run failed:\n{done.stderr[-2000:]}")
    return {"peak_rss_mb": rss[0] / 1024, "log_disk_mb": found[0] / 1e6, "log_size_mb": found[1] / 1e6,
            "log_disk_last_mb": found[2] / 1e6, "seconds": took}


def main() -> None:
    mb = int(sys.argv[1]) if len(sys.argv) > 1 else 400
    quiet, loud = one_run(0), one_run(mb)
    for name, result in (("quiet node", quiet), (f"node printing {mb} MB", loud)):
        print(f"{name:>24}: worldgen peak RSS {result['peak_rss_mb']:7.1f} MB; the node's log "
              f"{result['log_size_mb']:7.1f} MB long, {result['log_disk_mb']:6.1f} MB on disk at most, "
              f"{result['log_disk_last_mb']:5.1f} MB at the end; "
              f"{result['seconds']:5.1f} s")
    extra = loud["peak_rss_mb"] - quiet["peak_rss_mb"]
    print(f"peak RSS above the quiet run: {extra:.1f} MB (target < 100): {'ok' if extra < 100 else 'MISSED'}")
    print(f"log on disk at most: {loud['log_disk_mb']:.1f} MB (target < 100): "
          f"{'ok' if loud['log_disk_mb'] < 100 else 'MISSED'}; at the end {loud['log_disk_last_mb']:.1f} MB "
          f"(target < 6): {'ok' if loud['log_disk_last_mb'] < 6 else 'MISSED'}")


if __name__ == "__main__":
    main()
