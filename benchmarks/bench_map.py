"""How fast ``worldgen build`` turns a SLAM map (map_server's map.yaml + PGM) into a world, and into how many boxes.

Draws a 400 × 400-pixel map at 0.05 m (a 20 m × 20 m office floor: a corridor and eight offices with doors, walls
two or three pixels thick with ragged faces, desks and chairs as a scan sees them, speckle noise, unknown outside
and in shadows), then the same floor in the middle of a 4000 × 4000 map as gmapping saves it (200 m × 200 m, nearly
all unknown). Prints, for each, the median wall time of N runs of ``worldgen build`` (Python start included), the
peak memory, and what Gazebo gets: occupied pixels, walls, posts (lone pixels), collision boxes, the world's size.
Targets: < 1.5 s each.

    python benchmarks/bench_map.py [--runs N]
"""

from __future__ import annotations

import argparse
import random
import shutil
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_build import timed_build   # noqa: E402  (the same child-process timing as the spec benchmark)

FREE, UNKNOWN, WALL = 254, 205, 0
TARGET = 1.5


def office_floor(n: int = 400, seed: int = 1) -> list[list[int]]:
    """An n × n office floor as a scan leaves it (see the module's docstring)."""
    rnd = random.Random(seed)
    px = [[UNKNOWN] * n for _ in range(n)]

    def fill(r0, r1, c0, c1, value):
        for r in range(max(r0, 0), min(r1, n - 1) + 1):
            for c in range(max(c0, 0), min(c1, n - 1) + 1):
                px[r][c] = value

    m = 20                                      # the building's outer wall, 3 pixels thick
    fill(m, n - m - 1, m, n - m - 1, WALL)
    fill(m + 3, n - m - 4, m + 3, n - m - 4, FREE)
    mid = n // 2                                # a corridor along the middle, 2 m wide, walls 2 pixels thick
    fill(mid - 22, mid - 21, m, n - m - 1, WALL)
    fill(mid + 20, mid + 21, m, n - m - 1, WALL)
    step = (n - 2 * m) // 4                     # four offices on each side, 2-pixel partitions
    for k in range(1, 4):
        x = m + k * step
        fill(m, mid - 21, x, x + 1, WALL)
        fill(mid + 20, n - m - 1, x, x + 1, WALL)
    for k in range(4):                          # a 0.9 m door from each office into the corridor
        x = m + k * step + step // 2
        fill(mid - 22, mid - 21, x - 9, x + 8, FREE)
        fill(mid + 20, mid + 21, x - 9, x + 8, FREE)
    for k in range(4):                          # in each office: a desk's outline, its shadow, two chairs' legs
        for top in (m + 30, mid + 40):
            c0 = m + k * step + 15
            fill(top, top + 16, c0, c0 + 30, WALL)
            fill(top + 2, top + 14, c0 + 2, c0 + 28, UNKNOWN)
            for dx in (5, 20):
                for dr, dc in ((0, 0), (0, 8), (8, 0), (8, 8)):
                    px[top + 24 + dr][c0 + dx + dc] = WALL
    walls = [(r, c) for r in range(n) for c in range(n) if px[r][c] == WALL]
    for r, c in walls:                          # ragged faces: a scan's wall pixels bulge here and there
        if rnd.random() < 0.04:
            rr, cc = r + rnd.choice((-1, 1)), c + rnd.choice((-1, 1))
            if px[rr][cc] == FREE:
                px[rr][cc] = WALL
    for _ in range(300):                        # speckle: lone occupied pixels, and grey unknown ones
        r, c = rnd.randrange(m, n - m), rnd.randrange(m, n - m)
        if px[r][c] == FREE:
            px[r][c] = WALL if rnd.random() < 0.5 else 128
    return px


def write_map(folder: Path, pixels: list[list[int]], origin: float) -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "map.pgm").write_bytes(f"P5\n{len(pixels[0])} {len(pixels)}\n255\n".encode()
                                     + bytes(v for row in pixels for v in row))
    path = folder / "map.yaml"
    path.write_text(f"image: map.pgm\nresolution: 0.05\norigin: [{origin}, {origin}, 0.0]\nnegate: 0\n"
                    "occupied_thresh: 0.65\nfree_thresh: 0.196\n")
    return path


def measure(label: str, source: Path, occupied: int, runs: int) -> bool:
    out = source.parent / "out"
    wall, rss = timed_build(source, out, runs)
    text = (out / "map.world").read_text()
    walls, posts = text.count('<link name="Wall_'), text.count('<model name="map_post_')
    ok = wall < TARGET
    print(f"{label:22s} wall {wall:6.3f} s (median of {runs}, target < {TARGET:g} s: {'ok' if ok else 'MISSED'})  "
          f"peak RSS {rss:6.1f} MiB\n{'':22s} {occupied} occupied pixels -> {walls} walls, {posts} posts, "
          f"{text.count('<collision ')} collision boxes; world {len(text) / 1e6:.2f} MB")
    return ok


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=5)
    args = parser.parse_args()
    tmp = Path(tempfile.mkdtemp(prefix="bench_map."))
    try:
        t = time.perf_counter()
        floor = office_floor()
        occupied = sum(row.count(WALL) for row in floor)
        ok = measure("400 x 400 office floor", write_map(tmp / "small", floor, -10.0), occupied, args.runs)
        big = [[UNKNOWN] * 4000 for _ in range(4000)]
        for r, row in enumerate(floor):
            big[1800 + r][1800:2200] = row
        ok &= measure("4000 x 4000 (gmapping)", write_map(tmp / "big", big, -100.0), occupied, args.runs)
        print(f"(benchmark took {time.perf_counter() - t:.1f} s)")
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
