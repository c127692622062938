"""Gazebo's relative pose and twist arithmetic (sim/reference_frames). No ROS master."""
import math

import pytest

from tutorial_turtlebot.sim.files.limits import unit_quaternion
from tutorial_turtlebot.sim.kinematics import quat_from_rpy, to_body
from tutorial_turtlebot.sim.world import reference_frames as rf


def yaw_quat(yaw):
    return (0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2))


def approx(values, expected, tol=1e-9):
    assert len(values) == len(expected)
    for v, e in zip(values, expected):
        assert v == pytest.approx(e, abs=tol)


def test_relative_pose_is_frame_inverse_times_pose():
    frame = ((1.0, 2.0, 0.0), yaw_quat(math.pi / 2))
    pose = ((1.0, 3.0, 0.5), yaw_quat(math.pi / 2 + 0.3))
    (p, q) = rf.relative_pose(pose, frame)
    approx(p, (1.0, 0.0, 0.5))          # 1 m along the frame's x (which is world +y)
    approx(q, yaw_quat(0.3))


def test_compose_undoes_relative_pose():
    frame = ((0.3, -1.0, 0.2), unit_quaternion((0.1, 0.2, 0.3, 0.9)))
    pose = ((2.0, 1.0, -0.5), unit_quaternion((0.4, -0.1, 0.2, 0.8)))
    p, q = rf.compose(frame, rf.relative_pose(pose, frame))
    approx(p, pose[0])
    approx(q, pose[1])


def test_relative_twist_rotates_the_difference_without_omega_cross_r():
    frame_orientation = yaw_quat(math.pi / 2)
    twist = ((1.0, 1.0, 0.0), (0.0, 0.0, 0.5))
    frame_twist = ((0.0, 1.0, 0.0), (0.0, 0.0, 0.5))      # the frame spins too: no r term
    v, w = rf.relative_twist(twist, frame_twist, frame_orientation)
    approx(v, (0.0, -1.0, 0.0))          # world +x is the frame's -y
    approx(w, (0.0, 0.0, 0.0))


def test_set_model_twist_is_rotated_into_the_world():
    v, w = rf.model_twist_to_world(((1.0, 0.0, 0.0), (0.0, 0.0, 1.0)), yaw_quat(math.pi / 2))
    approx(v, (0.0, 1.0, 0.0))
    approx(w, (0.0, 0.0, 1.0))


def test_set_link_twist_subtracts_the_frame_velocity_unrotated():
    v, w = rf.link_twist_to_world(((1.0, 0.0, 0.0), (0.0, 0.0, 1.0)),
                                  ((0.5, 0.5, 0.0), (0.0, 0.0, 0.25)))
    approx(v, (0.5, -0.5, 0.0))
    approx(w, (0.0, 0.0, 0.75))


def test_rotate_is_to_body_of_the_conjugate():
    """rotate is R v, kinematics.to_body R^T v: one formula, so bit for bit the same."""
    q = quat_from_rpy(0.3, -0.7, 2.1)
    v = (0.4, -1.3, 2.2)
    assert rf.rotate(q, v) == to_body(rf.conjugate(q), v)
    assert rf.rotate(rf.conjugate(q), v) == to_body(q, v)
    approx(rf.rotate(q, to_body(q, v)), v)
    approx(rf.rotate(yaw_quat(math.pi / 2), (1.0, 0.0, 0.0)), (0.0, 1.0, 0.0))


def test_world_frame_names():
    assert all(rf.is_world_frame(n) for n in ("", "world", "map", "/map"))
    assert not rf.is_world_frame("turtlebot3_burger")


def test_rpy_round_trip():
    for rpy in ((0.1, -0.2, 0.3), (0.0, 0.0, -3.0), (1.0, 0.5, 2.0)):
        approx(rf.rpy_from_quat(rf.quat_from_rpy(*rpy)), rpy)
