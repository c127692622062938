"""What gazebo_ros_block_laser makes of a ray sensor: sensor_msgs/PointCloud's points and its
one channel (PutLaserData), from the ranges of every ray (ray_grid.gazebo_ranges). No ROS, no
pybullet.

(samples x resolution) x (vertical samples x vertical resolution) points, row by row (vertical
index outer), each at the range interpolated between the four rays around it: below range_min
it is -inf, beyond range_max +inf (REP 117; a coordinate whose sine or cosine is 0 is then
NaN), and the point is that range in the sensor frame (x forward, z up; m) along the plugin's
angles: the middle of the reading's two corner rays, so half a ray step beyond its first ray
(the last ray's own angle for the last). A ray that meets nothing reads range_max: its point
lies at range_max, with no noise; every other point gets gaussian noise of the plugin's sigma
on each coordinate. The channel is the rays' retro-reflection (0 here: no laser_retro is
simulated) plus that noise.
"""
import math
from typing import Tuple

import numpy as np

from ..files.plugins.sensor_types import RayScan

AT_MAX_RANGE = 1e-6        # m: a range this close to range_max gets no noise (EPSILON_DIFF)


def _corners(count: int, rays_count: int):
    """For each of ``count`` readings over ``rays_count`` rays: (lower ray, upper ray, fraction
    from the lower), as Gazebo interpolates."""
    b = (np.zeros(count) if count == 1
         else np.arange(count, dtype=np.float64) * (rays_count - 1) / (count - 1))
    low = np.floor(b).astype(int)
    high = np.minimum(low + 1, rays_count - 1)
    return low, high, b - np.floor(b)


def _angle(low, high, rays_count: int, first: float, last: float):
    """The angle (rad) of a reading between rays ``low`` and ``high``: their mean, as the
    plugin computes it (0 for a single ray, where the plugin divides by zero)."""
    if rays_count == 1:
        return np.zeros(len(low))
    return 0.5 * (low + high) * (last - first) / (rays_count - 1) + first


def block_cloud(rays: RayScan, ranges: np.ndarray, sigma: float,
                rng: np.random.Generator) -> Tuple[np.ndarray, np.ndarray]:
    """(points (N, 3) float32 in the sensor frame, channel values (N,) float32) of one reading
    of ``ranges`` (one per ray, Gazebo's order), ``sigma`` the plugin's gaussianNoise (m)."""
    h, v = rays.samples, rays.vertical_samples
    grid = np.asarray(ranges, dtype=np.float64).reshape(v, h)
    columns = max(int(h * rays.resolution), 0)
    rows = max(int(v * rays.vertical_resolution), 0)
    ha, hb, hf = _corners(columns, h)
    va, vb, vf = _corners(rows, v)
    hf, vf = hf[np.newaxis, :], vf[:, np.newaxis]
    r = ((1 - vf) * ((1 - hf) * grid[np.ix_(va, ha)] + hf * grid[np.ix_(va, hb)])
         + vf * ((1 - hf) * grid[np.ix_(vb, ha)] + hf * grid[np.ix_(vb, hb)]))
    r[r < rays.range_min] = -math.inf
    r[r > rays.range_max] = math.inf
    yaw = _angle(ha, hb, h, rays.min_angle, rays.max_angle)[np.newaxis, :]
    pitch = _angle(va, vb, v, rays.vertical_min_angle, rays.vertical_max_angle)[:, np.newaxis]
    with np.errstate(invalid="ignore"):
        points = np.stack([r * np.cos(pitch) * np.cos(yaw), r * np.cos(pitch) * np.sin(yaw),
                           r * np.sin(pitch) * np.ones_like(yaw)], axis=-1).reshape(-1, 3)
    channel = np.zeros(len(points))
    if sigma > 0 and len(points):
        noisy = np.abs(rays.range_max - r.reshape(-1)) > AT_MAX_RANGE
        points[noisy] += rng.normal(0.0, sigma, (int(noisy.sum()), 3))
        channel += rng.normal(0.0, sigma, len(points))
    return points.astype(np.float32), channel.astype(np.float32)
