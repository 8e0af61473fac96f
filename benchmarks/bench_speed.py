"""Speed of ``worldgen validate`` against the floor, measured in the same run (issue 26).

The floor is a Python start that imports what validate cannot do without: ``python -c 'import pybullet, numpy,
lxml.etree'``. Each round runs the floor, ``validate`` of the class room (the corpus's enclosed room with its
launch file, as README and bench_validate.py use) and the same with ``--skip-sim``, in an order that rotates from
round to round, so that a busy machine slows all three alike. Printed: the medians of wall time and of CPU time
(user + system of the process and its children, which other programs on the machine do not inflate), each as a
multiple of the floor's; the simulation's share (validate − ``--skip-sim``); "the simulation alone", a Python
start that imports only what the simulated job needs and runs it on the same world from the same spawn, one
thing after another (no command line, no checks; validate overlaps its own start with the simulator's: its
server imports pybullet while the command reads its inputs, so it can come in under this); and, in this process,
the simulated job's own phases (robot load, settle, scan, spin, stop-at-wall) on the same scene.

    .venv/bin/python benchmarks/bench_speed.py [--rounds N] [--also OTHER_CHECKOUT]

Target: validate of the class room at most 3 times the floor.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
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
FLOOR = [sys.executable, "-c", "import pybullet, numpy, lxml.etree"]
SIM_ALONE = ("import json, os, sys\n"
             "from worldgen.check.sim_job import simulate\n"
             "from worldgen.robots import robot_urdf\n"
             "simulate(world={'path': sys.argv[1], 'text': None, 'model_paths': []}, robot=sys.argv[2],\n"
             "         spawn=json.loads(sys.argv[3]), urdf=robot_urdf(sys.argv[2]))\n"
             "os._exit(0)")   # as worldgen leaves: without the interpreter's teardown
TARGET = 3.0


def timed(cmd: list[str], env: dict) -> tuple[float, float]:
    """Wall and CPU seconds (user + system, the process and all it waited for) of one run of ``cmd``, run from
    the file system's root (``python -m`` puts the working folder before PYTHONPATH)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    proc = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, env=env, cwd=os.path.abspath(os.sep))
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if proc.returncode not in (0, 1):
        raise SystemExit(f"{' '.join(cmd)} failed ({proc.returncode}): {proc.stderr.decode()[-2000:]}")
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def class_args(tmp: Path) -> tuple[list[str], str]:
    if CLASS_ROOM.is_file():
        return [str(CLASS_ROOM), "--launch", str(CLASS_LAUNCH)], "the class room (corpus, its launch file's spawn)"
    sys.path.insert(0, str(REPO / "benchmarks"))
    from bench_validate import room_world

    (tmp / "room.world").write_text(room_world(5.0, False, False))
    return [str(tmp / "room.world"), "--spawn", "0,0"], "a 5 m room (written here: no corpus)"


def measure(commands: dict[str, tuple[list[str], dict]], rounds: int) -> dict[str, list[tuple[float, float]]]:
    names = list(commands)
    for name in names:   # warm the file cache and any cache worldgen keeps
        timed(*commands[name])
    samples: dict[str, list[tuple[float, float]]] = {name: [] for name in names}
    for i in range(rounds):
        order = names[i % len(names):] + names[:i % len(names)]
        for name in order:
            samples[name].append(timed(*commands[name]))
    return samples


def planned(args: list[str]):
    """The job validate runs for ``args`` (its world, robot and spawn)."""
    sys.path.insert(0, str(REPO))
    from worldgen.check.validate import Options, plan

    [job] = plan([args[0]], Options(launch=Path(args[2]) if len(args) > 2 and args[1] == "--launch" else None,
                                    spawn=(0.0, 0.0, 0.0) if "--spawn" in args else None))
    return job


def phases(args: list[str]) -> None:
    """The simulated job's phases on the class room's scene, in this process (pybullet imported already)."""
    from worldgen.check.sim_job import sim_numbers
    from worldgen.robots import robot_urdf
    from worldgen.sdf.reader import read_world

    job = planned(args)
    scene = read_world(job.world)
    urdf = robot_urdf(job.robot)
    sim_numbers(scene, job.robot, job.spawn, urdf=urdf)   # warm
    walls = []
    for _ in range(3):
        numbers = sim_numbers(scene, job.robot, job.spawn, urdf=urdf)
        walls.append(numbers.wall_seconds)
    stop = numbers.stop
    print(f"  simulated job in-process: median {statistics.median(walls) * 1000:.0f} ms for "
          f"{numbers.sim_seconds:.1f} simulated s (stop-at-wall {stop.time:.1f} s of them)" if stop else
          f"  simulated job in-process: median {statistics.median(walls) * 1000:.0f} ms")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--rounds", type=int, default=11)
    parser.add_argument("--also", type=Path, metavar="CHECKOUT",
                        help="also time validate of another checkout (an older commit's, say) in the same rounds")
    opts = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        # as installed (pip compiles a wheel's modules): bytecode kept, in a folder of this run's own, even
        # where PYTHONDONTWRITEBYTECODE is set; the first round of each command writes it
        env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
        env["PYTHONPYCACHEPREFIX"] = str(Path(tmp) / "pycache")
        args, label = class_args(Path(tmp))
        validate = [sys.executable, "-m", "worldgen", "validate", *args, "--format", "json"]
        ours = dict(env, PYTHONPATH=os.pathsep.join(p for p in (str(REPO), env.get("PYTHONPATH")) if p))
        job = planned(args)
        alone = [sys.executable, "-c", SIM_ALONE, str(job.world), job.robot, json.dumps(list(job.spawn))]
        commands = {"floor": (FLOOR, env), "validate": (validate, ours),
                    "validate --skip-sim": (validate + ["--skip-sim"], ours), "the simulation alone": (alone, ours)}
        if opts.also is not None:
            commands[f"validate ({opts.also.name})"] = (validate, dict(env, PYTHONPATH=str(opts.also.resolve())))
        samples = measure(commands, opts.rounds)
        report(commands, samples, label, opts.rounds)
        phases(args)   # inside the folder: the room written there when no corpus is beside the checkout


def report(commands: dict, samples: dict, label: str, rounds: int) -> None:
    """The medians against the floor, and the target."""
    wall = {n: statistics.median(s[0] for s in v) for n, v in samples.items()}
    cpu = {n: statistics.median(s[1] for s in v) for n, v in samples.items()}
    print(f"validate of {label}; medians of {rounds} interleaved rounds on {os.cpu_count()} cores")
    print(f"  {'':26s} {'wall':>8s} {'× floor':>8s} {'cpu':>8s} {'× floor':>8s}")
    for name in commands:
        print(f"  {name:26s} {wall[name]:7.3f}s {wall[name] / wall['floor']:7.2f}x "
              f"{cpu[name]:7.3f}s {cpu[name] / cpu['floor']:7.2f}x")
    share = wall["validate"] - wall["validate --skip-sim"]
    print(f"  the simulation's share (validate − --skip-sim): {share:.3f} s wall, "
          f"{cpu['validate'] - cpu['validate --skip-sim']:.3f} s cpu")
    print(f"  the simulation alone (its start, then the job) is {wall['the simulation alone'] / wall['floor']:.2f}x "
          f"the floor")
    ratio = wall["validate"] / wall["floor"]
    print(f"  validate / floor = {ratio:.2f}x wall (target ≤ {TARGET:g}x): {'met' if ratio <= TARGET else 'NOT met'}")


if __name__ == "__main__":
    main()
