"""``worldgen validate`` as a library: inputs → jobs → results.

An input is a world file (``.world``, ``.sdf``, ``model.sdf``, or anything holding ``<sdf>``), a floorplan spec
(built to SDF on the fly, exactly as ``worldgen build`` writes it), a roslaunch or ROS 2 Python launch file (the
world it starts, its robot model and spawn pose), a catkin or ament package folder (each of its launch files) or any
other folder (searched for packages, else worlds and specs: :mod:`worldgen.check.discover`). :func:`plan` turns
inputs into :class:`Job` s; a path that is missing or cannot be read becomes a failed job of its own (check
``input``), and only bad options, or every path being bad, are an :class:`~worldgen.core.errors.InputError` before
anything runs; :func:`run_job` validates one job into its :class:`~worldgen.check.report.Result` s;
:func:`run_jobs` runs many on worker threads, each driving its own child processes for the simulator, and returns
the results in job order. With ``sdformat`` set, libsdformat's own check runs too, in the same worker thread (the
library in a child process of its own), so ``jobs`` run that in parallel as well.

Spawn pose, first found: ``--spawn``; the launch file (``--launch``, or the input when it is one); the spec's
``robot`` entry (the input spec, or a spec of the same name beside the world). With none, the world is checked
from the deepest free point of each closed room, one result per room (:mod:`worldgen.check.nospawn`). The report
says which. Findings about a world built from a spec name the spec's rooms and walls
(:mod:`worldgen.check.spec_names`), and the spec's own oddities are warned about (:mod:`worldgen.check.spec_lint`).
"""

from __future__ import annotations

import tempfile
from dataclasses import dataclass, field
from dataclasses import replace as dc_replace
from pathlib import Path
from typing import Callable, Sequence

from . import budget
from .camera_view import check_camera
from .launch_world import world_not_found
from .checks import (GEOMETRIC_CHECKS, SDFORMAT_ABSENT, SIM_CHECKS, check_enclosed, check_parse,
                     check_spawn_clear, check_sdformat, floor_under, robot_body)
from ..core.errors import InputError, SpecError, WorldFileError
from ..core.packages import ros_package_path
from ..core.inputs import check_regular, refuse_unread
from ..core.spawnpose import plan_pose
from ..core.findings import Finding
from . import sim_run
from .report import Result
from .sources import WorldSource
from ..spec.load import spec_beside
from ..spec.model import ROBOT_MODELS, SPEC_SUFFIXES

LAUNCH_SUFFIXES = (".launch", ".launch.xml", ".launch.py", "_launch.py")
NO_HIT_CHOICES = ("inf", "zero")
SIM_TIMEOUT = 120.0   # s of wall time for one world's simulation
SIM_JOB = "worldgen.check.sim_job:simulate"


@dataclass(frozen=True)
class Options:
    """The command-line options of ``worldgen validate``, as values."""

    robot: str | None = None                               # None: from the launch file or spec, else burger
    spawn: tuple[float, float, float] | None = None        # x, y, yaw
    launch: Path | None = None
    model_paths: tuple[Path, ...] = ()
    lidar_no_hit: str = "inf"
    skip_sim: bool = False
    sim_timeout: float = SIM_TIMEOUT
    sdformat: bool = False                                 # also libsdformat's own check (slow on big worlds)


@dataclass
class Job:
    """One world to validate and what is known about it before it is read.

    ``world`` is the file to read (None when it could not be found: ``findings`` say why); ``spec`` is set for
    spec inputs, whose world is built when the job runs from ``floorplan``, the spec as loaded while planning
    (None when it could not be). ``pre_checks`` are the checks already done while
    planning (``launch``, ``package``), whose findings are in ``findings``. A ``package_only`` job is a
    package folder's own row: its package check and nothing to simulate.
    """

    path: str
    world: Path | None = None
    spec: Path | None = None
    floorplan: object | None = None
    spawn: tuple[float, float, float] | None = None
    spawn_source: str = ""
    robot: str = "burger"
    robot_source: str = "default"
    findings: list[Finding] = field(default_factory=list)
    pre_checks: list[str] = field(default_factory=list)
    package_only: bool = False
    names_from: object | None = None   # the spec a world was built from (beside it): findings use its names


# ---------------------------------------------------------------------------------------------------- options

def check_options(options: Options) -> None:
    """Refuse option values that make no sense (InputError): a no-hit mode, the robot, model paths."""
    if options.lidar_no_hit not in NO_HIT_CHOICES:
        raise InputError(f"bad --lidar-no-hit value {options.lidar_no_hit!r}", hint="use inf or zero")
    if options.robot is not None:
        robot_body(options.robot)   # raises InputError for an unknown model or unreadable file
    for p in options.model_paths:
        if not Path(p).is_dir():
            raise InputError("--model-path is not a folder", path=p,
                             hint="give a folder holding Gazebo models (NAME/model.config + model.sdf)")
    if options.launch is not None and not Path(options.launch).is_file():
        raise InputError("--launch file not found", path=options.launch, hint="give an existing .launch file")


# ------------------------------------------------------------------------------------------------------ plan

def input_kind(path: Path) -> str:
    """``package``, ``model-folder``, ``folder`` (any other folder), ``spec``, ``launch`` or ``world`` (by suffix,
    else by content)."""
    if path.is_dir():
        if (path / "package.xml").is_file():
            return "package"
        if (path / "model.sdf").is_file() or (path / "model.config").is_file():
            return "model-folder"
        return "folder"
    name = path.name.lower()
    if name.endswith(LAUNCH_SUFFIXES):
        return "launch"
    if path.suffix.lower() in SPEC_SUFFIXES:
        return "spec"
    refuse_unread(path, "a world, spec or launch file")
    try:
        with open(path, "rb") as handle:
            head = handle.read(4096).decode("utf-8", "replace")
    except OSError as err:
        raise InputError(f"cannot be read: {err.strerror}", path=path) from None
    launch_at, sdf_at = head.find("<launch"), head.find("<sdf")
    if launch_at >= 0 and (sdf_at < 0 or launch_at < sdf_at):
        return "launch"
    return "world"


def plan(paths: Sequence[str | Path], options: Options, notes: list[str] | None = None) -> list[Job]:
    """The jobs for ``paths`` in order (a package gives a job for its own check, then one per launch file; any
    other folder is searched for packages, else for worlds and specs: :mod:`worldgen.check.discover`, what
    was found appended to ``notes``). A path that is missing or cannot be read is a failed job of its own
    (check ``input``); InputError for bad options, or when every path is bad."""
    if not paths:
        raise InputError("no input given", hint="give world, spec or launch files, or package folders")
    check_options(options)
    launch_info = _read_launch(Path(options.launch)) if options.launch is not None else None
    jobs: list[Job] = []
    errors: list[InputError] = []
    for given in paths:
        try:
            jobs += _plan_path(Path(given), str(given), options, launch_info, notes)
        except InputError as err:
            errors.append(err)
            jobs.append(_input_job(str(given), err))
    if len(errors) == len(paths):
        raise errors[0]
    return jobs


def _input_job(display: str, err: InputError) -> Job:
    """A path that cannot be validated at all, as a failed row of its own."""
    return Job(path=display, pre_checks=["input"], package_only=True, findings=[
        Finding("input", "error", err.message, where=display, fix=err.hint or "check the path")])


def _plan_path(path: Path, display: str, options: Options, launch_info, notes) -> list[Job]:
    if not path.exists():
        raise InputError("no such file or folder", path=path, hint="check the path")
    check_regular(path, InputError, "input")
    kind = input_kind(path)
    if kind == "package":
        return _package_jobs(path, options)
    if kind == "folder":
        return _folder_jobs(path, options, launch_info, notes)
    if kind == "launch":
        job = _launch_path_job(path, display)
    elif kind == "spec":
        job = _spec_job(path, display)
    else:
        job = Job(path=display, world=path)   # read_world reads a model folder's model.sdf itself
        if kind == "world":
            budget.refuse(budget.file_shapes(path), "the world", path, budget.WORLD_HINT)
            _spec_beside(job, path)
    if launch_info is not None:
        _apply_launch(job, launch_info, Path(options.launch))
    return [_apply_options(job, options)]


def _folder_jobs(folder: Path, options: Options, launch_info, notes) -> list[Job]:
    """A folder that is no package: each package found in it, else each world, model folder and spec. A package
    the folder holds once serves all of it (:func:`.discover.shared_packages`: the course's world package handed in
    beside the submissions): its launch files' ``$(find)`` look there before ``ROS_PACKAGE_PATH``."""
    from .discover import search_folder, shared_packages, unpackaged_finding

    found = search_folder(folder)
    if notes is not None:
        notes.append(found.note)
    if not found.packages and not found.files:
        raise InputError("holds no catkin package, world file or spec", path=folder,
                         hint="give a workspace, its src/, a folder of packages, or world/spec files")
    jobs: list[Job] = []
    shared = tuple(shared_packages(found.packages))
    for pkg in found.packages:
        jobs += _package_jobs(pkg, options, shared)
    jobs += [Job(path=str(child), pre_checks=["package"], package_only=True, findings=[unpackaged_finding(child)])
             for child in found.unpackaged]
    for kind, path in found.files:
        try:
            jobs += _plan_path(path, str(path), options, launch_info, None)
        except InputError as err:   # one file refused: a failed row, the others still run
            jobs.append(_input_job(str(path), err))
    return jobs


def _read_launch(path: Path, shared: tuple[Path, ...] | None = None):
    from ..launch.reader import read_launch

    return read_launch(path, ros_package_path=_search_path(shared))


def _search_path(shared: tuple[Path, ...] | None) -> list[Path] | None:
    """Where ``$(find)`` looks after a launch file's own workspace: a graded folder's ``shared`` packages, then
    ``ROS_PACKAGE_PATH`` (None: no folder graded, the process's ROS_PACKAGE_PATH only)."""
    return None if shared is None else [*shared, *ros_package_path()]


def _package_jobs(folder: Path, options: Options, shared: tuple[Path, ...] | None = None) -> list[Job]:
    """A package gives a row of its own (the package check) and one job per launch file (whose read is said on
    its row, not the package's); ``shared``: the packages of the folder graded that serve all of it."""
    from ..packages.check import package_launch_files
    from .discover import is_metapackage

    findings = _package_findings(folder, shared)
    launches = package_launch_files(folder)
    if not launches and not is_metapackage(folder):
        findings.append(Finding("package", "error", "the package has no launch files",
                                where=str(folder), fix="add a launch/ file that starts the world "
                                                       "(worldgen launch WORLD --package PKG writes one)"))
    jobs = [Job(path=str(folder), pre_checks=["package"], findings=findings, package_only=True)]
    for launch in launches:
        jobs.append(_apply_options(_launch_path_job(launch, str(launch), shared), options))
    return jobs


def _package_findings(folder: Path, shared: tuple[Path, ...] | None = None) -> list[Finding]:
    """:func:`worldgen.packages.check.check_package`, its ids put under ``package-`` (``cmake`` →
    ``package-cmake``), less what its launch files' rows say."""
    from ..packages.check import check_package

    return [f if f.check.startswith("package") else dc_replace(f, check=f"package-{f.check}")
            for f in check_package(folder, ros_package_path=_search_path(shared), launch_rows=True)]


def _launch_path_job(path: Path, display: str, shared: tuple[Path, ...] | None = None) -> Job:
    """The job of a launch file given as an input: one that roslaunch could not parse either is a failed
    ``launch`` check, not bad input. ``shared``: see :func:`_package_jobs`."""
    try:
        info = _read_launch(path, shared)
    except WorldFileError as err:
        return Job(path=display, pre_checks=["launch"], findings=[
            _error_finding("launch", err, path, "fix the launch file so that roslaunch can read it")])
    return _launch_job(path, info, display, graded=shared is not None, search=_search_path(shared))


def _launch_job(path: Path, info, display: str, graded: bool = False, search=None) -> Job:
    from ..launch.reader import nothing_to_simulate

    job = Job(path=display, pre_checks=["launch"], findings=list(info.findings))
    why = nothing_to_simulate(path, info)   # nodes beside a world started elsewhere; a spawn other files include
    if why is not None:
        job.package_only = True
        job.findings.append(Finding("launch", "info", why, where=str(path)))
        return job
    if info.world_path is not None and Path(info.world_path).is_file():
        job.world = Path(info.world_path)
    else:   # one error, the missing package's findings folded into it
        job.findings = world_not_found(info, path, job.findings, graded, search)
    _take_launch_pose(job, info, path)
    return job


def _take_launch_pose(job: Job, info, path: Path) -> None:
    pose = plan_pose(info.spawn)
    if pose is not None:
        job.spawn, job.spawn_source = pose, f"from launch file {path}"
    if info.model in ROBOT_MODELS:
        job.robot, job.robot_source = info.model, f"from launch file {path}"


def _apply_launch(job: Job, info, path: Path) -> None:
    """``--launch FILE`` for a world given on the command line: its spawn pose and robot, and whether it starts
    this world at all."""
    if "launch" not in job.pre_checks:
        job.pre_checks.append("launch")
        job.findings += list(info.findings)
    _take_launch_pose(job, info, path)
    if job.world is None:
        return
    launch_world = Path(info.world_path) if info.world_path is not None else None
    if launch_world is not None and launch_world.is_file():
        if launch_world.resolve() != job.world.resolve():
            job.findings.append(Finding(
                "launch", "warning", f"the launch file starts {launch_world}, not {job.world}",
                where=str(path), fix="point the launch file's world_name at this world, or validate the world "
                                     "it starts"))
        return
    ref = info.world_ref or "(none)"
    same_name = Path(ref).name == job.world.name
    job.findings.append(Finding(
        "launch", "info" if same_name else "warning",
        f"the launch file's world {ref} cannot be found here; validating {job.world} given on the command line "
        "instead" + ("" if same_name else f" (whose name differs from {Path(ref).name})"),
        where=str(path), fix=None if same_name else "check that the launch file starts this world"))


def _spec_job(path: Path, display: str) -> Job:
    job = Job(path=display, spec=path)
    try:
        from ..spec.load import load_spec

        job.floorplan = load_spec(path)
    except SpecError as err:
        job.findings.append(_parse_error(err, path))
        job.pre_checks.append("parse")
        return job
    budget.refuse(budget.spec_shapes(job.floorplan), "the spec", path, budget.SPEC_HINT)   # before it is built
    _take_spec_pose(job, job.floorplan, path)
    return job


def _take_spec_pose(job: Job, spec, path: Path) -> None:
    if spec.robot is not None:
        job.spawn = (float(spec.robot.at[0]), float(spec.robot.at[1]), float(spec.robot.yaw))
        job.spawn_source = f"from spec {path}"
        job.robot, job.robot_source = spec.robot.model, f"from spec {path}"


def _spec_beside(job: Job, world: Path) -> None:
    """A world built by ``worldgen build`` has its spec beside it (same name): take the robot pose from it."""
    found = spec_beside(world)
    if found is not None:
        _take_spec_pose(job, found[1], found[0])
        job.names_from = found[1]


def _apply_options(job: Job, options: Options) -> Job:
    if options.spawn is not None:
        job.spawn, job.spawn_source = options.spawn, "from --spawn"
    if options.robot is not None:
        job.robot, job.robot_source = options.robot, "from --robot"
    return job   # no spawn anywhere: each closed room's deepest point, once the world is read (nospawn)


# ------------------------------------------------------------------------------------------------------- run

def run_job(job: Job, options: Options) -> list[Result]:
    """Validate one job: read the world, run the geometric checks here and the simulated ones on the same scene
    in one child process. Never raises for a problem with the file: problems become findings. One result, or,
    when nothing gives a spawn, one per closed room of the world (:mod:`worldgen.check.nospawn`)."""
    result = Result(path=job.path, spawn=job.spawn, spawn_source=job.spawn_source, robot=job.robot,
                    robot_source=job.robot_source, findings=list(job.findings), checks=list(job.pre_checks))
    if job.package_only:
        result.spawn, result.spawn_source = None, ""
        return [result]
    if job.spec is not None:
        if job.floorplan is None:
            return [_skip_rest(result, "the spec cannot be read", options)]
        from ..geometry.building import build_geometry
        from ..sdf.writer import world_sdf

        try:
            building = build_geometry(job.floorplan)   # once: the world's text, then the spec's names and checks
            source = WorldSource(job.spec.with_suffix(".world"), world_sdf(building))
        except SpecError as err:
            result.checks.append("parse")
            result.findings.append(_parse_error(err, job.spec))
            return [_skip_rest(result, "the spec cannot be built", options)]
        return _named(_run_world(result, source, options), job, building)
    if job.world is None:
        return [_skip_rest(result, "no world to read", options)]
    return _named(_run_world(result, WorldSource(job.world), options), job)


def _named(results: list[Result], job: Job, building=None) -> list[Result]:
    """Findings about a world built from a spec speak of the spec's rooms and walls (and its own checks of the
    spec are added): :mod:`worldgen.check.spec_names`, :mod:`worldgen.check.spec_lint`; ``building``: the
    spec's geometry, when built already."""
    spec = job.floorplan if job.floorplan is not None else job.names_from
    if spec is None:
        return results
    from ..geometry.building import build_geometry
    from .spec_lint import lint_spec
    from .spec_names import rename_findings, wall_sides

    try:
        building = build_geometry(spec) if building is None else building
    except SpecError:   # a spec beside a world that no longer builds: nothing to name
        return results
    sides = wall_sides(spec, building)
    extra = lint_spec(spec, building, sides)
    for r in results:
        r.findings = rename_findings(r.findings, spec, r.spawn[:2] if r.spawn else None, sides) + list(extra)
    return results


def _parse_error(err, path: Path) -> Finding:
    """A file that cannot be read at all (WorldFileError, SpecError) as the ``parse`` check's finding."""
    return _error_finding("parse", err, path, "fix the file so that Gazebo can load it")


def _error_finding(check: str, err, path: Path, fix: str) -> Finding:
    """A :class:`~worldgen.core.errors.WorldgenError` as an error finding of ``check``: its file and line, its hint
    (else ``fix``)."""
    where = err.path or str(path)
    return Finding(check, "error", err.message, where=f"{where}:{err.line}" if err.line else where,
                   fix=err.hint or fix)


def _skip_rest(result: Result, why: str, options: Options) -> Result:
    for check in (*GEOMETRIC_CHECKS, *(("sdformat",) if options.sdformat else ()), *SIM_CHECKS):
        if check not in result.checks and check not in result.skipped:
            result.skipped[check] = why
    return result


def _run_world(result: Result, source: WorldSource, options: Options) -> list[Result]:
    """Read the world and check it, with a temporary folder of the job's own (only this user can read it). With
    the spawn known already, the simulation starts first, reading the world itself (:mod:`.sim_run`)."""
    with tempfile.TemporaryDirectory(prefix="worldgen_validate_") as tmp:
        early = sim_run.start_early(result, source, options, Path(tmp), SIM_JOB)
        try:
            return _check_world(result, source, options, Path(tmp), early)
        finally:
            if early is not None:   # not waited for (the world could not be read here): stopped
                early.cancel()


def _check_world(result: Result, source: WorldSource, options: Options, tmp: Path, early=None) -> list[Result]:
    result.checks.append("parse")
    try:
        scene = source.read(tuple(options.model_paths))
        if early is not None:
            early.read(scene)
    except WorldFileError as err:
        result.findings.append(_parse_error(err, source.path))
        scene = None
    over = budget.too_many(scene, str(source.path)) if scene is not None else None
    if over is not None:   # its includes took it past the limit
        result.findings.append(over)
        return [_skip_rest(result, "too many shapes to check", options)]
    if options.sdformat:   # even when our reader gave up: libsdformat may say more about why
        _sdformat(result, source, options, tmp)
    if scene is None:
        return [_skip_rest(result, "the world cannot be read", options)]
    outcomes = [check_parse(scene), check_camera(scene, result.robot)]   # the camera's: None without floor markings
    result.checks += ["camera"] if outcomes[1] is not None else []
    for outcome in filter(None, outcomes):
        result.findings += outcome.findings
        result.metrics.update(outcome.metrics)
    if result.spawn is not None:
        return [_check_from(result, scene, options, tmp, early)]
    from .nospawn import default_spawns

    rooms = [dc_replace(result, spawn=place.spawn, spawn_source=place.source, room=place.room,
                        findings=list(result.findings) + list(place.findings), checks=list(result.checks),
                        skipped=dict(result.skipped), metrics=dict(result.metrics))
             for place in default_spawns(scene, result.robot)]
    sims = sim_run.Ahead(rooms, scene, options, tmp, SIM_JOB)
    try:
        return [_check_from(one, scene, options, *sims.take(i)) for i, one in enumerate(rooms)]
    finally:
        sims.cancel()


def _check_from(result: Result, scene, options: Options, tmp: Path, early=None) -> Result:
    """The checks of ``scene`` from the result's spawn. The simulation (``early``, or started now) runs while the
    geometric checks do here, under ``worldgen validate`` (a fork server)."""
    sim = None if options.skip_sim else early or sim_run.start_sim(result, scene, options, tmp, SIM_JOB)
    try:
        body = robot_body(result.robot)
        ground, floor = floor_under(scene, result.spawn)
        result.metrics.update(floor)
        for name, check in (("enclosed", check_enclosed), ("spawn-clear", check_spawn_clear)):
            result.checks.append(name)
            outcome = check(scene, result.spawn, body, ground)
            result.findings += outcome.findings
            result.metrics.update(outcome.metrics)
    except BaseException:   # no simulation left running for a job that failed here
        if sim is not None:
            sim.cancel()
        raise
    if sim is None:
        for name in SIM_CHECKS:
            result.skipped[name] = "--skip-sim"
        return result
    sim_run.judge(result, sim, scene, options, (ground, floor["floor"]), tmp, SIM_JOB)
    return result


def _sdformat(result: Result, source: WorldSource, options: Options, tmp: Path) -> None:
    """libsdformat's check of the world (a spec's world text written to ``tmp`` first; a model folder's SDF
    file), run here in the job's worker thread (the library itself runs in a child process)."""
    shown = str(source.path)
    if source.text is not None:
        world_file = tmp / source.path.name
        world_file.write_text(source.text, encoding="utf-8")
    elif source.path.is_dir():
        from ..sdf.resolve import model_sdf_file

        world_file = model_sdf_file(source.path)[0]
        if world_file is None:
            result.skipped["sdformat"] = "the model folder has no SDF file"
            return
        shown = str(world_file)
    else:
        world_file = source.path
    outcome = check_sdformat(world_file, tuple(options.model_paths), shown_as=shown)
    if outcome is None:
        result.skipped["sdformat"] = SDFORMAT_ABSENT
        result.findings.append(Finding("sdformat", "info", f"{SDFORMAT_ABSENT}; check skipped",
                                       fix="install libsdformat 12 or newer (Debian 12, Ubuntu 22.04: apt install "
                                           "libsdformat-dev), or leave out --sdformat"))
        return
    result.checks.append("sdformat")
    result.findings += outcome.findings
    result.metrics.update(outcome.metrics)


def run_jobs(planned: Sequence[Job], options: Options, workers: int = 1,
             progress: Callable[[Job, list[Result]], None] | None = None) -> list[Result]:
    """Run planned jobs on ``workers`` threads (each drives its own simulator processes); results in job order,
    ``progress(job, its results)`` called as each job finishes."""
    if workers <= 1 or len(planned) <= 1:
        results = []
        for job in planned:
            done = run_job(job, options)
            results += done
            if progress:
                progress(job, done)
        return results
    from concurrent.futures import ThreadPoolExecutor, as_completed   # (and logging: only with workers)

    with ThreadPoolExecutor(max_workers=workers) as pool:
        futures = {pool.submit(run_job, job, options): job for job in planned}
        if progress:
            for future in as_completed(futures):
                progress(futures[future], future.result())
        return [r for f in futures for r in f.result()]


def validate(paths: Sequence[str | Path], options: Options = Options(), jobs: int = 1,
             progress: Callable[[Job, list[Result]], None] | None = None) -> list[Result]:
    """:func:`plan` then :func:`run_jobs`: every input validated, results in input order."""
    return run_jobs(plan(paths, options), options, jobs, progress)
