"""The wheel commands of gazebo_ros_diff_drive, without the simulator.

At each update (``update_rate`` Hz, 30 for TurtleBot3) the last ``cmd_vel`` (v, ω) becomes target rim speeds
``v ∓ ω·separation/2`` (left, right). The commanded rim speed moves toward the target by at most
``acceleration·dt`` (1 m/s² for TurtleBot3) and jumps to it once within 0.01 m/s; with ``acceleration`` 0 it
jumps at once. The wheel joints then get ``rim speed / radius`` as a velocity-motor target, with the wheel torque
as the force limit. There is no command timeout: the last command holds.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from ..robots.profile import DriveParams

SNAP = 0.01  # m/s: closer than this to the target, the plugin sets the target speed directly


@dataclass
class DiffDrive:
    params: DriveParams
    command: tuple[float, float] = (0.0, 0.0)                    # cmd_vel (v m/s, ω rad/s)
    rim: list[float] = field(default_factory=lambda: [0.0, 0.0])  # commanded rim speeds (left, right), m/s

    def targets(self) -> tuple[float, float]:
        v, omega = self.command
        half = omega * self.params.wheel_separation / 2
        return v - half, v + half

    def update(self, dt: float) -> tuple[float, float]:
        """Advance the ramp by ``dt`` seconds; returns the wheel joint speeds (left, right) in rad/s."""
        step = self.params.acceleration * dt
        for i, target in enumerate(self.targets()):
            gap = target - self.rim[i]
            if self.params.acceleration <= 0 or abs(gap) < SNAP:
                self.rim[i] = target
            else:
                self.rim[i] += max(-step, min(step, gap))
        return self.rim[0] / self.params.wheel_radius, self.rim[1] / self.params.wheel_radius
