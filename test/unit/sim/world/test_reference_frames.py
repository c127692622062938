"""Gazebo's relative pose and twist arithmetic (sim/reference_frames). No ROS master."""
import math

import pytest

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
    frame = ((0.3, -1.0, 0.2), rf.normalized((0.1, 0.2, 0.3, 0.9)))
    pose = ((2.0, 1.0, -0.5), rf.normalized((0.4, -0.1, 0.2, 0.8)))
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


def test_quaternions_are_normalised_and_zero_is_identity():
    approx(rf.normalized((0.0, 0.0, 2.0, 2.0)), (0.0, 0.0, math.sqrt(0.5), math.sqrt(0.5)))
    assert rf.normalized((0.0, 0.0, 0.0, 0.0)) == rf.IDENTITY_QUAT
    with pytest.raises(ValueError):
        rf.normalized((0.0, float("nan"), 0.0, 1.0))


def test_world_frame_names():
    assert all(rf.is_world_frame(n) for n in ("", "world", "map", "/map"))
    assert not rf.is_world_frame("turtlebot3_burger")


def test_rpy_round_trip():
    for rpy in ((0.1, -0.2, 0.3), (0.0, 0.0, -3.0), (1.0, 0.5, 2.0)):
        approx(rf.rpy_from_quat(rf.quat_from_rpy(*rpy)), rpy)
