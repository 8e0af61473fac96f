"""One ``worldgen run WORLD NODE…`` from the command line's values to its report and files."""

from __future__ import annotations

from pathlib import Path


def run_single(world_path: Path, node_args, *, task, target, duration, rate, spawn, robot, no_hit, fmt, junit=None,
               plot=None, csv_path=None, bag=None, force=False, robot_ns=None, launch=None, html=None, html_page=None):
    """Check everything (exit-2 errors before anything starts; then every node's imports, a failed result
    without starting anything when some are missing: see :mod:`.preflight`), run, write the files; returns the
    :class:`~worldgen.check.report.Result` and the report text. ``html``: the replay page's file, made by
    ``html_page(result, world, trace)`` (the command line's, from :mod:`worldgen.view`; the bridge draws
    nothing itself), with every scan recorded for it."""
    from ..core.fsio import check_free, write_files
    from .nodes import resolve_nodes
    from .preflight import node_findings
    from .report import result_of, run_json, run_text, task_context
    from .rosenv import import_rospy, node_python
    from .rubrics import PERSON, person_loop
    from .run import RunOptions, parse_duration, run_nodes
    from .world import graded_robot, load_world

    check_free([p for p in (junit, plot, csv_path, bag, html) if p is not None], force)
    import_rospy()
    python = node_python()
    world = load_world(world_path, spawn=spawn, robot=robot, launch=launch)
    search = [world_path.parent] if world_path.is_file() else []
    nodes = resolve_nodes(list(node_args), python, search)
    if robot_ns is not None:
        world = graded_robot(world, robot_ns)
    task_context(world, task)   # a line-follow world without tape, say: one line before anything starts
    missing = node_findings(nodes, python)
    if missing:
        return _blocked(world_path, world, missing, task, fmt, junit, [n.name for n in nodes])
    options = RunOptions(duration=parse_duration(duration, task), rate=rate, no_hit=no_hit, task=task,
                         target=target, bag=None, person=person_loop(world.spawn) if task == "person-follow" else None,
                         robot_ns=robot_ns, record_scans=html is not None)
    bag_tmp = None
    if bag is not None:
        bag_tmp = Path(bag).with_name(f".{Path(bag).name}.part")
        options.bag = bag_tmp.resolve()
    try:
        outcome = run_nodes(world, nodes, options)
        result = result_of(str(world_path), world, outcome, task, target)
        files = {}
        if plot is not None:
            from .record import plot_png
            files[plot] = plot_png(world, outcome.trace, result, person=PERSON if options.person else None)
        if csv_path is not None:
            from .record import trace_csv
            files[csv_path] = trace_csv(outcome.trace)
        if junit is not None:
            from ..check.report import to_junit
            files[junit] = to_junit([result])
        if html is not None:
            files[html] = html_page(result, world, outcome.trace)
        if files:
            write_files(files, force=True)
        if bag_tmp is not None and bag_tmp.is_file():
            bag_tmp.replace(bag)
    finally:
        if bag_tmp is not None and bag_tmp.exists():
            bag_tmp.unlink()
    text = run_json(result, task) if fmt == "json" else run_text(result, task, [n.name for n in nodes])
    return result, text


def _blocked(world_path: Path, world, missing, task, fmt, junit, names: list[str]):
    """A run that did not start (modules the nodes import are missing): its result, JUnit, and text."""
    from .preflight import blocked_result, blocked_text
    from .report import run_json

    result = blocked_result(str(world_path), world, missing, task)
    if junit is not None:
        from ..check.report import to_junit
        from ..core.fsio import write_files

        write_files({junit: to_junit([result])}, force=True)
    return result, run_json(result, task) if fmt == "json" else blocked_text(result, task, names)
