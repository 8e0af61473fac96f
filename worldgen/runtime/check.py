"""Can a node's imports be found by the Python that will run it? Checked before anything starts.

Each node's imports are read statically (:mod:`.imports`); their top-level names are then looked up with
``importlib.util.find_spec`` in one child process of the interpreter the nodes run with, in the environment they
get, with ``sys.path[0]`` set to each node's own folder in turn (as ``python3 node.py`` sets it, so a sibling
helper module is found). ``find_spec`` of a top-level name locates it without importing it, so no node code and no
package code runs; one process answers for a whole folder of submissions.

A name that is not found is a **gap**, told apart by what fills it:

* a module of the node's own catkin workspace — found only in its package's ``src/`` (a ``setup.py`` package), or
  named as a package beside it (``from my_pkg.msg import X``) — needs the workspace built and sourced
  (``catkin_make``), not a Debian package;
* a module of :data:`~worldgen.runtime.table.TABLE` needs its package (or, for Python 2's names, renaming);
* anything else is unknown to worldgen: pip, or ``apt-cache search``.

``gazebo_msgs`` is never a gap: worldgen generates it for the nodes it runs. :func:`findings` turns gaps into
``runtime`` error findings (where: ``FILE:LINE``; fix: what to install).
"""

from __future__ import annotations

import json
import os
import shlex
import subprocess
from dataclasses import dataclass, field
from pathlib import Path
from typing import Container, Iterable, Mapping

from ..core.errors import InputError
from ..core.findings import Finding
from .imports import NodeSource, read_node
from .naming import Naming
from .table import provider
from ..core.packages import crawl, manifest_name, owning_package, source_tree

TIMEOUT = 60.0   # s for the child to answer (it only reads directories)

# Run by the nodes' Python (3.8 or newer): for each [folder, extra, names], where each name is found, with the
# folder (when not null) first on sys.path; the names not found are tried again with the extra folders last.
# Prints JSON: the Python's version and one {name: where} per request.
RESOLVER = r"""
import importlib.util, json, os, sys, sysconfig
stdlib = tuple(os.path.realpath(sysconfig.get_paths()[k]) + os.sep for k in ("stdlib", "platstdlib"))
def where(name, folder):
    try:
        spec = importlib.util.find_spec(name)
    except (ImportError, ValueError, AttributeError):
        return None
    if spec is None:
        return None
    origin = spec.origin if spec.has_location else None
    places = [origin] if origin else list(spec.submodule_search_locations or [])
    real = [os.path.realpath(p) for p in places]
    if not real:
        return "stdlib"
    if folder and all(p.startswith(os.path.realpath(folder) + os.sep) for p in real):
        return "local"
    if all(p.startswith(stdlib) and "-packages" + os.sep not in p for p in real):
        return "stdlib"
    return "site"
base = sys.path[1:]
answers = []
for folder, extra, names in json.load(sys.stdin):
    sys.path[:] = ([folder] if folder else []) + base
    found = {name: where(name, folder) for name in names}
    missing = [name for name in names if found[name] is None]
    if missing and extra:
        sys.path[:] = ([folder] if folder else []) + base + extra
        for name in missing:
            if where(name, folder) is not None:
                found[name] = "build"
    answers.append(found)
sys.stdout.write(json.dumps({"version": sys.version.split()[0], "answers": answers}))
"""

OK_STATES = ("stdlib", "local", "site", "worldgen")


@dataclass
class NodeReport:
    """One node file: what it imports, and where each top-level module it needs was found (``stdlib``,
    ``local`` beside the node, ``site`` installed, ``worldgen`` made by worldgen) or why not (``build``: the
    workspace's own, unbuilt; None: not installed)."""

    source: NodeSource
    found: dict[str, str | None] = field(default_factory=dict)

    @property
    def path(self) -> Path:
        return self.source.path

    def gaps(self) -> list[str]:
        """The modules the node needs that its Python cannot find, in import order."""
        return [m for m, state in self.found.items() if state not in OK_STATES]


def _own_src(node: Path) -> list[str]:
    """The node's catkin package's own Python folder: its ``src/`` when it has a ``setup.py``."""
    package = owning_package(node, levels=4)
    if package is None or not (package / "setup.py").is_file() or not (package / "src").is_dir():
        return []
    return [str(package / "src")]


def _workspace_names(node: Path, cache: dict[Path, set[str]]) -> set[str]:
    """The names of the node's own catkin package and, when it sits in a workspace's source space (a ``src/``
    or a folder with a top-level ``CMakeLists.txt``), of every package there."""
    package = owning_package(node, levels=4)
    if package is None:
        return set()
    tree = source_tree(package)
    if tree.name != "src" and not (tree / "CMakeLists.txt").is_file():
        tree = package
    if tree not in cache:
        cache[tree] = {n for n in (manifest_name(p / "package.xml") for p in crawl(tree, limit=500)) if n}
    return cache[tree] | {n for n in [manifest_name(package / "package.xml")] if n}


def ask(python: str, env: Mapping[str, str], request: list) -> tuple[str, list[dict[str, str | None]]]:
    """``python``'s version and, for each ``[folder, extra, names]`` of ``request``, where each name is found
    (see :data:`RESOLVER`); InputError when ``python`` cannot run."""
    try:
        proc = subprocess.run([python, "-c", RESOLVER], input=json.dumps(request), capture_output=True, text=True,
                              env=dict(env), timeout=TIMEOUT)
    except (OSError, subprocess.SubprocessError) as err:
        raise InputError(f"cannot run {python} to look the nodes' imports up: {err}",
                         hint="set WORLDGEN_ROS_PYTHON to the Python that runs your nodes") from None
    if proc.returncode != 0:
        last = (proc.stderr.strip().splitlines() or ["no output"])[-1]
        raise InputError(f"{python} could not look the nodes' imports up: {last}",
                         hint="set WORLDGEN_ROS_PYTHON to the Python 3 that runs your nodes")
    answer = json.loads(proc.stdout)
    return answer["version"], answer["answers"]


@dataclass
class Survey:
    """The nodes' reports, and the version of the Python that answered."""

    version: str
    reports: list[NodeReport]


def survey(nodes: Iterable[str | Path], python: str, env: Mapping[str, str] | None = None) -> Survey:
    """Each node file's report (see the module docstring), in the order given, each file once; one child
    process of ``python`` with ``env`` (default: this process's environment) answers for all of them."""
    env = os.environ if env is None else env
    reports: list[NodeReport] = []
    seen: set[Path] = set()
    for node in nodes:
        path = Path(node)
        if path.resolve() in seen:
            continue
        seen.add(path.resolve())
        try:
            source = read_node(path)
        except OSError as err:
            source = NodeSource(path, error=(0, f"cannot read it: {err.strerror}"))
        reports.append(NodeReport(source))
    pending = [r for r in reports if r.source.needed()]
    request = [[str(r.path.resolve().parent), _own_src(r.path), list(r.source.needed())] for r in pending]
    version, answers = ask(python, env, request)
    workspaces: dict[Path, set[str]] = {}
    for report, found in zip(pending, answers):
        for module in report.source.needed():
            state = found.get(module)
            if state is None and provider(module) is not None and provider(module).worldgen:
                state = "worldgen"
            elif state is None and module in _workspace_names(report.path, workspaces):
                state = "build"
            report.found[module] = state
    return Survey(version, reports)


def findings(reports: Iterable[NodeReport], python: str, naming: Naming = Naming(), skip: Container[str] = ()
             ) -> list[Finding]:
    """A ``runtime`` error finding per node that does not parse, and per module a node needs that its Python
    cannot find (but those in ``skip``): the module, the node file and line (``where``), and what to install
    (``fix``), named as ``naming``'s stack names packages."""
    found: list[Finding] = []
    for report in reports:
        error = report.source.error
        if error is not None:
            line, message = error
            where = f"{report.path}:{line}" if line else str(report.path)
            if line:
                found.append(Finding("runtime", "error", f"{report.path.name} does not parse as Python 3, which ROS "
                                     f"{'2' if naming.ros2 else 'Noetic'} runs nodes with: {message}", where=where,
                                     fix=f"make it Python 3 code ({python} -m py_compile "
                                         f"{shlex.quote(str(report.path))} shows where)"))
            else:
                found.append(Finding("runtime", "error", f"{report.path.name}: {message}", where=where))
        needed = report.source.needed()
        for module in report.gaps():
            if module in skip:
                continue
            item = needed[module]
            site = f"{report.path.name}:{item.line} imports it" + (f" (in {item.function}, when that runs)"
                                                                     if item.function else "")
            where = f"{report.path}:{item.line}"
            if report.found[module] == "build":
                found.append(Finding("runtime", "error", f"{module} is the catkin workspace's own Python, not built "
                                     f"or not on the path of {python}: {site}", where=where,
                                     fix="build the workspace: catkin_make -DPYTHON_EXECUTABLE=/usr/bin/python3, "
                                         "then source devel/setup.bash in the shell that runs worldgen"))
                continue
            known = provider(module)
            package = naming.package(module)
            named = f" ({package})" if package else ""
            if known is not None and known.python3:
                message = f"{module} does not exist in Python 3: {site}"
            else:
                message = f"{module}{named} is not installed for {python}: {site}"
            found.append(Finding("runtime", "error", message, where=where, fix=naming.hint(module)))
    return found
