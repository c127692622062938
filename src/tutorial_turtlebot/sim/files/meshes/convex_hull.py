"""Convex hulls of meshes (a movable mesh collides as its hull: Bullet's moving bodies are
convex), computed here without scipy. No ROS and no pybullet. Units: those of the vertices (m).
"""
from typing import Dict, List, Tuple

import numpy as np

from ...kinematics import cross_2d
from .mesh_types import Mesh


def convex_hull_vertices(mesh: Mesh) -> np.ndarray:
    """(H, 3) the corner points of the convex hull of the vertices the faces use, m (a flat mesh:
    the corners of its outline; a line: its two ends)."""
    points = np.unique(mesh.vertices[np.unique(mesh.faces)], axis=0)
    centre = points.mean(axis=0)
    _, sizes, axes = np.linalg.svd(points - centre, full_matrices=False)
    rank = int(np.sum(sizes > 1e-9 * sizes[0])) if len(sizes) and sizes[0] > 0 else 0
    if rank == 3 and len(points) >= 4:
        return _hull_3d(points)
    if rank == 2:
        flat = (points - centre) @ axes[:2].T
        return points[_hull_2d(flat)]
    if rank == 1:
        along = (points - centre) @ axes[0]
        return points[[int(np.argmin(along)), int(np.argmax(along))]]
    return points[:1]


def _hull_2d(points: np.ndarray) -> List[int]:
    """Indices of the corners of the convex hull of 2-D points (monotone chain, collinear points
    dropped), counter-clockwise."""
    order = sorted(range(len(points)), key=lambda i: (points[i][0], points[i][1]))

    def chain(indices):
        out: List[int] = []
        for i in indices:
            while len(out) >= 2 and cross_2d(points[out[-2]], points[out[-1]], points[i]) <= 0:
                out.pop()
            out.append(i)
        return out

    lower, upper = chain(order), chain(reversed(order))
    return lower[:-1] + upper[:-1]


def _hull_3d(points: np.ndarray) -> np.ndarray:
    """Corners of the convex hull of points that span 3-D (quickhull with conflict lists), then
    only the hull vertices whose face normals span 3-D: a point on an edge or a face is no corner.
    """
    eps = 1e-9 * float(np.ptp(points, axis=0).max())
    faces: Dict[int, Tuple[int, int, int]] = {}
    planes: Dict[int, Tuple[np.ndarray, float]] = {}   # face -> (unit outward normal, offset)
    edges: Dict[Tuple[int, int], int] = {}             # directed edge -> its face
    conflicts: Dict[int, np.ndarray] = {}              # face -> the points outside it

    def add_faces(corners):
        """Add faces (i, j, k), counter-clockwise from outside; returns their keys."""
        p, q, r = (points[[f[i] for f in corners]] for i in range(3))
        normals = np.cross(q - p, r - p)
        normals /= np.linalg.norm(normals, axis=1)[:, None]
        keys = list(range(len(planes), len(planes) + len(corners)))
        for key, corner, normal, origin in zip(keys, corners, normals, p):
            faces[key], planes[key] = corner, (normal, float(normal @ origin))
            for i in range(3):
                edges[corner[i], corner[(i + 1) % 3]] = key
        return keys

    def assign(candidates, keys):
        if not len(candidates) or not keys:
            return
        normals = np.array([planes[k][0] for k in keys])
        offsets = np.array([planes[k][1] for k in keys])
        distance = points[candidates] @ normals.T - offsets
        best = np.argmax(distance, axis=1)
        outside = distance[np.arange(len(candidates)), best] > eps
        for j, key in enumerate(keys):
            conflicts[key] = candidates[outside & (best == j)]

    # The start: a tetrahedron of far-apart points, counter-clockwise from outside.
    a = int(np.argmax(points @ np.array([1.0, 0.318309886, 0.141421356])))
    b = int(np.argmax(np.linalg.norm(points - points[a], axis=1)))
    c = int(np.argmax(np.linalg.norm(np.cross(points - points[a], points[b] - points[a]), axis=1)))
    normal = np.cross(points[b] - points[a], points[c] - points[a])
    d = int(np.argmax(np.abs((points - points[a]) @ normal)))
    if (points[d] - points[a]) @ normal > 0:
        b, c = c, b
    start = add_faces([(a, b, c), (a, d, b), (b, d, c), (c, d, a)])
    assign(np.arange(len(points)), start)
    todo = list(start)
    while todo:
        key = todo.pop()
        if key not in faces or not len(conflicts.get(key, ())):
            continue
        eye = int(conflicts[key][np.argmax(points[conflicts[key]] @ planes[key][0])])
        visible, queue = {key}, [key]
        while queue:                      # the faces the eye sees: a connected cap
            corner = faces[queue.pop()]
            for i in range(3):
                other = edges[corner[(i + 1) % 3], corner[i]]
                if other not in visible and points[eye] @ planes[other][0] - planes[other][1] > eps:
                    visible.add(other)
                    queue.append(other)
        horizon = [(f[i], f[(i + 1) % 3]) for k in visible for f in [faces[k]] for i in range(3)
                   if edges[f[(i + 1) % 3], f[i]] not in visible]
        orphans = np.concatenate([conflicts.pop(k, np.zeros(0, dtype=np.int64)) for k in visible])
        for k in visible:
            corner = faces.pop(k)
            for i in range(3):
                del edges[corner[i], corner[(i + 1) % 3]]
        new = add_faces([(p, q, eye) for p, q in horizon])
        assign(orphans[orphans != eye], new)
        todo.extend(new)
    around: Dict[int, List[np.ndarray]] = {}
    for key, corner in faces.items():
        for vertex in corner:
            around.setdefault(vertex, []).append(planes[key][0])
    return points[[v for v in sorted(around)
                   if np.linalg.matrix_rank(np.array(around[v]), tol=1e-7) == 3]]
