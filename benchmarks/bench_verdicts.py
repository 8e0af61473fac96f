"""The verdicts of ``worldgen validate`` (simulator included) over the shared corpus and the examples, to show that
a change made for speed changes none of them.

    .venv/bin/python benchmarks/bench_verdicts.py -o before.json          # record
    .venv/bin/python benchmarks/bench_verdicts.py --compare before.json   # record again and compare

Runs, as tests/test_validate_corpus.py reads the corpus: every world and model at the origin (``--spawn 0,0``,
``--model-path corpus/gazebo_models``), every one without a spawn (the deepest point of each closed room), the
ROBOTIS worlds at their launch files' spawns, the corpus's launch files, the examples' specs, and the same
again with a Waffle. A verdict is a result's ``ok``, its checks run and skipped, and each finding's check and
severity; ``--compare`` fails (exit 1) when any differs and lists how far the simulated numbers moved (stop
distance, spin drift, settle height), which may move within their tolerances.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
CORPUS = REPO.parent / "shared" / "corpus"
NUMBERS = ("stop_distance_m", "spin_drift_m", "settle_height_m", "stop_time_s", "sim_seconds")
ROBOTIS = "ROBOTIS-GIT__turtlebot3_simulations@"
LAUNCH_SPAWNS = [   # tests/test_validate_corpus.py's SIM_RUNS (reference/turtlebot3.md §10)
    ("0,0", ["noetic-devel__turtlebot3_gazebo_worlds_turtlebot3_stage_1.world",
             "noetic-devel__turtlebot3_gazebo_worlds_turtlebot3_stage_2.world",
             "noetic-devel__turtlebot3_gazebo_worlds_turtlebot3_stage_3.world"]),
    ("-0.7,0", ["noetic-devel__turtlebot3_gazebo_worlds_turtlebot3_stage_4.world"]),
    ("-2,-0.5", ["noetic-devel__turtlebot3_gazebo_worlds_turtlebot3_world.world",
                 "jazzy__turtlebot3_gazebo_worlds_turtlebot3_world.world"]),
]


def runs() -> dict[str, list[str]]:
    files = [str(p) for p in sorted((CORPUS / "worlds").iterdir()) + sorted((CORPUS / "models").iterdir())]
    models = ["--model-path", str(CORPUS / "gazebo_models")]
    specs = [str(p) for p in sorted(REPO.glob("examples/**/*.yaml")) if p.parent.name != "map"]
    out = {"origin": files + ["--spawn", "0,0"] + models,
           "no-spawn": files + models,
           "launch-files": [str(p) for p in sorted((CORPUS / "launch").iterdir())] + models,
           "specs": specs,
           "waffle-origin": files + ["--spawn", "0,0", "--robot", "waffle"] + models,
           "waffle-specs": specs + ["--robot", "waffle"]}
    for spawn, names in LAUNCH_SPAWNS:
        out[f"spawn {spawn}"] = [str(CORPUS / "worlds" / (ROBOTIS + n)) for n in names] + ["--spawn", spawn] + models
    return out


def verdicts(args: list[str], jobs: int) -> tuple[dict, float]:
    t0 = time.perf_counter()
    proc = subprocess.run([sys.executable, "-m", "worldgen", "validate", "--format", "json", "-j", str(jobs), *args],
                          capture_output=True, text=True, env=dict(os.environ, PYTHONPATH=str(REPO)))
    elapsed = time.perf_counter() - t0
    if proc.returncode not in (0, 1) or "Traceback" in proc.stderr:
        raise SystemExit(f"validate {' '.join(args)} failed ({proc.returncode}):\n{proc.stderr[-3000:]}")
    out = {}
    for r in json.loads(proc.stdout)["results"]:
        key = _key(r["path"]) + (f" [room {r['room']}]" if r.get("room") is not None else "")
        out[key] = {"ok": r["ok"], "checks": r["checks"], "skipped": sorted(r.get("skipped", {})),
                    "findings": sorted(f"{f['check']}:{f['severity']}" for f in r["findings"]),
                    "numbers": {k: r["metrics"].get(k) for k in NUMBERS if k in r["metrics"]}}
    return out, elapsed


def _key(path: str) -> str:
    """A result's path from the corpus or the checkout on (the same in any checkout)."""
    for marker in ("/shared/corpus/", "/examples/"):
        if marker in path:
            return marker.strip("/").rpartition("/")[2] + "/" + path.rpartition(marker)[2]
    return path


def compare(before: dict, after: dict) -> int:
    before, after = ({run: {_key(k): v for k, v in results.items()} for run, results in side.items()}
                     for side in (before, after))
    differ = 0
    for run, results in before.items():
        for path, old in results.items():
            new = after.get(run, {}).get(path)
            if new is None:
                print(f"MISSING  {run}: {path}")
                differ += 1
                continue
            changed = [k for k in ("ok", "checks", "skipped", "findings") if old[k] != new[k]]
            if changed:
                differ += 1
                print(f"DIFFERS  {run}: {path}")
                for k in changed:
                    print(f"    {k}: {old[k]} -> {new[k]}")
    moved: dict[str, float] = {}
    for run, results in before.items():
        for path, old in results.items():
            new = after.get(run, {}).get(path) or {}
            for k, v in old["numbers"].items():
                w = new.get("numbers", {}).get(k)
                if isinstance(v, (int, float)) and isinstance(w, (int, float)):
                    moved[k] = max(moved.get(k, 0.0), abs(w - v))
    count = sum(len(r) for r in before.values())
    print(f"{count} results compared: {differ} verdicts differ")
    print("largest change of each number: " + ", ".join(f"{k} {v:.4f}" for k, v in sorted(moved.items())))
    return 1 if differ else 0


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("-o", "--output", type=Path, help="write the verdicts here (JSON)")
    parser.add_argument("--compare", type=Path, help="verdicts recorded earlier: fail when any differs")
    parser.add_argument("-j", "--jobs", type=int, default=2)
    opts = parser.parse_args()
    if not CORPUS.is_dir():
        raise SystemExit(f"no corpus at {CORPUS}")
    recorded, total = {}, 0.0
    for name, args in runs().items():
        recorded[name], elapsed = verdicts(args, opts.jobs)
        total += elapsed
        print(f"{name:16s} {len(recorded[name]):3d} results  {elapsed:6.1f} s", flush=True)
    print(f"all runs: {total:.1f} s wall")
    if opts.output:
        opts.output.write_text(json.dumps(recorded, indent=1, sort_keys=True) + "\n")
    if opts.compare:
        sys.exit(compare(json.loads(opts.compare.read_text()), recorded))


if __name__ == "__main__":
    main()
