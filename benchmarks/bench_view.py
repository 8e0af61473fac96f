"""The 3D pages' size and speed, against issue 18's targets:

- size: the class room's world page (examples/enclosed_room.yaml) under 1.5 MB; a 60-second replay (30 Hz
  odometry, a 360-beam scan at 5 Hz, as `worldgen run --html` records) under 3 MB; an hour-long replay too;
- written: the time to make and write each page, under 1 s (median of 5, in this process after a first warm-up);
- opens: from navigation until the page is ready to orbit (its scene built and drawn once) in Debian's headless
  chromium with WebGL on the CPU (SwiftShader), under 2 s (median of 5 loads, each in a fresh context).

Also a real world saved with Gazebo (ROBOTIS' turtlebot3_world, whose model has meshes) when ../shared/corpus is
beside the checkout.

    .venv/bin/python benchmarks/bench_view.py
"""

from __future__ import annotations

import math
import statistics
import sys
import tempfile
import time
import types
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))
EXAMPLES = REPO / "examples"
CORPUS = REPO.parent / "shared" / "corpus"
RUNS = 5
CHROMIUM_ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                 "--disable-background-networking", "--disable-component-update", "--disable-sync",
                 "--enable-unsafe-swiftshader"]


def trace(seconds: float) -> dict:
    """What `run --html` records for a robot driving a slow circle: odometry at 30 Hz, scans at 5 Hz."""
    odom, ranges = [], []
    for i in range(int(seconds * 30) + 1):
        t = i / 30
        a = 0.1 * t
        odom.append([t, math.cos(a), math.sin(a), a + math.pi / 2, 0.1, 0.1, 0.1, 0.1])
        if i % 6 == 0:
            ranges.append([round(t, 3), round(math.cos(a), 4), round(math.sin(a), 4), round(a, 4),
                           [1000 + (b * 37 + i) % 2400 for b in range(360)]])
    return {"odom": odom, "scans": [[r[0], 1.0, 1.5, 0.9, 0.8] for r in ranges], "contacts": [],
            "lidar": {"angle_min": 0.0, "angle_increment": 2 * math.pi / 360, "range_min": 0.12,
                      "range_max": 3.5, "count": 360}, "ranges": ranges}


def replay_maker(seconds: float):
    from worldgen.check.report import Result
    from worldgen.check.sources import load_scene
    from worldgen.view.grades import run_page

    scene, _ = load_scene(EXAMPLES / "enclosed_room.yaml", "spec")
    world = types.SimpleNamespace(path=EXAMPLES / "enclosed_room.yaml", scene=scene, spawn=(1.0, 0.0, 0.0),
                                  robot="burger")
    recorded = trace(seconds)
    return lambda: run_page(Result(path="ada", checks=["node", "spin"]), world, recorded)


def written(make, out: Path) -> tuple[float, float, int]:
    """Seconds to make and write the page the first time (imports and the robot's description included: what one
    `worldgen view` pays) and the median after, and its size."""
    start = time.perf_counter()
    make()
    first = time.perf_counter() - start
    times = []
    for _ in range(RUNS):
        start = time.perf_counter()
        data = make()
        out.write_bytes(data)
        times.append(time.perf_counter() - start)
    return first, statistics.median(times), len(data)


def opens(pages: list[Path]) -> list[float]:
    """Median seconds from navigation to `window.worldgen.ready`, per page."""
    from playwright.sync_api import sync_playwright

    out = []
    with sync_playwright() as p:
        browser = p.chromium.launch(executable_path="/usr/bin/chromium", args=CHROMIUM_ARGS)
        for page_file in pages:
            times = []
            for _ in range(RUNS):
                context = browser.new_context(viewport={"width": 1200, "height": 800})
                page = context.new_page()
                start = time.perf_counter()
                page.goto(page_file.as_uri())
                page.wait_for_function("() => window.worldgen && window.worldgen.ready === true", timeout=30000)
                times.append(time.perf_counter() - start)
                context.close()
            out.append(statistics.median(times))
        browser.close()
    return out


def main() -> None:
    from worldgen.view.page import world_page

    cases = [("class room (enclosed_room.yaml)", lambda: world_page(EXAMPLES / "enclosed_room.yaml"), 1.5e6),
             ("two rooms, door and window (two_rooms.yaml)", lambda: world_page(EXAMPLES / "two_rooms.yaml"), 1.5e6),
             ("60 s replay (30 Hz poses, 5 Hz scans)", replay_maker(60.0), 3e6),
             ("1 h replay (thinned)", replay_maker(3600.0), 3e6)]
    real = CORPUS / "worlds" / "ROBOTIS-GIT__turtlebot3_simulations@noetic-devel__turtlebot3_gazebo_worlds_turtlebot3_world.world"
    if real.is_file():
        models = (CORPUS / "models", CORPUS / "gazebo_models")
        cases.append(("turtlebot3_world.world (corpus, meshes)", lambda: world_page(real, spawn=(-2.0, -0.5, 0.0),
                                                                                     model_paths=models), None))
    with tempfile.TemporaryDirectory() as tmp:
        rows, files = [], []
        for i, (name, make, limit) in enumerate(cases):
            out = Path(tmp) / f"page{i}.html"
            first, seconds, size = written(make, out)
            rows.append((name, size, limit, first, seconds))
            files.append(out)
        try:
            opened = opens(files)
        except Exception as err:   # no chromium or Playwright here: sizes and write times only
            print(f"(not opened in chromium: {err})")
            opened = [None] * len(files)
    print(f"{'page':<46} {'size':>9} {'target':>9} {'first':>6} {'written':>8} {'opens':>7}")
    for (name, size, limit, first, seconds), open_s in zip(rows, opened):
        target = f"< {limit / 1e6:.1f} MB" if limit else "–"
        size_ok = "" if limit is None or size < limit else " MISSED"
        print(f"{name:<46} {size / 1e6:>7.2f} MB {target:>9} {first:>5.2f}s {seconds:>7.2f}s "
              f"{'' if open_s is None else f'{open_s:6.2f}s'}{size_ok}")
    print(f"targets: written < 1 s, opens < 2 s (medians of {RUNS}; first: the first page made in this process)")


if __name__ == "__main__":
    main()
