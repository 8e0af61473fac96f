"""A run's result: metrics, the nodes' findings and the task's verdict, as a
:class:`~worldgen.check.report.Result` (so folders of submissions get ``validate``'s JSON and JUnit), and the
single run's own text and JSON."""

from __future__ import annotations

import json
import math

from ..check.report import Result, _clean
from .outcome import Outcome
from .world import World
from ..core.errors import InputError
from ..geometry.placement import world_rooms
from .rubrics import judge
from .track import camera_floor_distance, tape_track


def room_side(world: World) -> float | None:
    """The shorter side of the free floor's bounding box around the spawn (None: no closed room there)."""
    try:
        import shapely

        rooms = world_rooms(world.scene, 0.0)
        here = shapely.Point(world.spawn[0], world.spawn[1])
        region = next((p for p in rooms.free if p.covers(here)), None)
    except Exception:   # noqa: BLE001  (an odd world only loses the wall-follow room size)
        return None
    if region is None:
        return None
    xmin, ymin, xmax, ymax = region.bounds
    return min(xmax - xmin, ymax - ymin)


def result_of(path: str, world: World, outcome: Outcome, task: str | None, target: float | None) -> Result:
    result = Result(path=path, spawn=world.spawn, spawn_source=f"from {world.spawn_source}", robot=world.robot,
                    robot_source=world.robot_source, findings=list(outcome.findings), metrics=dict(outcome.metrics),
                    checks=["node"])
    if task is not None:
        found, numbers = judge(task, outcome.trace, outcome.metrics, target, task_context(world, task))
        result.checks.append(task)
        result.findings += found
        result.metrics.update(numbers)
    return result


def task_context(world: World, task: str | None):
    """What the task's rubric needs of the world (see :func:`.rubrics.judge`); InputError for a line-follow world
    without tape or a robot without a camera."""
    if task == "wall-follow":
        return room_side(world)
    if task == "line-follow":
        lookahead = camera_floor_distance(world.robot)
        if lookahead is None:
            raise InputError(f"--task line-follow needs a robot with a camera; {world.robot} has none",
                             hint="give --robot waffle_pi, the class's robot with a camera")
        return tape_track(world.scene, str(world.path)), lookahead
    return None


def run_json(result: Result, task: str | None) -> str:
    doc = {"ok": result.ok, "task": task, "findings": [f.to_dict() for f in result.sorted_findings()],
           "metrics": _clean(result.metrics), "robot": result.robot,
           "spawn": [round(v, 4) for v in result.spawn] if result.spawn else None}
    return json.dumps(doc, indent=2, allow_nan=False, ensure_ascii=False) + "\n"


def _m(value, unit: str = " m") -> str:
    if value is None:
        return "–"
    return f"{value:.2f}{unit}" if math.isfinite(value) else "inf"


def run_text(result: Result, task: str | None, nodes: list[str]) -> str:
    m = result.metrics
    x, y, yaw = result.spawn
    lines = [f"{', '.join(nodes)} on {result.robot} at ({x:g}, {y:g}, {yaw:g}) {result.spawn_source} in {result.path}"]
    rtf = m.get("real_time_factor")
    lines.append(f"  {_m(m.get('sim_time_s'), ' s')} simulated" + (f" at {rtf:.1f}x real time" if rtf else ""))
    pose = m.get("final_pose")
    lines.append(f"  cmd_vel messages {m.get('cmd_vel_messages', 0)}; path {_m(m.get('path_length_m'))}; rotation "
                 f"{_m(m.get('rotation_rad'), ' rad')}; final pose "
                 + (f"({pose[0]:.2f}, {pose[1]:.2f}, {pose[2]:.2f})" if pose else "–"))
    contacts = m.get("contacts") or []
    lines.append(f"  front distance {_m(m.get('final_front_distance_m'))}; min clearance "
                 f"{_m(m.get('min_clearance_m'))}; contacts " +
                 (f"{len(contacts)} (first: {contacts[0]['shape']} at t = {contacts[0]['time']:.1f} s)"
                  if contacts else "none"))
    for ns, r in sorted((m.get("robots") or {}).items()):
        pose = r.get("final_pose")
        lines.append(f"  robot {ns}{' (graded)' if ns == m.get('graded_robot') else ''}: cmd_vel messages "
                     f"{r.get('cmd_vel_messages', 0)}; path {_m(r.get('path_length_m'))}; final pose "
                     + (f"({pose[0]:.2f}, {pose[1]:.2f}, {pose[2]:.2f})" if pose else "–")
                     + f"; contacts {len(r.get('contacts') or [])}")
    if task == "line-follow" and m.get("share_on_line") is not None:
        lines.append(f"  on the tape {m['share_on_line']:.0%} of the time (the camera's floor point, "
                     f"{m['camera_floor_distance_m']:.2f} m ahead, within 0.1 m of its centre-line); "
                     f"{m['laps']:.2f} laps of the {m['tape_length_m']:.2f} m tape")
    for f in result.sorted_findings():
        lines.append(f"  {f.severity:<7} {f.check}: {f.message}")
        if f.where:
            lines.append(f"          where: {f.where}")
        if f.fix:
            lines.append(f"          fix: {f.fix}")
    verdict = "PASS" if result.ok else "FAIL"
    lines.append(f"{task or 'run'}: {verdict}")
    return "\n".join(lines) + "\n"


def _within(where: str | None, submission: str) -> str:
    """A finding's place (``path:line``) as the submission's row shows it: relative to the submission's folder
    (empty when it is the submission itself, or none is known)."""
    folder = submission.rstrip("/") + "/"
    if not where or where.rstrip("/") + "/" == folder:
        return ""
    return where[len(folder):] if where.startswith(folder) else where


def folder_text(results: list[Result]) -> str:
    """One line per submission (verdict, node, the numbers that matter), its error findings below it."""
    rows = [["submission", "verdict", "node", "front", "path", "turned", "contacts"]]
    for r in results:
        m = r.metrics
        rows.append([r.path, "ok" if r.ok else "FAIL", m.get("node", "–"), _m(m.get("final_front_distance_m")),
                     _m(m.get("path_length_m")),
                     "–" if m.get("rotation_rad") is None else f"{m['rotation_rad'] / math.tau:+.2f} turns",
                     str(len(m.get("contacts") or []))])
    widths = [max(len(row[i]) for row in rows) for i in range(len(rows[0]))]
    lines = []
    for i, row in enumerate(rows):
        lines.append("  ".join(c.ljust(w) for c, w in zip(row, widths)).rstrip())
        if i:
            r = results[i - 1]
            for f in r.sorted_findings():
                if f.severity == "error":
                    place = _within(f.where, r.path)
                    lines.append(f"    {f.check}: {f.message}" + (f" ({place})" if place else ""))
    failed = sum(not r.ok for r in results)
    lines.append(f"{len(results)} submission(s): {len(results) - failed} passed, {failed} failed")
    return "\n".join(lines) + "\n"
