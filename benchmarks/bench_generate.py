"""Speed of ``worldgen generate``: 1000 specs of each kind made in one process (target: under 10 s a kind), and
100 generated worlds (20 of each kind) built and validated with ``worldgen validate DIR --skip-sim -j 2``
(target: under 60 s on a 2-core machine).

    .venv/bin/python benchmarks/bench_generate.py [--count 1000] [--worlds 100]

The specs are made with each kind's defaults (the Waffle Pi's sizes) from seeds 0, 1, 2 …; the 100 worlds are
written to a temporary folder, built once in this process (spec → geometry → SDF, as ``worldgen build`` does) to
time the build alone, then validated by the command itself, which builds each spec again before its checks.
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

KINDS = ("maze", "rooms", "clutter", "arena", "track")
SPEC_TARGET = 10.0      # s for 1000 specs of a kind
VALIDATE_TARGET = 60.0  # s for 100 worlds built and validated, -j 2


def specs(count: int) -> None:
    from worldgen.generate.worlds import generate

    generate("maze", 0, 1)   # measure the robot once, outside the timing
    print(f"{count} specs of each kind, one process:")
    for kind in KINDS:
        wall, cpu = time.perf_counter(), time.process_time()
        worlds = generate(kind, 0, count)
        wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
        size = sum(len(w.text) for w in worlds) / len(worlds)
        verdict = "ok" if wall < SPEC_TARGET * count / 1000 else "SLOW"
        print(f"  {kind:8} {wall:6.2f} s wall ({cpu:5.2f} s CPU), {1000 * wall / count:5.2f} ms a spec, "
              f"{size / 1024:4.1f} KB a spec   [{verdict}: target {SPEC_TARGET * count / 1000:g} s]")


def worlds(total: int) -> None:
    from worldgen.generate.worlds import generate
    from worldgen.geometry.building import build_geometry
    from worldgen.sdf.writer import world_sdf

    each = max(1, total // len(KINDS))
    with tempfile.TemporaryDirectory(prefix="bench-generate-") as tmp:
        folder = Path(tmp) / "set"
        folder.mkdir()
        made = [w for kind in KINDS for w in generate(kind, 1000, each)]
        for w in made:
            (folder / w.file_name).write_text(w.text)
        t0 = time.perf_counter()
        for w in made:
            world_sdf(build_geometry(w.spec))
        built = time.perf_counter() - t0
        t0 = time.perf_counter()
        proc = subprocess.run([sys.executable, "-m", "worldgen", "validate", str(folder), "--skip-sim", "-j", "2"],
                              capture_output=True, text=True, cwd=tmp)
        checked = time.perf_counter() - t0
        summary = proc.stdout.strip().splitlines()[-1] if proc.stdout.strip() else proc.stderr.strip()[-300:]
        verdict = "ok" if checked < VALIDATE_TARGET * len(made) / 100 and proc.returncode == 0 else "SLOW or FAILED"
        print(f"{len(made)} generated worlds ({each} of each kind):")
        print(f"  built in this process (spec → geometry → SDF): {built:5.2f} s, {1000 * built / len(made):5.1f} ms a "
              "world")
        print(f"  worldgen validate DIR --skip-sim -j 2: {checked:5.2f} s (exit {proc.returncode}: {summary})   "
              f"[{verdict}: target {VALIDATE_TARGET * len(made) / 100:g} s]")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--count", type=int, default=1000, help="specs of each kind (default 1000)")
    parser.add_argument("--worlds", type=int, default=100, help="worlds built and validated (default 100)")
    args = parser.parse_args()
    specs(args.count)
    worlds(args.worlds)


if __name__ == "__main__":
    main()
