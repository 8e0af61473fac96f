"""A node graded across many worlds: ``worldgen run --worlds SOURCE NODE… --task T``.

SOURCE is a folder of worlds or specs (searched as ``validate`` searches one) or ``KIND:COUNT[@SEED]``: COUNT
worlds of a ``worldgen generate`` kind, made on the fly with that kind's defaults from seeds SEED … SEED+COUNT−1
(SEED 0 when left out) into a temporary folder that lives as long as the grading. Each world is run with its own
spawn (its spec's robot entry) by a *runner* the caller gives — a function of one world returning its results,
one per graded thing: the node's single run, or one per submission of a class's folder, so that every
submission meets the same worlds. Nothing here speaks ROS: the command line hands in a runner built on its
transport.

The report: one line per world (and submission), the pass rate, ``--min-pass FRACTION`` for the verdict (every
world must pass unless said otherwise), the failing worlds each with the one command that runs it again alone
(``rerun``, also the caller's), JSON ``{"ok", "passed", "total", "min_pass", "worlds": [...]}`` and JUnit (a test
case per world and check, named after the world).
"""

from __future__ import annotations

import contextlib
import json
import math
import re
import tempfile
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Callable, Iterator, List, Optional, Sequence

from ..check.report import Result, to_junit
from ..core.errors import InputError
from ..check.discover import find_loose
from ..generate.options import KINDS
from ..generate.worlds import generate
from .grade import grade_folder
from .outcome import Outputs
from .single import run_single
from .supervise import in_parallel

GENERATED = re.compile(r"^(?P<kind>[a-z]+):(?P<count>\d+)(?:@(?P<seed>\d+))?$")
MAX_WORLDS = 1000


@dataclass(frozen=True)
class WorldItem:
    """One world of a SOURCE: ``name`` as reports show it, ``path`` the spec or world file to run in, ``source``
    what names it alone on a command line (its file, or ``KIND:1@SEED``)."""

    name: str
    path: Path
    source: str


@dataclass
class WorldRun:
    """What one world came to: a result per graded thing (one for a node, one per submission)."""

    world: WorldItem
    results: List[Result] = field(default_factory=list)


# --------------------------------------------------------------------------------------------------- sources

def parse_source(text: str):
    """``KIND:COUNT[@SEED]`` → (kind, count, seed), or None when ``text`` is not of that form (a folder)."""
    match = GENERATED.match(text.strip())
    if match is None:
        return None
    kind, count, seed = match["kind"], int(match["count"]), int(match["seed"] or 0)
    if kind not in KINDS:
        raise InputError(f"--worlds {text}: there is no kind of world called '{kind}'",
                         hint=f"write KIND:COUNT[@SEED] with KIND one of {', '.join(KINDS)}, or give a folder")
    if not 1 <= count <= MAX_WORLDS:
        raise InputError(f"--worlds {text}: {count} worlds", hint=f"ask for 1 to {MAX_WORLDS}")
    return kind, count, seed


@contextlib.contextmanager
def world_items(source: str) -> Iterator[List[WorldItem]]:
    """The worlds of ``source`` (see the module docstring), for as long as the ``with`` block runs; InputError
    when there are none."""
    generated = parse_source(source)
    if generated is None:
        yield _folder_items(Path(source))
        return

    kind, count, seed = generated
    with tempfile.TemporaryDirectory(prefix="worldgen-worlds-") as tmp:
        items = []
        for world in generate(kind, seed, count):
            path = Path(tmp) / world.file_name
            path.write_text(world.text, encoding="utf-8")
            items.append(WorldItem(world.name, path, f"{kind}:1@{world.seed}"))
        yield items


def _folder_items(folder: Path) -> List[WorldItem]:
    if not folder.is_dir():
        raise InputError("is neither a folder of worlds nor KIND:COUNT[@SEED]", path=folder,
                         hint="give a folder of specs or worlds, or e.g. --worlds rooms:10 (ten generated flats)")
    found = [path for kind, path in find_loose(folder) if kind in ("world", "spec")]
    if not found:
        raise InputError("holds no world or spec to run in", path=folder,
                         hint="give a folder of .yaml specs or .world files, e.g. one worldgen generate wrote")
    return [WorldItem(str(p.relative_to(folder).with_suffix("")), p, str(p)) for p in found]


# ----------------------------------------------------------------------------------------------- the grading

def across_worlds(items: Sequence[WorldItem], runner: Callable[[WorldItem], List[Result]], *, jobs: int = 1,
                  progress: Optional[Callable[[WorldRun], None]] = None) -> List[WorldRun]:
    """``runner`` in every world, ``jobs`` worlds at once; the runs in the worlds' order. A world whose results
    carry another path are named after the world (a node's run), or after the submission and the world."""
    def one(item: WorldItem) -> WorldRun:
        run = WorldRun(item, list(runner(item)))
        if progress is not None:
            progress(run)
        return run

    if jobs <= 1 or len(items) <= 1:
        return [one(item) for item in items]
    return in_parallel(one, list(items), jobs)


@dataclass(frozen=True)
class Tally:
    """One graded thing's results over the worlds: ``who`` (None for a single node, else the submission)."""

    who: Optional[str]
    passed: int
    total: int
    failing: tuple   # (WorldRun, Result) pairs

    @property
    def rate(self) -> float:
        return self.passed / self.total if self.total else 0.0

    def ok(self, min_pass: float) -> bool:
        return self.total > 0 and self.rate >= min_pass - 1e-12


def tallies(runs: Sequence[WorldRun]) -> List[Tally]:
    """Per graded thing (a node; else each submission, in the order they first come), its passes and failures."""
    single = all(len(run.results) <= 1 for run in runs)
    order: List[Optional[str]] = []
    rows: dict = {}
    for run in runs:
        for result in run.results:
            who = None if single else result.path
            if who not in rows:
                order.append(who)
                rows[who] = []
            rows[who].append((run, result))
    return [Tally(who, sum(r.ok for _, r in rows[who]), len(rows[who]),
                  tuple((run, r) for run, r in rows[who] if not r.ok)) for who in order]


def check_min_pass(value: float) -> float:
    if not (0.0 <= value <= 1.0) or math.isnan(value):
        raise InputError(f"--min-pass {value:g} is not a share", hint="give a fraction from 0 to 1, e.g. 0.8")
    return value


# ------------------------------------------------------------------------------------------------ runners

def node_runner(nodes: Sequence[str], request, transport) -> Callable[[WorldItem], List[Result]]:
    """A runner of the nodes (``run``'s NODE… arguments) in one world, on ``transport``, as ``run WORLD NODE…``
    runs them (:func:`worldgen.bridge.single.run_single`, every file left unwritten)."""
    def runner(item: WorldItem) -> List[Result]:
        return [run_single(item.path, list(nodes), request, Outputs(fmt="json"), transport)[0]]
    return runner


def class_runner(folder: Path, nodes: Sequence[str], request, transport, *, jobs: int = 1, shard=None
                 ) -> Callable[[WorldItem], List[Result]]:
    """A runner of every submission of ``folder`` in one world (:func:`worldgen.bridge.grade.grade_folder`,
    ``jobs`` submissions at once): every submission meets the same worlds."""
    def runner(item: WorldItem) -> List[Result]:
        return grade_folder(folder, item.path, request, transport, jobs=jobs, nodes=tuple(nodes), shard=shard)
    return runner


def rerun_maker(nodes: Sequence[str], flags: Sequence[str]) -> Callable[[WorldItem, Result], str]:
    """The command that runs one world again alone: ``worldgen run`` with the world (its file, or ``--worlds
    KIND:1@SEED`` for a generated one), the node (a submission's own, from its result), and ``flags`` (the task,
    rate and the rest, as given)."""
    import shlex

    def rerun(world: WorldItem, result: Result) -> str:
        node = result.metrics.get("node")   # a submission's node, relative to the submission
        args = [str(Path(result.path) / node)] if node else (list(nodes) or [result.path])
        where = ["--worlds", world.source] if GENERATED.match(world.source) else [world.source]
        return " ".join(shlex.quote(a) for a in ["worldgen", "run", *where, *args, *flags])
    return rerun


# --------------------------------------------------------------------------------------------------- reports

def _m(value, unit: str = " m") -> str:
    return "–" if value is None else f"{value:.2f}{unit}"


def worlds_text(runs: Sequence[WorldRun], min_pass: float, rerun: Callable[[WorldItem, Result], str],
                task: Optional[str]) -> str:
    """One line per world (and submission) with the numbers that matter and its errors below, the pass rate per
    node or submission against ``min_pass``, and each failing world with the command that runs it again."""
    classes = any(len(run.results) > 1 for run in runs)   # a class: a column naming each submission
    rows = [["world", *(["submission"] if classes else []), "verdict", "front", "path", "turned", "contacts"]]
    errors = []
    for run in runs:
        for r in run.results:
            m = r.metrics
            rows.append([run.world.name, *([r.path] if classes else []), "ok" if r.ok else "FAIL",
                         _m(m.get("final_front_distance_m")),
                         _m(m.get("path_length_m")),
                         "–" if m.get("rotation_rad") is None else f"{m['rotation_rad'] / math.tau:+.2f} turns",
                         str(len(m.get("contacts") or []))])
            errors.append([f"    {f.check}: {f.message}" for f in r.sorted_findings() if f.severity == "error"])
    widths = [max(len(row[i]) for row in rows) for i in range(len(rows[0]))]
    lines = []
    for i, row in enumerate(rows):
        lines.append("  ".join(c.ljust(w) for c, w in zip(row, widths)).rstrip())
        if i:
            lines += errors[i - 1][:2]
    what = task or "the run"
    for tally in tallies(runs):
        who = f"{tally.who}: " if tally.who else ""
        verdict = "PASS" if tally.ok(min_pass) else "FAIL"
        lines.append(f"{who}{what} passed in {tally.passed} of {tally.total} worlds ({tally.rate:.0%}); "
                     f"--min-pass {min_pass:g}: {verdict}")
        if tally.failing:
            lines.append("  failing worlds, each run again alone with:")
            lines += [f"    {run.world.name}: {rerun(run.world, r)}" for run, r in tally.failing]
    return "\n".join(lines) + "\n"


def worlds_json(runs: Sequence[WorldRun], min_pass: float, rerun: Callable[[WorldItem, Result], str]) -> str:
    """``{"ok", "passed", "total", "min_pass", "worlds": [...]}`` — each world its source, verdict, the command
    that reruns it and its result as ``validate --format json`` writes one; with several submissions also
    ``"submissions"``, each one's passes, total and verdict."""
    marks = tallies(runs)
    worlds = []
    for run in runs:
        for r in run.results:
            worlds.append({"world": run.world.name, "source": run.world.source, "ok": r.ok,
                           "rerun": None if r.ok else rerun(run.world, r), "result": r.to_dict()})
    doc = {"ok": all(t.ok(min_pass) for t in marks), "passed": sum(t.passed for t in marks),
           "total": sum(t.total for t in marks), "min_pass": min_pass, "worlds": worlds}
    if any(t.who is not None for t in marks):
        doc["submissions"] = [{"path": t.who, "ok": t.ok(min_pass), "passed": t.passed, "total": t.total}
                              for t in marks]
    return json.dumps(doc, indent=2, allow_nan=False, ensure_ascii=False) + "\n"


def worlds_junit(runs: Sequence[WorldRun], suite: str = "worldgen run --worlds") -> bytes:
    """JUnit as ``run`` writes it, a test case per world (and submission) and check, named after the world."""
    named = []
    for run in runs:
        for r in run.results:
            name = run.world.name if len(run.results) <= 1 else f"{r.path} @ {run.world.name}"
            named.append(replace(r, path=name))
    return to_junit(named, suite_name=suite)


def worlds_ok(runs: Sequence[WorldRun], min_pass: float) -> bool:
    return all(t.ok(min_pass) for t in tallies(runs))
