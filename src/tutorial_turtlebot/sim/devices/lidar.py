"""The LDS-01 laser: ray geometry and how distances become ``LaserScan.ranges``.

Two kinds (doc/turtlebot3.md 2.2, 6): ``gazebo`` is what gazebo_ros_laser sends (0 to 6.28319 rad
in 360 samples, so the last ray repeats the first; +inf past range_max, -inf at or under
range_min, gaussian noise then clamped into [range_min, range_max]); ``lds01`` is what the real
hls_lfcd_lds_driver publishes (exact 1 degree steps, 0.0 for no return or too close).
Angles are in the ``base_scan`` frame, counter-clockwise from +x; distances in metres.
"""
import math
from dataclasses import replace

import numpy as np

from ...errors import UserError
from ..files.plugins.robot_plugin_types import LaserConfig


LASER_MODELS = {
    "gazebo": LaserConfig("gazebo", 0.0, 6.28319, 6.28319 / 359),
    "lds01": LaserConfig("lds01", 0.0, math.radians(359), math.radians(1), no_return=0.0,
                         too_close=0.0),
}


def laser_config(name: str) -> LaserConfig:
    """The config called ``name``; an unknown one raises UserError naming the valid ones."""
    try:
        return LASER_MODELS[name]
    except (KeyError, TypeError):
        raise UserError("unknown lidar_model %r: valid are %s"
                        % (name, ", ".join(LASER_MODELS))) from None


def as_real_driver(laser: LaserConfig) -> LaserConfig:
    """``laser`` as the real hls_lfcd_lds_driver publishes a full turn: ``samples`` equal steps
    of 2*pi/samples from angle_min (exactly 1 degree for 360), 0.0 for no return or too close."""
    step = 2.0 * math.pi / laser.samples
    return replace(laser, name="lds01", angle_increment=step,
                   angle_max=laser.angle_min + step * (laser.samples - 1), no_return=0.0,
                   too_close=0.0)


def ray_directions(cfg: LaserConfig) -> np.ndarray:
    """Unit vectors (samples x 3) of each ray in the scan frame, index 0 straight ahead.
    Python's math (the C library's) makes them, not numpy's: numpy's vectorised sin and cos
    differ in the last bit between its versions and processors, and a ray that grazes an edge
    then lands elsewhere."""
    angles = cfg.angle_min + cfg.angle_increment * np.arange(cfg.samples)
    return np.array([(math.cos(a), math.sin(a), 0.0) for a in angles.tolist()])


def ranges_from_distances(cfg: LaserConfig, distances: np.ndarray,
                          rng: np.random.Generator) -> np.ndarray:
    """Published ranges (float32) from true distances to the first hit (inf where none)."""
    d = np.asarray(distances, dtype=np.float64)
    noisy = d + rng.normal(0.0, cfg.noise_sigma, d.shape) if cfg.noise_sigma > 0 else d
    out = np.clip(noisy, cfg.range_min, cfg.range_max)
    out[d >= cfg.range_max] = cfg.no_return
    out[d <= cfg.range_min] = cfg.too_close
    return out.astype(np.float32)
