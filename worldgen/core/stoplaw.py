"""The stop-at-wall control law, shared by ``worldgen drive`` (and validate's stop check) and the generated
``stop_at_wall.py`` node (``templates/nodes/stop_at_wall.py.j2`` writes the same law out for rospy): the same
target, gains, rate, front cone, stop band and speed clamp give the same commands.

Once per LiDAR scan (5 Hz on a TurtleBot3), with ``front`` the nearest valid reading within ±front_angle of
straight ahead (None when nothing is seen there):

* nothing seen ahead: drive at ``max_speed``; the PID memory is cleared;
* holding (stopped at the wall): speed 0 until ``front`` grows beyond ``target + stop_band + RESUME_MARGIN``
  (the wall moved away, or the robot was carried off), so LiDAR noise near the target cannot start it again;
* ``front ≤ target + stop_band``: stop and hold;
* else ``v = kp·e + ki·∫e dt + kd·de/dt`` with ``e = front − target``, clamped to ``[0, max_speed]``: the robot
  never reverses. The integral and derivative start from the second scan (``dt`` is the time between scans).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Optional

# The class's defaults, written into the generated node and used by ``worldgen drive``.
TARGET = 0.5           # m from the wall ahead
KP = 0.5               # (m/s) per metre of error
MAX_SPEED = 0.22       # m/s: the burger's top speed
FRONT_ANGLE = 10.0     # degrees either side of straight ahead
STOP_BAND = 0.01       # m: stop once the front distance is within this of the target (or closer)
RESUME_MARGIN = 0.1    # m beyond the stop band before a holding robot drives again


@dataclass
class StopLaw:
    """The law's parameters and its memory (holding, integral, last error); :meth:`step` once per scan."""

    target: float = TARGET
    kp: float = KP
    ki: float = 0.0
    kd: float = 0.0
    max_speed: float = MAX_SPEED
    stop_band: float = STOP_BAND
    holding: bool = False
    integral: float = 0.0
    last_error: Optional[float] = None

    def step(self, front: Optional[float], dt: float) -> float:
        """The forward speed (m/s, ≥ 0) for a scan whose front distance is ``front`` (None: nothing seen),
        ``dt`` seconds after the previous scan."""
        if front is None:
            self.holding, self.integral, self.last_error = False, 0.0, None
            return self.max_speed
        error = front - self.target
        if self.holding and error <= self.stop_band + RESUME_MARGIN:
            return 0.0
        if error <= self.stop_band:
            self.holding, self.integral, self.last_error = True, 0.0, None
            return 0.0
        self.holding = False
        derivative = 0.0
        if self.last_error is not None and dt > 0:
            self.integral += error * dt
            derivative = (error - self.last_error) / dt
        self.last_error = error
        command = self.kp * error + self.ki * self.integral + self.kd * derivative
        return min(self.max_speed, max(0.0, command))
