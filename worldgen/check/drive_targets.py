"""What ``worldgen drive`` runs in when it is given a launch file, a package or any folder rather than one world.

The same search as ``worldgen validate`` (:func:`worldgen.check.validate.plan`): every package in the folder, each
launch file with the world it starts and the spawn pose and robot it gives; a folder without packages gives its
worlds and specs. A launch file whose world cannot be found, or a path that cannot be read, is a target with a
``problem`` (reported as a failure, the others still run).

With no spawn anywhere, :func:`default_spawn` is the deepest free point of the world's largest closed room
(:mod:`worldgen.check.nospawn`), never the origin, which is often inside a wall.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from pathlib import Path
from typing import List, Optional, Tuple

from ..core.errors import InputError, WorldgenError
from ..sim.exercise import Exercise
from ..sim.process import SimCrashed, SimError
from .nospawn import default_spawns
from .sources import load_scene, run_on_scene
from .validate import Options, plan


@dataclass(frozen=True)
class DriveTarget:
    """One world to drive in: ``path`` (a world, model folder or spec; None with a ``problem``), its ``kind``
    (``world`` or ``spec``), the spawn (x, y, yaw) and robot a launch file gives (None: the spec's, else the
    default), and what to call it."""

    shown: str
    path: Optional[Path] = None
    kind: str = "world"
    spawn: Optional[Tuple[float, float, float]] = None
    spawn_source: str = ""
    robot: Optional[str] = None
    problem: Optional[str] = None


def drive_targets(path: str | Path) -> List[DriveTarget]:
    """The targets of ``path`` in the order ``validate`` would check them (InputError when nothing can be)."""
    targets: List[DriveTarget] = []
    for job in plan([path], Options()):
        errors = [f for f in job.findings if f.severity == "error" and f.check in ("input", "launch")]
        if job.package_only:
            if "input" in job.pre_checks:
                targets.append(DriveTarget(job.path, problem=errors[0].message if errors else "cannot be read"))
            continue   # a package's own row: nothing to drive
        if job.spec is not None:
            targets.append(DriveTarget(job.path, job.spec, "spec"))
        elif job.world is None:
            targets.append(DriveTarget(job.path, problem=errors[0].message if errors else "no world to drive in"))
        else:
            robot = job.robot if job.robot_source.startswith("from launch file") else None
            targets.append(DriveTarget(job.path, job.world, "world", job.spawn, job.spawn_source, robot))
    return targets


def default_spawn(scene, robot: str) -> Tuple[Tuple[float, float, float], str]:
    """The spawn for a world with none given, and the sentence saying so: the largest closed room's deepest
    free point (see the module docstring)."""
    first = default_spawns(scene, robot)[0]
    return first.spawn, first.source


def drive_one(world: Path, kind: str, exercise: Exercise, model_paths=(), launch_pose=None, timeout: float = 300.0
              ) -> dict:
    """Run ``exercise`` (:func:`worldgen.sim.exercise.drive_exercise`, in a child process) in one world or spec.
    Spawn: the exercise's (``--spawn``), else ``launch_pose`` ((x, y, yaw), its source), else the spec's robot,
    else the deepest free point of the largest closed room."""
    scene, spec_robot = load_scene(world, "spec" if kind == "spec" else "world", model_paths)
    note = None
    if exercise.spawn is None and launch_pose is not None:
        exercise, note = replace(exercise, spawn=tuple(launch_pose[0])), launch_pose[1]
    elif exercise.spawn is None and spec_robot is None:
        pose, note = default_spawn(scene, exercise.robot or "burger")
        exercise = replace(exercise, spawn=tuple(pose))
    result = run_on_scene("worldgen.sim.exercise:drive_exercise", scene,
                          {"world": str(world), "exercise": exercise.to_dict(), "spec_robot": spec_robot}, timeout)
    if note is not None:
        result["spawn_source"] = note
    return result


def drive_all(path: str | Path, exercise: Exercise, model_paths=(), timeout: float = 300.0
              ) -> List[Tuple[str, Optional[dict], Optional[str]]]:
    """:func:`drive_one` in every target of ``path``: (what to call it, the result, None) each, or (…, None, why it
    failed) for a target that cannot be driven in; InputError when ``path`` holds nothing to drive in."""
    targets = drive_targets(path)
    if not targets:
        raise InputError("holds no world, spec, launch file or package to drive in", path=path,
                         hint="give a .world/.sdf file, a spec, a launch file, a package or a folder holding them")
    done: List[Tuple[str, Optional[dict], Optional[str]]] = []
    for target in targets:
        failure, result = target.problem, None
        if failure is None:
            pose = (target.spawn, target.spawn_source) if target.spawn is not None else None
            asked = replace(exercise, robot=exercise.robot or target.robot)
            try:
                result = drive_one(target.path, target.kind, asked, model_paths, pose, timeout)
                result["world"] = target.shown
            except (SimCrashed, SimError) as err:
                failure = f"the simulation failed: {str(err).splitlines()[0]}"
            except WorldgenError as err:
                failure = str(err)
        done.append((target.shown, result, failure))
    return done
