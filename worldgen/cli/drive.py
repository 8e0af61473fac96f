"""``worldgen drive WORLD``: the class's sensory-motor exercises (spin in place, stop at a wall with P/PI/PID
gains) run headless in pybullet, with the figures a student compares and an optional plot and CSV."""

from __future__ import annotations

import json
import math
import sys
from pathlib import Path

import click

from ..core import stoplaw
from ..sim.exercise import BEHAVIOURS, Exercise, Gains
from ..core.errors import EXIT_FAILED, EXIT_OK

SIM_TIMEOUT = 300.0   # s of wall time for all runs together


class FiniteFloat(click.FloatRange):
    """A float in an optional range that must be finite: click lets ``nan`` through any range (every comparison
    with it is false) and ``inf`` through open-ended ones."""

    def convert(self, value, param, ctx):
        number = super().convert(value, param, ctx)
        if not math.isfinite(number):
            self.fail(f"{value} is not a finite number.", param, ctx)
        return number

    def _describe_range(self) -> str:
        """The range the help shows: none when there are no bounds (click would show ``x<=None``)."""
        return "" if self.min is None and self.max is None else super()._describe_range()


@click.command("drive")
@click.argument("world", type=click.Path(path_type=Path))
@click.option("--behavior", "--behaviour", "behaviour", type=click.Choice(BEHAVIOURS),
              default="stop-at-wall", show_default=True, help="The exercise to run.")
@click.option("--robot", default=None, metavar="burger|waffle|waffle_pi|FILE",
              help="Robot model, or a .urdf/.urdf.xacro file. Default: the spec's, else burger.")
@click.option("--spawn", default=None, metavar="X,Y[,YAW]",
              help="Spawn pose in metres and radians. Default: the launch file's or spec's, else the deepest free point "
                   "of the largest closed room.")
@click.option("--target", type=FiniteFloat(min=0.0, min_open=True), default=stoplaw.TARGET, show_default=True,
              help="Stop-at-wall: distance to stop at (m).")
@click.option("--kp", type=FiniteFloat(), multiple=True,
              help=f"Proportional gain (repeat for several runs on one plot). Default {stoplaw.KP:g}.")
@click.option("--ki", type=FiniteFloat(), multiple=True,
              help="Integral gain (once for all runs, or once per run). Default 0.")
@click.option("--kd", type=FiniteFloat(), multiple=True,
              help="Derivative gain (once for all runs, or once per run). Default 0.")
@click.option("--duration", type=FiniteFloat(min=0.1, max=600), default=None, metavar="S",
              help="Simulated seconds per run. Default: 30 for stop-at-wall, one full turn for spin.")
@click.option("--max-speed", type=FiniteFloat(min=0.01, max=1.0), default=stoplaw.MAX_SPEED, show_default=True,
              help="Stop-at-wall: speed limit of the command (m/s; burger 0.22, waffle 0.26).")
@click.option("--stop-band", type=FiniteFloat(min=0.0, max=1.0), default=stoplaw.STOP_BAND, show_default=True,
              metavar="M", help="Stop-at-wall: stop, and hold, once the front distance is within M of the target.")
@click.option("--omega", type=FiniteFloat(min=-3.0, max=3.0), default=1.0, show_default=True,
              help="Spin: turn rate (rad/s; burger at most 2.84, waffle 1.82).")
@click.option("--rate", type=click.Choice(["5", "30"]), default="5", show_default=True,
              help="Stop-at-wall: control loop rate in Hz (the LiDAR's 5 Hz or the drive's 30 Hz).")
@click.option("--front-angle", type=FiniteFloat(min=0.0, max=90.0), default=stoplaw.FRONT_ANGLE, show_default=True,
              metavar="DEG", help="Stop-at-wall: the front distance is the nearest beam within ±DEG of ahead.")
@click.option("--tolerance", type=FiniteFloat(min=0.0), default=0.05, show_default=True,
              help="Stop-at-wall: the run passes when it ends within this of the target (m).")
@click.option("--lidar-no-hit", type=click.Choice(["inf", "zero"]), default="inf", show_default=True,
              help="What a beam that hits nothing reads: inf as in Gazebo, 0 as the real LDS-01 driver.")
@click.option("--model-path", "model_paths", multiple=True, type=click.Path(path_type=Path), metavar="DIR",
              help="Folder of Gazebo models for model:// includes (repeatable).")
@click.option("--plot", type=click.Path(path_type=Path, dir_okay=False), default=None, metavar="FILE.png",
              help="Write a figure: distance to the wall against time, one curve per gain set.")
@click.option("--csv", "csv_path", type=click.Path(path_type=Path, dir_okay=False), default=None, metavar="FILE",
              help="Write the time series as CSV.")
@click.option("--html", type=click.Path(path_type=Path, dir_okay=False), default=None, metavar="FILE.html",
              help="Write a 3D page replaying the (first gain set's) run: robot, path, scans, plots.")
@click.option("--force", is_flag=True, help="Overwrite existing --plot/--csv/--html files.")
@click.option("--format", "fmt", type=click.Choice(["text", "json"]), default="text", show_default=True)
def drive(world, behaviour, robot, spawn, target, kp, ki, kd, duration, max_speed, stop_band, omega, rate,
          front_angle, tolerance, lidar_no_hit, model_paths, plot, csv_path, html, force, fmt):
    """Run a sensory-motor exercise in WORLD (a .world/.sdf file or a floorplan spec) and report it. WORLD may
    also be a launch file, a package or any folder: each world a launch file starts is driven from its spawn.

    stop-at-wall runs the generated stop_at_wall.py node's law: v = kp·e + ki·∫e + kd·de/dt (e = front LiDAR
    distance − target) clamped to [0, max-speed], full speed when nothing is ahead, stop and hold once within
    stop-band of the target; it reports final distance, overshoot, settling time and contacts. spin turns in
    place and reports the drift. Exit status: 0 every run stopped where it should without touching
    anything, 1 a run touched something or missed the target band, 2 bad input.
    """
    from ..core.errors import InputError, WorldgenError
    from ..core.fsio import check_free, write_files
    from ..sim.process import SimCrashed, SimError
    from ..core.spawnpose import parse_spawn
    from ..check.drive_targets import drive_one
    from ..check.validate import input_kind

    if not world.exists():
        raise InputError("no such file", path=world, hint="give a .world/.sdf file or a floorplan spec (.yaml)")
    kind = input_kind(world)
    for folder in model_paths:
        if not folder.is_dir():
            raise InputError("--model-path is not a folder", path=folder, hint="give a folder of Gazebo models")
    from .outputs import check_suffix

    check_suffix(plot, "png", "--plot")
    check_suffix(html, "html", "--html")
    outputs = [p for p in (plot, csv_path, html) if p is not None]
    if html is not None:
        from ..view.page import require_three

        require_three()
    check_free(outputs, force)
    exercise = Exercise(
        behaviour=behaviour, robot=_robot_arg(robot), spawn=tuple(parse_spawn(spawn)) if spawn is not None else None,
        gains=gain_sets(kp, ki, kd), target=target, duration=duration, max_speed=max_speed, omega=omega,
        rate=float(rate), front_angle=front_angle, no_hit=lidar_no_hit, tolerance=tolerance, stop_band=stop_band,
        record_scans=html is not None)
    if kind in ("folder", "package", "launch"):   # every world a launch file starts, with its spawn
        if outputs:
            raise InputError("--plot, --csv and --html take a single world", path=world,
                             hint="give one world or spec file to plot, or leave out --plot/--csv/--html")
        sys.exit(drive_many(world, exercise, model_paths, fmt))
    try:
        result = drive_one(world, kind, exercise, model_paths, timeout=SIM_TIMEOUT)
    except (SimCrashed, SimError) as err:
        raise WorldgenError(f"the simulation failed: {str(err).splitlines()[0]}", path=world,
                            hint="'worldgen validate' says more about the world; please report it to the worldgen "
                                 "developers if it loads in Gazebo") from None
    files = {}
    if plot is not None:
        from ..sim.plot import plot_png
        files[plot] = plot_png(result)
    if csv_path is not None:
        from ..sim.plot import series_csv
        files[csv_path] = series_csv(result)
    if html is not None:
        from ..view.page import drive_page
        first = result["runs"][0]
        files[html] = drive_page(world, result, model_paths,
                                 [] if first["ok"] or result["behaviour"] == "spin" else _failures(first))
    written = write_files(files, force=force) if files else []
    click.echo(json.dumps(_finite(_summary(result)), indent=2) if fmt == "json" else text_report(result))
    if fmt != "json":   # (the JSON report stays the whole of stdout)
        for path in written:
            click.echo(f"wrote {path}")
    sys.exit(EXIT_OK if all(run["ok"] for run in result["runs"]) else EXIT_FAILED)


def drive_many(path: Path, exercise: Exercise, model_paths, fmt: str) -> int:
    """Drive in every world ``path`` holds (:func:`worldgen.check.drive_targets.drive_all`); print one report per
    world (JSON: ``{"ok", "worlds": [...]}``) and return the exit code: 0 when every run passed, 1 otherwise (a
    world that cannot be driven in is a failure, the rest still run)."""
    from ..check.drive_targets import drive_all

    reports, texts = [], []
    for shown, result, failure in drive_all(path, exercise, model_paths, SIM_TIMEOUT):
        if failure is not None:
            reports.append({"world": shown, "ok": False, "error": failure})
            texts.append(f"{exercise.behaviour} in {shown}: FAILED: {failure}")
            continue
        reports.append(_finite(_summary(result)))
        texts.append(text_report(result))
    ok = all(r["ok"] for r in reports)
    if fmt == "json":
        click.echo(json.dumps({"ok": ok, "worlds": reports}, indent=2))
    else:
        click.echo("\n".join(texts))
        click.echo(f"{len(reports)} world(s): {sum(r['ok'] for r in reports)} passed, "
                   f"{sum(not r['ok'] for r in reports)} failed")
    return EXIT_OK if ok else EXIT_FAILED


def _robot_arg(robot: str | None) -> str | None:
    """Check the robot option here (a bad one is bad input, exit 2) and pass files as absolute paths."""
    if robot is None:
        return None
    from ..robots import MODELS, robot_file
    path = robot_file(robot)
    return robot if robot in MODELS else str(path)


def gain_sets(kp: tuple, ki: tuple, kd: tuple) -> tuple[Gains, ...]:
    """Zip repeated --kp/--ki/--kd into gain sets; a gain given once (or not at all) applies to every run."""
    from ..core.errors import InputError

    runs = max(len(kp), len(ki), len(kd), 1)
    columns = {}
    for name, values, default in (("kp", kp, stoplaw.KP), ("ki", ki, 0.0), ("kd", kd, 0.0)):
        if len(values) not in (0, 1, runs):
            raise InputError(f"--{name} is given {len(values)} times for {runs} runs",
                             hint=f"give --{name} once (used for every run) or once per run")
        columns[name] = list(values) * runs if len(values) == 1 else list(values) or [default] * runs
    return tuple(Gains(**{name: columns[name][i] for name in ("kp", "ki", "kd")}) for i in range(runs))


def _summary(result: dict) -> dict:
    """The JSON report: everything but the time series (those go to --csv), the LiDAR's layout (recorded for
    --html) and the wall-clock time (so the same run gives the same report)."""
    runs = [{k: v for k, v in run.items() if k != "series"} for run in result["runs"]]
    return {**{k: v for k, v in result.items() if k not in ("wall_seconds", "lidar")}, "runs": runs,
            "ok": all(run["ok"] for run in runs)}


def _finite(value):
    """Standard JSON: inf and nan become null."""
    if isinstance(value, float) and not math.isfinite(value):
        return None
    if isinstance(value, dict):
        return {k: _finite(v) for k, v in value.items()}
    if isinstance(value, list):
        return [_finite(v) for v in value]
    return value


def _m(value) -> str:
    return "-" if value is None else f"{value:.3f}"


def text_report(result: dict) -> str:
    from ..sim.plot import gains_label

    x, y, yaw = result["spawn"]
    source = result["spawn_source"]
    source = source if source.startswith(("no spawn given", "from ")) else f"from {source}"
    lines = [f"{result['behaviour']} in {result['world']}: {result['robot']} at x={x:.2f} y={y:.2f} "
             f"yaw={yaw:.2f} ({source})"]
    if result["behaviour"] == "spin":
        for run in result["runs"]:
            lines.append(f"  turned {math.degrees(run['turned']):.0f}° at {run['omega']:g} rad/s: drift "
                         f"{run['drift'] * 1000:.1f} mm at the end, {run['max_drift'] * 1000:.1f} mm at most "
                         f"(limit {run['drift_limit'] * 1000:.0f} mm)" + _contacts_text(run) +
                         ("  ok" if run["ok"] else "  FAILED"))
    else:
        first = result["runs"][0]
        lines.append(f"  target {first['target']:g} m ±{first['tolerance']:g} m; settling band ±{first['band']:g} m "
                     "around the final distance; distances from base_scan to the wall ahead")
        lines.append(f"  {'gains':<22} {'final':>7} {'error':>7} {'closest':>7} {'overshoot':>9} "
                     f"{'settling':>8}  result")
        for run in result["runs"]:
            settling = "-" if run["settling_time"] is None else f"{run['settling_time']:.1f} s"
            verdict = "ok" if run["ok"] else "FAILED: " + "; ".join(_failures(run))
            lines.append(f"  {gains_label(run):<22} {_m(run['final_distance']):>7} {_m(run['steady_state_error']):>7} "
                         f"{_m(run['min_distance']):>7} {_m(run['overshoot']):>9} {settling:>8}  {verdict}")
    lines.append(f"  ({result['sim_seconds']:.1f} s simulated in {result['wall_seconds']:.1f} s)")
    return "\n".join(lines)


def _failures(run: dict) -> list[str]:
    reasons = []
    if run["contacts"]:
        reasons.append(_contacts_text(run).strip())
    if run["final_distance"] is None:   # the law had nothing to stop at: not a matter of gains
        reasons.append("no wall ahead at the end: the robot saw nothing to stop at (an open side or a gap the "
                       "robot left through? worldgen validate WORLD names the gaps)")
        return reasons
    if not run["within_tolerance"]:
        reasons.append(f"ended {run['final_distance'] - run['target']:+.3f} m from the target")
    if not run["stopped"]:
        reasons.append("still moving at the end" if run.get("stop_time") is not None else
                       f"never came within {run.get('stop_band', 0):g} m of the target to stop (try a larger "
                       "--kp or a longer --duration)")
    return reasons


def _contacts_text(run: dict) -> str:
    if not run["contacts"]:
        return ""
    first = run["contacts"][0]
    more = f" (+{len(run['contacts']) - 1} more)" if len(run["contacts"]) > 1 else ""
    return f"  touched {first['shape']} with {first['link']} at t={first['time']:.1f} s{more}"


COMMANDS = [drive]
