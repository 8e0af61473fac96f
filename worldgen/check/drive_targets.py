"""What ``worldgen drive`` runs in when it is given a launch file, a package or any folder rather than one world.

The same search as ``worldgen validate`` (:func:`worldgen.check.validate.plan`): every package in the folder, each
launch file with the world it starts and the spawn pose and robot it gives; a folder without packages gives its
worlds and specs. A launch file whose world cannot be found, or a path that cannot be read, is a target with a
``problem`` (reported as a failure, the others still run).

With no spawn anywhere, :func:`default_spawn` is the deepest free point of the world's largest closed room
(:mod:`worldgen.check.nospawn`), never the origin, which is often inside a wall.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import List, Optional, Tuple


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
    from .validate import Options, plan

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
    from .nospawn import default_spawns

    first = default_spawns(scene, robot)[0]
    return first.spawn, first.source
