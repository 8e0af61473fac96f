"""The ROS 2 transport (`worldgen run --ros humble|jazzy`) against its targets, with the real rclpy of PyPI's Jazzy
wheels (`.venv-ros2`, made by `.ci/ros2-peer`; WORLDGEN_ROS2_PYTHON names another):

- the real-time factor at --rate 1 with every topic subscribed, reliable and best effort (target 1.00 ± 0.03);
- the course's ROS 2 stop_at_wall.py graded in the class room at --rate max (target ≥ 10× real time, and a pass);
- the Waffle Pi's 640 × 480 rgb8 camera at 30 Hz reaching an rclpy subscriber at --rate 1 (target: no frame dropped
  between the first one received and the last).

    .venv/bin/python benchmarks/bench_ros2.py [--stack humble|jazzy] [--runs N]
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
NODES = REPO / "tests" / "ros2nodes"
ROOM = REPO / "examples" / "enclosed_room.yaml"


def worldgen(args: list[str], python: str) -> tuple[float, dict | None]:
    env = dict(os.environ, WORLDGEN_ROS2_PYTHON=python, PYTHONPATH=str(REPO))
    started = time.monotonic()
    done = subprocess.run([sys.executable, "-m", "worldgen", "run", *args, "--format", "json"], env=env,
                          capture_output=True, text=True, timeout=600)
    wall = time.monotonic() - started
    try:
        return wall, json.loads(done.stdout)
    except ValueError:
        print(done.stderr, file=sys.stderr)
        return wall, None


def course_node(stack: str, root: Path) -> Path:
    subprocess.run([sys.executable, "-m", "worldgen", "course", "--ros", stack, "-w", str(root)], check=True,
                   capture_output=True, env=dict(os.environ, PYTHONPATH=str(REPO)))
    return next(root.rglob("stop_at_wall.py"))


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--stack", choices=("humble", "jazzy"), default="jazzy")
    parser.add_argument("--runs", type=int, default=3)
    opts = parser.parse_args()
    python = os.environ.get("WORLDGEN_ROS2_PYTHON") or str(REPO / ".venv-ros2" / "bin" / "python")
    stack = opts.stack
    print(f"ROS 2 transport, {stack}, nodes run by {python}, {os.cpu_count()} cores")
    with tempfile.TemporaryDirectory() as tmp:
        rtf = []
        for _ in range(opts.runs):
            _, doc = worldgen([str(ROOM), str(NODES / "probe.py"), f"_out:={tmp}/probe.json", "--ros", stack,
                               "--duration", "10", "--rate", "1"], python)
            rtf.append(doc["metrics"]["real_time_factor"])
        ok = all(abs(r - 1.0) <= 0.03 for r in rtf)
        print(f"real-time factor at --rate 1, every topic subscribed twice: {' '.join(f'{r:.3f}' for r in rtf)} "
              f"(target 1.00 ± 0.03: {'met' if ok else 'NOT met'})")
        node = course_node(stack, Path(tmp) / "ws")
        fast, walls, passed = [], [], True
        for _ in range(opts.runs):
            wall, doc = worldgen([str(ROOM), str(node), "--ros", stack, "--task", "stop-at-wall", "--rate", "max"],
                                 python)
            fast.append(doc["metrics"]["real_time_factor"])
            walls.append(wall)
            passed = passed and doc["ok"]
        print(f"course stop_at_wall.py at --rate max: {statistics.median(fast):.1f}x real time (median of "
              f"{len(fast)}; target ≥ 10x: {'met' if statistics.median(fast) >= 10 else 'NOT met'}), "
              f"{statistics.median(walls):.2f} s wall per run, {'pass' if passed else 'FAIL'}")
        out = Path(tmp) / "camera.json"
        worldgen([str(ROOM), str(NODES / "camera_count.py"), f"_out:={out}", "--robot", "waffle_pi", "--ros", stack,
                  "--duration", "5", "--rate", "1"], python)
        seen = json.loads(out.read_text())
        stamps = sorted(set(seen["stamps"]))
        expected = round((stamps[-1] - stamps[0]) * 30) + 1 if stamps else 0
        dropped = expected - len(stamps)
        print(f"camera 640x480 rgb8 at 30 Hz, --rate 1, 5 s: {len(stamps)} pictures from t={stamps[0]:.3f} to "
              f"{stamps[-1]:.3f} s, {dropped} dropped between (target 0: {'met' if dropped == 0 else 'NOT met'})"
              if stamps else "camera: no picture arrived (NOT met)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
