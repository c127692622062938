"""Gazebo's pose and twist arithmetic for its world API (gazebo_ros_api_plugin), without ROS.

A pose is ((x, y, z), (qx, qy, qz, qw)); a twist is ((vx, vy, vz), (wx, wy, wz)), linear in m/s
and angular in rad/s, both in the world frame unless said otherwise. A reference frame is the
pose and twist of another model or link; "", "world", "map" and "/map" name the world itself.

The rules (doc/turtlebot3.md 7.2), which are Gazebo's, not textbook kinematics:
- get_model_state / get_link_state relative to a frame F: pose = F^-1 * pose;
  velocities = R_F^-1 (v - v_F), with no omega x r term.
- set_model_state relative to F: pose = F * pose; the twist is rotated into the world
  (R_F v), F's own velocity is not added.
- set_link_state relative to F: pose = F * pose; velocity = v - v_F, not rotated.
"""
import math
from typing import Sequence, Tuple

# the world API's pose type and conversions are kinematics' own
from ..kinematics import IDENTITY, Pose, Quat, quat_from_rpy, rpy_from_quat, to_body
from ..kinematics import Vector3 as Vec

REEXPORTED = (IDENTITY, quat_from_rpy, rpy_from_quat)  # used as rf.* by world/ and the tests

Twist = Tuple[Vec, Vec]
ZERO_TWIST: Twist = ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0))
WORLD_FRAMES = ("", "world", "map", "/map")


def is_world_frame(name: str) -> bool:
    """Whether a reference frame name means the world."""
    return name in WORLD_FRAMES


def finite(*values: Sequence[float]) -> bool:
    """Whether every number in the given sequences is finite (no NaN, no inf)."""
    return all(math.isfinite(v) for seq in values for v in seq)


def multiply(a: Quat, b: Quat) -> Quat:
    """Hamilton product a * b (apply b, then a)."""
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return (aw * bx + ax * bw + ay * bz - az * by,
            aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw,
            aw * bw - ax * bx - ay * by - az * bz)


def conjugate(q: Quat) -> Quat:
    """The inverse rotation of a unit quaternion."""
    return (-q[0], -q[1], -q[2], q[3])


def rotate(q: Quat, v: Sequence[float]) -> Vec:
    """Vector ``v`` rotated by the unit quaternion ``q``: R(q) v, which is R(q*)^T v, the body
    frame of the inverse rotation (kinematics.to_body of the conjugate)."""
    return to_body(conjugate(q), v)


def compose(a: Pose, b: Pose) -> Pose:
    """a * b: pose ``b`` given in frame ``a``, expressed where ``a`` is given."""
    (pa, qa), (pb, qb) = a, b
    r = rotate(qa, pb)
    return (pa[0] + r[0], pa[1] + r[1], pa[2] + r[2]), multiply(qa, qb)


def inverse(a: Pose) -> Pose:
    """a^-1."""
    p, q = a
    qi = conjugate(q)
    r = rotate(qi, p)
    return (-r[0], -r[1], -r[2]), qi


def relative_pose(pose: Pose, frame: Pose) -> Pose:
    """``pose`` (world) seen from ``frame`` (world): frame^-1 * pose."""
    return compose(inverse(frame), pose)


def relative_twist(twist: Twist, frame_twist: Twist, frame_orientation: Quat) -> Twist:
    """get_*_state's velocities relative to a frame: R_F^-1 (v - v_F), no omega x r term."""
    qi = conjugate(frame_orientation)
    (v, w), (vf, wf) = twist, frame_twist
    return (rotate(qi, [a - b for a, b in zip(v, vf)]),
            rotate(qi, [a - b for a, b in zip(w, wf)]))


def model_twist_to_world(twist: Twist, frame_orientation: Quat) -> Twist:
    """set_model_state's twist given in a frame: rotated into the world, frame velocity not
    added."""
    return rotate(frame_orientation, twist[0]), rotate(frame_orientation, twist[1])


def link_twist_to_world(twist: Twist, frame_twist: Twist) -> Twist:
    """set_link_state's twist given in a frame: the frame's velocity subtracted, not rotated."""
    (v, w), (vf, wf) = twist, frame_twist
    return (tuple(a - b for a, b in zip(v, vf)), tuple(a - b for a, b in zip(w, wf)))
