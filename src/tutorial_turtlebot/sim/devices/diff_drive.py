"""Differential drive as Gazebo's ``libgazebo_ros_diff_drive`` does it (doc/turtlebot3.md 2.1).

A command (linear.x m/s, angular.z rad/s) becomes rim speeds ``v -/+ w * separation / 2`` for the
left/right wheel; on every control tick each rim speed moves toward its target by at most
``acceleration * dt``, and both jump to the target once either wheel is within 0.01 m/s of it.
Units: m, s, rad; wheel speeds are returned in rad/s (rim speed / radius).
"""
import math
from typing import List, Tuple

# Beyond these no real command makes sense; with the model clamp off, commands are still held
# inside them so the physics cannot explode (m/s, rad/s).
SAFE_LINEAR = 2.0
SAFE_ANGULAR = 20.0
SNAP_TOLERANCE = 0.01  # m/s: Gazebo's "close enough, jump to the target"


def sanitize_command(linear: float, angular: float, max_linear: float,
                     max_angular: float) -> Tuple[float, float, List[str]]:
    """Return (linear, angular, problems): NaN or infinite fields raise ValueError, values beyond
    the given limits are clamped to them and named in ``problems`` (for a warning)."""
    if not (math.isfinite(linear) and math.isfinite(angular)):
        raise ValueError("cmd_vel has a NaN or infinite field (linear.x=%r, angular.z=%r)"
                         % (linear, angular))
    problems = []
    if abs(linear) > max_linear:
        problems.append("linear.x %.3g m/s clamped to +-%.3g" % (linear, max_linear))
        linear = math.copysign(max_linear, linear)
    if abs(angular) > max_angular:
        problems.append("angular.z %.3g rad/s clamped to +-%.3g" % (angular, max_angular))
        angular = math.copysign(max_angular, angular)
    return linear, angular, problems


def wheel_rim_speeds(linear: float, angular: float, separation: float) -> Tuple[float, float]:
    """(left, right) rim speeds in m/s for a body twist."""
    half = angular * separation / 2.0
    return linear - half, linear + half


def body_twist(left_rim: float, right_rim: float, separation: float) -> Tuple[float, float]:
    """(linear m/s, angular rad/s) of the body from (left, right) rim speeds in m/s."""
    return (left_rim + right_rim) / 2.0, (right_rim - left_rim) / separation


class DiffDriveController:
    """Turns the latest command into wheel joint velocity targets, acceleration-limited."""

    def __init__(self, separation: float, radius: float, acceleration: float):
        self.separation = separation
        self.radius = radius
        self.acceleration = acceleration  # m/s^2 at the rim; <= 0 means no limit
        self.reset()

    def reset(self) -> None:
        """Stop: zero command and zero wheel speeds."""
        self._target = (0.0, 0.0)
        self._rim = [0.0, 0.0]

    def set_command(self, linear: float, angular: float) -> None:
        """New body command (already sanitized), kept until the next one (no timeout, as Gazebo)."""
        self._target = wheel_rim_speeds(linear, angular, self.separation)

    @property
    def stopped(self) -> bool:
        """Commanded to stand still, and the ramp has come down to it."""
        return self._target == (0.0, 0.0) and self._rim == [0.0, 0.0]

    def update(self, dt: float) -> Tuple[float, float]:
        """Advance the ramp by one control tick of ``dt`` s; return (left, right) in rad/s."""
        target = self._target
        if self.acceleration <= 0 or any(abs(t - r) < SNAP_TOLERANCE
                                         for t, r in zip(target, self._rim)):
            self._rim = list(target)
        else:
            step = self.acceleration * dt
            self._rim = [r + max(-step, min(step, t - r)) for t, r in zip(target, self._rim)]
        return self._rim[0] / self.radius, self._rim[1] / self.radius
