"""The simulated camera's cost (moderngl on EGL, Mesa's llvmpipe on the CPU):

- the renderer alone: frames per second of wall time (and ms per frame, including the read-back) of the Waffle Pi's
  640 × 480 camera in the class room (examples/enclosed_room.yaml), and of the Waffle's 1920 × 1080 R200, with
  llvmpipe's default threads (one per core), with LP_NUM_THREADS=1, and pinned to one core (taskset -c 0);
- `worldgen run ROOM camera_steer.py --robot waffle_pi` (a student-style node that steers by every picture,
  tests/rosnodes/camera_steer.py, so the camera renders at 30 Hz): the real-time factor at --rate 1 (target ≥ 0.95)
  with the simulator's share of a core, the same with the whole run pinned to one core, and the real-time factor
  at --rate max (target ≥ 5).

    .venv/bin/python benchmarks/bench_camera.py [--quick]
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

from procs import cpu_seconds, simulator_pid   # benchmarks/procs.py, beside this script

REPO = Path(__file__).resolve().parent.parent
NODE = REPO / "tests" / "rosnodes" / "camera_steer.py"
ROOM = REPO / "examples" / "enclosed_room.yaml"
FRAMES = 100     # per batch
BATCHES = 7

RENDER = r"""
import json, statistics, sys, time
from worldgen.bridge.world import load_world
from worldgen.sim.session import Session
world = load_world(sys.argv[1], robot=sys.argv[2])
batches, frames = int(sys.argv[3]), int(sys.argv[4])
with Session(world.scene, sys.argv[2], world.spawn) as session:
    camera = session.main.profile.cameras[0]
    session.camera_image(session.main, camera)
    times = []
    for _ in range(batches):
        start = time.perf_counter()
        for _ in range(frames):
            session.camera_image(session.main, camera)
        times.append((time.perf_counter() - start) / frames)
print(json.dumps({"median": statistics.median(times), "best": min(times)}))
"""


def render_ms(robot: str, env_extra: dict, pin: bool, batches: int) -> dict:
    env = dict(os.environ, PYTHONPATH=str(REPO), **env_extra)
    cmd = [sys.executable, "-c", RENDER, str(ROOM), robot, str(batches), str(FRAMES if robot == "waffle_pi" else 20)]
    if pin:
        cmd = ["taskset", "-c", "0"] + cmd
    out = subprocess.run(cmd, env=env, capture_output=True, text=True, check=True).stdout
    return json.loads(out.strip().splitlines()[-1])


def run(rate: str, duration: float, pin: bool = False) -> dict:
    """One `worldgen run` of the camera-steering node: its real-time factor, and the simulator's CPU share while
    it ran (sampled from /proc, start-up excluded)."""
    marker = f"WORLDGEN_BENCH_CAMERA={time.monotonic_ns()}"
    env = dict(os.environ, PYTHONPATH=str(REPO), WORLDGEN_BENCH_CAMERA=marker.split("=")[1])
    cmd = [sys.executable, "-m", "worldgen", "run", str(ROOM), str(NODE), "--robot", "waffle_pi", "--rate", rate,
           "--duration", str(duration), "--format", "json"]
    if pin:
        cmd = ["taskset", "-c", "0"] + cmd
    proc = subprocess.Popen(cmd, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    pid, first, last = None, None, None
    while proc.poll() is None:
        pid = pid or simulator_pid(marker.encode())
        if pid is not None:
            try:
                sample = (time.monotonic(), cpu_seconds(pid))
                first, last = first or sample, sample
            except OSError:
                pass
        time.sleep(0.2)
    out, err = proc.communicate()
    metrics = json.loads(out)["metrics"]
    share = (last[1] - first[1]) / (last[0] - first[0]) if first and last and last[0] > first[0] else None
    return {"rtf": metrics["real_time_factor"], "share": share, "cmd_vel": metrics["cmd_vel_messages"],
            "sim_time": metrics["sim_time_s"]}


def main() -> int:
    quick = "--quick" in sys.argv
    batches = 3 if quick else BATCHES
    pin = shutil.which("taskset") is not None
    print(f"machine: {os.cpu_count()} cores; load average {os.getloadavg()[0]:.2f} at the start")
    cases = [("llvmpipe default threads", {}, False), ("LP_NUM_THREADS=1", {"LP_NUM_THREADS": "1"}, False)]
    if pin:
        cases.append(("pinned to one core (taskset -c 0)", {}, True))
    for label, extra, pinned in cases:
        for robot, size in (("waffle_pi", "640 x 480"), ("waffle", "1920 x 1080")):
            got = render_ms(robot, extra, pinned, batches)
            print(f"renderer, {size}, {label}: {got['median'] * 1000:5.2f} ms/frame "
                  f"({1 / got['median']:5.0f} frames/s; best {got['best'] * 1000:.2f} ms)")
    duration = 10.0 if quick else 20.0
    real = run("1", duration)
    print(f"worldgen run --robot waffle_pi --rate 1, node on every picture: {real['rtf']:.3f}x real time "
          f"(target >= 0.95), simulator {real['share'] * 100:.0f} % of one core, {real['cmd_vel']} cmd_vel")
    if pin:
        one = run("1", duration, pin=True)
        print(f"  the same, everything pinned to one core: {one['rtf']:.3f}x real time, "
              f"simulator {one['share'] * 100:.0f} % of it")
    fast = run("max", duration)
    print(f"worldgen run --robot waffle_pi --rate max, node on every picture: {fast['rtf']:.1f}x real time "
          f"(target >= 5), simulator {fast['share'] * 100:.0f} % of one core, {fast['cmd_vel']} cmd_vel")
    print(f"load average {os.getloadavg()[0]:.2f} at the end")
    return 0


if __name__ == "__main__":
    sys.exit(main())
