"""The rays of a ray sensor as Gazebo casts them (devices.ray_grid): their order and directions,
and the ranges read from where they hit. Sensor frame: x forward, z up; m, rad."""
import math

import numpy as np

from tutorial_turtlebot.sim.devices.ray_grid import gazebo_ranges, ray_grid
from tutorial_turtlebot.sim.files.plugins.sensor_types import RayScan


def test_rays_run_horizontal_first_then_up_with_a_positive_pitch_looking_up():
    rays = RayScan(samples=3, min_angle=-0.5, max_angle=0.5, vertical_samples=2,
                   vertical_min_angle=-0.2, vertical_max_angle=0.2)
    grid = ray_grid(rays)
    assert grid.shape == (6, 3)
    np.testing.assert_allclose(np.linalg.norm(grid, axis=1), 1.0)
    # index i + j * samples: yaw -0.5, 0, 0.5 at pitch -0.2, then at pitch +0.2
    yaws = np.arctan2(grid[:, 1], grid[:, 0])
    pitches = np.arcsin(grid[:, 2])
    np.testing.assert_allclose(yaws, [-0.5, 0.0, 0.5] * 2, atol=1e-12)
    np.testing.assert_allclose(pitches, [-0.2] * 3 + [0.2] * 3, atol=1e-12)


def test_one_sample_looks_straight_ahead_whatever_its_angles():
    grid = ray_grid(RayScan(samples=1, min_angle=0.3, max_angle=0.7))
    np.testing.assert_allclose(grid, [[1.0, 0.0, 0.0]])


def test_a_range_counts_from_the_sensor_and_a_miss_reads_range_max():
    rays = RayScan(samples=3, range_min=0.4, range_max=1.0)
    ranges = gazebo_ranges(rays, np.array([0.3, math.inf, 0.0]))
    np.testing.assert_allclose(ranges, [0.7, 1.0, 0.4])
