"""How fast ``worldgen build`` is, as a user runs it: the whole process, Python start included.

Prints, for the class room (examples/enclosed_room.yaml) and for a generated 20 × 20 grid of 400 rooms sharing
walls, with a door between every pair of neighbours, the median wall time of 5 runs of ``worldgen build`` and the
peak memory (max RSS) of each run's process. Targets: class room < 0.3 s, 400 rooms < 3 s.

    python benchmarks/bench_build.py [--runs N]
"""

from __future__ import annotations

import argparse
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
CLASS_ROOM = REPO / "examples" / "enclosed_room.yaml"
TARGETS = {"class room": 0.3, "400 rooms": 3.0}


def grid_spec(n: int = 20, size: float = 3.0) -> str:
    """An n × n grid of size × size rooms; each room has a door in its east wall and one in its north wall
    (except on the outside), so every neighbouring pair is joined and every inner wall is shared."""
    lines = ["name: grid_%dx%d" % (n, n), "rooms:"]
    for i in range(n):
        for j in range(n):
            lines.append(f"  - name: r_{i}_{j}")
            lines.append(f"    rect: {{center: [{(i + 0.5) * size}, {(j + 0.5) * size}], size: [{size}, {size}]}}")
            doors = []
            if i < n - 1:
                doors.append("{type: door, wall: 1, offset: 1.0, width: 0.9}")
            if j < n - 1:
                doors.append("{type: door, wall: 2, offset: 1.1, width: 0.9}")
            if doors:
                lines.append(f"    openings: [{', '.join(doors)}]")
    lines.append(f"robot: {{model: burger, at: [{size / 2}, {size / 2}], yaw: 0}}")
    return "\n".join(lines) + "\n"


def class_room_spec() -> str:
    if CLASS_ROOM.is_file():
        return CLASS_ROOM.read_text()
    return ("name: enclosed_room\nrooms:\n  - name: room\n    rect: {center: [0, 0], size: [5, 5]}\n"
            "robot: {model: burger, at: [0, 0], yaw: 0}\n")


def worldgen_command() -> list[str]:
    exe = Path(sys.executable).with_name("worldgen")
    return [str(exe)] if exe.exists() else [sys.executable, "-m", "worldgen"]


def one_run(spec: Path, out: Path) -> tuple[float, int]:
    """Wall time (s) and peak RSS (KiB) of one ``worldgen build`` in a fresh child process."""
    code = ("import resource, subprocess, sys, time\n"
            "t = time.perf_counter()\n"
            "subprocess.run(sys.argv[1:], check=True, stdout=subprocess.DEVNULL)\n"
            "print(time.perf_counter() - t, resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)\n")
    done = subprocess.run([sys.executable, "-c", code, *worldgen_command(), "build", str(spec), "-o", str(out),
                           "--force"], check=True, capture_output=True, text=True)
    seconds, rss = done.stdout.split()
    return float(seconds), int(rss)


def timed_build(spec: Path, out: Path, runs: int) -> tuple[float, float]:
    """Median wall time (s) and peak RSS (MiB) of ``worldgen build`` over ``runs`` fresh processes, after one
    warm-up run (file cache, bytecode)."""
    one_run(spec, out)
    results = [one_run(spec, out) for _ in range(runs)]
    return statistics.median(r[0] for r in results), max(r[1] for r in results) / 1024


def measure(name: str, text: str, runs: int, tmp: Path) -> bool:
    spec = tmp / f"{name.replace(' ', '_')}.yaml"
    spec.write_text(text)
    out = tmp / name.replace(' ', '_')
    wall, rss = timed_build(spec, out, runs)
    (world,) = out.glob("*.world")
    text = world.read_text()
    target = TARGETS[name]
    ok = wall < target
    print(f"{name:11s}  wall {wall:6.3f} s (median of {runs}, target < {target:g} s: {'ok' if ok else 'MISSED'})"
          f"  peak RSS {rss:6.1f} MiB  world {len(text.encode()) / 1e6:6.2f} MB,"
          f" {text.count('<link ')} links, {text.count('<collision ')} collisions")
    return ok


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=5)
    args = parser.parse_args()
    tmp = Path(tempfile.mkdtemp(prefix="bench_build."))
    try:
        t = time.perf_counter()
        ok = measure("class room", class_room_spec(), args.runs, tmp)
        ok &= measure("400 rooms", grid_spec(), args.runs, tmp)
        print(f"(benchmark took {time.perf_counter() - t:.1f} s)")
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
