"""The index page of a folder's grades (``worldgen validate|run FOLDER --html DIR``): one self-contained HTML file
with a row per submission — its verdict, the numbers that matter for what was graded, its counts of errors and
warnings and its findings — each row linking to that submission's own page.

:func:`index_rows` reads the :class:`~worldgen.check.report.Result` objects into plain rows (dicts a test or a
program can read, numbers kept as numbers); :func:`index_page` renders them with ``templates/view/index.html.j2``
(Jinja2, autoescaped) into UTF-8 bytes. The page loads nothing: its style and script are inline, a Content
Security Policy forbids every other source, and it works from a CI job's artifacts or a laptop offline. Without
JavaScript it is a plain table with the findings under each row (``<details>``); with it, a click on a column
header sorts the rows (numbers by value, again to reverse; stable: ties keep the order they had, so a sort by
a measure and then by verdict groups the verdicts in the measure's order), and a filter box and a
"failures only" switch narrow them. The rows are also embedded as JSON (``<script type="application/json"
id="worldgen-index">``). The same rows give the same bytes: no dates, no random ids.
"""

from __future__ import annotations

import json
import math
import re
from typing import Iterable, Sequence
from urllib.parse import quote

from ..check.report import Result, _clean
from ..core.resources import templates_dir

TEMPLATE = "view/index.html.j2"
RUN_CHECKS = ("node", "runtime")   # a Result whose first check is one of these is a run's, not validate's
VERDICT_RANK = {"FAIL": 0, "warn": 1, "ok": 2}   # ascending sort: failures first

# A run's measures, in column order: (metric key, label, unit, how). The task's own numbers come first (each
# task's keys are its own: see bridge/rubrics.py), then what every run measures (bridge/metrics.py).
RUN_METRICS = (
    ("final_front_distance_m", "front distance", "m", "num"),
    ("stop_error_m", "stop error", "m", "signed"),      # front distance − target: negative is past the target
    ("turns", "turns", "", "num"),
    ("centre_drift_m", "centre drift", "m", "num"),
    ("sides_m", "sides", "", "len"),
    ("closing_gap_m", "closing gap", "m", "num"),
    ("share_in_band", "in band", "%", "share"),
    ("travelled_m", "travelled", "m", "num"),
    ("share_in_range", "in range", "%", "share"),
    ("min_person_distance_m", "nearest to person", "m", "num"),
    ("share_on_line", "on line", "%", "share"),
    ("laps", "laps", "", "num"),
    ("covered", "covered", "%", "share"),
    ("worst_distance_m", "worst off line", "m", "num"),
    ("contacts", "contacts", "", "len"),
    ("min_clearance_m", "min clearance", "m", "num"),
    ("path_length_m", "path", "m", "num"),
    ("sim_time_s", "sim time", "s", "num"),
    ("cmd_vel_messages", "cmd_vel msgs", "", "num"),
    ("node", "node", "", "text"),
)

# validate's measures after spawn, robot and enclosed (see check/checks.py and check/validate.py).
VALIDATE_METRICS = (
    ("min_clearance_m", "clearance", "m", "num"),
    ("lidar_no_hit_beams", "no-hit beams", "", "num"),
    ("spin_drift_m", "spin drift", "cm", "cm"),
    ("stop_distance_m", "stopped at", "m", "num"),
    ("sim_seconds", "sim time", "s", "num"),
)

KEY_ORDER = {key: i for i, key in enumerate(
    ("spawn", "robot", "enclosed", "gaps", "widest_gap_m", *(spec[0] for spec in VALIDATE_METRICS + RUN_METRICS)))}
DIGITS = {"m": 2, "cm": 1, "s": 1, "%": 0}   # decimals shown per unit; numbers without a unit get 2


# ------------------------------------------------------------------------------------------------------ rows

def index_rows(results: Iterable[Result], hrefs: dict[str, str] | Sequence[str | None] | None = None) -> list[dict]:
    """One row per result, in the given order.

    A row: ``name`` (:attr:`Result.name`), ``path``, ``verdict`` (``ok``/``warn``/``FAIL``), ``ok``, ``href``
    (``hrefs[result.name]`` or ``hrefs[result.path]``, or with a list ``hrefs[i]`` for the i-th result: a relative
    file path, percent-encoded; None without one),
    ``kind`` (``run`` or ``validate``), ``task`` (a run's task, or None), ``metrics`` (a list of ``{"key",
    "label", "value", "unit", "text"}``: value a number, a string or None, text as shown), ``errors``,
    ``warnings``, ``notes`` (counts by severity), ``findings`` (``{"severity", "check", "message", "where",
    "fix"}``, errors first, None where a finding has no such part) and ``skipped`` (check → why it did not run).
    """
    hrefs = hrefs or {}
    rows = []
    for i, r in enumerate(results):
        run = bool(r.checks) and r.checks[0] in RUN_CHECKS
        if isinstance(hrefs, dict):
            href = hrefs.get(r.name, hrefs.get(r.path))
        else:   # one per result, in order: results of the same name (a file given twice) keep their own pages
            href = hrefs[i] if i < len(hrefs) else None
        count = {s: sum(f.severity == s for f in r.findings) for s in ("error", "warning", "info")}
        rows.append({
            "name": r.name,
            "path": r.path,
            "verdict": r.verdict,
            "ok": r.ok,
            "href": None if href is None else _relative_href(href),
            "kind": "run" if run else "validate",
            "task": _task_of(r) if run else None,
            "metrics": _run_metrics(r) if run else _validate_metrics(r),
            "errors": count["error"],
            "warnings": count["warning"],
            "notes": count["info"],
            "findings": [{"severity": f.severity, "check": f.check, "message": f.message, "where": f.where,
                          "fix": f.fix} for f in r.sorted_findings()],
            "skipped": dict(r.skipped),
        })
    return rows


def _relative_href(href: str) -> str:
    """A relative link to a file: separators as ``/``, everything else that is not plain percent-encoded (so a
    ``:``, ``?`` or ``#`` in a student's folder name stays part of the file name, never a scheme or a query)."""
    return quote(str(href).replace("\\", "/").lstrip("/"), safe="/")


def _task_of(r: Result) -> str | None:
    """A run's task: the check after ``node`` (run.result_of), or the one skipped (a run that could not start)."""
    return r.checks[1] if len(r.checks) > 1 else next(iter(r.skipped), None)


def _metric(key: str, label: str, unit: str, value) -> dict:
    return {"key": key, "label": label, "value": value, "unit": unit, "text": _text(value, unit)}


def _number(value) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _text(value, unit: str, signed: bool = False) -> str:
    """``value`` as the table shows it: its unit's decimals (:data:`DIGITS`), ``signed`` with a + on a positive
    value, and never a negative zero (−0.001 m reads 0.00 m: no sign on a zero)."""
    if value is None:
        return "–"
    if not _number(value):
        return str(value)
    if isinstance(value, float) and not math.isfinite(value):
        return "nan" if math.isnan(value) else ("inf" if value > 0 else "-inf")
    if isinstance(value, int):
        text = f"{value:+d}" if signed else str(value)
    else:
        digits = DIGITS.get(unit, 2)
        value = round(value, digits) + 0.0   # + 0.0: -0.0 becomes 0.0
        text = f"{value:+.{digits}f}" if signed and value else f"{value:.{digits}f}"
    return text + ("%" if unit == "%" else f" {unit}" if unit else "")


def _measure(m: dict, key: str, label: str, unit: str, how: str) -> dict | None:
    """The metric ``key`` of ``m`` as a row's metric, or None when ``m`` has no such key (or a value of the wrong
    kind: a run's metrics are the students' nodes' doing, so nothing in them is taken on trust)."""
    if key not in m:
        return None
    value = m[key]
    if how == "text":
        return _metric(key, label, unit, None if value is None else str(value))
    if how == "len":
        return _metric(key, label, unit, len(value)) if isinstance(value, (list, tuple, dict)) else None
    if value is not None and not _number(value):
        return None
    if how in ("share", "cm") and value is not None and math.isfinite(value):
        value = round(value * 100.0, 9)   # a percentage, centimetres (rounded: 0.0162 × 100 is 1.6199999…)
    row = _metric(key, label, unit, value)
    if how == "signed":
        row["text"] = _text(value, unit, signed=True)
    return row


def _run_metrics(r: Result) -> list[dict]:
    found = (_measure(r.metrics, *spec) for spec in RUN_METRICS)
    return [m for m in found if m is not None]


def _validate_metrics(r: Result) -> list[dict]:
    m = r.metrics
    out = []
    if r.spawn:
        out.append(_metric("spawn", "spawn", "", "(" + ", ".join(f"{round(v, 3) + 0.0:g}" for v in r.spawn) + ")"))
    out.append(_metric("robot", "robot", "", r.robot.replace("\\", "/").rsplit("/", 1)[-1]))
    if "enclosed" in m:
        out.append(_metric("enclosed", "enclosed", "", _enclosed_text(m)))
    gaps = m.get("gaps")
    if isinstance(gaps, list):
        out.append(_metric("gaps", "gaps", "", len(gaps)))
        widths = [g.get("width") for g in gaps if isinstance(g, dict) and _number(g.get("width"))]
        if widths:
            out.append(_metric("widest_gap_m", "widest gap", "m", max(widths)))
    found = (_measure(m, *spec) for spec in VALIDATE_METRICS)
    return out + [x for x in found if x is not None]


def _enclosed_text(m: dict) -> str:
    """As validate's text table says it: yes, NO, leaks (the robot is held in, the LiDAR's beams are not), in
    wall (the spawn is inside an obstacle), – (not known)."""
    if m.get("spawn_inside"):
        return "in wall"
    enclosed = m.get("enclosed")
    if enclosed is False and m.get("robot_enclosed"):
        return "leaks"
    return {True: "yes", False: "NO"}.get(enclosed, "–")


# ------------------------------------------------------------------------------------------------------ page

def index_page(rows: list[dict], title: str, subtitle: str = "") -> bytes:
    """The index page of ``rows`` (from :func:`index_rows`) as UTF-8 HTML: see the module docstring."""
    columns = _columns(rows)
    table = []
    for i, row in enumerate(rows):
        by_label = {m["label"]: m for m in row["metrics"]}
        table.append({"row": row, "index": i, "rank": VERDICT_RANK.get(row["verdict"], 3),
                      "cells": [_cell(by_label.get(c["label"])) for c in columns],
                      "summary": _findings_summary(row)})
    counts = {v: sum(r["verdict"] == v for r in rows) for v in ("ok", "warn", "FAIL")}
    page = _env().get_template(TEMPLATE).render(
        title=title, subtitle=subtitle, columns=columns, table=table, counts=counts, total=len(rows),
        data=_json_data(rows))
    return _NOT_TEXT.sub("\ufffd", page).encode("utf-8")


def _columns(rows: list[dict]) -> list[dict]:
    """The union of the rows' metric labels, in the order of :data:`VALIDATE_METRICS` and :data:`RUN_METRICS`
    (labels of other keys after them, as first met); a column is numeric when every value in it that is not None
    is a number."""
    labels: list[str] = []
    units: dict[str, str] = {}
    ranks: dict[str, int] = {}
    kinds: dict[str, set] = {}
    for row in rows:
        for m in row["metrics"]:
            label = m["label"]
            if label not in units:
                labels.append(label)
                units[label] = m["unit"]
                kinds[label] = set()
            ranks[label] = min(ranks.get(label, len(KEY_ORDER)), KEY_ORDER.get(m.get("key"), len(KEY_ORDER)))
            if m["value"] is not None:
                kinds[label].add(_number(m["value"]))
    labels.sort(key=lambda label: ranks[label])
    return [{"label": label, "unit": units[label], "numeric": kinds[label] == {True}} for label in labels]


def _cell(metric: dict | None) -> dict:
    """What the template shows of one metric: its text and, for a number, its raw value as the sort key."""
    if metric is None:
        return {"text": "", "sort": None, "title": None}
    value = metric["value"]
    sort = _sort_key(value) if _number(value) else None
    title = None
    if isinstance(value, float) and math.isfinite(value):
        title = f"{value:.4g}" + (f" {metric['unit']}" if metric["unit"] else "")
    return {"text": metric["text"], "sort": sort, "title": title}


def _sort_key(value) -> str | None:
    """A number as JavaScript's ``Number()`` reads it (``Infinity`` for inf; None for nan: it does not sort)."""
    if isinstance(value, float):
        if math.isnan(value):
            return None
        if math.isinf(value):
            return "Infinity" if value > 0 else "-Infinity"
        return repr(value)
    return str(value)


def _findings_summary(row: dict) -> str:
    parts = [_plural(row["errors"], "error"), _plural(row["warnings"], "warning"), _plural(row["notes"], "note")]
    text = ", ".join(p for p in parts if p)
    if row["skipped"]:
        text += (", " if text else "") + _plural(len(row["skipped"]), "check") + " not run"
    return text


def _plural(n: int, word: str) -> str:
    return "" if not n else f"{n} {word}{'' if n == 1 else 's'}"


def _json_data(rows: list[dict]):
    """The rows as JSON safe inside ``<script>``: no ``</`` (which would end the element) and no ``<!--``."""
    from markupsafe import Markup

    text = json.dumps(_clean(rows), ensure_ascii=False, allow_nan=False, separators=(",", ":"))
    return Markup(text.replace("</", "<\\/").replace("<!--", "\\u003c!--"))


_WORD_END = re.compile(r"(?<=[/\\])|(?<=[_.\-])(?=[A-Za-z])")   # after / or \, or a _ . - before a letter
LONGEST_PIECE = 24   # characters of a name without such a place before one is made
SHORT = 12           # a text this long or shorter is never wrapped (waffle_pi, subs/alice)


def _breakable(text) -> str:
    """``text`` escaped, with a place to wrap (``<wbr>``) after each ``/`` and ``\\`` and each ``_``, ``.`` or ``-``
    before a letter (not inside a number: ``1.571``, ``-1``), and every :data:`LONGEST_PIECE` characters of a piece
    without one: a name wraps between its words, never inside one, and a name with no such place cannot widen the
    table past the window. A text of :data:`SHORT` characters or fewer is left whole."""
    from markupsafe import Markup, escape

    text = str(text)
    if len(text) <= SHORT:
        return escape(text)
    pieces = [part[i:i + LONGEST_PIECE] for part in _WORD_END.split(text) for i in range(0, len(part), LONGEST_PIECE)]
    return Markup("<wbr>").join(escape(piece) for piece in pieces)


_NOT_TEXT = re.compile("[\x00-\x08\x0b\x0c\x0e-\x1f\x7f\ud800-\udfff]")   # controls; a file name's undecodable bytes


def _csp_hash(text: str) -> str:
    """The Content Security Policy source for an inline script of exactly ``text``."""
    import base64
    import hashlib

    return "sha256-" + base64.b64encode(hashlib.sha256(str(text).encode("utf-8")).digest()).decode("ascii")


_ENV: dict[str, object] = {}


def _env():
    """Jinja2 for HTML: every value escaped (render_template's environment escapes only XML templates)."""
    env = _ENV.get("env")
    if env is None:
        import jinja2

        env = jinja2.Environment(loader=jinja2.FileSystemLoader(str(templates_dir())), autoescape=True,
                                 undefined=jinja2.StrictUndefined, keep_trailing_newline=True, trim_blocks=True,
                                 lstrip_blocks=True)
        env.filters["csp_hash"] = _csp_hash
        env.filters["breakable"] = _breakable
        _ENV["env"] = env
    return env
