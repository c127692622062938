"""Refuse a spawn pose that puts the robot inside an obstacle. Knows nothing of ROS or pybullet.

The robot is taken as an upright cylinder about its spawn point: ``footprint_radius`` wide, from
``FLOOR_CLEARANCE`` above the floor up to ``height``. A world's collision shapes (``world_sdf``)
that overlap that cylinder are obstacles; planes are floors and never are. Shapes whose axis
stands upright (every shape of this package's worlds) are measured exactly in plan; a tilted one
is measured at a few heights of the cylinder's axis (close, not exact). A mesh is measured
against the plan view of its triangles that reach into the cylinder's heights (whole triangles,
so a sloping face can count as a little nearer than it is), and the point is inside it when a ray
from the cylinder's axis crosses its surface an odd number of times.

Units: metres, in the world frame (z up), as in world_sdf.
"""
import math
import os
from typing import Iterable, Optional, Sequence, Tuple

import numpy as np

from ...errors import WorldError
from ..kinematics import cross_2d, matrix_from_rpy
from ..files.mesh_file import load_mesh
from ..files.world_sdf import Shape, World

FLOOR_CLEARANCE = 0.01   # m: shapes entirely below this are floor coverings the robot drives on
DEFAULT_HEIGHT = 0.2     # m: the top of the robot (burger 0.192, waffle 0.141, above the floor)
TILTED_SAMPLES = 21      # heights at which a tilted shape is measured
MAX_STEP = 0.05          # m: a shape whose top is at most this above a robot's base is a floor
                         # it is put on (resting_height); a TurtleBot3 wheel's radius is 0.033
MAX_STEPS = 4            # raised floors stacked on each other that resting_height climbs

Point = Tuple[float, float]


def check_spawn(world: World, x: float, y: float, footprint_radius: float, z: float = 0.0,
                height: float = DEFAULT_HEIGHT) -> None:
    """Raise WorldError (one line naming the pose and the obstacle) if a robot of
    ``footprint_radius`` (m) spawned with base_footprint at (x, y, z) would stand inside or
    overlap one of ``world``'s collision shapes; return None if it stands clear."""
    hit = find_obstacle(world, x, y, footprint_radius, z, height)
    if hit is None:
        return
    shape, distance = hit
    where = "spawn (%s, %s)" % (_number(x), _number(y))
    world_file = os.path.basename(world.path)
    if distance <= 0.0:
        raise WorldError("%s is inside %s (%s): choose another x_pos, y_pos"
                         % (where, shape.name, world_file))
    raise WorldError("%s is %.3f m from %s (%s): a robot of footprint radius %.3f m would stand "
                     "in it: choose another x_pos, y_pos"
                     % (where, distance, shape.name, world_file, footprint_radius))


def resting_height(world: World, x: float, y: float, footprint_radius: float, z: float = 0.0,
                   height: float = DEFAULT_HEIGHT) -> float:
    """The z at which a robot spawned at (x, y, z) stands: ``z``, or the top of a raised floor
    under it. A shape in the robot's footprint whose top there is at most MAX_STEP above its
    base is such a floor (a platform, a floor mesh a little above 0): the robot is put on it,
    as Gazebo's physics would push a robot spawned into it up onto it. Higher shapes stay
    obstacles for check_spawn."""
    for _ in range(MAX_STEPS):
        hit = find_obstacle(world, x, y, footprint_radius, z, height)
        if hit is None:
            return z
        top = _top_near(hit[0], x, y, footprint_radius)
        if top is None or not z < top <= z + MAX_STEP:
            return z
        z = top
    return z


def _top_near(shape: Shape, x: float, y: float, radius: float) -> Optional[float]:
    """The highest z of ``shape`` within ``radius`` of (x, y) in plan: exact for an upright
    primitive, whole triangles for a mesh; None for a tilted primitive (not a floor)."""
    rotation = matrix_from_rpy(*shape.pose[3:])
    centre = np.array(shape.pose[:3])
    if shape.kind == "mesh":
        mesh = load_mesh(shape.mesh, shape.size)
        triangles = (mesh.vertices @ rotation.T + centre)[mesh.faces]
        near = _plan_triangle_distances(triangles[:, :, :2], np.array((x, y))) <= radius
        return float(triangles[near][:, :, 2].max()) if near.any() else None
    if abs(abs(rotation[2, 2]) - 1.0) > 1e-9:
        return None
    low, high = _local_z_range(shape)
    return float(max(centre[2] + rotation[2, 2] * low, centre[2] + rotation[2, 2] * high))


def find_obstacle(world: World, x: float, y: float, footprint_radius: float, z: float = 0.0,
                  height: float = DEFAULT_HEIGHT) -> Optional[Tuple[Shape, float]]:
    """The nearest collision shape within ``footprint_radius`` of (x, y) in plan, over the
    heights z + FLOOR_CLEARANCE .. z + height, with its distance (m; <= 0 when (x, y) is inside
    it); None if there is none."""
    if not footprint_radius >= 0.0 or not height > FLOOR_CLEARANCE:
        raise ValueError("footprint_radius must be >= 0 and height > %g m" % FLOOR_CLEARANCE)
    band = (z + FLOOR_CLEARANCE, z + height)
    best = None
    for shape in world.collisions:
        if shape.kind == "plane" or _mesh_farther(shape, x, y, footprint_radius):
            continue
        distance = plan_distance(shape, x, y, band)
        if distance is not None and distance < footprint_radius:
            if best is None or distance < best[1]:
                best = (shape, distance)
    return best


def _mesh_farther(shape: Shape, x: float, y: float, radius: float) -> bool:
    """Whether a mesh shape lies wholly farther than ``radius`` (m) from (x, y) in plan: its
    vertices' sphere around the mesh frame's origin does (a cheap test before the exact one)."""
    if shape.kind != "mesh":
        return False
    reach = float(np.sqrt((load_mesh(shape.mesh, shape.size).vertices ** 2).sum(axis=1).max()))
    return math.hypot(shape.pose[0] - x, shape.pose[1] - y) - reach >= radius


def plan_distance(shape: Shape, x: float, y: float, band: Tuple[float, float]) -> Optional[float]:
    """Horizontal distance (m) from the vertical line through (x, y) to ``shape`` within the
    heights ``band`` (negative inside it); None if the shape lies wholly above or below."""
    rotation = matrix_from_rpy(*shape.pose[3:])
    centre = np.array(shape.pose[:3])
    if shape.kind == "mesh":
        mesh = load_mesh(shape.mesh, shape.size)
        return _mesh_distance((mesh.vertices @ rotation.T + centre)[mesh.faces], x, y, band)
    axis_z = rotation[2, 2]
    if abs(abs(axis_z) - 1.0) > 1e-9:
        return _sampled_distance(shape, rotation, centre, x, y, band)
    low, high = _local_z_range(shape)
    z0, z1 = sorted((centre[2] + axis_z * low, centre[2] + axis_z * high))
    if z1 <= band[0] or z0 >= band[1]:
        return None
    local = rotation.T @ (np.array((x, y, centre[2])) - centre)
    lx, ly = float(local[0]), float(local[1])
    if shape.kind == "box":
        return _rectangle_distance(lx, ly, shape.size[0] / 2, shape.size[1] / 2)
    if shape.kind == "cylinder":
        return math.hypot(lx, ly) - shape.size[0]
    if shape.kind == "sphere":
        nearest = min(max(centre[2], band[0]), band[1])          # the widest slice in the band
        radius = math.sqrt(max(shape.size[0] ** 2 - (nearest - centre[2]) ** 2, 0.0))
        return math.hypot(lx, ly) - radius
    return _polygon_distance(lx, ly, shape.points)


def _local_z_range(shape: Shape) -> Tuple[float, float]:
    if shape.kind == "box":
        return -shape.size[2] / 2, shape.size[2] / 2
    if shape.kind == "cylinder":
        return -shape.size[1] / 2, shape.size[1] / 2
    if shape.kind == "sphere":
        return -shape.size[0], shape.size[0]
    return 0.0, shape.size[0]                                   # polyline: extruded up from 0


def _sampled_distance(shape: Shape, rotation, centre, x: float, y: float,
                      band: Tuple[float, float]) -> float:
    """A tilted shape: the least 3D distance from points along the vertical segment at (x, y)
    within ``band`` to the shape (negative inside)."""
    best = math.inf
    for z in np.linspace(band[0], band[1], TILTED_SAMPLES):
        local = rotation.T @ (np.array((x, y, z)) - centre)
        best = min(best, _point_distance(shape, *(float(v) for v in local)))
    return best


def _point_distance(shape: Shape, lx: float, ly: float, lz: float) -> float:
    """Signed 3D distance from a point (in the shape's frame) to the shape."""
    if shape.kind == "box":
        half = np.array(shape.size) / 2
        q = np.abs((lx, ly, lz)) - half
        return float(np.linalg.norm(np.maximum(q, 0.0)) + min(q.max(), 0.0))
    if shape.kind == "cylinder":
        radial = math.hypot(lx, ly) - shape.size[0]
        axial = abs(lz) - shape.size[1] / 2
        return math.hypot(max(radial, 0.0), max(axial, 0.0)) + min(max(radial, axial), 0.0)
    if shape.kind == "sphere":
        return math.sqrt(lx * lx + ly * ly + lz * lz) - shape.size[0]
    plan = _polygon_distance(lx, ly, shape.points)             # polyline prism, z 0..height
    vertical = max(-lz, lz - shape.size[0])
    return math.hypot(max(plan, 0.0), max(vertical, 0.0)) + min(max(plan, vertical), 0.0)


def _mesh_distance(triangles: np.ndarray, x: float, y: float,
                   band: Tuple[float, float]) -> Optional[float]:
    """Plan distance from (x, y) to the (M, 3, 3) world-frame ``triangles`` that reach into the
    heights ``band`` (negative inside the closed surface); None if none does."""
    z = triangles[:, :, 2]
    near = triangles[(z.max(axis=1) > band[0]) & (z.min(axis=1) < band[1])]
    if not len(near):
        return None
    distance = float(_plan_triangle_distances(near[:, :, :2], np.array((x, y))).min())
    inside = _crossings(triangles, np.array((x, y, (band[0] + band[1]) / 2))) % 2 == 1
    return -distance if inside else distance


def _plan_triangle_distances(tri: np.ndarray, p: np.ndarray) -> np.ndarray:
    """Distance from the point ``p`` to each (M, 3, 2) triangle in the plane (0 inside one)."""
    a, b, c = tri[:, 0], tri[:, 1], tri[:, 2]
    best = np.full(len(tri), np.inf)
    for u, v in ((a, b), (b, c), (c, a)):
        edge = v - u
        length2 = np.einsum("ij,ij->i", edge, edge)
        t = np.clip(np.einsum("ij,ij->i", p - u, edge) / np.where(length2 > 0, length2, 1.0),
                    0.0, 1.0)
        best = np.minimum(best, np.linalg.norm(u + edge * t[:, None] - p, axis=1))
    cross = [cross_2d(u.T, v.T, p) for u, v in ((a, b), (b, c), (c, a))]
    area = cross_2d(a.T, b.T, c.T)
    inside = (np.abs(area) > 1e-12) & (
        ((cross[0] >= 0) & (cross[1] >= 0) & (cross[2] >= 0))
        | ((cross[0] <= 0) & (cross[1] <= 0) & (cross[2] <= 0)))
    return np.where(inside, 0.0, best)


def _crossings(tri: np.ndarray, origin: np.ndarray) -> int:
    """How many of the (M, 3, 3) triangles a ray from ``origin`` along +x (tilted a hair off
    the axes, so that it misses edges and corners) crosses (Moller-Trumbore)."""
    direction = np.array((1.0, 1.3e-7, 0.7e-7))
    e1, e2 = tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]
    h = np.cross(direction, e2)
    det = np.einsum("ij,ij->i", e1, h)
    ok = np.abs(det) > 1e-14
    inv = np.where(ok, 1.0 / np.where(ok, det, 1.0), 0.0)
    s = origin - tri[:, 0]
    u = np.einsum("ij,ij->i", s, h) * inv
    q = np.cross(s, e1)
    v = (q @ direction) * inv
    t = np.einsum("ij,ij->i", e2, q) * inv
    return int(np.count_nonzero(ok & (u >= 0) & (v >= 0) & (u + v <= 1) & (t > 0)))


def _rectangle_distance(px: float, py: float, half_x: float, half_y: float) -> float:
    qx, qy = abs(px) - half_x, abs(py) - half_y
    return math.hypot(max(qx, 0.0), max(qy, 0.0)) + min(max(qx, qy), 0.0)


def _polygon_distance(px: float, py: float, points: Sequence[Point]) -> float:
    """Signed distance to a simple polygon: negative inside."""
    distance = min(_segment_distance(px, py, a, b) for a, b in _edges(points))
    return -distance if _inside(px, py, points) else distance


def _edges(points: Sequence[Point]) -> Iterable[Tuple[Point, Point]]:
    return ((points[i - 1], points[i]) for i in range(len(points)))


def _segment_distance(px: float, py: float, a: Point, b: Point) -> float:
    dx, dy = b[0] - a[0], b[1] - a[1]
    length2 = dx * dx + dy * dy
    t = 0.0 if length2 == 0 else max(0.0, min(1.0, ((px - a[0]) * dx + (py - a[1]) * dy) / length2))
    return math.hypot(px - a[0] - t * dx, py - a[1] - t * dy)


def _inside(px: float, py: float, points: Sequence[Point]) -> bool:
    inside = False
    for (x0, y0), (x1, y1) in _edges(points):
        if (y0 > py) != (y1 > py) and px < x0 + (py - y0) * (x1 - x0) / (y1 - y0):
            inside = not inside
    return inside


def footprint_radius(description) -> float:
    """Radius (m) of the smallest circle about base_footprint (the root link of a
    ``urdf_file.RobotDescription``) that holds every collision shape of the robot in plan."""
    root = description.root_link
    radius = 0.0
    for name, link in description.links.items():
        for collision in link.collisions:
            pose = description.transform(root, name) @ collision.origin.matrix()
            radius = max(radius, _shape_reach(collision.geometry, pose))
    return radius


def _shape_reach(geometry, pose) -> float:
    """The farthest any point of ``geometry`` (placed by the 4x4 ``pose``) lies from the z axis."""
    shape, size = geometry.shape, geometry.size
    if shape == "sphere":
        return math.hypot(*pose[:2, 3]) + size[0]
    if shape == "box":
        corners = [(sx * size[0] / 2, sy * size[1] / 2, sz * size[2] / 2)
                   for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]
    elif shape == "cylinder":
        radius, length = size
        corners = [(radius * math.cos(a), radius * math.sin(a), sz * length / 2)
                   for a in np.linspace(0.0, 2 * math.pi, 32, endpoint=False) for sz in (-1, 1)]
    else:                                    # a mesh: its corners, scaled by ``size``
        corners = load_mesh(geometry.filename, size).vertices
    points = pose[:3, :3] @ np.array(corners).T + pose[:3, 3:4]
    return float(np.max(np.hypot(points[0], points[1])))


def _number(value: float) -> str:
    """-1.1 -> '-1.1', 0 -> '0.0', 0.2454 -> '0.245'."""
    return repr(round(float(value), 3) + 0.0)
