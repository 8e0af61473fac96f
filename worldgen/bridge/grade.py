"""A teaching assistant's folder: ``worldgen run submissions/ --task stop-at-wall -j 2 --junit grades.xml``.

Each submission is a catkin package under the folder (or, when the folder holds no package, each of its
subfolders). Its node for the task is the script named as the course names it (``stop_at_wall.py``,
``spin_in_circles.py``, ``drive_square.py``, ``wall_follower.py``, ``person_follower.py``), or the file named on
the command line, or its only Python file. Every node's imports are looked up first, for the whole folder in one
go (:mod:`.preflight`); a submission whose node imports a module that is not installed is not started, its result
holding a ``runtime`` finding per missing module. Every other submission runs in its own master on its own port,
``jobs`` at once, and gets one :class:`~worldgen.check.report.Result`; a submission that cannot run is an error
finding, never the end of the grading. A package the others depend on that holds no node for the task (the
course's world package handed in beside the labs), and a metapackage, are no submission: they are left out
(:func:`not_submissions`).
"""

from __future__ import annotations

from pathlib import Path
from typing import Callable, NamedTuple, Optional

from ..check.discover import depended_on, is_metapackage, unpackaged, unpackaged_finding
from ..check.discover import shard as take_shard
from ..check.report import Result
from ..core.errors import InputError, WorldFileError, WorldgenError
from ..core.findings import Finding
from ..core.packages import MANIFEST, build_type, crawl, manifest_name
from ..core.resources import examples_dir
from ..pyread.setup_py import read_setup
from .outcome import RunRequest
from .preflight import blocked_result, many_findings
from .report import result_of, task_context
from .supervise import in_parallel
from .transport import Transport, tried
from .world import load_world

TASK_NODES = {"stop-at-wall": "stop_at_wall.py", "spin": "spin_in_circles.py", "drive-square": "drive_square.py",
              "wall-follow": "wall_follower.py", "person-follow": "person_follower.py",
              "line-follow": "line_follower.py"}


def submissions(folder: Path) -> list[Path]:
    """The catkin packages under ``folder`` (crawled as rospack does; a workspace through its ``src/`` only; a
    symlinked folder leading out of ``folder`` not followed), else its subfolders; sorted."""
    found = [p for p in crawl(folder, workspaces=True, outside=[]) if p != folder]   # never out of the folder
    if not found:
        found = [p for p in folder.iterdir() if p.is_dir() and not p.name.startswith(".")]
    return sorted(found)


def not_submissions(found: list[Path], task: str | None, names=()) -> dict[Path, str]:
    """The packages of a graded folder that are no submission, each with why, among those holding no node for the
    task: one that another package there depends on (package.xml) — the course's world package handed in beside
    the labs (their launch files start its world), a student's own world or message package — and a metapackage
    (REP 127), which only groups the packages beside it (the course's ``intro_robo``)."""
    needed = depended_on(found)
    left = {}
    for p in found:
        if is_metapackage(p):
            why = "a metapackage: it only groups the packages beside it"
        elif (manifest_name(p / MANIFEST) or p.name) in needed:
            why = "packages in the folder depend on it and it holds no node for the task"
        else:
            continue
        if not _has_node(p, task, names):
            left[p] = why
    return left


def _has_node(submission: Path, task: str | None, names) -> bool:
    try:
        node_of(submission, task, list(names))
    except InputError:
        return False
    return True


def node_of(submission: Path, task: str | None, names: list[str]) -> Path:
    """The submission's node for ``task`` (see the module docstring); InputError naming what was looked for."""
    wanted = list(names) or ([TASK_NODES[task]] if task else [])
    for name in wanted:
        hits = sorted(p for p in submission.rglob(Path(name).name) if p.is_file())
        if hits:
            return hits[0]
    scripts = sorted(p for p in submission.rglob("*.py") if p.is_file() and p.name != "setup.py")
    if len(scripts) == 1:
        return scripts[0]
    files = f"{len(scripts)} Python file{'' if len(scripts) == 1 else 's'}"
    found = f"no {' or '.join(wanted)}, and {files}" if wanted else (f"{files} and no --task to pick one by" if
                                                                    scripts else "no Python file")
    raise InputError(f"cannot tell which node to run: {found}", path=submission,
                     hint="name the node file after the task, or give its name after the folder")


class Hooks(NamedTuple):
    """What the caller of :func:`grade_folder` hears as the grading goes."""

    each: Optional[Callable] = None       # each(result, world, trace): every run that ran, its scans recorded
    left_out: Optional[Callable] = None   # left_out(package, why): a package that is no submission, before any runs


def grade_folder(folder: Path, world_path: Path | None, request: RunRequest, transport: Transport, *, jobs: int = 1,
                 nodes=(), shard: tuple[int, int] | None = None, hooks: Hooks = Hooks()) -> list[Result]:
    """One result per submission in ``folder`` (each run on its own, ``jobs`` at once); with ``shard``
    (K, N), only the K-th of N stable shares of the submissions (:func:`worldgen.check.discover.shard`).
    ``hooks`` (:class:`Hooks`) hear each run (a replay page) and each package that is no submission
    (:func:`not_submissions`)."""
    each, left_out = hooks
    python = transport.node_python()
    world = load_world(world_path or examples_dir() / "enclosed_room.yaml", spawn=request.spawn,
                       robot=request.robot, launch=request.launch)
    task = request.task
    task_context(world, task)   # a line-follow world without tape, say: one line before anything starts
    found = submissions(folder)
    packaged = any((p / MANIFEST).is_file() for p in found)
    handed_in = set(unpackaged(folder, found)) if packaged else set()   # no package.xml: a failed row, not left out
    passed_over = not_submissions(found, task, nodes)
    if left_out is not None:
        for package, why in passed_over.items():
            left_out(package, why)
    found = [p for p in found if p not in passed_over]
    found = sorted([*found, *handed_in])
    if not found:
        raise InputError("holds no submissions (no catkin packages, no folders)", path=folder,
                         hint="give the folder holding one folder or package per student")
    if shard is not None:
        found = take_shard(found, *shard, key=str)
    options = request.options(world, record_scans=each is not None)
    planned = {s: _plan(s, task, nodes, python, transport) for s in found if s not in handed_in}
    missing = many_findings({str(s): p[1] for s, p in planned.items() if not isinstance(p, WorldgenError)}, python,
                            naming=transport.naming())

    def one(submission: Path) -> Result:
        if submission in handed_in:
            result = Result(path=str(submission), spawn=world.spawn, spawn_source=f"from {world.spawn_source}",
                            robot=world.robot, robot_source=world.robot_source, checks=["package"])
            result.findings.append(unpackaged_finding(submission))
            if task:
                result.skipped[task] = "the submission holds no package"
            return result
        plan = planned[submission]
        try:
            if isinstance(plan, WorldgenError):
                raise plan
            node, specs = plan
            if missing[str(submission)]:
                result = blocked_result(str(submission), world, missing[str(submission)], task)
                result.metrics["node"] = str(node.relative_to(submission))
                return result
            outcome = _run(world, specs, options, transport)
        except WorldgenError as err:
            result = Result(path=str(submission), spawn=world.spawn, spawn_source=f"from {world.spawn_source}",
                            robot=world.robot, robot_source=world.robot_source, checks=["node"])
            result.findings.append(Finding("node", "error", str(err), where=str(submission)))
            if task:
                result.skipped[task] = "the node could not run"
            return result
        result = result_of(str(submission), world, outcome, task, request.target)
        result.metrics["node"] = str(node.relative_to(submission))
        if each is not None:
            each(result, world, outcome.trace)
        return result

    return in_parallel(one, found, jobs)


def _plan(submission: Path, task: str | None, names, python: str, transport: Transport):
    """The submission's node file and the processes it starts, or the WorldgenError saying why it cannot run
    (an ament_python package whose setup.py does not parse cannot be built: its node never runs under ROS)."""
    try:
        _check_buildable(submission)
        node = node_of(submission, task, list(names))
        return node, transport.resolve_nodes([str(node)], python)
    except WorldgenError as err:
        return err


def _check_buildable(submission: Path) -> None:
    """InputError when ``submission`` is an ament_python package whose setup.py does not parse (colcon fails)."""
    setup_py = submission / "setup.py"
    if not setup_py.is_file() or build_type(submission) != "ament_python":
        return
    try:
        read_setup(setup_py)
    except WorldFileError as err:
        raise InputError(f"colcon cannot build the package: {err.message}", path=err.path, line=err.line,
                         hint=err.hint) from None


def _run(world, specs, options, transport: Transport):
    """One submission's run; a start-up that lost a race for a port to another job is tried again."""
    return tried(transport, lambda: transport.run_nodes(world, specs, options))
