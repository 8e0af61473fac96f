"""The class's exercises as rubrics: from a run's trace and metrics, a verdict and findings a student can act on.

==============  ===========================================================================================
stop-at-wall    stopped (slower than 0.02 m/s through the last second), the front beam's true distance within
                ±0.1 m of the target (0.5 m), no contact
spin            at least two full turns, and the centre of each turn within 0.1 m of the first one's
drive-square    four ≈ 90° corners (±20°) between straight sides, the first four sides within 20 % of each
                other, and the end of the fourth side within 0.3 m of where the first began
wall-follow     after first reaching the wall, the nearest wall within target (0.4 m) ± 0.15 m in ≥ 80 % of
                the scans, and at least one room side travelled (the room's shorter side less twice the target)
person-follow   a person-sized cylinder walks a loop ahead of the robot; the robot keeps 0.3–1.2 m from it in
                ≥ 70 % of the time and never touches it
line-follow     the camera's floor point (where the bottom of its image meets the floor ahead) within 0.1 m
                of the tape's centre-line in ≥ 90 % of the time, a full lap of a loop (or the whole of an open
                line) travelled along it, no contact (see :mod:`.track`)
==============  ===========================================================================================
"""

from __future__ import annotations

import math

from ..core.findings import Finding
from .metrics import path_length, stopped
from .track import follow_numbers

TASKS = ("stop-at-wall", "spin", "drive-square", "wall-follow", "person-follow", "line-follow")
DEFAULT_TARGET = {"stop-at-wall": 0.5, "wall-follow": 0.4}
DEFAULT_DURATION = {"stop-at-wall": 20.0, "spin": 30.0, "drive-square": 60.0, "wall-follow": 60.0,
                    "person-follow": 60.0, "line-follow": 120.0}
STOP_TOLERANCE = 0.1
SPIN_TURNS, SPIN_DRIFT = 2, 0.1
CORNER, CORNER_TOLERANCE, SIDE_SPREAD, SQUARE_CLOSE = math.pi / 2, math.radians(20), 0.2, 0.3
WALL_BAND, WALL_SHARE = 0.15, 0.8
PERSON_NEAR, PERSON_FAR, PERSON_SHARE = 0.3, 1.2, 0.7
PERSON = {"radius": 0.2, "height": 1.7, "ahead": 1.4, "loop_radius": 0.6, "speed": 0.1}
LINE_BAND, LINE_SHARE, LINE_LAPS = 0.1, 0.9, 1.0


def person_loop(spawn) -> dict:
    """The scripted person of person-follow: a loop of :data:`PERSON` ``loop_radius`` centred ``ahead`` m in front
    of the spawn pose, walked counter-clockwise at ``speed`` m/s from its point nearest the robot."""
    x, y, yaw = spawn
    centre = [x + PERSON["ahead"] * math.cos(yaw), y + PERSON["ahead"] * math.sin(yaw)]
    return {"centre": centre, "phase": yaw + math.pi, **PERSON}


def judge(task: str, trace: dict, metrics: dict, target: float | None, context=None
          ) -> tuple[list[Finding], dict]:
    """The task's findings (errors fail it) and the numbers it measured. ``context`` is what the task needs of
    the world: wall-follow, the room's shorter side (m); line-follow, the tape (a :class:`~.track.Track`) and the
    camera's floor distance (m), as a pair."""
    target = DEFAULT_TARGET.get(task) if target is None else target
    return {"stop-at-wall": _stop_at_wall, "spin": _spin, "drive-square": _square, "wall-follow": _wall_follow,
            "person-follow": _person_follow, "line-follow": _line_follow}[task](trace, metrics, target, context)


def _contact_findings(task: str, metrics: dict, shape: str | None = None) -> list[Finding]:
    hits = [c for c in metrics.get("contacts", []) if shape is None or c["shape"] == shape]
    if not hits:
        return []
    first = hits[0]
    more = f" (and {len(hits) - 1} more contacts)" if len(hits) > 1 else ""
    return [Finding(task, "error", f"the robot touched {first['shape']} with {first['link']} at "
                                   f"t = {first['time']:.1f} s{more}",
                    fix="slow down earlier, or keep more distance")]


def _stop_at_wall(trace, metrics, target, _side):
    findings = _contact_findings("stop-at-wall", metrics)
    odom = trace.get("odom", [])
    front = metrics.get("final_front_distance_m")
    if not stopped(odom):
        findings.append(Finding("stop-at-wall", "error",
                                f"the robot is still moving at the end ({metrics.get('final_speed_mps') or 0:.2f} m/s)",
                                fix="publish a zero Twist once the target distance is reached"))
    if front is None and (metrics.get("min_clearance_m") or 1.0) < 0.12:
        findings.append(Finding("stop-at-wall", "error", "the robot ended against the wall, closer than the "
                                                         "LiDAR's 0.12 m minimum range",
                                fix="stop at the target distance: treat inf/0 readings as 'nothing seen'"))
    elif front is None:
        findings.append(Finding("stop-at-wall", "error", "no wall ahead within the LiDAR's range at the end",
                                fix="drive towards the wall ahead"))
    elif abs(front - target) > STOP_TOLERANCE:
        side = "short of" if front > target else "past"
        findings.append(Finding("stop-at-wall", "error",
                                f"stopped {front:.2f} m from the wall ahead, {abs(front - target):.2f} m {side} the "
                                f"{target:g} m target (±{STOP_TOLERANCE:g} m)",
                                fix="check the front distance (nearest valid beam ahead) and the stop condition"))
    return findings, {"stop_error_m": None if front is None else front - target}


def _turn_centres(odom) -> list[tuple[float, float]]:
    """The mean position over each complete turn (2π of rotation either way)."""
    centres, xs, ys, turned = [], [], [], 0.0
    for a, b in zip(odom, odom[1:]):
        turned += math.remainder(b[3] - a[3], math.tau)
        xs.append(b[1])
        ys.append(b[2])
        if abs(turned) >= math.tau:
            centres.append((sum(xs) / len(xs), sum(ys) / len(ys)))
            xs, ys, turned = [], [], 0.0
    return centres


def _spin(trace, metrics, _target, _side):
    findings = _contact_findings("spin", metrics)
    turns = abs(metrics.get("rotation_rad") or 0.0) / math.tau
    centres = _turn_centres(trace.get("odom", []))
    drift = max((math.dist(centres[0], c) for c in centres), default=0.0)
    if turns < SPIN_TURNS:
        findings.append(Finding("spin", "error", f"the robot turned {turns:.2f} full turns; {SPIN_TURNS} are needed",
                                fix="publish a Twist with angular.z set, again and again (or once: it holds)"))
    if drift >= SPIN_DRIFT:
        findings.append(Finding("spin", "error", f"the centre of the circles drifted {drift:.2f} m "
                                                 f"(limit {SPIN_DRIFT:g} m)",
                                fix="keep the same linear and angular speed throughout"))
    return findings, {"turns": turns, "centre_drift_m": drift}


def _segments(odom):
    """Straight sides ``(start_row, end_row, length, heading)`` of an odometry trace, heading unwrapped."""
    sides, heading, current = [], 0.0, None
    for a, b in zip(odom, odom[1:]):
        heading += math.remainder(b[3] - a[3], math.tau)
        straight = abs(b[4]) > 0.03 and abs(b[5]) < 0.3
        if straight:
            if current is None:
                current = [a, b, 0.0, heading]
            current[1] = b
            current[2] += math.hypot(b[1] - a[1], b[2] - a[2])
            current[3] = heading
        elif current is not None:
            sides.append(current)
            current = None
    if current is not None:
        sides.append(current)
    merged = []
    for side in (s for s in sides if s[2] >= 0.15):
        if merged and abs(side[3] - merged[-1][3]) < math.radians(15):   # a wobble, not a corner
            merged[-1] = [merged[-1][0], side[1], merged[-1][2] + side[2], side[3]]
        else:
            merged.append(side)
    return merged, heading


def _square(trace, metrics, _target, _side):
    findings = _contact_findings("drive-square", metrics)
    sides, final_heading = _segments(trace.get("odom", []))
    corners = [b[3] - a[3] for a, b in zip(sides, sides[1:])]
    if len(sides) == 4 and abs(final_heading - sides[-1][3]) > math.radians(45):
        corners.append(final_heading - sides[-1][3])   # the turn back to the first heading
    lengths = [s[2] for s in sides[:4]]
    numbers = {"sides_m": lengths, "corners_deg": [math.degrees(c) for c in corners[:4]]}
    if len(sides) < 4:
        findings.append(Finding("drive-square", "error", f"found {len(sides)} straight sides; a square has 4",
                                fix="drive a side, turn 90°, four times"))
        return findings, numbers
    bad = [math.degrees(c) for c in corners[:4] if abs(abs(c) - CORNER) > CORNER_TOLERANCE]
    if len(corners) < 4 or bad:
        findings.append(Finding("drive-square", "error",
                                f"corners of {', '.join(f'{math.degrees(c):.0f}°' for c in corners[:4])}; four of "
                                f"90° ± {math.degrees(CORNER_TOLERANCE):.0f}° are needed",
                                fix="turn by 90° (π/2 rad) at each corner: measure the turn with /odom"))
    spread = (max(lengths) - min(lengths)) / max(lengths)
    if spread > SIDE_SPREAD:
        findings.append(Finding("drive-square", "error",
                                f"sides of {', '.join(f'{v:.2f}' for v in lengths)} m differ by {spread:.0%} "
                                f"(at most {SIDE_SPREAD:.0%})", fix="drive the same distance on every side"))
    start, end = sides[0][0], sides[3][1]
    gap = math.hypot(end[1] - start[1], end[2] - start[2])
    numbers["closing_gap_m"] = gap
    if gap > SQUARE_CLOSE:
        findings.append(Finding("drive-square", "error", f"the square ends {gap:.2f} m from where it began "
                                                         f"(at most {SQUARE_CLOSE:g} m)",
                                fix="equal sides and 90° corners close the square"))
    return findings, numbers


def _wall_follow(trace, metrics, target, room_side):
    findings = _contact_findings("wall-follow", metrics)
    scans = [row for row in trace.get("scans", []) if row[3] is not None]
    reached = next((i for i, row in enumerate(scans) if row[3] <= target + WALL_BAND), None)
    if reached is None:
        findings.append(Finding("wall-follow", "error", f"the robot never came within {target + WALL_BAND:.2f} m "
                                                        "of a wall", fix="drive to a wall first"))
        return findings, {"share_in_band": 0.0}
    after = scans[reached:]
    share = sum(abs(row[3] - target) <= WALL_BAND for row in after) / len(after)
    t0 = after[0][0]
    odom = [row for row in trace.get("odom", []) if row[0] >= t0]

    travelled = path_length(odom)
    need = max(0.5, (room_side or 2.0 + 2 * target) - 2 * target)
    if share < WALL_SHARE:
        findings.append(Finding("wall-follow", "error",
                                f"the nearest wall was {target:g} ± {WALL_BAND:g} m away in {share:.0%} of the time "
                                f"after reaching it (at least {WALL_SHARE:.0%} needed)",
                                fix="steer on the distance to the wall beside the robot"))
    if travelled < need:
        findings.append(Finding("wall-follow", "error",
                                f"the robot travelled {travelled:.2f} m along the walls; one room side is "
                                f"{need:.2f} m", fix="keep moving forward while following the wall"))
    return findings, {"share_in_band": share, "travelled_m": travelled, "room_side_m": need}


def _person_follow(trace, metrics, _target, _side):
    findings = _contact_findings("person-follow", metrics, shape="person")
    odom, people = trace.get("odom", []), trace.get("person", [])
    pairs = list(zip(odom, people))
    distances = [math.hypot(o[1] - p[1], o[2] - p[2]) - PERSON["radius"] for o, p in pairs]
    share = sum(PERSON_NEAR <= d <= PERSON_FAR for d in distances) / len(distances) if distances else 0.0
    if share < PERSON_SHARE:
        findings.append(Finding("person-follow", "error",
                                f"the robot was {PERSON_NEAR:g}–{PERSON_FAR:g} m from the person in {share:.0%} of "
                                f"the time (at least {PERSON_SHARE:.0%} needed)",
                                fix="turn towards the nearest object in the scan and close the distance to it"))
    return findings, {"share_in_range": share, "min_person_distance_m": min(distances, default=None)}


def _line_follow(trace, metrics, _target, context):
    track, lookahead = context
    findings = _contact_findings("line-follow", metrics)
    numbers = follow_numbers(track, trace.get("odom", []), lookahead, LINE_BAND)
    numbers["camera_floor_distance_m"] = lookahead
    share, laps, covered = numbers["share_on_line"], numbers["laps"], numbers["covered"]
    lost = abs(metrics.get("rotation_rad") or 0.0) > math.tau and (metrics.get("path_length_m") or 0.0) < 1.0
    if share < LINE_SHARE:
        findings.append(Finding("line-follow", "error",
                                f"the camera's floor point ({lookahead:.2f} m ahead) was within {LINE_BAND:g} m of "
                                f"the tape ({track.name}) in {share:.0%} of the time (at least {LINE_SHARE:.0%} "
                                "needed)" + ("; the robot mostly turned in place, as a node that never sees the "
                                             "line does" if lost else ""),
                                fix="mask the tape's colour in HSV (check the range on a camera image: yellow tape "
                                    "has a hue near 30 in OpenCV) and turn towards the mask's centroid"))
    if track.loop and laps < LINE_LAPS:
        findings.append(Finding("line-follow", "error", f"the robot went {laps:.0%} of the way round the loop along "
                                                        "the tape; a full lap is needed",
                                fix="keep moving forward while steering on the line (or run longer: --duration)"))
    elif not track.loop and covered < LINE_SHARE:
        findings.append(Finding("line-follow", "error", f"the robot followed {covered:.0%} of the line; at least "
                                                        f"{LINE_SHARE:.0%} is needed",
                                fix="keep moving forward while steering on the line"))
    return findings, numbers
