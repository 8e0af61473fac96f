"""``worldgen doctor``: is everything the nodes import installed, and what one ``apt-get install`` fills the gaps.

Given node files or folders (a class's submissions: the ``.py`` files in them, and every catkin package's
``scripts/`` and ``nodes/``, packages found as ``validate`` and ``run`` find them), each node's imports are
looked up for the Python that runs the nodes (:mod:`.check`); given nothing, the class runtime
(:data:`~worldgen.runtime.table.CLASS_RUNTIME`) is. The report is a table — module, needed by, provided by (Debian /
ROS Noetic), state — then what apt cannot fix (a node that does not parse, the workspace's own unbuilt packages,
modules worldgen knows no package for), then exactly one ``sudo apt-get install`` line with every package
missing, sorted. The same inputs give the same report.
"""

from __future__ import annotations

import functools
import json
import os
import shutil
import subprocess
from dataclasses import dataclass, field
from pathlib import Path
from typing import Mapping, Sequence

from ..core.errors import InputError
from ..core.findings import Finding
from .naming import ROS2_RUNTIME, Naming
from .table import provider, runtime_modules
from .check import OK_STATES, ask, findings, survey
from ..core.packages import IGNORE_MARKER, MANIFEST, crawl, is_workspace

MAX_NODES = 5000   # files taken from one folder (a folder as big as a disk stops there)
NOT_NODES = ("__pycache__", "test", "tests")   # folders outside packages whose Python files are no nodes
RUNTIME = "class runtime"


@dataclass
class Row:
    """One module: the places that import it (file, line), its state (``ok``/``MISSING``), and what provides it."""

    module: str
    sites: list[tuple[str, int]] = field(default_factory=list)
    missing: bool = False
    build: bool = False

    def provided_by(self, naming: Naming = Naming()) -> str:
        if self.build:
            return "your workspace (colcon build)" if naming.ros2 else "your catkin workspace (catkin_make)"
        return naming.shown(self.module)

    def needed_by(self) -> str:
        if not self.sites:
            return RUNTIME
        first = f"{self.sites[0][0]}:{self.sites[0][1]}"
        return first if len(self.sites) == 1 else f"{first} and {len(self.sites) - 1} more"


@dataclass
class Doctor:
    """What ``worldgen doctor`` found: the Python, the node files (none: the class runtime was checked), the
    rows, the findings, and the apt packages that fill the gaps."""

    python: str
    version: str
    nodes: list[str]
    rows: list[Row]
    findings: list[Finding]
    packages: list[str]
    naming: Naming = Naming()

    @property
    def ok(self) -> bool:
        return not self.findings and not any(r.missing for r in self.rows)

    @property
    def client(self) -> str:
        """The ROS client library the nodes need: rclpy on ROS 2, rospy on ROS 1."""
        return "rclpy" if self.naming.ros2 else "rospy"

    @property
    def rospy(self) -> bool | None:
        """Whether the client library (rospy, or rclpy on ROS 2) was found (None: no node imports it)."""
        row = next((r for r in self.rows if r.module == self.client), None)
        return None if row is None else not row.missing

    @property
    def install(self) -> str | None:
        return f"sudo apt-get install {' '.join(self.packages)}" if self.packages else None


def _is_python(path: Path) -> bool:
    if path.suffix == ".py":
        return path.name != "setup.py"
    try:
        with open(path, "rb") as handle:
            head = handle.read(200).split(b"\n", 1)[0]
    except OSError:
        return False
    return head.startswith(b"#!") and b"python" in head


def _folder_nodes(folder: Path) -> list[Path]:
    """The ``.py`` files under ``folder`` outside packages, the Python files in each catkin package's ``scripts/``
    and ``nodes/``, and an ament_python package's own modules (``PKG/PKG/*.py`` but ``__init__.py``); hidden
    folders, ``CATKIN_IGNORE``, a workspace's generated spaces and tests skipped (folders named ``test`` or
    ``tests``, as catkin and pytest name them, and ``conftest.py``: what they import is pytest's, not a node's)."""
    found: list[Path] = []
    for package in crawl(folder, workspaces=True, limit=MAX_NODES):
        for sub in ("scripts", "nodes"):
            if (package / sub).is_dir():
                found += sorted(p for p in (package / sub).rglob("*") if p.is_file() and _is_python(p))
        own = package / package.name
        if (package / "setup.py").is_file() and own.is_dir():
            found += sorted(p for p in own.glob("*.py") if p.name != "__init__.py")
    for dirpath, dirnames, filenames in os.walk(folder):
        here = Path(dirpath)
        if MANIFEST in filenames or IGNORE_MARKER in filenames:
            dirnames.clear()
            continue
        keep = ["src"] if is_workspace(here) else dirnames
        dirnames[:] = sorted(d for d in keep if not d.startswith(".") and d not in NOT_NODES)
        found += [here / f for f in sorted(filenames) if f.endswith(".py") and f not in ("setup.py", "conftest.py")]
        if len(found) > MAX_NODES:
            break
    return sorted(set(found))


def node_files(paths: Sequence[str | Path]) -> list[Path]:
    """The node files to check for ``paths`` (files as given, folders searched; see the module docstring);
    InputError for a path that is missing or not a Python file, or when no node is found at all."""
    found: list[Path] = []
    for item in paths:
        path = Path(item)
        if path.is_dir():
            found += _folder_nodes(path)
        elif not path.exists():
            raise InputError("no such file or folder", path=path, hint="give node files or a folder of submissions")
        elif not _is_python(path):
            raise InputError("is not a Python node", path=path, hint="give a rospy node's .py file or a folder")
        else:
            found.append(path)
    if not found:
        raise InputError("no Python node found", path=paths[0] if len(paths) == 1 else None,
                         hint="give node files, or a folder holding .py files or catkin packages with scripts/")
    return found


@functools.lru_cache(maxsize=None)
def _apt_has(package: str) -> bool:
    """Whether apt knows ``package`` (for names from the ``*_msgs`` rule); False without apt-cache."""
    if shutil.which("apt-cache") is None:
        return False
    try:
        proc = subprocess.run(["apt-cache", "show", "--no-all-versions", package], capture_output=True, timeout=30)
    except (OSError, subprocess.SubprocessError):
        return False
    return proc.returncode == 0 and bool(proc.stdout.strip())


def _package(module: str, naming: Naming) -> str | None:
    """The package apt installs for ``module`` here, if any (a ``*_msgs`` rule's name only when apt has it)."""
    known = provider(module)
    if not naming.ros2 and (known is None or known.worldgen):
        return None
    package = naming.package(module)
    guessed = (known is None or known.guessed) and not (naming.ros2 and package and package.startswith("ros-"))
    return package if package and (not guessed or _apt_has(package)) else None


def _packages(rows: list[Row], naming: Naming) -> list[str]:
    return sorted({p for p in (_package(r.module, naming) for r in rows if r.missing and not r.build) if p})


def _sort(rows: dict[str, Row]) -> list[Row]:
    return [rows[m] for m in sorted(rows, key=lambda m: (m.lower(), m))]


def check_nodes(paths: Sequence[str | Path], python: str, env: Mapping[str, str] | None = None,
                naming: Naming = Naming()) -> Doctor:
    """The report for node files and folders (see the module docstring)."""
    files = node_files(paths)
    found = survey(files, python, env)
    reports = found.reports
    rows: dict[str, Row] = {}
    for report in reports:
        needed = report.source.needed()
        for module, state in report.found.items():
            if naming.shown(module).startswith("–") and state in ("stdlib", "local"):
                continue
            row = rows.setdefault(module, Row(module))
            row.sites.append((str(report.path), needed[module].line))
            row.missing |= state not in OK_STATES
            row.build |= state == "build"
    for row in rows.values():
        row.sites.sort(key=lambda s: (s[0], s[1]))
    ordered = _sort(rows)
    packages = _packages(ordered, naming)
    filled = {r.module for r in ordered if not r.build and _package(r.module, naming) in packages}
    notes = findings(reports, python, naming, skip=filled)
    return Doctor(python, found.version, [str(f) for f in files], ordered, notes, packages, naming)


def check_machine(python: str, env: Mapping[str, str] | None = None, naming: Naming = Naming()) -> Doctor:
    """The class runtime on this machine (ROS 2's: rclpy and the common messages): each of its modules looked up
    for ``python``."""
    modules = list(ROS2_RUNTIME) if naming.ros2 else runtime_modules()
    version, answers = ask(python, os.environ if env is None else env, [[None, [], modules]])
    rows = {}
    for module in modules:
        state = answers[0].get(module)
        rows[module] = Row(module, missing=state not in OK_STATES)
    ordered = _sort(rows)
    return Doctor(python, version, [], ordered, [], _packages(ordered, naming), naming)


def to_text(doc: Doctor) -> str:
    """The table, what apt cannot fix, and the one ``sudo apt-get install`` line (or that nothing is missing)."""
    if doc.nodes:
        lines = [f"worldgen doctor: {len(doc.nodes)} node file(s), for {doc.python} (Python {doc.version})"]
    else:
        lines = [f"worldgen doctor: the class runtime, for {doc.python} (Python {doc.version}), which runs the nodes; "
                 + (f"{doc.client} found" if doc.rospy else f"{doc.client} MISSING: no node can run")]
    table = [["module", "needed by", doc.naming.column, "state"]]
    table += [[r.module, r.needed_by(), r.provided_by(doc.naming), "MISSING" if r.missing else "ok"]
              for r in doc.rows]
    widths = [max(len(row[i]) for row in table) for i in range(4)]
    lines += ["  ".join(c.ljust(w) for c, w in zip(row, widths)).rstrip() for row in table]
    if doc.findings:
        lines.append("not fixed by apt:")
        for f in doc.findings:
            lines.append(f"  {f.where}: {f.message}" + (f" ({f.fix})" if f.fix else ""))
    if doc.install:
        lines.append(doc.install)
    elif doc.ok:
        lines.append("nothing to install: every module is found")
    else:
        lines.append("nothing apt can install: see above")
    return "\n".join(lines) + "\n"


def to_json(doc: Doctor) -> str:
    """``{"ok", "python", "python_version", "rospy", "nodes", "modules", "findings", "install", "packages"}``
    (``rospy``: whether it was found; null when no node imports it)."""
    modules = []
    for row in doc.rows:
        known = provider(row.module)
        modules.append({"module": row.module, "state": "MISSING" if row.missing else "ok",
                        "needed_by": [{"file": f, "line": n} for f, n in row.sites],
                        "debian": known.debian if known else None, "noetic": known.noetic if known else None,
                        "provided_by": row.provided_by(doc.naming)})
    doc_json = {"ok": doc.ok, "python": doc.python, "python_version": doc.version, "rospy": doc.rospy,
                "nodes": doc.nodes,
                "modules": modules, "findings": [f.to_dict() for f in doc.findings], "install": doc.install,
                "packages": doc.packages}
    return json.dumps(doc_json, indent=2, ensure_ascii=False) + "\n"
