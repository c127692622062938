"""Odometry integrated from wheel joint angles, as the real TurtleBot3's OpenCR does it.

Starts at (0, 0, 0) in ``odom`` and drifts with wheel slip. Units: m, rad, s.
"""
import math
from typing import Optional, Tuple

from .diff_drive import body_twist


class WheelOdometry:
    """Dead reckoning of ``base_footprint`` in ``odom`` from (left, right) wheel angles in rad."""

    def __init__(self, separation: float, radius: float):
        self.separation = separation
        self.radius = radius
        self.reset()

    def reset(self) -> None:
        """Back to the origin; the next update only records the wheel angles."""
        self.x = self.y = self.yaw = 0.0
        self.linear = self.angular = 0.0
        self._last: Optional[Tuple[float, float]] = None

    def update(self, left: float, right: float, dt: float) -> None:
        """Integrate the wheel rotation since the last call, ``dt`` s ago (midpoint rule)."""
        if self._last is not None and dt > 0:
            dl = (left - self._last[0]) * self.radius
            dr = (right - self._last[1]) * self.radius
            ds, dyaw = body_twist(dl, dr, self.separation)
            heading = self.yaw + dyaw / 2.0
            self.x += ds * math.cos(heading)
            self.y += ds * math.sin(heading)
            self.yaw = math.atan2(math.sin(self.yaw + dyaw), math.cos(self.yaw + dyaw))
            self.linear, self.angular = ds / dt, dyaw / dt
        self._last = (left, right)
