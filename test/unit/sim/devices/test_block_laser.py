"""gazebo_ros_block_laser's cloud (devices.block_laser): a point per reading in the sensor
frame at the plugin's angles (the middle of a reading's two corner rays: half a ray step on,
the last ray its own), rays that meet nothing at range_max without noise, readings outside
min..max at +-inf, interpolation between rays. Units: m, rad."""
import math

import numpy as np

from tutorial_turtlebot.sim.devices.block_laser import block_cloud
from tutorial_turtlebot.sim.devices.ray_grid import gazebo_ranges
from tutorial_turtlebot.sim.files.plugins.sensor_types import RayScan

RAYS = RayScan(samples=3, min_angle=-0.3, max_angle=0.3, vertical_samples=2,
               vertical_min_angle=-0.4, vertical_max_angle=0.4, range_min=0.4, range_max=1.0)


def test_each_ray_is_a_point_along_its_angles():
    ranges = np.array([0.5, 0.6, 0.7, 0.8, 0.9, 1.0])
    points, channel = block_cloud(RAYS, ranges, 0.0, np.random.default_rng(0))
    assert points.dtype == np.float32 and points.shape == (6, 3)
    np.testing.assert_allclose(np.linalg.norm(points, axis=1), ranges, rtol=1e-6)
    # the plugin's angles: yaw -0.15, 0.15, 0.3 (rays at -0.3, 0, 0.3), pitch 0 then 0.4
    for index, yaw, pitch in ((0, -0.15, 0.0), (4, 0.15, 0.4), (5, 0.3, 0.4)):
        r = ranges[index]
        np.testing.assert_allclose(points[index], [r * math.cos(pitch) * math.cos(yaw),
                                                   r * math.cos(pitch) * math.sin(yaw),
                                                   r * math.sin(pitch)], rtol=1e-6, atol=1e-7)
    np.testing.assert_array_equal(channel, np.zeros(6, dtype=np.float32))


def test_clipping_ranges_outside_min_max_are_infinite_and_misses_at_max():
    """What a cast gives (gazebo_ranges) is always within min..max; a reading outside is
    REP 117's -inf (too near) or +inf (too far)."""
    cast = gazebo_ranges(RAYS, np.array([0.2, math.inf, 0.0, 0.6, math.inf, 0.1]))
    points, _ = block_cloud(RAYS, cast, 0.0, np.random.default_rng(0))
    norms = np.linalg.norm(points, axis=1)
    assert np.all((norms >= 0.4 - 1e-6) & (norms <= 1.0 + 1e-6)), norms
    raw, _ = block_cloud(RAYS, np.array([0.3, 1.2, 0.5, 0.5, 0.5, 0.5]), 0.0,
                         np.random.default_rng(0))
    assert raw[0, 0] == -math.inf and raw[1, 0] == math.inf     # x: cos of both angles > 0


def test_noise_leaves_the_points_at_range_max_where_they_are():
    ranges = np.array([1.0, 0.6, 1.0, 0.6, 1.0, 0.6])
    quiet, _ = block_cloud(RAYS, ranges, 0.0, np.random.default_rng(0))
    noisy, channel = block_cloud(RAYS, ranges, 0.01, np.random.default_rng(0))
    np.testing.assert_array_equal(noisy[0::2], quiet[0::2])
    assert np.all(np.abs(noisy[1::2] - quiet[1::2]) > 0)
    assert np.all(channel != 0)


def test_a_resolution_of_two_interpolates_between_rays():
    rays = RayScan(samples=2, resolution=2.0, min_angle=-0.2, max_angle=0.2, range_min=0.1,
                   range_max=5.0)
    points, _ = block_cloud(rays, np.array([1.0, 2.0]), 0.0, np.random.default_rng(0))
    assert len(points) == 4
    # readings at 0, 1/3, 2/3, 1 of the way: linear ranges, the angle of the ray pair's middle
    np.testing.assert_allclose(np.linalg.norm(points, axis=1), [1.0, 4 / 3, 5 / 3, 2.0],
                               rtol=1e-6)
