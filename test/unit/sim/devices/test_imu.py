"""An IMU link's device arithmetic (devices/imu): the acceleration from velocity changes,
gravity's reaction in the sensor frame, Gazebo's per-axis bias and white noise. Units: m/s,
m/s^2, rad/s, s."""
import math

import numpy as np

from tutorial_turtlebot.sim.devices.imu import Accelerometer, AxisNoises, imu_axes
from tutorial_turtlebot.sim.files.plugins.gazebo_ros_imu_sensor import AxisNoise
from tutorial_turtlebot.sim.kinematics import quat_from_rpy

GRAVITY = (0.0, 0.0, -9.8)


def test_the_acceleration_is_the_velocity_change_since_the_last_reading():
    meter = Accelerometer()
    np.testing.assert_allclose(meter.acceleration(1.0, (1.0, 0.0, 0.0)), 0.0)
    np.testing.assert_allclose(meter.acceleration(1.5, (2.0, 0.0, -1.0)), (2.0, 0.0, -2.0))
    meter.reset()
    np.testing.assert_allclose(meter.acceleration(2.0, (5.0, 0.0, 0.0)), 0.0)


def test_at_rest_up_reads_plus_gravity_and_a_pitched_sensor_sees_it_on_x():
    rates, felt = imu_axes((0.0, 0.0, 0.0, 1.0), (0.0, 0.0, 0.5), (0.0, 0.0, 0.0), GRAVITY)
    np.testing.assert_allclose(felt, (0.0, 0.0, 9.8))
    np.testing.assert_allclose(rates, (0.0, 0.0, 0.5))
    _, felt = imu_axes(quat_from_rpy(0.0, math.pi / 2, 0.0), (0, 0, 0), (0, 0, 0), GRAVITY)
    np.testing.assert_allclose(felt, (-9.8, 0.0, 0.0), atol=1e-9)
    _, falling = imu_axes((0.0, 0.0, 0.0, 1.0), (0, 0, 0), GRAVITY, GRAVITY)
    np.testing.assert_allclose(falling, 0.0)


def test_the_bias_is_drawn_once_and_the_white_noise_each_reading():
    noises = AxisNoises((AxisNoise(), AxisNoise(0.0, 0.0, 0.3), AxisNoise(0.1, 0.05)),
                        np.random.default_rng(3))
    readings = np.array([noises.applied((0.0, 0.0, 0.0)) for _ in range(2000)])
    assert np.all(readings[:, 0] == 0.0)
    assert np.all(np.abs(readings[:, 1]) == 0.3)              # the bias, of a random sign
    assert abs(readings[:, 2].mean() - 0.1) < 0.01 and abs(readings[:, 2].std() - 0.05) < 0.005
