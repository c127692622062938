"""gazebo_ros_range's reading (devices.range_sensor): the nearest ray, noise below range_max,
range_max exactly when nothing is hit. Units: m."""
import numpy as np

from tutorial_turtlebot.sim.devices.range_sensor import (INFRARED, ULTRASOUND, radiation_type,
                                                         range_reading)


def test_the_nearest_ray_is_the_reading():
    rng = np.random.default_rng(0)
    assert range_reading(np.array([0.9, 0.5, 0.7]), 2.0, 0.0, rng) == np.float32(0.5)


def test_nothing_hit_reads_range_max_exactly_without_noise():
    rng = np.random.default_rng(0)
    for _ in range(20):
        assert range_reading(np.array([0.75, 0.75]), 0.75, 0.05, rng) == np.float32(0.75)


def test_noise_spreads_a_hit_and_never_passes_range_max():
    rng = np.random.default_rng(1)
    readings = np.array([range_reading(np.array([0.5]), 2.0, 0.01, rng) for _ in range(400)])
    assert abs(readings.mean() - 0.5) < 0.002
    assert 0.008 < readings.std() < 0.012
    near_max = [range_reading(np.array([1.999]), 2.0, 0.05, rng) for _ in range(100)]
    assert max(near_max) == np.float32(2.0) and min(near_max) < 1.999


def test_radiation_ultrasound_else_infrared():
    assert (radiation_type("ultrasound"), radiation_type("infrared"),
            radiation_type("laser")) == (ULTRASOUND, INFRARED, INFRARED) == (0, 1, 1)
