"""Rotations and small rigid-body helpers: every conversion between roll-pitch-yaw, quaternion
and 3x3 matrix lives here. Quaternions are (x, y, z, w), as pybullet and geometry_msgs order
them; vectors are (x, y, z) in metres or m/s; angles in radians, REP 103. Roll, pitch, yaw are
fixed-axis angles as SDF and URDF define them: R = Rz(yaw) Ry(pitch) Rx(roll).

The simulator's one pose type is ``Pose``: ((x, y, z), (qx, qy, qz, qw)), a child frame's
position (m) and orientation in its parent frame. ``XyzRpy`` is not a second pose type but the
six numbers SDF and URDF write one as ("x y z roll pitch yaw"); the functions below convert."""
import math
from typing import Sequence, Tuple

import numpy as np

Vector3 = Tuple[float, float, float]
Quat = Tuple[float, float, float, float]
Pose = Tuple[Vector3, Quat]
XyzRpy = Tuple[float, float, float, float, float, float]   # x, y, z (m), roll, pitch, yaw (rad)

IDENTITY_QUAT: Quat = (0.0, 0.0, 0.0, 1.0)
IDENTITY: Pose = ((0.0, 0.0, 0.0), IDENTITY_QUAT)
ZERO_XYZ_RPY: XyzRpy = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)


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


def cross_2d(o, a, b):
    """z of the cross product (a - o) x (b - o) of plane points (x, y): > 0 when o, a, b turn
    counter-clockwise, < 0 clockwise, 0 on one line; twice the signed area of the triangle.
    Works element-wise on numpy arrays indexed [x, y] first (e.g. the transposes of (N, 2)
    arrays of points)."""
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])


def wrap_angle(a: float) -> float:
    """Angle wrapped into [-pi, pi)."""
    return (a + math.pi) % (2.0 * math.pi) - math.pi


def matrix_from_rpy(roll: float, pitch: float, yaw: float) -> np.ndarray:
    """3x3 rotation matrix R = Rz(yaw) Ry(pitch) Rx(roll): v_parent = R @ v_child."""
    cr, sr = math.cos(roll), math.sin(roll)
    cp, sp = math.cos(pitch), math.sin(pitch)
    cy, sy = math.cos(yaw), math.sin(yaw)
    return np.array(((cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr),
                     (sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr),
                     (-sp, cp * sr, cp * cr)))


def rpy_from_matrix(m) -> Tuple[float, float, float]:
    """(roll, pitch, yaw) of a 3x3 rotation matrix, the inverse of ``matrix_from_rpy``; at
    gimbal lock (pitch +-pi/2) the whole turn about z is put in yaw. Never -0.0."""
    cos_pitch = math.hypot(m[0][0], m[1][0])
    pitch = math.atan2(-m[2][0], cos_pitch) + 0.0      # + 0.0 turns -0.0 into 0.0
    if cos_pitch < 1e-9:
        return 0.0, pitch, math.atan2(-m[0][1], m[1][1]) + 0.0
    return math.atan2(m[2][1], m[2][2]) + 0.0, pitch, math.atan2(m[1][0], m[0][0]) + 0.0


def quat_from_rpy(roll: float, pitch: float, yaw: float) -> Quat:
    """Quaternion of fixed-axis roll, pitch, yaw (the rotation of ``matrix_from_rpy``)."""
    cr, sr = math.cos(roll / 2), math.sin(roll / 2)
    cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
    cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
    return (sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy,
            cr * cp * sy - sr * sp * cy, cr * cp * cy + sr * sp * sy)


def rpy_from_quat(q: Sequence[float]) -> Tuple[float, float, float]:
    """(roll, pitch, yaw) of a unit quaternion, the inverse of ``quat_from_rpy``."""
    x, y, z, w = q
    roll = math.atan2(2 * (w * x + y * z), 1 - 2 * (x * x + y * y))
    pitch = math.asin(max(-1.0, min(1.0, 2 * (w * y - z * x))))
    yaw = math.atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))
    return roll, pitch, yaw


def quat_from_matrix(m) -> Quat:
    """Unit quaternion of a 3x3 rotation matrix (the inverse of ``rotation_matrix``)."""
    trace = m[0][0] + m[1][1] + m[2][2]
    if trace > 0:
        s = 2.0 * math.sqrt(trace + 1.0)
        return ((m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s,
                0.25 * s)
    i = max(range(3), key=lambda k: m[k][k])
    j, k = (i + 1) % 3, (i + 2) % 3
    s = 2.0 * math.sqrt(1.0 + m[i][i] - m[j][j] - m[k][k])
    q = [0.0, 0.0, 0.0, 0.0]
    q[i] = 0.25 * s
    q[j] = (m[j][i] + m[i][j]) / s
    q[k] = (m[k][i] + m[i][k]) / s
    q[3] = (m[k][j] - m[j][k]) / s
    return tuple(q)


def pose_from_xyz_rpy(values: Sequence[float]) -> Pose:
    """The ``Pose`` of the six numbers (x, y, z, roll, pitch, yaw) of an SDF or URDF pose."""
    return tuple(values[:3]), quat_from_rpy(*values[3:6])


def xyz_rpy_from_pose(pose: Pose) -> XyzRpy:
    """The six numbers (x, y, z, roll, pitch, yaw) of a ``Pose``, the inverse of
    ``pose_from_xyz_rpy``."""
    return tuple(pose[0]) + rpy_from_quat(pose[1])


def transform_from_xyz_rpy(xyz: Sequence[float], rpy: Sequence[float]) -> np.ndarray:
    """4x4 homogeneous transform T of a child frame at ``xyz`` (m) turned by ``rpy`` (rad) in
    its parent: p_parent = T @ p_child."""
    t = np.eye(4)
    t[:3, :3] = matrix_from_rpy(*rpy)
    t[:3, 3] = xyz
    return t


def compose_xyz_rpy(parent: Sequence[float], child: Sequence[float]) -> XyzRpy:
    """The pose ``child`` (x, y, z, roll, pitch, yaw in the ``parent`` frame) expressed where
    ``parent`` is given, as six numbers again."""
    r = matrix_from_rpy(*parent[3:])
    x, y, z = (float(v) for v in np.asarray(parent[:3]) + r @ np.asarray(child[:3]))
    return (x, y, z) + rpy_from_matrix(r @ matrix_from_rpy(*child[3:]))
