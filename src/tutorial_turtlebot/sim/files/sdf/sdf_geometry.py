"""Geometry helpers of SDF shapes, for the world loader (world_sdf): a box's size (a side of 0
as Gazebo's ODE takes it), a plane's drawn size (beyond limits.MAX_SIZE clamped: the plane
collides as an infinite plane all the same) and its normal as a pose, a polyline's polygon
cleaned and checked.
No ROS, no pybullet.

Units: metres, radians; poses are kinematics.XyzRpy in the frame of the shape's parent.
"""
import math
import os
from typing import List, Optional, Sequence, Tuple

from .. import limits
from ..xml_reader import Element
from ...kinematics import ZERO_XYZ_RPY, XyzRpy, cross_2d, rpy_from_matrix

Point = Tuple[float, float]
ZERO_SIDE = "a <box> side of 0 is built %g mm thick" % (limits.MIN_BOX_SIDE * 1000)
PLANE_CLAMPED = "only its drawing is clamped: it collides as an infinite plane, as in Gazebo"


def box_size(reader, box: Element) -> Tuple[float, float, float]:
    """The sides (m) of ``box``'s <size> (SDF's default 1 1 1), read by ``reader`` (world_sdf's
    loader: its one-line refusals and warnings). A side of 0 is limits.MIN_BOX_SIDE, with one
    warning per file: Gazebo 11's ODE builds a box of side 0 (flat: it collides on its faces),
    Bullet needs a side. A negative, nan or too large side stays refused."""
    node = box.child("size")
    if node is None:
        return (1.0, 1.0, 1.0)
    size = reader.floats(node, 3, finite=False)
    if 0 in size and not limits.size_problem("<size>", [v or 1.0 for v in size]):
        size = tuple(v or limits.MIN_BOX_SIDE for v in size)
        name = os.path.basename(reader.path)
        if not any(name in w and ZERO_SIDE in w for w in reader.warnings):
            reader.warn_short(node, "<size> %s: %s (Gazebo's ODE takes 0 itself; said once "
                                    "per file)" % (node.value, ZERO_SIDE))
    problem = limits.size_problem("<size>", size)
    if problem:
        reader.fail_bare(node, problem)
    return size


def plane_size(reader, plane: Element) -> Tuple[float, float]:
    """The drawn sides (m) of ``plane``'s <size> (SDF's default 1 1). A plane collides as an
    infinite plane, in Gazebo and here (world_bullet), and libsdformat bounds no size: the size
    only says what is drawn. A side beyond limits.MAX_SIZE is drawn that long, with one
    warning (the collision stays infinite); a side that is not a positive finite number stays
    refused (limits.size_problem). The warning is said once per file."""
    node = plane.child("size")
    if node is None:
        return (1.0, 1.0)
    size = reader.floats(node, 2, finite=False)
    clamped = tuple(min(v, limits.MAX_SIZE) if math.isfinite(v) else v for v in size)
    problem = limits.size_problem("<size>", clamped)
    if problem:
        reader.fail_bare(node, problem)
    name = os.path.basename(reader.path)
    if clamped != tuple(size) and not any(name in w and PLANE_CLAMPED in w
                                          for w in reader.warnings):
        reader.warn_short(node, "plane <size> %s drawn %g x %g m (%s; said once per file)"
                          % (node.value, clamped[0], clamped[1], PLANE_CLAMPED))
    return clamped


def normal_pose(n: Sequence[float]) -> XyzRpy:
    """A rotation taking +z onto the unit vector ``n`` (the shortest one)."""
    axis = (-n[1], n[0], 0.0)                    # z x n
    s, c = math.hypot(axis[0], axis[1]), n[2]
    if s < 1e-12:
        return ZERO_XYZ_RPY if c > 0 else (0.0, 0.0, 0.0, math.pi, 0.0, 0.0)
    ux, uy = axis[0] / s, axis[1] / s
    t = 1.0 - c                                  # Rodrigues with a horizontal unit axis (ux, uy, 0)
    m = ((c + ux * ux * t, ux * uy * t, uy * s),
         (ux * uy * t, c + uy * uy * t, -ux * s),
         (-uy * s, ux * s, c))
    return (0.0, 0.0, 0.0) + rpy_from_matrix(m)


def _segments_cross(p1, p2, q1, q2) -> bool:
    d1, d2 = cross_2d(q1, q2, p1), cross_2d(q1, q2, p2)
    d3, d4 = cross_2d(p1, p2, q1), cross_2d(p1, p2, q2)
    return d1 * d2 < 0 and d3 * d4 < 0


def clean_polygon(points: List[Point]) -> Optional[Tuple[Point, ...]]:
    """Counter-clockwise corners without repeats (a closing repeat of the first included) or
    straight-through points; None if the polygon is degenerate or crosses itself."""
    pts = list(points)
    changed = True
    while changed and len(pts) >= 3:
        changed = False
        for i in range(len(pts)):
            a, b, c = pts[i - 1], pts[i], pts[(i + 1) % len(pts)]
            if abs(cross_2d(a, b, c)) < 1e-12:
                del pts[i]
                changed = True
                break
    if len(pts) < 3:
        return None
    n = len(pts)
    edges = [(pts[i], pts[(i + 1) % n]) for i in range(n)]
    for i in range(n):
        for j in range(i + 2, n):
            if (j + 1) % n != i and _segments_cross(*edges[i], *edges[j]):
                return None
    area = sum(cross_2d((0.0, 0.0), pts[i - 1], pts[i]) for i in range(n))
    return tuple(pts if area > 0 else pts[::-1])
