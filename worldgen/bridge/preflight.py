"""Before a run starts: every Python node it would start has its imports looked up for the Python that runs it
(:mod:`worldgen.runtime.check`), so that a node importing numpy on a machine without it is an error finding
naming the package — found in a second, before any master or simulator starts — rather than a node dying at
start-up and a robot that never moves.

``worldgen run`` refuses to start on such findings (:func:`blocked_result`); ``worldgen sim``, which starts no
node, prints them for a launch file's nodes as warnings (:func:`launch_warnings`); ``worldgen doctor`` asks
:func:`doctor_python` which Python to check.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path
from typing import Mapping, Sequence

from ..check.report import Result
from ..core.errors import WorldgenError
from ..core.findings import Finding
from ..runtime.check import findings, survey
from .nodes import NodeSpec


def noetic() -> bool:
    """Whether this system takes ROS from ROS's own apt repository (``ros-noetic-*`` names first)."""
    from .rosenv import distro_package

    return distro_package().startswith("ros-")


def python_sources(specs: Sequence[NodeSpec], python: str) -> list[str]:
    """The files of the nodes that ``python`` runs (a compiled node has no imports to check)."""
    return [s.source for s in specs if s.source and len(s.command) >= 2 and s.command[0] == python]


def node_findings(specs: Sequence[NodeSpec], python: str, env: Mapping[str, str] | None = None) -> list[Finding]:
    """The ``runtime`` findings of the nodes ``specs`` (empty: every import is found)."""
    sources = python_sources(specs, python)
    if not sources:
        return []
    return findings(survey(sources, python, env).reports, python, noetic())


def many_findings(groups: Mapping[str, Sequence[NodeSpec]], python: str, env: Mapping[str, str] | None = None
                  ) -> dict[str, list[Finding]]:
    """:func:`node_findings` for several runs (a folder of submissions) with one child process: findings by
    the key of each group."""
    sources = {key: python_sources(specs, python) for key, specs in groups.items()}
    files = [f for key in sorted(sources) for f in sources[key]]
    if not files:
        return {key: [] for key in groups}
    by_file = {Path(r.path).resolve(): r for r in survey(files, python, env).reports}
    flavour = noetic()
    return {key: findings([by_file[Path(f).resolve()] for f in sources[key]], python, flavour) for key in groups}


def blocked_result(path: str, world, found: list[Finding], task: str | None) -> Result:
    """The result of a run that did not start because of ``found``."""
    result = Result(path=path, spawn=world.spawn, spawn_source=f"from {world.spawn_source}", robot=world.robot,
                    robot_source=world.robot_source, findings=list(found), checks=["runtime"])
    if task:
        result.skipped[task] = "the nodes could not start: modules they import are missing"
    return result


def blocked_text(result: Result, task: str | None, nodes: list[str]) -> str:
    """The text report of a run that did not start: what is missing, where, and what to install."""
    lines = [f"{', '.join(nodes)}: not started, {len(result.findings)} problem(s) found before starting "
             f"(nothing ran)"]
    for f in result.sorted_findings():
        lines.append(f"  {f.severity:<7} {f.check}: {f.where}: {f.message}")
        if f.fix:
            lines.append(f"          fix: {f.fix}")
    lines.append(f"{task or 'run'}: FAIL")
    return "\n".join(lines) + "\n"


def launch_warnings(launch: Path) -> list[str]:
    """For ``worldgen sim`` with a launch file: a warning line per missing module of the launch file's own
    nodes (those worldgen does not stand in for); nothing when they cannot be found or rospy is missing (sim
    says so itself)."""
    from .nodes import resolve_nodes
    from .rosenv import node_python

    try:
        python = node_python()
        found = node_findings(resolve_nodes([str(launch)], python), python)
    except WorldgenError:
        return []
    return [f"worldgen sim: warning: {f.where}: {f.message}" + (f" (fix: {f.fix})" if f.fix else "")
            for f in found]


def doctor_python() -> str:
    """The Python ``worldgen doctor`` checks: the one that runs nodes (see :func:`.rosenv.node_python`), or,
    when none imports rospy, the one that would be tried first (so that its report shows rospy missing)."""
    from .rosenv import ENV_PYTHON, SYSTEM_PYTHON, node_python

    try:
        return node_python()
    except WorldgenError:
        pass
    for python in (os.environ.get(ENV_PYTHON), SYSTEM_PYTHON):
        if python and os.access(python, os.X_OK):
            return python
    return sys.executable
