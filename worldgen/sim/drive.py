"""The wheel commands of gazebo_ros_diff_drive, without the simulator.

At each update (``update_rate`` Hz, 30 for TurtleBot3) the last ``cmd_vel`` (v, ω) becomes target rim speeds
``v ∓ ω·separation/2`` (left, right), which the plugin compares with the wheels' measured rim speeds:

* when ``acceleration`` is 0, or *either* wheel is within 0.01 m/s of its target, both wheels get their targets
  at once;
* otherwise each wheel's ramped speed moves by the gap between its target and its *measured* speed, at most
  ``acceleration·dt`` (1 m/s² for TurtleBot3), and the wheels get the ramped speeds.

The ramped speeds are the plugin's own state: the direct settings of the first case leave them where they were,
so after a run of small command changes (each taken at once) a large change ramps from the stale value
(gazebo_ros_pkgs issue #1007): a P controller's stop can lurch, and a forward command after
such a turn veers. Kept, because a student's node meets it in Gazebo too; the exercises start from a synced
ramp (:meth:`Session.start_exercise`). The wheel joints get ``rim speed / radius`` as a velocity-motor target,
with the wheel torque as the force limit. There is no command timeout: the last command holds.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from ..robots.profile import DriveParams

SNAP = 0.01  # m/s: either wheel closer than this to its target, the plugin sets both targets directly


@dataclass
class DiffDrive:
    params: DriveParams
    command: tuple[float, float] = (0.0, 0.0)                        # cmd_vel (v m/s, ω rad/s)
    ramped: list[float] = field(default_factory=lambda: [0.0, 0.0])  # the plugin's wheel_speed_instr_, m/s

    def targets(self) -> tuple[float, float]:
        v, omega = self.command
        half = omega * self.params.wheel_separation / 2
        return v - half, v + half

    def update(self, dt: float, current: tuple[float, float]) -> tuple[float, float]:
        """One plugin update ``dt`` seconds after the last, with the wheels' measured rim speeds ``current``
        (left, right; m/s); returns the wheel joint speeds (left, right) to command, in rad/s."""
        targets = self.targets()
        if self.params.acceleration <= 0 or any(abs(t - c) < SNAP for t, c in zip(targets, current)):
            rims = targets
        else:
            step = self.params.acceleration * dt
            for i, (target, now) in enumerate(zip(targets, current)):
                self.ramped[i] += max(-step, min(step, target - now))
            rims = tuple(self.ramped)
        return rims[0] / self.params.wheel_radius, rims[1] / self.params.wheel_radius
