"""One ``worldgen run WORLD NODE…`` from the command line's values to its report and files."""

from __future__ import annotations

from pathlib import Path

from ..check.report import check_junit_target, to_junit
from ..core.fsio import check_free, write_files
from .outcome import Outputs, RunRequest
from .preflight import blocked_result, blocked_text, node_findings
from .record import plot_png, trace_csv
from .report import result_of, run_json, run_text, task_context
from .rubrics import PERSON
from .transport import Transport, tried
from .world import graded_robot, load_world


def run_single(world_path: Path, node_args, request: RunRequest, outputs: Outputs, transport: Transport):
    """Check everything (exit-2 errors before any node starts; then every node's imports, a failed result
    without starting any node when some are missing: see :mod:`.preflight`), run, write the files; returns the
    :class:`~worldgen.check.report.Result` and the report text. ``outputs.html``: the replay page's file, made by
    ``outputs.html_page(result, world, trace)`` (the command line's, from :mod:`worldgen.view`; the bridge draws
    nothing itself), with every scan recorded for it."""
    o = outputs
    check_free([p for p in (o.plot, o.csv, o.bag, o.html) if p is not None], o.force)
    if o.junit is not None:
        check_junit_target(o.junit, o.force)   # an earlier report is replaced
    python = transport.node_python()

    def attempt():
        with transport.head_start() as head:   # the master's and simulator's starts, while the rest is read
            return _checked_run(world_path, node_args, request, o, transport, python, head)

    return tried(transport, attempt)   # a start-up that lost a port to another job: again, on another port


def _checked_run(world_path: Path, node_args, request: RunRequest, o: Outputs, transport: Transport, python: str,
                 head):
    """:func:`run_single` once the node's Python is known, in ``head`` (see :meth:`.Transport.head_start`)."""
    world = load_world(world_path, spawn=request.spawn, robot=request.robot, launch=request.launch)
    search = [world_path.parent] if world_path.is_file() else []
    nodes = transport.resolve_nodes(list(node_args), python, search)
    if request.robot_ns is not None:
        world = graded_robot(world, request.robot_ns)
    task_context(world, request.task)   # a line-follow world without tape, say: one line before anything starts
    missing = node_findings(nodes, python, naming=transport.naming())
    names = [n.name for n in nodes]
    if missing:
        return _blocked(world_path, world, missing, request.task, o, names)
    options = request.options(world, record_scans=o.html is not None)
    bag_tmp = None
    if o.bag is not None:
        bag_tmp = Path(o.bag).with_name(f".{Path(o.bag).name}.part")
        options.bag = bag_tmp.resolve()
    try:
        outcome = transport.run_nodes(world, nodes, options, head=head)
        result = result_of(str(world_path), world, outcome, request.task, request.target)
        files = {}
        if o.plot is not None:
            files[o.plot] = plot_png(world, outcome.trace, result, person=PERSON if options.person else None)
        if o.csv is not None:
            files[o.csv] = trace_csv(outcome.trace)
        if o.junit is not None:
            files[o.junit] = to_junit([result])
        if o.html is not None:
            files[o.html] = o.html_page(result, world, outcome.trace)
        if files:
            write_files(files, force=True)
        if bag_tmp is not None and bag_tmp.is_file():
            bag_tmp.replace(o.bag)
    finally:
        if bag_tmp is not None and bag_tmp.exists():
            bag_tmp.unlink()
    text = run_json(result, request.task) if o.fmt == "json" else run_text(result, request.task, names)
    return result, text


def _blocked(world_path: Path, world, missing, task, outputs: Outputs, names: list[str]):
    """A run that did not start (modules the nodes import are missing): its result, JUnit, and text."""
    result = blocked_result(str(world_path), world, missing, task)
    if outputs.junit is not None:
        write_files({outputs.junit: to_junit([result])}, force=True)
    return result, run_json(result, task) if outputs.fmt == "json" else blocked_text(result, task, names)
