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
MAX_POSES = 6001     # 10 minutes at POSE_RATE, both ends
MAX_SCANS = 301      # a minute at SCAN_RATE, both ends


def _r(value, digits: int = 3):
    if value is None:
        return None
    value = float(value)
    return round(value, digits) + 0.0 if math.isfinite(value) else None


def thin(times: list[float], rate: float, limit: int) -> list[int]:
    """Indices of ``times`` (sorted) for at most ``rate`` a second and ``limit`` in all: the sample nearest each
    tick of a grid (``1/rate`` apart, or wider so that ``limit`` ticks span the run), and the last sample.
    Rounding to the nearest tick, not flooring, keeps a sensor's own rate through its jitter."""
    if not times:
        return []
    limit = max(2, limit)
    t0, span = times[0], times[-1] - times[0]
    step = max(1.0 / rate, span / (limit - 1))
    kept, tick, best = [], 0, 0   # best: the sample nearest the current tick so far
    for i, t in enumerate(times):
        nearest = math.floor((t - t0) / step + 0.5)
        if nearest != tick:
            kept.append(best)
            tick, best = nearest, i
        elif abs(t - t0 - tick * step) < abs(times[best] - t0 - tick * step):
            best = i
    kept.append(best)
    if kept[-1] != len(times) - 1:
        if len(kept) < limit:
            kept.append(len(times) - 1)
        else:
            kept[-1] = len(times) - 1
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
    omega = series.get("w_cmd") or [0.0] * len(times)
    out = {"t": [_r(times[i]) for i in keep], "x": [_r(series["x"][i]) for i in keep],
           "y": [_r(series["y"][i]) for i in keep], "yaw": [_r(series["yaw"][i], 4) for i in keep],
           "v": [_r(command[i]) for i in keep], "w": [_r(omega[i]) for i in keep], "d": [_r(front[i]) for i in keep]}
    odom = [[times[i], series["x"][i], series["y"][i]] for i in range(len(times))]
    start = chosen.get("start_t", 0.0)   # contacts carry the session's time, the series the exercise's
    out["contacts"] = contacts([dict(c, time=c["time"] - start) for c in chosen.get("contacts") or []], odom)
    rows = [[times[i], *row[:3], row[3]] for i, row in enumerate(series.get("scan") or []) if row is not None]
    scan = scans_data(result.get("lidar"), rows)
    if scan is not None:
        out["scans"] = scan
    return out
