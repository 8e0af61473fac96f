"""Validation results and their three readings: a text table for people, JSON for programs, JUnit XML for CI.

A :class:`Result` is one validated file: its spawn pose and where that came from, the checks that ran, their
findings and the numbers they measured. Every writer here is deterministic (no times, no dates): the same results
give the same bytes.
"""

from __future__ import annotations

import json
import math
import os
import re
from dataclasses import dataclass, field
from pathlib import Path

from ..core.errors import InputError, OutputExistsError
from ..core.findings import SEVERITIES, Finding

CHECK_ORDER = ("input", "parse", "sdformat", "launch", "package", "enclosed", "spawn-clear", "camera", "settle",
               "lidar", "spin", "stop-at-wall")


@dataclass
class Result:
    """One validated file.

    ``checks`` lists the checks that ran, in order; ``skipped`` maps a check that did not run to why.
    A finding whose id is not a check's id (the world reader's own ids) belongs to ``parse``.
    """

    path: str
    spawn: tuple[float, float, float] | None = None
    spawn_source: str = ""
    robot: str = "burger"
    robot_source: str = "default"
    findings: list[Finding] = field(default_factory=list)
    metrics: dict = field(default_factory=dict)
    checks: list[str] = field(default_factory=list)
    skipped: dict[str, str] = field(default_factory=dict)
    room: int | None = None   # no spawn given: the closed room (1 = largest) this result checked from

    @property
    def name(self) -> str:
        """The path, and the room checked from when there are several: ``maze.world [room 2]``."""
        return self.path if self.room is None else f"{self.path} [room {self.room}]"

    @property
    def verdict(self) -> str:
        """``FAIL``, ``warn`` or ``ok``."""
        return "FAIL" if not self.ok else ("warn" if any(f.severity == "warning" for f in self.findings) else "ok")

    @property
    def ok(self) -> bool:
        return not any(f.severity == "error" for f in self.findings)

    def check_of(self, finding: Finding) -> str:
        """The check a finding is reported under: its own id when that check ran, the check whose id prefixes
        it (``launch-find`` → ``launch``), else ``parse`` (the world reader's ids)."""
        if finding.check in self.checks:
            return finding.check
        head = finding.check.split("-", 1)[0]
        return head if head in self.checks else "parse"

    def sorted_findings(self) -> list[Finding]:
        """Errors first, then warnings, then info; within a severity, in check order then as found."""
        rank = {name: i for i, name in enumerate(CHECK_ORDER)}
        indexed = list(enumerate(self.findings))
        indexed.sort(key=lambda item: (SEVERITIES.index(item[1].severity),
                                       rank.get(self.check_of(item[1]), len(rank)), item[0]))
        return [f for _, f in indexed]

    def to_dict(self) -> dict:
        doc = {
            "path": self.path,
            "ok": self.ok,
            "robot": self.robot,
            "robot_source": self.robot_source,
            "spawn": [round(v, 4) for v in self.spawn] if self.spawn else None,
            "spawn_source": self.spawn_source,
            "checks": list(self.checks),
            "skipped": dict(self.skipped),
            "findings": [f.to_dict() for f in self.sorted_findings()],
            "metrics": _clean(self.metrics),
        }
        if self.room is not None:
            doc["room"] = self.room
        return doc


def _clean(value):
    """JSON-safe metrics: floats rounded to 4 decimals, non-finite floats as strings ("inf")."""
    if isinstance(value, dict):
        return {k: _clean(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_clean(v) for v in value]
    if isinstance(value, float):
        if math.isfinite(value):
            return round(value, 4) + 0.0
        return "inf" if value > 0 else ("-inf" if value < 0 else "nan")
    return value


_SURROGATE = re.compile("[\ud800-\udfff]")


def _unicode(text: str) -> str:
    """``text`` that any UTF-8 stream can take: the undecodable bytes of a file name (which Python keeps as lone
    surrogates) become U+FFFD."""
    return _SURROGATE.sub("\ufffd", text)


# ------------------------------------------------------------------------------------------------------ JSON

def to_json(results: list[Result]) -> str:
    """``{"ok": bool, "results": [...]}``, indented, keys in a fixed order, ending with a newline."""
    doc = {"ok": all(r.ok for r in results), "results": [r.to_dict() for r in results]}
    return _unicode(json.dumps(doc, indent=2, allow_nan=False, ensure_ascii=False) + "\n")


# ------------------------------------------------------------------------------------------------------ text

def _fmt_m(value) -> str:
    if value is None:
        return "–"
    return f"{value:.2f} m" if math.isfinite(value) else "inf"


def _row(r: Result) -> list[str]:
    m = r.metrics
    enclosed = m.get("enclosed")
    enclosed_text = {True: "yes", False: "NO", None: "–"}[enclosed] if "enclosed" in m else "–"
    if enclosed is False and m.get("robot_enclosed"):
        enclosed_text = "leaks"   # the robot is held in, the LiDAR's beams are not
    if m.get("spawn_inside"):
        enclosed_text = "in wall"
    verdict = r.verdict
    beams = m.get("lidar_no_hit_beams")
    drift = m.get("spin_drift_m")
    return [
        _short(r.name),
        verdict,
        enclosed_text,
        _fmt_m(m.get("min_clearance_m")),
        "–" if beams is None else f"{beams}/{m.get('lidar_beams', 360)}",
        "–" if drift is None else f"{drift * 100:.1f} cm",
        _fmt_m(m.get("stop_distance_m")),
    ]


FILE_COLUMN = 48   # longer paths are shortened from the left in the table (findings keep them whole)


def _short(path: str) -> str:
    return path if len(path) <= FILE_COLUMN else "…" + path[-(FILE_COLUMN - 1):]


HEADER = ["file", "verdict", "enclosed", "clearance", "no-hit", "spin drift", "stopped at"]


def to_text(results: list[Result]) -> str:
    """A table with one row per file, each followed by its spawn line and its findings (errors first)."""
    rows = [HEADER] + [_row(r) for r in results]
    widths = [max(len(row[i]) for row in rows) for i in range(len(HEADER))]
    lines = ["  ".join(cell.ljust(w) for cell, w in zip(HEADER, widths)).rstrip()]
    for r, row in zip(results, rows[1:]):
        lines.append("  ".join(cell.ljust(w) for cell, w in zip(row, widths)).rstrip())
        if r.spawn:
            x, y, yaw = r.spawn
            robot = r.robot.replace("\\", "/").rsplit("/", 1)[-1]   # a robot file by its name
            if r.spawn_source.startswith("no spawn given"):
                lines.append(f"    {robot}: {r.spawn_source}")
            else:
                lines.append(f"    {robot} spawn ({x:g}, {y:g}, {yaw:g}) {r.spawn_source}".rstrip())
        for f in r.sorted_findings():
            lines.append(f"    {f.severity:<7} {f.check}: {f.message}")
            if f.where:
                lines.append(f"            where: {f.where}")
            if f.fix:
                lines.append(f"            fix: {f.fix}")
    failed = sum(not r.ok for r in results)
    lines.append(f"{len(results)} file(s): {len(results) - failed} passed, {failed} failed")
    return _unicode("\n".join(lines) + "\n")


# ----------------------------------------------------------------------------------------------------- JUnit

def to_junit(results: list[Result], suite_name: str = "worldgen validate") -> bytes:
    """One ``<testsuite>`` with a ``<testcase classname=FILE name=CHECK>`` per file and check; errors are
    ``<failure>`` elements, warnings and notes go to ``<system-out>``, checks that did not run are ``<skipped>``."""
    from lxml import etree

    suites = etree.Element("testsuites")
    suite = etree.SubElement(suites, "testsuite", name=suite_name)
    tests = failures = skipped = 0
    for r in results:
        by_check: dict[str, list[Finding]] = {c: [] for c in ("parse", *r.checks)}
        for f in r.findings:
            by_check[r.check_of(f)].append(f)
        if "parse" not in r.checks and not by_check["parse"]:
            del by_check["parse"]
        classname = _xml_safe(r.name)
        for check, found in by_check.items():
            case = etree.SubElement(suite, "testcase", classname=classname, name=check)
            tests += 1
            errors = [f for f in found if f.severity == "error"]
            if errors:
                failures += 1
                failure = etree.SubElement(case, "failure", message=_xml_safe(errors[0].message), type=check)
                failure.text = _xml_safe("\n".join(_finding_line(f) for f in errors))
            others = [f for f in found if f.severity != "error"]
            if others:
                etree.SubElement(case, "system-out").text = _xml_safe("\n".join(_finding_line(f) for f in others))
        for check, why in r.skipped.items():
            case = etree.SubElement(suite, "testcase", classname=classname, name=check)
            etree.SubElement(case, "skipped", message=why)
            tests += 1
            skipped += 1
    for element in (suites, suite):
        element.set("tests", str(tests))
        element.set("failures", str(failures))
        element.set("errors", "0")
        element.set("skipped", str(skipped))
    return etree.tostring(suites, pretty_print=True, xml_declaration=True, encoding="UTF-8")


def check_junit_target(path, force: bool = False, forceable: bool = True) -> None:
    """Refuse (InputError, before anything runs) a ``--junit`` FILE that cannot take the report: a folder, a path
    through a file, or a file that exists and is not a JUnit report (a ``package.xml`` named by mistake) unless
    ``force`` (``forceable``: the command has ``--force``). A report an earlier run wrote there (or an empty file)
    is replaced."""
    from ..core.safexml import parse_file   # lxml: only when a --junit FILE is given

    path = Path(path)
    if path.is_dir():
        raise InputError(f"cannot write {path}: it is a folder", hint="give a file name for --junit")
    for parent in path.parents:
        if parent.exists():
            if not parent.is_dir():
                raise InputError(f"cannot write {path}: {parent} is not a folder",
                                 hint="give --junit a path in an existing or new folder")
            break
    if force or not os.path.lexists(path) or (path.is_file() and path.stat().st_size == 0):   # (an empty placeholder)
        return
    root = parse_file(path) if path.is_file() else None
    if root is None or root.tag not in ("testsuites", "testsuite"):
        raise OutputExistsError(f"{path} exists and is not a JUnit report", path=None,
                                hint="give --junit another name: it replaces only an earlier report"
                                     + (", or pass --force to overwrite the file" if forceable else ""))


_NOT_XML = re.compile("[\x00-\x08\x0b\x0c\x0e-\x1f\ud800-\udfff\ufffe\uffff]")


def _xml_safe(text: str) -> str:
    """``text`` with what XML 1.0 cannot hold (control characters; the undecodable bytes of a file name, which
    Python keeps as lone surrogates) replaced by U+FFFD."""
    return _NOT_XML.sub("\ufffd", text)


def _finding_line(f: Finding) -> str:
    text = f"{f.severity}: {f.message}"
    if f.where:
        text += f" [where: {f.where}]"
    if f.fix:
        text += f" [fix: {f.fix}]"
    return text
