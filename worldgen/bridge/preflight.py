"""Before a run starts: every Python node it would start has its imports looked up for the Python that runs it
(:mod:`worldgen.runtime.check`), so that a node importing numpy on a machine without it is an error finding
naming the package — found in a second, before any master or simulator starts — rather than a node dying at
start-up and a robot that never moves.

``worldgen run`` refuses to start on such findings (:func:`blocked_result`); ``worldgen sim``, which starts no
node, prints them for a launch file's nodes as warnings (:func:`worldgen.ros1.transport.launch_warnings`).
"""

from __future__ import annotations

from pathlib import Path
from typing import Mapping, Sequence

from ..check.report import Result
from ..core.findings import Finding
from ..runtime.check import findings, survey
from ..runtime.naming import Naming
from .outcome import NodeSpec


def python_sources(specs: Sequence[NodeSpec], python: str) -> list[str]:
    """The files of the nodes that ``python`` runs (a compiled node has no imports to check)."""
    return [s.source for s in specs if s.source and len(s.command) >= 2 and s.command[0] == python]


def node_findings(specs: Sequence[NodeSpec], python: str, env: Mapping[str, str] | None = None, *,
                  naming: Naming = Naming()) -> list[Finding]:
    """The ``runtime`` findings of the nodes ``specs`` (empty: every import is found), packages named as
    ``naming`` says."""
    sources = python_sources(specs, python)
    if not sources:
        return []
    return findings(survey(sources, python, env).reports, python, naming)


def many_findings(groups: Mapping[str, Sequence[NodeSpec]], python: str, env: Mapping[str, str] | None = None,
                  *, naming: Naming = Naming()) -> dict[str, list[Finding]]:
    """:func:`node_findings` for several runs (a folder of submissions) with one child process: findings by
    the key of each group."""
    sources = {key: python_sources(specs, python) for key, specs in groups.items()}
    files = [f for key in sorted(sources) for f in sources[key]]
    if not files:
        return {key: [] for key in groups}
    by_file = {Path(r.path).resolve(): r for r in survey(files, python, env).reports}
    return {key: findings([by_file[Path(f).resolve()] for f in sources[key]], python, naming) for key in groups}


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
