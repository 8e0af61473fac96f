"""``validate``'s simulated checks for one spawn: started in a child process, judged when it ends.

:func:`start_sim` hands the child the scene this process read (pickled into the job's private folder).
:func:`start_early` starts it sooner, before this process has read the world: under ``worldgen validate`` the
child is a fork of a server that has imported the reader already, so it reads the same world itself (a small
one: at most :data:`EARLY_WORLD_BYTES`) while this process does, and says what it read
(:func:`~worldgen.check.sim_job.scene_digest`). :func:`judge` takes its numbers only when that is the scene
checked here, and simulates this scene when it is not (the file changed between the two reads), so the
simulator always drives in exactly the scene the geometric checks looked at. A crash, a timeout or an error
in the child becomes one error finding naming the stage it happened in. :class:`Ahead` starts the simulations
of a world's several spawns (its closed rooms) a few at a time ahead of the checks that wait for them.
"""

from __future__ import annotations

import signal
from pathlib import Path

from ..core.errors import WorldFileError, WorldgenError
from ..core.findings import Finding
from .checks import SIM_CHECKS, sim_findings
from .report import Result
from .sim_job import in_reach

EARLY_WORLD_BYTES = 1 << 20   # a world (or a spec's SDF) up to this size is read by an early child as well
SIMS_AHEAD = 2                # a world's rooms: simulations under way at once (two cores; each a fork's memory)


def start_early(result: Result, source, options, tmp: Path, job: str):
    """The simulation of ``source`` (a :class:`~worldgen.check.sources.WorldSource`) from the result's spawn,
    started before this process reads the world; None when that gains nothing (no spawn yet, no fork server, a
    large world, ``--skip-sim``)."""
    from ..sim.forkserver import active
    from ..sim.process import start_isolated

    if options.skip_sim or result.spawn is None or active() is None:
        return None
    if source.text is not None:
        size = len(source.text.encode("utf-8"))
    elif source.path.is_file():
        size = source.path.stat().st_size
    else:   # a model folder: read here first
        return None
    if size > EARLY_WORLD_BYTES:
        return None
    world = {"path": str(source.path), "text": source.text, "model_paths": [str(p) for p in options.model_paths]}
    return EarlyRun(start_isolated(job, {**_kwargs(result, options, tmp), "world": world}, options.sim_timeout))


class EarlyRun:
    """A run started by :func:`start_early`; :meth:`read` tells it the scene this process read, as read (the
    checks may keep things on its shapes)."""

    def __init__(self, pending):
        self.pending, self.digest = pending, None

    def read(self, scene) -> None:
        from .sim_job import scene_digest

        self.digest = scene_digest(scene)

    def result(self) -> dict:
        return self.pending.result()

    def cancel(self) -> None:
        self.pending.cancel()


def start_sim(result: Result, scene, options, tmp: Path, job: str):
    """The simulation of ``scene`` from the result's spawn, started in a child process (a
    :class:`~worldgen.sim.process.Pending` run)."""
    from ..sim.process import start_isolated

    scene_file = tmp / "scene.pickle"
    kwargs = _kwargs(result, options, tmp)
    in_reach(scene, result.spawn, kwargs["urdf"]).save(scene_file)   # what the child loads, and no more
    return start_isolated(job, {**kwargs, "scene_file": str(scene_file)}, options.sim_timeout)


class Ahead:
    """The simulations of ``results`` (one scene, a spawn each: a world's closed rooms), each in a folder of its
    own under ``tmp`` (its scene file, its stage), started up to :data:`SIMS_AHEAD` at a time under a fork server,
    so that one room's runs while the checks wait for another's; without a server (or with ``--skip-sim``)
    none starts here and each room's checks start their own, as for a single spawn. The simulations are the
    same ones, in the same scene: only when they run changes. :meth:`cancel` stops those not taken."""

    def __init__(self, results: list[Result], scene, options, tmp: Path, job: str):
        from ..sim.forkserver import active

        self.results, self.scene, self.options, self.job = results, scene, options, job
        self.folders = [tmp / f"spawn{i}" for i in range(len(results))]
        self.started: dict[int, object] = {}
        self.ahead = SIMS_AHEAD if not options.skip_sim and active() is not None else 0

    def take(self, i: int) -> tuple[Path, object | None]:
        """Room ``i``'s folder and its simulation (None: not started here), the next ones started first."""
        for k in range(i, min(i + self.ahead, len(self.results))):
            if k not in self.started:
                self.folders[k].mkdir(exist_ok=True)
                self.started[k] = start_sim(self.results[k], self.scene, self.options, self.folders[k], self.job)
        self.folders[i].mkdir(exist_ok=True)
        return self.folders[i], self.started.pop(i, None)

    def cancel(self) -> None:
        for sim in self.started.values():
            sim.cancel()
        self.started.clear()


def _kwargs(result: Result, options, tmp: Path) -> dict:
    from ..robots import robot_urdf

    return {"robot": result.robot, "spawn": list(result.spawn), "no_hit": options.lidar_no_hit,
            "stage_file": str(tmp / "stage"),
            "urdf": robot_urdf(result.robot)}   # processed here (and kept: robots.cache), not xacro'd per child


def judge(result: Result, sim, scene, options, floor: tuple[float, str | None], tmp: Path, job: str) -> None:
    """The simulated checks' findings once ``sim`` has ended (``floor``: the floor's height and slab under the
    spawn); a failed run is one error finding and the checks it prevented are skipped."""
    from ..sim.process import SimCrashed, SimError

    stage_file = tmp / "stage"
    try:
        numbers = _numbers(result, sim, scene, options, tmp, job)
        failure = None
    except SimCrashed as err:
        what = (f"did not finish within {options.sim_timeout:g} s" if err.timed_out else
                f"crashed ({_exit_text(err.rc)})")
        failure = f"pybullet {what} while {_stage(stage_file)}"
    except SimError as err:
        failure = f"the simulation failed while {_stage(stage_file)}: {err}"
    except WorldgenError as err:
        failure = f"the simulation could not run ({_stage(stage_file)}): {err}"
    if failure is not None:
        result.checks.append("settle")
        result.findings.append(Finding("settle", "error", failure,
                                       fix="--skip-sim checks this world without the simulator; please report "
                                           "the world to the worldgen developers if it loads in Gazebo"))
        for name in SIM_CHECKS[1:]:
            result.skipped[name] = "the simulation did not run to the end"
        return
    result.checks += [name for name in SIM_CHECKS if name in numbers["ran"]]
    for name in SIM_CHECKS:
        if name not in numbers["ran"]:
            result.skipped[name] = "not possible with this robot"
    outcome = sim_findings(numbers, options.lidar_no_hit, *floor)
    result.findings += outcome.findings
    result.metrics.update(outcome.metrics)
    result.metrics["sim_seconds"] = numbers.get("sim_seconds")   # (not its wall time: reports are deterministic)


def _numbers(result: Result, sim, scene, options, tmp: Path, job: str) -> dict:
    """What ``sim`` measured, if it drove in ``scene``; else (an early child read something else, or could not
    read it) what a run on ``scene`` itself measures."""
    if not isinstance(sim, EarlyRun):
        return sim.result()
    try:
        numbers = sim.result()
    except WorldFileError:   # the file changed under the child
        numbers = {}
    if sim.digest is not None and numbers.pop("scene_digest", None) == sim.digest:
        return numbers
    return start_sim(result, scene, options, tmp, job).result()


def _stage(stage_file: Path) -> str:
    try:
        return stage_file.read_text(encoding="utf-8").strip() or "starting"
    except OSError:
        return "starting"


def _exit_text(rc: int | None) -> str:
    if rc is None:
        return "no exit code"
    if rc < 0:
        try:
            return f"killed by {signal.Signals(-rc).name}"
        except ValueError:
            return f"killed by signal {-rc}"
    return f"exit code {rc}"
