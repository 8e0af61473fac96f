"""``worldgen validate PATH…``: worlds, specs, launch files and packages checked headless; text, JSON or JUnit."""

from __future__ import annotations

import sys
from pathlib import Path

import click

from ..core.errors import EXIT_FAILED, EXIT_OK


@click.command("validate")
@click.argument("paths", nargs=-1, required=True, type=click.Path(path_type=Path), metavar="PATH...")
@click.option("--robot", default=None, metavar="burger|waffle|waffle_pi|FILE",
              help="Robot model, or a .urdf/.urdf.xacro file. Default: the launch file's or spec's, else burger.")
@click.option("--spawn", default=None, metavar="X,Y[,YAW]",
              help="Spawn pose in metres and radians. Default: the launch file's, else the spec's, else the deepest "
                   "free point of each closed room.")
@click.option("--launch", "launch_file", type=click.Path(path_type=Path), default=None, metavar="FILE",
              help="Take the spawn pose and robot model from this launch file, and check that it starts the world.")
@click.option("--model-path", "model_paths", multiple=True, type=click.Path(path_type=Path), metavar="DIR",
              help="Folder of Gazebo models for model:// includes (repeatable; searched before GAZEBO_MODEL_PATH).")
@click.option("--format", "fmt", type=click.Choice(["text", "json"]), default="text", show_default=True,
              help="Report format on stdout.")
@click.option("--junit", type=click.Path(path_type=Path, dir_okay=False), default=None, metavar="FILE",
              help="Also write a JUnit XML report (one testcase per file and check).")
@click.option("-j", "--jobs", type=click.IntRange(1, 64), default=1, show_default=True,
              help="Files validated at once (each in its own simulator process).")
@click.option("--lidar-no-hit", type=click.Choice(["inf", "zero"]), default="inf", show_default=True,
              help="What a beam that hits nothing reads: inf as in Gazebo, 0 as the real LDS-01 driver.")
@click.option("--shard", default=None, metavar="K/N",
              help="Validate only shard K of N (1 ≤ K ≤ N): a stable share of the planned files, for a CI matrix; "
                   "the N shards together cover every file once.")
@click.option("--skip-sim", is_flag=True, help="Only the geometric checks (parse, enclosed, spawn-clear).")
@click.option("--sdformat", is_flag=True,
              help="Also libsdformat's own check of each world, where the library is installed (slow and "
                   "memory-hungry on big worlds).")
@click.option("--html", type=click.Path(path_type=Path, file_okay=False), default=None, metavar="DIR",
              help="Also write a folder of pages: index.html, a row per file (verdict, key numbers, findings), each "
                   "linking to that file's 3D page. Replaces the report an earlier --html wrote there.")
def validate(paths, robot, spawn, launch_file, model_paths, fmt, junit, jobs, lidar_no_hit, shard, skip_sim,
             sdformat, html):
    """Check worlds for a TurtleBot3 class: the room is closed around the spawn point, the robot spawns clear
    and settles, the LiDAR sees walls, it can spin in place and stop 0.5 m before a wall.

    PATH is a .world/.sdf/model.sdf file, a floorplan spec (.yaml), a launch file (roslaunch XML or ROS 2
    .launch.py, read without running it), a catkin or ament package folder, or any folder (a catkin or colcon
    workspace, its src/, a folder of submissions): searched for packages, else for worlds and specs.
    A missing path is a failed result of its own. Progress goes to stderr (a bar on a terminal, a line per
    file otherwise). Exit status: 0 every check passed (warnings allowed), 1 a check failed, 2 bad input.
    """
    args = (paths, robot, spawn, launch_file, model_paths, fmt, junit, jobs, lidar_no_hit, shard, skip_sim, sdformat,
            html)
    from ..sim.forkserver import active

    if skip_sim or active() is not None:   # nothing to simulate, or the program started the server (worldgen.__main__)
        return _validate(*args)
    import importlib

    from ..check.preload import SHARED_MODULES, SIM_MODULES
    from ..sim.forkserver import forking, one_blas_thread

    # the simulations' fork server, forked while this process runs one thread (numpy's BLAS held to it) and has
    # imported what a run needs of worldgen; the server imports pybullet and the simulator while this process
    # imports the checks and reads the inputs
    one_blas_thread()
    for name in SHARED_MODULES:
        importlib.import_module(name)
    with forking(SIM_MODULES):
        _validate(*args)


def _validate(paths, robot, spawn, launch_file, model_paths, fmt, junit, jobs, lidar_no_hit, shard, skip_sim,
              sdformat, html):
    from ..core.fsio import write_file
    from ..check.report import check_junit_target, to_json, to_junit, to_text
    from ..core.spawnpose import parse_spawn
    from ..check.discover import parse_shard
    from ..check.discover import shard as take_shard
    from ..check.progress import progress_for
    from ..check.validate import Options, plan, run_jobs

    shard_k_n = parse_shard(shard) if shard is not None else None
    options = Options(robot=robot, spawn=parse_spawn(spawn) if spawn is not None else None, launch=launch_file,
                      model_paths=tuple(model_paths), lidar_no_hit=lidar_no_hit, skip_sim=skip_sim,
                      sdformat=sdformat)
    if junit is not None:
        from .outputs import check_suffix

        check_suffix(junit, "junit", "--junit")
        check_junit_target(junit, forceable=False)
    if html is not None:
        from ..view.grades import check_report_folder
        from ..view.page import require_three

        check_report_folder(html)
        require_three()
    notes: list[str] = []
    planned = plan(paths, options, notes)
    for note in notes:
        click.echo(f"worldgen: {note}", err=True)
    if shard_k_n is not None:
        planned = take_shard(planned, *shard_k_n, key=lambda job: job.path)
        click.echo(f"worldgen: shard {shard_k_n[0]}/{shard_k_n[1]}: {len(planned)} of the planned files", err=True)
    with progress_for(len(planned)) as progress:
        results = run_jobs(planned, options, jobs, progress=progress)
    if junit is not None:   # first: when it cannot be written, exit 2 leaves stdout empty
        write_file(junit, to_junit(results), force=True)
    if html is not None:
        from ..view.grades import validate_page, write_report

        write_report(html, results, lambda r: validate_page(r, model_paths),
                     "worldgen validate " + " ".join(str(p) for p in paths))
    click.echo(to_json(results) if fmt == "json" else to_text(results), nl=False)
    sys.exit(EXIT_OK if all(r.ok for r in results) else EXIT_FAILED)


COMMANDS = [validate]
