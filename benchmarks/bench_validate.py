"""Speed of ``worldgen validate``: the whole command on the class's enclosed room (target < 1.5 s wall), the
simulated-to-real time ratio inside it, and the throughput of 50 worlds with -j 1 and -j 2 (target: -j 2 at
least 1.6 times -j 1 on a 2-core machine).

    .venv/bin/python benchmarks/bench_validate.py

The class room and its launch file come from the shared corpus; without it a 5 m room written here stands in.
The 50 worlds are rooms of 3 to 6.8 m (some with a door, some with pillars) written to a temporary folder.
"""

from __future__ import annotations

import json
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
CORPUS = REPO.parent / "shared" / "corpus"
CLASS = "Intro-Robotics-UChicago-Spring-2022__warmup_project__"
CLASS_ROOM = CORPUS / "worlds" / f"{CLASS}worlds_turtlebot3_in_enclosed_room.world"
CLASS_LAUNCH = CORPUS / "launch" / f"{CLASS}launch_turtlebot3_in_room.launch"
WORLDGEN = [sys.executable, "-m", "worldgen", "validate"]


def wall_link(name: str, start, end, height: float = 0.5, thickness: float = 0.15) -> str:
    (x0, y0), (x1, y1) = start, end
    return (f"<link name='{name}'><pose>{(x0 + x1) / 2} {(y0 + y1) / 2} 0 0 0 {math.atan2(y1 - y0, x1 - x0)}</pose>"
            f"<collision name='c'><pose>0 0 {height / 2} 0 0 0</pose><geometry><box><size>"
            f"{math.dist(start, end)} {thickness} {height}</size></box></geometry></collision></link>")


def pillar_link(name: str, x: float, y: float) -> str:
    return (f"<link name='{name}'><pose>{x} {y} 0.25 0 0 0</pose><collision name='c'><geometry><cylinder>"
            "<radius>0.15</radius><length>0.5</length></cylinder></geometry></collision></link>")


def room_world(size: float, door: bool, pillars: bool) -> str:
    h = size / 2
    walls = [((-h, -h), (h, -h)), ((h, -h), (h, h)), ((h, h), (-h, h)), ((-h, h), (-h, -h))]
    if door:
        walls[1:2] = [((h, -h), (h, -0.45)), ((h, 0.45), (h, h))]
    links = [wall_link(f"Wall_{i}", a, b) for i, (a, b) in enumerate(walls)]
    if pillars:
        links += [pillar_link(f"pillar_{i}", sx * h / 2, sy * h / 2)
                  for i, (sx, sy) in enumerate([(1, 1), (-1, 1), (1, -1), (-1, -1)])]
    return ("<sdf version='1.6'><world name='default'><model name='ground_plane'><static>1</static><link name='l'>"
            "<collision name='c'><geometry><plane><normal>0 0 1</normal></plane></geometry></collision></link>"
            f"</model><model name='room'><static>1</static>{''.join(links)}</model></world></sdf>\n")


def run(args, env=None) -> tuple[float, subprocess.CompletedProcess]:
    t0 = time.perf_counter()
    proc = subprocess.run(WORLDGEN + [str(a) for a in args], capture_output=True, text=True, env=env)
    elapsed = time.perf_counter() - t0
    if proc.returncode not in (0, 1):
        raise SystemExit(f"worldgen validate failed: {proc.stderr}")
    return elapsed, proc


def sim_ratio(world: Path, spawn) -> float:
    """Simulated seconds per wall second of the job validate runs in its child process, run here on the scene
    validate reads once and hands over."""
    sys.path.insert(0, str(REPO))
    from worldgen.sdf.reader import read_world
    from worldgen.check.sim_job import sim_numbers

    numbers = sim_numbers(read_world(world), spawn=spawn)
    return numbers.sim_seconds / numbers.wall_seconds


def main() -> None:
    env = dict(os.environ, PYTHONPATH=str(REPO))
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        if CLASS_ROOM.is_file():
            class_args = [CLASS_ROOM, "--launch", CLASS_LAUNCH]
            label = "class enclosed room (corpus, spawn from its launch file)"
        else:
            (tmp / "room.world").write_text(room_world(5.0, False, False))
            class_args, label = [tmp / "room.world"], "5 m room (written here)"
        run(class_args + ["--format", "json"], env)   # warm the file cache
        times = []
        for _ in range(5):
            elapsed, proc = run(class_args + ["--format", "json"], env)
            times.append(elapsed)
        doc = json.loads(proc.stdout)["results"][0]
        print(f"validate {label}:")
        print(f"  process wall time  median {statistics.median(times):.3f} s, best {min(times):.3f} s "
              f"(target < 1.5 s)")
        ratios = [sim_ratio(class_args[0], doc["spawn"]) for _ in range(3)]
        print(f"  simulated {doc['metrics']['sim_seconds']:.1f} s of settle + scan + spin + stop-at-wall; "
              f"sim/real ratio median {statistics.median(ratios):.0f}x (the simulator job as validate's child runs "
              "it: robot load, physics)")

        worlds = []
        for i in range(50):
            path = tmp / f"room_{i:02d}.world"
            path.write_text(room_world(3.0 + 0.08 * (i % 48), door=i % 5 == 0, pillars=i % 3 == 0))
            worlds.append(path)
        results = {}
        for jobs in (1, 2):
            elapsed, proc = run(worlds + ["-j", str(jobs), "--format", "json"], env)
            doc = json.loads(proc.stdout)
            assert len(doc["results"]) == 50
            results[jobs] = elapsed
            print(f"50 worlds with -j {jobs}: {elapsed:.2f} s wall, {50 / elapsed:.1f} worlds/s "
                  f"({sum(r['ok'] for r in doc['results'])} pass, {sum(not r['ok'] for r in doc['results'])} fail)")
        print(f"  -j 2 speed-up {results[1] / results[2]:.2f}x (target >= 1.6x on {os.cpu_count()} cores)")


if __name__ == "__main__":
    main()
