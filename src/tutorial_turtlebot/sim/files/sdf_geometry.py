"""Geometry helpers of SDF shapes, for the world loader (world_sdf): a plane's normal as a pose, a
polyline's polygon cleaned and checked. Plain math: no ROS, no pybullet.

Units: metres, radians; poses are kinematics.XyzRpy in the frame of the shape's parent.
"""
import math
from typing import List, Optional, Sequence, Tuple

from ..kinematics import ZERO_XYZ_RPY, XyzRpy, cross_2d, rpy_from_matrix

Point = Tuple[float, float]


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
