"""The rays of a ``<sensor type="ray">`` as Gazebo's MultiRayShape casts them, and the ranges it
reads from them (RaySensor's LaserShape()->GetRange), for the plugins that read every ray
(range_sensor, block_laser). No ROS, no pybullet.

Ray (i, j) of ``samples`` x ``vertical_samples`` is index i + j * samples; it points along the
sensor's x turned by yaw min_angle + i * (max - min) / (samples - 1) about z and pitched up by
vertical_min_angle + j * (...) (one sample: angle 0), and runs from range_min to range_max
(m). Its range is range_min plus the distance from its start to the first surface, range_max
where it meets none: a surface nearer than range_min is not seen. Sensor frame: x forward,
z up; angles in rad.
"""
import math
from typing import List

import numpy as np

from ..files.plugins.sensor_types import RayScan


def _angles(count: int, low: float, high: float) -> List[float]:
    if count == 1:
        return [0.0]
    return [i * (high - low) / (count - 1) + low for i in range(count)]


def ray_grid(rays: RayScan) -> np.ndarray:
    """Unit vectors (vertical_samples * samples, 3) of every ray in the sensor frame, Gazebo's
    order. Python's math makes them (numpy's vectorised sin and cos differ in the last bit
    between versions), as lidar.ray_directions."""
    yaws = _angles(rays.samples, rays.min_angle, rays.max_angle)
    pitches = _angles(rays.vertical_samples, rays.vertical_min_angle, rays.vertical_max_angle)
    return np.array([(math.cos(p) * math.cos(y), math.cos(p) * math.sin(y), math.sin(p))
                     for p in pitches for y in yaws])


def gazebo_ranges(rays: RayScan, distances: np.ndarray) -> np.ndarray:
    """Each ray's range (m, float64) from the ``distances`` (m) between its start, range_min
    out, and the first surface it meets (inf where none within range_max - range_min)."""
    d = np.asarray(distances, dtype=np.float64)
    out = rays.range_min + d
    out[~np.isfinite(d)] = rays.range_max
    return out
