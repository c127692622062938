"""A planar move as Gazebo's ``libgazebo_ros_planar_move`` does it: no wheels, the base's velocity
set at every physics step from the command (linear.x, linear.y in the base's heading, m/s;
angular.z rad/s), zeroed once the command is older than the timeout; odometry's twist from the
pose's change between two odometry ticks. Units: m, s, rad; velocities in the world frame unless
named otherwise (REP 103).
"""
import math
from typing import Optional, Tuple


def world_velocity(x: float, y: float, yaw_rate: float,
                   yaw: float) -> Tuple[Tuple[float, float, float], Tuple[float, float, float]]:
    """(linear m/s, angular rad/s) in the world of a base heading ``yaw`` (rad) commanded
    ``x``, ``y`` (m/s in its heading) and ``yaw_rate`` (rad/s); z velocity 0, as Gazebo sets."""
    c, s = math.cos(yaw), math.sin(yaw)
    return (x * c - y * s, y * c + x * s, 0.0), (0.0, 0.0, yaw_rate)


class PlanarMoveController:
    """The latest command, held for ``timeout`` s of sim time (negative: for ever)."""

    def __init__(self, timeout: float = -1.0):
        self.timeout = timeout
        self.reset()

    def reset(self) -> None:
        """Stop: zero command."""
        self._command = (0.0, 0.0, 0.0)
        self._since: Optional[float] = None

    def set_command(self, x: float, y: float, yaw_rate: float, now: float) -> None:
        """New command (m/s, m/s, rad/s in the base frame) at sim time ``now`` (s)."""
        self._command = (x, y, yaw_rate)
        self._since = now

    def command(self, now: float) -> Tuple[float, float, float]:
        """(x, y, yaw rate) to apply at sim time ``now`` (s): zeros past the timeout."""
        if self.timeout >= 0 and self._since is not None and now - self._since > self.timeout:
            return 0.0, 0.0, 0.0
        return self._command


class PoseOdometry:
    """The odometry twist of gazebo_ros_planar_move: the change of the pose since the last
    tick over the time between them, in the base frame (linear) and about z (angular)."""

    def __init__(self):
        self.reset()

    def reset(self) -> None:
        self._last: Optional[Tuple[float, float, float, float]] = None   # x, y, yaw, t
        self.linear = (0.0, 0.0)
        self.angular = 0.0

    def update(self, x: float, y: float, yaw: float, now: float,
               commanded_rate: float = 0.0) -> None:
        """A tick at sim time ``now`` (s) with the base at (x, y, yaw) (m, rad). A yaw rate
        beyond pi per tick cannot be told from the poses: the commanded one is taken."""
        last, self._last = self._last, (x, y, yaw, now)
        if last is None or now <= last[3]:
            return
        dt = now - last[3]
        vx, vy = (x - last[0]) / dt, (y - last[1]) / dt
        c, s = math.cos(yaw), math.sin(yaw)
        self.linear = (c * vx + s * vy, c * vy - s * vx)
        if commanded_rate > math.pi / dt:
            self.angular = commanded_rate
        else:
            turn = math.atan2(math.sin(yaw - last[2]), math.cos(yaw - last[2]))
            self.angular = turn / dt
