"""What stop_at_obstacle and wander command after each laser scan (no ROS here).

``update(scan)`` takes a LaserScan-like scan (see scan_reading) and returns (linear m/s along +x,
angular rad/s counter-clockwise), REP 103. Distances are measured from the lidar (``base_scan``),
in metres; the front sector is +-``sector`` rad around straight ahead.
"""
import math
from typing import Optional, Tuple

import numpy as np

from ..robot_models import MODELS
from .scan_reading import bearings, more_open_side, nearest_in_sector, obstacle_ranges


class StopAtObstacle:
    """Drive forward at ``speed`` (m/s) until the nearest obstacle in the front sector is under
    ``stop_distance`` (m), then rest until it is at least ``stop_distance + clear_margin``.

    The margin keeps sensor noise (sigma 0.01 m in Gazebo) from making it creep on in steps.
    No valid reading in the sector means nothing within range_max: the way is clear.
    """

    def __init__(self, speed: float = 0.15, stop_distance: float = 0.5,
                 sector: float = math.radians(15.0), clear_margin: float = 0.05):
        self.speed = speed
        self.stop_distance = stop_distance
        self.sector = sector
        self.clear_margin = clear_margin
        self.stopped = False
        self.front: Optional[float] = None  # m, nearest obstacle in the sector at the last scan

    def update(self, scan) -> Tuple[float, float]:
        """The command for this scan."""
        self.front = nearest_in_sector(scan, self.sector)
        if self.stopped:
            self.stopped = self.front is not None and \
                self.front < self.stop_distance + self.clear_margin
        else:
            self.stopped = self.front is not None and self.front < self.stop_distance
        return (0.0, 0.0) if self.stopped else (self.speed, 0.0)


FORWARD = "forward"
TURN_LEFT = "turning left"
TURN_RIGHT = "turning right"


class Wander:
    """The wander-bot made right for a TurtleBot3.

    Drive forward at ``speed`` (m/s) until something is under ``stop_distance`` (m) ahead, then
    turn in place at ``turn_speed`` (rad/s) toward the more open side, keeping that direction,
    until the way ahead is at least ``stop_distance + clear_margin``; then forward again.

    "Ahead" is the front sector (+-``sector`` rad) plus the corridor the robot drives through:
    the points in front of the lidar closer than ``robot_radius`` (m) to its line of travel.
    Keeping that corridor clear keeps everything at least ``robot_radius`` from the turning
    centre, so turning in place never touches anything either. It never drives forward while
    anything is under ``stop_distance`` ahead, and never drives backwards.
    """

    def __init__(self, speed: float = 0.2, turn_speed: float = 1.0, stop_distance: float = 0.5,
                 sector: float = math.radians(15.0), clear_margin: float = 0.1,
                 robot_radius: float = MODELS["burger"].turn_radius):
        self.speed = speed
        self.turn_speed = turn_speed
        self.stop_distance = stop_distance
        self.sector = sector
        self.clear_margin = clear_margin
        self.robot_radius = robot_radius
        self.state = FORWARD
        self.front = math.inf  # m, distance to the nearest thing ahead at the last scan

    def distance_ahead(self, scan) -> float:
        """Distance (m) to the nearest thing ahead: the nearest obstacle in the front sector, or
        the forward distance to one in the corridor if that is less; inf if there is none."""
        in_sector = nearest_in_sector(scan, self.sector)
        ranges = obstacle_ranges(scan)
        seen = np.isfinite(ranges)
        rays = bearings(scan)[seen]
        x = ranges[seen] * np.cos(rays)
        y = ranges[seen] * np.sin(rays)
        corridor = x[(x > 0.0) & (np.abs(y) < self.robot_radius)]
        nearest = math.inf if in_sector is None else in_sector
        return min(nearest, float(corridor.min())) if corridor.size else nearest

    def update(self, scan) -> Tuple[float, float]:
        """The command for this scan."""
        self.front = self.distance_ahead(scan)
        if self.state == FORWARD and self.front < self.stop_distance:
            self.state = TURN_LEFT if more_open_side(scan) == "left" else TURN_RIGHT
        elif self.state != FORWARD and self.front >= self.stop_distance + self.clear_margin:
            self.state = FORWARD
        if self.state == FORWARD:
            return self.speed, 0.0
        return 0.0, self.turn_speed if self.state == TURN_LEFT else -self.turn_speed
