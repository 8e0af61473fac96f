"""What the robot did, from the simulator node's trace (:func:`.node.finish` writes it): the numbers
``worldgen run`` reports and the rubrics judge.

The trace holds ``odom`` rows ``[t, x, y, yaw, v, ω, cmd_v, cmd_ω]`` at the drive's 30 Hz, ``scans`` rows
``[t, front, front_cone, nearest, clearance]`` at 5 Hz (true distances from ``base_scan``: the front beam, the
nearest within ±10° of ahead, the nearest of all beams; and the robot's clearance from any shape), ``cmd`` rows
``[t, v, ω]`` per ``/cmd_vel`` message, ``person`` rows ``[t, x, y]``, the contacts and the timing. The front
distance reported and graded is the cone's, the class's stop-at-wall law's own (the front beam alone overstates
the distance to a wall met at an angle: the course's node stopped 0.52 m from one was graded 0.60 m).
"""

from __future__ import annotations

import math


def path_length(odom: list[list[float]]) -> float:
    return sum(math.hypot(b[1] - a[1], b[2] - a[2]) for a, b in zip(odom, odom[1:]))


def rotation(odom: list[list[float]]) -> float:
    """Signed yaw turned in total (rad): the sum of each step's wrapped change."""
    return sum(math.remainder(b[3] - a[3], math.tau) for a, b in zip(odom, odom[1:]))


def last_value(rows: list[list], column: int):
    return rows[-1][column] if rows else None


def compute(trace: dict) -> dict:
    """The metrics of one run (see the module docstring)."""
    odom, scans = trace.get("odom", []), trace.get("scans", [])
    timing = trace.get("timing") or {}
    final = odom[-1] if odom else None
    clearances = [row[4] for row in scans if row[4] is not None]
    cmds = trace.get("cmd", [])
    return {
        "cmd_vel_messages": trace.get("cmd_vel_messages", 0),
        "first_cmd_vel_s": cmds[0][0] if cmds else None,
        "path_length_m": path_length(odom),
        "rotation_rad": rotation(odom),
        "final_pose": [final[1], final[2], final[3]] if final else None,
        "final_speed_mps": final[4] if final else None,
        "final_front_distance_m": last_value(scans, 2),   # as the class's node measures it: nearest within ±10°
        "min_clearance_m": min(clearances) if clearances else None,
        "contacts": [{"link": c["link"], "shape": c["shape"], "time": c["time"]} for c in trace.get("contacts", [])],
        "sim_time_s": timing.get("sim_time_s"),
        "real_time_factor": timing.get("real_time_factor"),
    }


def stopped(odom: list[list[float]], seconds: float = 1.0, speed: float = 0.02) -> bool:
    """Slower than ``speed`` (m/s, and 0.1 rad/s) through the last ``seconds``."""
    if not odom:
        return False
    end = odom[-1][0]
    last = [row for row in odom if row[0] >= end - seconds]
    return all(abs(row[4]) < speed and abs(row[5]) < 0.1 for row in last)
