"""A skid steer as Gazebo's ``libgazebo_ros_skid_steer_drive`` drives it: on every control
tick, each side's two wheels get the rim speed ``linear -/+ angular * separation / 2`` (left /
right, m/s) over the wheel radius, with no ramp; the command is kept until the next (no
timeout). Units: m, s, rad; wheel speeds in rad/s.
"""
from typing import Tuple

from .diff_drive import wheel_rim_speeds

# The order of the plugin's joints: left front, right front, left rear, right rear.
SIDES = (0, 1, 0, 1)   # 0: left, 1: right


def wheel_speeds(linear: float, angular: float, separation: float,
                 radius: float) -> Tuple[float, float, float, float]:
    """(left front, right front, left rear, right rear) joint speeds in rad/s for a body twist
    (linear m/s along x, angular rad/s about z)."""
    left, right = wheel_rim_speeds(linear, angular, separation)
    return tuple((left, right)[side] / radius for side in SIDES)


class SkidSteerController:
    """The latest command as (left, right) wheel joint speeds (rad/s), with no ramp."""

    def __init__(self, separation: float, radius: float):
        self.separation = separation
        self.radius = radius
        self.reset()

    def reset(self) -> None:
        """Stop: zero command."""
        self._command = (0.0, 0.0)

    def set_command(self, linear: float, angular: float) -> None:
        """New body command (m/s, rad/s; already sanitized), kept until the next one."""
        self._command = (linear, angular)

    @property
    def stopped(self) -> bool:
        """Commanded to stand still."""
        return self._command == (0.0, 0.0)

    def update(self, dt: float) -> Tuple[float, float]:
        """One control tick of ``dt`` s: (left, right) joint speeds in rad/s, each for both
        wheels of its side."""
        left, right = wheel_rim_speeds(*self._command, self.separation)
        return left / self.radius, right / self.radius
