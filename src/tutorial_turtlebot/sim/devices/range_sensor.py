"""What gazebo_ros_range makes of a ray sensor: sensor_msgs/Range's reading (PutRangeData), from
the ranges of every ray (ray_grid.gazebo_ranges). No ROS, no pybullet. Units: m, rad.
"""
import numpy as np

ULTRASOUND, INFRARED = 0, 1     # sensor_msgs/Range radiation_type
FLOAT32_MAX = float(np.finfo(np.float32).max)


def radiation_type(radiation: str) -> int:
    """ULTRASOUND for the plugin's <radiation> "ultrasound", INFRARED for anything else."""
    return ULTRASOUND if radiation == "ultrasound" else INFRARED


def range_reading(ranges: np.ndarray, range_max: float, sigma: float,
                  rng: np.random.Generator) -> float:
    """The published range (m, a float32's value): the smallest of ``ranges``; below
    ``range_max`` it gets gaussian noise of ``sigma`` and is held to range_max at most (not
    to range_min: a noisy reading may fall below it), at range_max (nothing hit) it is
    range_max exactly, with no noise (gazebo_ros_range)."""
    nearest = np.float32(min(np.min(ranges), FLOAT32_MAX)) if len(ranges) else np.float32(
        FLOAT32_MAX)
    if nearest < np.float32(range_max):
        noise = rng.normal(0.0, sigma) if sigma > 0 else 0.0
        nearest = np.float32(min(float(nearest) + noise, range_max))
    return float(nearest)
