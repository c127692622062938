"""The kinematics of the drives besides the diff drive (devices.skid_steer, planar_move,
tricycle, force_based_move), as the gazebo_ros plugins compute them. Units: m, s, rad."""
import math

import pytest

from tutorial_turtlebot.sim.devices.force_based_move import push
from tutorial_turtlebot.sim.devices.planar_move import (PlanarMoveController, PoseOdometry,
                                                        world_velocity)
from tutorial_turtlebot.sim.devices.skid_steer import SkidSteerController, wheel_speeds
from tutorial_turtlebot.sim.devices.tricycle import (TricycleController, steering_angle,
                                                     yaw_rate)


def test_skid_steer_wheel_speeds_for_a_twist():
    """0.3 m/s and 1 rad/s on wheels 0.35 m apart, 0.05 m radius: rims 0.125 (left) and
    0.475 m/s (right), the front and rear wheel of a side alike."""
    lf, rf, lr, rr = wheel_speeds(0.3, 1.0, 0.35, 0.05)
    assert (lf, rf) == pytest.approx((2.5, 9.5))
    assert (lr, rr) == (lf, rf)
    assert wheel_speeds(0.0, 1.0, 0.35, 0.05) == pytest.approx((-3.5, 3.5, -3.5, 3.5))


def test_skid_steer_controller_has_no_ramp_and_keeps_the_command():
    controller = SkidSteerController(0.4, 0.075)
    assert controller.stopped
    controller.set_command(0.15, 0.0)
    assert controller.update(0.01) == pytest.approx((2.0, 2.0))
    assert controller.update(0.01) == pytest.approx((2.0, 2.0)) and not controller.stopped
    controller.reset()
    assert controller.stopped and controller.update(0.01) == (0.0, 0.0)


def test_planar_move_velocity_is_turned_by_the_heading():
    linear, angular = world_velocity(0.2, 0.1, 0.5, math.pi / 2)
    assert linear == pytest.approx((-0.1, 0.2, 0.0))
    assert angular == (0.0, 0.0, 0.5)


def test_planar_move_command_times_out():
    controller = PlanarMoveController(timeout=0.5)
    controller.set_command(0.2, 0.1, 0.3, now=1.0)
    assert controller.command(1.4) == (0.2, 0.1, 0.3)
    assert controller.command(1.6) == (0.0, 0.0, 0.0)
    forever = PlanarMoveController()
    forever.set_command(0.2, 0.0, 0.0, now=1.0)
    assert forever.command(1000.0) == (0.2, 0.0, 0.0)


def test_pose_odometry_is_the_change_in_the_base_frame():
    odometry = PoseOdometry()
    odometry.update(1.0, 1.0, math.pi / 2, now=0.0)
    assert odometry.linear == (0.0, 0.0)
    odometry.update(1.0, 1.1, math.pi / 2 + 0.05, now=0.1)   # 1 m/s along its heading (+y)
    assert odometry.linear[0] == pytest.approx(math.cos(0.05), rel=1e-6)
    assert odometry.angular == pytest.approx(0.5)


def test_tricycle_steering_angle_for_a_turn_radius():
    """A 0.4 m wheelbase on a 0.4 m circle: 45 degrees; right turns negative; straight 0."""
    assert steering_angle(0.4, 0.4) == pytest.approx(math.pi / 4)
    assert steering_angle(0.4, -0.4) == pytest.approx(-math.pi / 4)
    assert steering_angle(0.4, math.inf) == 0.0
    angle = steering_angle(0.4, 2.0)
    # the yaw rate that angle gives, times the radius of the rear axle, is its speed
    speed = 0.3
    assert yaw_rate(speed, angle, 0.4) * 2.0 == pytest.approx(speed * math.cos(angle))


def test_tricycle_controller_ramps_and_steers_as_the_plugin():
    controller = TricycleController(0.05, acceleration=1.0, deceleration=2.0)
    controller.set_command(0.3, 2.0)                       # 6 rad/s; the angle held to pi/2
    assert controller.wheel_speed(0.0, 0.1) == pytest.approx(0.2)   # going up: deceleration
    assert controller.wheel_speed(7.0, 0.1) == pytest.approx(6.9)   # going down: acceleration
    assert controller.wheel_speed(6.005, 0.1) == 6.005                # within the tolerance
    assert controller.steering(0.0) == (pytest.approx(math.pi / 2), 0.0)
    speed_steered = TricycleController(0.05, steering_speed=0.5)
    speed_steered.set_command(0.3, -0.4)
    assert speed_steered.steering(0.0) == (None, -0.5)
    assert speed_steered.steering(-0.395) == (None, 0.0)
    assert speed_steered.wheel_speed(0.0, 0.1) == pytest.approx(6.0)   # no ramp


def test_force_based_move_pushes_toward_the_command():
    fx, fy, torque = push((0.3, 0.0, 0.5), (0.1, 0.05), 0.0, (10000.0, 10000.0, 100.0),
                          mass=100.0, inertia=10.0, dt=0.0025)
    assert (fx, fy, torque) == pytest.approx((2000.0, -500.0, 50.0))
    # a light base: the gain is held to mass / dt, the error closed in one step, not overshot
    fx, _, torque = push((0.3, 0.0, 0.5), (0.0, 0.0), 0.0, (10000.0, 10000.0, 100.0),
                         mass=2.0, inertia=0.01, dt=0.0025)
    assert fx * 0.0025 / 2.0 == pytest.approx(0.3)
    assert torque * 0.0025 / 0.01 == pytest.approx(0.5)
