"""Speed of ``worldgen run`` against the floor measured in the same run (issue 26): one submission, a class's
folder, and where a run's time goes.

The floor is a Python start that imports what the simulator cannot do without: ``python -c 'import pybullet,
numpy, lxml.etree'`` (as bench_speed.py's). Each round runs, in an order that rotates from round to round so that a
busy machine slows all alike:

* the floor;
* ``worldgen run examples/enclosed_room.yaml stop_at_wall.py --task stop-at-wall --rate max`` — the course's node
  (``worldgen course``), 20 simulated seconds;
* with ``--grading``: a folder of 8 submissions (that node, each in a folder of its own) graded with ``-j 1`` and
  with ``-j 2``.

Printed: the medians of wall time, each also as a multiple of the floor's, against the targets (1.5 s for the run
and 6 s for 8 submissions at ``-j 2``, on a machine whose floor is 0.084 s: 18 and 71 floors). Then the phases of
a run of the same node, each run in a fresh process (as a command's: its imports, the node's Python, the master
and the simulator started, the world and the preflight meanwhile, the master answering, the simulator joining, the
node starting until it is ready, the simulated seconds, the ending, the report), medians of ``--rounds``.

    .venv/bin/python benchmarks/bench_run.py [--rounds N] [--grading]
"""

from __future__ import annotations

import argparse
import json
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))
ROOM = REPO / "examples" / "enclosed_room.yaml"
FLOOR = [sys.executable, "-c", "import pybullet, numpy, lxml.etree"]
FLOOR_THEN = 0.084   # s: the floor on the machine the targets were set on
TARGETS = {"run": 1.5, "grade -j 2": 6.0}
SUBMISSIONS = 8


def timed(cmd: list[str]) -> float:
    t0 = time.perf_counter()
    proc = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, cwd=REPO)
    wall = time.perf_counter() - t0
    if proc.returncode not in (0, 1):
        raise SystemExit(f"{' '.join(cmd)} failed ({proc.returncode}): {proc.stderr.decode()[-2000:]}")
    return wall


def course_node(tmp: Path) -> Path:
    from worldgen.packages.course_ros1 import write_course

    course = write_course(tmp / "course")
    return course / "lab_a_stop_at_wall" / "scripts" / "stop_at_wall.py"


def class_folder(tmp: Path, node: Path) -> Path:
    """A folder of :data:`SUBMISSIONS` submissions, each a folder holding the node."""
    folder = tmp / "submissions"
    for i in range(SUBMISSIONS):
        (folder / f"student_{i}").mkdir(parents=True)
        shutil.copy(node, folder / f"student_{i}" / "stop_at_wall.py")
    return folder


def measure(commands: dict[str, list[str]], rounds: int) -> dict[str, list[float]]:
    names = list(commands)
    times: dict[str, list[float]] = {n: [] for n in names}
    for r in range(rounds):
        for name in names[r % len(names):] + names[:r % len(names)]:
            times[name].append(timed(commands[name]))
    return times


def one_run_phases(node: Path) -> dict[str, float]:
    """Seconds of each phase of one run in this (fresh) process, from before its imports (see the module
    docstring)."""
    start = time.perf_counter()
    import worldgen.bridge.outcome as outcome
    import worldgen.bridge.supervise as supervise
    import worldgen.ros1.run as run
    import worldgen.ros1.transport as transport
    from worldgen.bridge.outcome import Outputs, RunRequest
    from worldgen.bridge.single import run_single
    from worldgen.cli.transports import transport_for

    marks: list[tuple[str, float]] = [("imports", time.perf_counter())]

    def wrap(owner, name: str, label: str, at_entry: bool = False) -> None:
        """A mark labelled ``label`` when ``owner.name`` returns (or, ``at_entry``, when it is called)."""
        names = [n for n in name.split("|") if hasattr(owner, n)]   # the first found (an older run's names too)
        if not names:
            return
        original = getattr(owner, names[0])

        def timed_call(*args, **kwargs):
            if at_entry:
                marks.append((label, time.perf_counter()))
            try:
                return original(*args, **kwargs)
            finally:
                if not at_entry:
                    marks.append((label, time.perf_counter()))
        setattr(owner, names[0], timed_call)

    wrap(transport.Ros1, "node_python", "the node's Python")
    wrap(run, "launch_master|import_rospy", "the master starting (not waited for)")
    wrap(run, "_run|start_master", "the world, the node, its preflight", at_entry=True)
    wrap(run, "await_master", "the master answering")
    wrap(run, "_wait_for_simulator", "the simulator joining")
    wrap(run, "wait_until_ready|_wait_for_nodes", "the node starting until ready")
    wrap(outcome, "wait_for_end", "the simulated seconds")
    wrap(supervise.Supervisor, "__exit__", "the ending")
    run_single(ROOM, [str(node)], RunRequest(task="stop-at-wall", rate=0.0), Outputs(), transport_for("noetic"))
    marks.append(("the report", time.perf_counter()))
    spent, previous = {}, start
    for label, at in marks:
        spent[label], previous = at - previous, at
    spent["in all"] = previous - start
    return spent


def phases(node: Path, rounds: int) -> dict[str, float]:
    """Median seconds of each phase of a run, each run in a fresh process (a command's first imports too)."""
    found: dict[str, list[float]] = {}
    for _ in range(rounds):
        out = subprocess.run([sys.executable, __file__, "--phases-of", str(node)], capture_output=True, text=True,
                             cwd=REPO, check=True).stdout
        for label, seconds in json.loads(out.splitlines()[-1]).items():
            found.setdefault(label, []).append(seconds)
    return {label: statistics.median(values) for label, values in found.items()}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--grading", action="store_true", help="also grade a folder of 8 submissions at -j 1, -j 2")
    parser.add_argument("--phases-of", type=Path, help=argparse.SUPPRESS)   # one run's phases, in a child
    args = parser.parse_args()
    if args.phases_of is not None:
        print(json.dumps(one_run_phases(args.phases_of)))
        return
    worldgen = [sys.executable, "-m", "worldgen", "run"]
    with tempfile.TemporaryDirectory(prefix="bench_run_") as tmp_name:
        tmp = Path(tmp_name)
        node = course_node(tmp)
        commands = {"floor": FLOOR,
                    "run": worldgen + [str(ROOM), str(node), "--task", "stop-at-wall", "--rate", "max"]}
        if args.grading:
            folder = class_folder(tmp, node)
            for jobs in (1, 2):
                commands[f"grade -j {jobs}"] = worldgen + [str(folder), "--task", "stop-at-wall", "--rate", "max",
                                                           "-j", str(jobs)]
        timed(commands["run"])   # warm: the node's Python learnt, the robot's description kept
        times = measure(commands, args.rounds)
        floor = statistics.median(times["floor"])
        print(f"floor (python -c 'import pybullet, numpy, lxml.etree'): {floor:.3f} s, median of {args.rounds}")
        for name, values in times.items():
            if name == "floor":
                continue
            median = statistics.median(values)
            line = f"{name:<12} {median:6.2f} s  = {median / floor:5.1f} floors  (min {min(values):.2f} s)"
            if name in TARGETS:
                allowed = TARGETS[name] / FLOOR_THEN
                line += (f"; target {TARGETS[name]:g} s = {allowed:.0f} floors: "
                         f"{'met' if median / floor <= allowed else 'NOT met'}")
            print(line)
        spent = phases(node, args.rounds)
        print(f"\nphases of one run (each in a fresh process after Python's start, median of {args.rounds}):")
        for label, seconds in spent.items():
            print(f"  {label:<40} {seconds:6.3f} s")


if __name__ == "__main__":
    main()
