"""A run, thinned to what the eye needs, for the 3D page's replay: the pose over time (at most
:data:`POSE_RATE` a second), what was commanded on ``cmd_vel``, the distance to the wall ahead, the contacts, and the
LiDAR scans (at most :data:`SCAN_RATE` a second, ranges in centimetres).

Two sources: ``worldgen run``'s trace (the graded robot's rows: ``odom`` ``[t, x, y, yaw, v, ω, cmd_v, cmd_ω]``,
``scans`` ``[t, range0, front, nearest, clearance]``, ``contacts``, and with scans recorded ``lidar`` and
``ranges`` ``[t, ox, oy, yaw, [mm…]]``), and one run of ``worldgen drive`` (its ``series``). Long runs are thinned
further so that a page stays under :data:`MAX_POSES` poses and :data:`MAX_SCANS` scans (an hour-long run is still a
page of a few megabytes).
"""

from __future__ import annotations

import math

POSE_RATE = 10.0     # poses a second: smooth at 16×, with the page interpolating between them
SCAN_RATE = 5.0      # scans a second: the LDS-01's own rate
MAX_POSES = 6000     # 10 minutes at POSE_RATE
MAX_SCANS = 300      # 60 s at SCAN_RATE


def _r(value, digits: int = 3):
    if value is None:
        return None
    value = float(value)
    return round(value, digits) + 0.0 if math.isfinite(value) else None


def thin(times: list[float], rate: float, limit: int) -> list[int]:
    """Indices of ``times`` (sorted) at most ``rate`` a second and ``limit`` in all, the first and last kept."""
    if not times:
        return []
    span = times[-1] - times[0]
    step = max(1.0 / rate, span / max(1, limit))
    kept, last = [0], times[0]
    for i in range(1, len(times) - 1):
        if times[i] - last >= step - 1e-9:
            kept.append(i)
            last = times[i]
    if len(times) > 1:
        kept.append(len(times) - 1)
    return kept


def _latest(rows: list, t: float, start: int) -> int:
    """The index of the last row of ``rows`` (by their t, row[0]) at or before ``t``, searching from ``start``."""
    i = start
    while i + 1 < len(rows) and rows[i + 1][0] <= t + 1e-9:
        i += 1
    return i


def scans_data(lidar: dict | None, rows: list) -> dict | None:
    """Scan rows ``[t, ox, oy, yaw, [mm…]]`` thinned, ranges in cm (−1: no hit)."""
    if not lidar or not rows:
        return None
    keep = thin([row[0] for row in rows], SCAN_RATE, MAX_SCANS)
    return {"min": _r(lidar["angle_min"], 5), "inc": _r(lidar["angle_increment"], 6), "max": _r(lidar["range_max"]),
            "t": [_r(rows[i][0]) for i in keep], "o": [[_r(v, 4) for v in rows[i][1:4]] for i in keep],
            "r": [[(mm + 5) // 10 if mm >= 0 else -1 for mm in rows[i][4]] for i in keep]}


def run_replay(trace: dict) -> dict:
    """The replay of ``worldgen run``'s trace (the graded robot)."""
    odom = trace.get("odom") or []
    scans = trace.get("scans") or []
    keep = thin([row[0] for row in odom], POSE_RATE, MAX_POSES)
    out = {"t": [], "x": [], "y": [], "yaw": [], "v": [], "w": [], "d": []}
    j = -1
    for i in keep:
        t, x, y, yaw, _, _, cmd_v, cmd_w = odom[i][:8]
        j = _latest(scans, t, j)
        front = scans[j][2] if 0 <= j < len(scans) and scans[j][0] <= t + 1e-9 else None
        for key, value, digits in (("t", t, 3), ("x", x, 3), ("y", y, 3), ("yaw", yaw, 4), ("v", cmd_v, 3),
                                   ("w", cmd_w, 3), ("d", front, 3)):
            out[key].append(_r(value, digits))
    out["contacts"] = contacts(trace.get("contacts") or [], odom)
    scan = scans_data(trace.get("lidar"), trace.get("ranges") or [])
    if scan is not None:
        out["scans"] = scan
    return out


def contacts(found: list[dict], odom: list) -> list[dict]:
    """Each contact at the robot's pose when it began (``n`` names what was touched)."""
    out = []
    for contact in found:
        t = float(contact.get("time", 0.0))
        row = min(odom, key=lambda r: abs(r[0] - t)) if odom else None
        if row is None:
            continue
        what = contact.get("shape") or ""
        out.append({"t": _r(t), "x": _r(row[1]), "y": _r(row[2]), "n": what})
    return out


def drive_replay(result: dict, run: int = 0) -> dict:
    """The replay of one run of ``worldgen drive`` (its ``series`` with x, y, yaw, and scans when recorded)."""
    chosen = result["runs"][run]
    series = chosen["series"]
    times = series["t"]
    keep = thin(times, POSE_RATE, MAX_POSES)
    front = series.get("true") or [None] * len(times)
    command = series.get("v_cmd") or [0.0] * len(times)
    omega = chosen.get("omega") if result.get("behaviour") == "spin" else 0.0
    out = {"t": [_r(times[i]) for i in keep], "x": [_r(series["x"][i]) for i in keep],
           "y": [_r(series["y"][i]) for i in keep], "yaw": [_r(series["yaw"][i], 4) for i in keep],
           "v": [_r(command[i]) for i in keep], "w": [_r(omega) for _ in keep], "d": [_r(front[i]) for i in keep]}
    odom = [[times[i], series["x"][i], series["y"][i]] for i in range(len(times))]
    out["contacts"] = contacts(chosen.get("contacts") or [], odom)
    rows = [[times[i], *row[:3], row[3]] for i, row in enumerate(series.get("scan") or []) if row is not None]
    scan = scans_data(result.get("lidar"), rows)
    if scan is not None:
        out["scans"] = scan
    return out
