"""``worldgen run WORLD NODE…``: the class's own ROS nodes on the simulated TurtleBot3, measured and graded."""

from __future__ import annotations

import sys
from pathlib import Path

import click

from ..bridge.outcome import Outputs, RunRequest, parse_rate
from ..bridge.rubrics import TASKS
from ..core.errors import EXIT_FAILED, EXIT_OK
from .drive import FiniteFloat
from .ros import cmd_vel_option, ros_option
from .transports import transport_for


@click.command("run", context_settings={"ignore_unknown_options": True})
@click.argument("world", type=click.Path(path_type=Path))
@click.argument("nodes", nargs=-1)
@click.option("--task", type=click.Choice(TASKS), default=None, help="Grade the run with this exercise's rubric.")
@click.option("--target", type=FiniteFloat(min=0.0, min_open=True), default=None, metavar="M",
              help="stop-at-wall: distance to stop at (0.5); wall-follow: distance to keep (0.4).")
@click.option("--duration", type=FiniteFloat(min=0.0, min_open=True, max=3600), default=None, metavar="S",
              help="Simulated seconds (default: 20, spin 30, the others 60).")
@click.option("--rate", default="1", show_default=True, metavar="R|max",
              help="Simulated time at R x real time, or max: as fast as the nodes keep up.")
@click.option("--spawn", default=None, metavar="X,Y[,YAW]",
              help="Spawn pose in metres and radians. Default: the launch file's, else the spec's, else 0,0,0.")
@click.option("--launch", "launch_file", type=click.Path(path_type=Path), default=None, metavar="FILE",
              help="Take the robots (several: one per <group ns>), spawn poses and parameters from this launch file.")
@click.option("--robot", default=None, metavar="burger|waffle|waffle_pi|FILE", help="Robot model or description.")
@click.option("--robot-ns", default=None, metavar="NS",
              help="With several robots (a launch file's <group ns>s): the one to grade. Every robot is reported.")
@click.option("--world", "folder_world", type=click.Path(path_type=Path), default=None, metavar="WORLD",
              help="With a folder of submissions: the world to grade them in (default: the class's room).")
@click.option("-j", "--jobs", type=click.IntRange(1, 16), default=1, show_default=True,
              help="With a folder of submissions: runs at once, each with its own master.")
@click.option("--shard", default=None, metavar="K/N",
              help="A folder of submissions: grade only shard K of N (a stable share, for a CI matrix).")
@click.option("--format", "fmt", type=click.Choice(["text", "json"]), default="text", show_default=True)
@click.option("--junit", type=click.Path(path_type=Path, dir_okay=False), default=None, metavar="FILE",
              help="Also write a JUnit XML report.")
@click.option("--plot", type=click.Path(path_type=Path, dir_okay=False), default=None, metavar="PNG",
              help="Top-down picture of the path over the walls, with start, end and contacts.")
@click.option("--csv", "csv_path", type=click.Path(path_type=Path, dir_okay=False), default=None, metavar="FILE",
              help="The time series (pose, speeds, commands, front distance) as CSV.")
@click.option("--bag", type=click.Path(path_type=Path, dir_okay=False), default=None, metavar="FILE",
              help="A rosbag of /scan, /odom and /cmd_vel.")
@click.option("--lidar-no-hit", type=click.Choice(["inf", "zero"]), default="inf", show_default=True,
              help="What a beam that hits nothing reads: inf as in Gazebo, 0 as the real LDS-01 driver.")
@click.option("--html", type=click.Path(path_type=Path), default=None, metavar="FILE.html|DIR",
              help="A 3D page replaying the run (robot, path, scans, cmd_vel and distance plots, findings). With a "
                   "folder of submissions: a folder with an index page and one replay per submission.")
@click.option("--force", is_flag=True, help="Overwrite existing --plot/--csv/--bag/--junit/--html files.")
@click.option("--worlds", "worlds_source", default=None, metavar="FOLDER|KIND:COUNT[@SEED]",
              help="Grade across many worlds, each with its own spawn: a folder of worlds or specs, or COUNT worlds "
                   "of a `worldgen generate` kind made on the fly (rooms:10, maze:24@100). WORLD is then the first "
                   "NODE, or a folder of submissions, each meeting the same worlds.")
@click.option("--min-pass", type=float, default=1.0, show_default=True, metavar="FRACTION",
              help="With --worlds: the share of the worlds that must pass for exit 0.")
@ros_option
@cmd_vel_option
def run(world, nodes, task, target, duration, rate, spawn, launch_file, robot, robot_ns, folder_world, jobs, shard, fmt,
        junit, plot, csv_path, bag, html, lidar_no_hit, force, worlds_source, min_pass, ros, cmd_vel):
    """Run NODE... (a .py file, PKG/TYPE, or a .launch file's nodes; `name:=value` after a node is its argument)
    on the simulated TurtleBot3 in WORLD, with a private ROS master, and report what the robot did. With --task,
    grade it: exit 0 pass, 1 fail.

    WORLD may be a folder of submissions (catkin packages): each one's node for --task runs in its own master
    and gets one result, as `validate` reports files. With --worlds, WORLD is left out: the nodes (or the folder
    of submissions) run in every world of the source, one line per world, the pass rate against --min-pass.
    """
    from ..core.spawnpose import parse_spawn
    from ..check.discover import parse_shard
    from .outputs import check_suffix

    check_suffix(plot, "png", "--plot")
    check_suffix(junit, "junit", "--junit")
    if junit is not None:
        from ..check.report import check_junit_target

        check_junit_target(junit, force)
    if html is not None:
        from ..view.page import require_three

        require_three()
    transport = transport_for(ros, cmd_vel)
    shard_k_n = parse_shard(shard) if shard is not None else None
    request = RunRequest(task=task, target=target, duration=duration, rate=parse_rate(rate), no_hit=lidar_no_hit,
                         spawn=parse_spawn(spawn) if spawn is not None else None, robot=robot, launch=launch_file,
                         robot_ns=robot_ns)
    if worlds_source is not None:
        given = {"--spawn": spawn, "--launch": launch_file, "--world": folder_world, "--plot": plot, "--csv": csv_path,
                 "--bag": bag, "--html": html}
        pairs = (("--task", task), ("--target", target), ("--duration", duration), ("--rate", rate),
                 ("--robot", robot), ("--lidar-no-hit", None if lidar_no_hit == "inf" else lidar_no_hit),
                 ("--ros", None if ros == "noetic" else ros), ("--cmd-vel", cmd_vel))
        flags = [x for f, v in pairs if v is not None for x in (f, f"{v:g}" if isinstance(v, float) else str(v))]
        _across_worlds(worlds_source, world, nodes, request, transport, jobs, shard_k_n, min_pass, fmt, junit, flags,
                       given)
    if world.is_dir() and not (world / "model.sdf").is_file() and not (world / "model.config").is_file():
        from ..bridge.grade import Hooks, grade_folder

        pages: dict = {}
        each = None
        if html is not None:
            from ..view.grades import BACK, check_report_folder, run_page

            check_report_folder(html)

            def each(result, world_run, trace):
                pages[result.path] = run_page(result, world_run, trace, back=BACK)

        hooks = Hooks(each, lambda package, why: click.echo(f"worldgen: {package}: not graded: {why}", err=True))
        results = grade_folder(world, folder_world, request, transport, jobs=jobs, nodes=nodes, shard=shard_k_n,
                               hooks=hooks)
        if html is not None:
            from ..view.grades import write_report

            write_report(html, results, lambda r: pages.get(r.path), f"worldgen run {world.name}")
        _write_reports(results, fmt, junit)
        sys.exit(EXIT_OK if all(r.ok for r in results) else EXIT_FAILED)
    if shard_k_n is not None:
        from ..core.errors import InputError

        raise InputError("--shard takes a folder of submissions", path=world,
                         hint="give the folder holding one package per student, or leave out --shard")
    if html is not None and html.is_dir():
        from ..core.errors import InputError

        raise InputError("is a folder: --html of one run is a page", path=html,
                         hint="give a file name such as run.html (a folder of pages is for a folder of submissions)")
    from ..bridge.single import run_single

    outputs = Outputs(fmt=fmt, junit=junit, plot=plot, csv=csv_path, bag=bag, html=html, force=force,
                      html_page=_replay_page(nodes) if html is not None else None)
    files = [p for p in (plot, csv_path, bag, html, junit) if p is not None]
    before = {p: _stamp(p) for p in files}
    result, text = run_single(world, nodes, request, outputs, transport)
    click.echo(text, nl=False)
    if fmt == "text":   # (JSON on stdout stays JSON alone)
        for path in files:
            if _stamp(path) not in (None, before[path]):
                click.echo(f"wrote {path}")
    sys.exit(EXIT_OK if result.ok else EXIT_FAILED)


def _stamp(path: Path):
    """A file's identity and last change (None: no file), to tell the files a run wrote."""
    try:
        info = path.stat()
    except OSError:
        return None
    return info.st_ino, info.st_mtime_ns, info.st_size


def _across_worlds(source: str, first: Path, nodes, request, transport, jobs: int, shard, min_pass: float, fmt: str,
                   junit: Path | None, flags: list, given: dict) -> None:
    """``run --worlds SOURCE``: the nodes (or each submission of the folder ``first``) in every world of SOURCE
    (:mod:`worldgen.bridge.worlds`); exits 0 when the share passed reaches ``min_pass``."""
    from ..bridge import worlds as across
    from ..core.errors import InputError
    from ..core.fsio import write_file

    used = [flag for flag, value in given.items() if value is not None]
    if used:
        raise InputError(f"{used[0]} is for one world, and --worlds runs many (each with its own spawn)",
                         hint=f"leave out {used[0]}, or run one world without --worlds")
    min_pass = across.check_min_pass(min_pass)
    folder = first.is_dir()
    node_args = list(nodes) if folder else [str(first), *nodes]
    runner = (across.class_runner(first, node_args, request, transport, jobs=jobs, shard=shard) if folder else
              across.node_runner(node_args, request, transport))
    rerun = across.rerun_maker([] if folder else node_args, flags)
    with across.world_items(source) as items:
        runs = across.across_worlds(items, runner, jobs=1 if folder else jobs,
                                    progress=lambda r: click.echo(f"[{r.world.name}] "
                                                                  f"{'ok' if all(x.ok for x in r.results) else 'FAIL'}",
                                                                  err=True))
    if junit is not None:
        write_file(junit, across.worlds_junit(runs), force=True)
    click.echo(across.worlds_json(runs, min_pass, rerun) if fmt == "json" else
               across.worlds_text(runs, min_pass, rerun, request.task), nl=False)
    sys.exit(EXIT_OK if across.worlds_ok(runs, min_pass) else EXIT_FAILED)


def _replay_page(nodes):
    """The replay page's maker for a run of ``nodes`` (its title: the nodes' names)."""
    names = [Path(n).name for n in nodes if ":=" not in n]

    def page(result, world, trace) -> bytes:
        from ..view.grades import run_page

        return run_page(result, world, trace, title=", ".join(names) or Path(result.path).name)
    return page


def _write_reports(results, fmt: str, junit: Path | None) -> None:
    from ..check.report import to_json, to_junit
    from ..core.fsio import write_file
    from ..bridge.report import folder_text

    if junit is not None:
        write_file(junit, to_junit(results, suite_name="worldgen run"), force=True)
    click.echo(to_json(results) if fmt == "json" else folder_text(results), nl=False)


COMMANDS = [run]
