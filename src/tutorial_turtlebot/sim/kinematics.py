"""Small rigid-body helpers. Quaternions are (x, y, z, w), as pybullet and geometry_msgs order
them; vectors are (x, y, z) in metres or m/s; angles in radians, REP 103."""
import math
from typing import Sequence, Tuple

import numpy as np

Quat = Tuple[float, float, float, float]


def yaw_from_quat(q: Sequence[float]) -> float:
    """Heading about +z (rad, counter-clockwise from +x) of a quaternion (x, y, z, w)."""
    x, y, z, w = q
    return math.atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))


def quat_from_yaw(yaw: float) -> Quat:
    """Quaternion (x, y, z, w) of a pure rotation by ``yaw`` about +z."""
    return (0.0, 0.0, math.sin(yaw / 2.0), math.cos(yaw / 2.0))


def rotation_matrix(q: Sequence[float]) -> np.ndarray:
    """3x3 matrix R of quaternion (x, y, z, w): v_world = R @ v_body."""
    x, y, z, w = q
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
    ])


def to_body(q: Sequence[float], v_world: Sequence[float]) -> Tuple[float, float, float]:
    """A world-frame vector expressed in the body frame whose orientation is ``q``: R^T v.
    Plain floats, no numpy: it runs at the IMU's 200 Hz, where numpy's per-call cost shows."""
    x, y, z, w = q
    vx, vy, vz = v_world
    return ((1 - 2 * (y * y + z * z)) * vx + 2 * (x * y + z * w) * vy + 2 * (x * z - y * w) * vz,
            2 * (x * y - z * w) * vx + (1 - 2 * (x * x + z * z)) * vy + 2 * (y * z + x * w) * vz,
            2 * (x * z + y * w) * vx + 2 * (y * z - x * w) * vy + (1 - 2 * (x * x + y * y)) * vz)


def wrap_angle(a: float) -> float:
    """Angle wrapped into [-pi, pi)."""
    return (a + math.pi) % (2.0 * math.pi) - math.pi
