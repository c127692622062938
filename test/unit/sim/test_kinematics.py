"""Quaternion (x, y, z, w) and frame helpers, checked against pybullet's own. No ROS master."""
import math

import numpy as np
import pybullet
import pytest

from tutorial_turtlebot.sim.kinematics import (cross_2d, quat_from_yaw, rotation_matrix, to_body,
                                               wrap_angle, yaw_from_quat)

YAWS = (0.0, 0.3, -0.3, math.pi / 2, -math.pi / 2, 2.5, -2.5, math.pi - 1e-9)


@pytest.mark.parametrize("yaw", YAWS)
def test_yaw_quat_round_trip(yaw):
    """yaw -> quaternion -> yaw gives the same angle; the quaternion is unit length."""
    q = quat_from_yaw(yaw)
    assert math.fsum(c * c for c in q) == pytest.approx(1.0)
    assert yaw_from_quat(q) == pytest.approx(yaw, abs=1e-12)


@pytest.mark.parametrize("yaw", YAWS)
def test_quat_order_is_xyzw_as_pybullet(yaw):
    """Same quaternion as pybullet.getQuaternionFromEuler((0, 0, yaw)), field by field."""
    assert quat_from_yaw(yaw) == pytest.approx(pybullet.getQuaternionFromEuler((0, 0, yaw)),
                                               abs=1e-7)


def test_yaw_of_quarter_turn():
    """A 90 degree left turn is (0, 0, sin 45, cos 45)."""
    assert quat_from_yaw(math.pi / 2) == pytest.approx((0, 0, math.sqrt(0.5), math.sqrt(0.5)))
    assert yaw_from_quat((0.0, 0.0, 0.0, 1.0)) == 0.0


def test_yaw_from_quat_ignores_small_tilt():
    """A robot pitched and rolled a little still reports its heading."""
    q = pybullet.getQuaternionFromEuler((0.05, -0.03, 1.2))
    assert yaw_from_quat(q) == pytest.approx(1.2, abs=1e-6)


@pytest.mark.parametrize("rpy", [(0, 0, 0), (0.1, -0.2, 0.3), (1.0, 0.5, -2.0),
                                 (-1.57, 0, 0), (0, 0, math.pi)])
def test_rotation_matrix_matches_pybullet(rpy):
    """rotation_matrix(q) is pybullet's getMatrixFromQuaternion (row-major)."""
    q = pybullet.getQuaternionFromEuler(rpy)
    expected = np.array(pybullet.getMatrixFromQuaternion(q)).reshape(3, 3)
    assert np.allclose(rotation_matrix(q), expected, atol=1e-7)


def test_to_body_of_a_yawed_robot():
    """Facing +y, a world +x velocity is to the robot's right (-y body), world +y is ahead."""
    q = quat_from_yaw(math.pi / 2)
    assert to_body(q, (1.0, 0.0, 0.0)) == pytest.approx((0.0, -1.0, 0.0), abs=1e-12)
    assert to_body(q, (0.0, 2.0, 0.0)) == pytest.approx((2.0, 0.0, 0.0), abs=1e-12)
    assert to_body(q, (0.0, 0.0, 9.8)) == pytest.approx((0.0, 0.0, 9.8), abs=1e-12)


def test_to_body_of_a_pitched_robot():
    """Nose down by 0.1 rad: gravity's reaction (+z world) shows a -x body component."""
    q = pybullet.getQuaternionFromEuler((0.0, 0.1, 0.0))
    body = to_body(q, (0.0, 0.0, 9.8))
    assert body == pytest.approx((-9.8 * math.sin(0.1), 0.0, 9.8 * math.cos(0.1)), abs=1e-6)


@pytest.mark.parametrize("rpy", [(0.1, -0.2, 0.3), (1.0, 0.5, -2.0)])
def test_to_body_inverts_rotation(rpy):
    """R @ to_body(q, v) == v, and the length is kept."""
    q = pybullet.getQuaternionFromEuler(rpy)
    v = np.array([0.3, -1.2, 2.0])
    body = to_body(q, v)
    assert rotation_matrix(q) @ body == pytest.approx(v)
    assert np.linalg.norm(body) == pytest.approx(np.linalg.norm(v))


@pytest.mark.parametrize("angle, wrapped", [
    (0.0, 0.0), (1.0, 1.0), (-1.0, -1.0), (math.pi, -math.pi), (-math.pi, -math.pi),
    (1.5 * math.pi, -0.5 * math.pi), (-1.5 * math.pi, 0.5 * math.pi), (2 * math.pi, 0.0),
    (7.0, 7.0 - 2 * math.pi), (-20.0, -20.0 + 6 * math.pi)])
def test_wrap_angle(angle, wrapped):
    """Angles wrap into [-pi, pi)."""
    assert wrap_angle(angle) == pytest.approx(wrapped, abs=1e-12)
    assert -math.pi <= wrap_angle(angle) < math.pi


def test_cross_2d_signs_the_turn():
    """z of (a - o) x (b - o): positive counter-clockwise, negative clockwise, 0 on a line;
    twice the triangle's area."""
    assert cross_2d((0.0, 0.0), (2.0, 0.0), (0.0, 3.0)) == 6.0
    assert cross_2d((1.0, 1.0), (1.0, 4.0), (3.0, 1.0)) == -6.0
    assert cross_2d((0.0, 0.0), (1.0, 1.0), (2.0, 2.0)) == 0.0


def test_cross_2d_element_wise_on_arrays_of_x_then_y():
    """On (2, N) arrays (transposed (N, 2) points) it is the cross product of each column,
    bit for bit the same as point by point; a single point broadcasts."""
    rng = np.random.default_rng(3)
    o, a, b = (rng.normal(size=(5, 2)) for _ in range(3))
    columns = cross_2d(o.T, a.T, b.T)
    assert columns.tolist() == [cross_2d(*p) for p in zip(o.tolist(), a.tolist(), b.tolist())]
    assert cross_2d(o.T, a.T, b[0]).tolist() == [cross_2d(p, q, b[0].tolist())
                                                 for p, q in zip(o.tolist(), a.tolist())]
