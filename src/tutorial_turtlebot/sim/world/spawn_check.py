"""Where a robot spawned or teleported stands, and what it overlaps there, as Gazebo has it.

Gazebo refuses no spawn for overlap: it puts a robot where it is asked to and lets the contacts
push it out. Here a robot asked to stand below the floor under it, or inside a solid floor,
is put on top of that floor at once (``landed_pose``: its spawn, spawn_model, set_model_state,
set_link_state), and a robot that overlaps a model where it stands is spawned all the same,
with one warning (``overlap_warning``).

**The landing rule.** The robot is measured by its URDF's collision geometry, turned as asked:
its top (m above its root link, base_footprint on a TurtleBot3) and its reach (m from the root's
vertical axis, in plan). Rays are cast straight down (pybullet's, on the world's collision
geometry as it is: boxes, cylinders, planes, polylines, meshes open or closed) at the root's
(x, y) and at points on two circles about it (the reach, and half of it), from the robot's top
at the requested pose down (on to BURIED_DEPTH below the requested z). The highest static
surface they meet is the floor under the robot: if it lies more than LIFT_TOLERANCE above the
requested z, the root link is put on it (same x, y and orientation); otherwise the pose is kept
as given (a robot above the floor falls, as in Gazebo). So a surface counts only if it is below
the robot's own top at the requested pose: a table top, a shelf, anything above the robot's head
is never climbed onto (the robot stands under it). Movable models and other robots are no floor
(the rays pass them by).

**Inside a solid floor.** A floor higher than the robot itself (a 0.19 m floor box under a
Waffle, 0.141 m tall, asked for z 0) holds the robot's whole body, and rays cast from inside a
solid meet none of its faces. Where the rays above found no floor to lift onto, the robot's
vertical span is probed at each footprint point: from SOLID_INSET above its root to SOLID_INSET
below its top, both ends must lie inside one and the same static solid collider (``solids_at``:
a box, cylinder, sphere, a polyline's convex piece, or the side of a plane below its surface),
and so, the solid being convex, the whole span between. Then rays cast down from BURIED_DEPTH
above the requested z to the probed top meet the solid's top in every column, the lowest surface
of each; the root link is put on the highest of them. Either one solid holds every column, or
the tops differ by at most TILE_STEP (a floor of tiles): a footprint held by a floor and a wall
beside it is an overlap. A solid that holds the whole footprint is stood on however high (a
pillar wider than the robot, a wall thick enough). Under a table top, over the robot's head or
lower than its top (a low bench), the root's end is in open space; a stage edge or a table leg
holds only some of the footprint's columns: none is lifted, and the overlap warning below
proposes the top as z_pos. A static mesh is triangles only (a closed one could as well be a room
as a solid), so a robot inside one is never taken as buried.

**Under the ground.** When the rays meet nothing at all from the robot's top down to
BURIED_DEPTH below the requested z, the robot has no floor below it: it stands under a world's
ground (a terrain mesh with no ground plane beneath, 0.3 m above the requested z, say) and
would fall for ever. Then it is put on the lowest static surface above it that rays cast down
from BURIED_DEPTH above the requested z meet (a mesh's triangles count from either side), the
highest such over its footprint; where there is none either, the pose is kept.

**Overlap.** Once the robot is placed: Bullet's closest points between its body and every other
body near it. A penetration deeper than OVERLAP_DEPTH (a TurtleBot3's caster dips 5 mm below its
wheels into the floor it stands on) is an overlap, named in one line with the model and a
``z_pos`` that stands the robot on top of it. A robot wholly inside a closed mesh touches none
of its triangles: neither Gazebo nor this sim pushes it out, and no warning is given.

``find_obstacle`` measures a world file's shapes in plan, without physics, for tests and tools
that look for a clear spot; the sim refuses nothing with it.

Units: metres, radians, in the world frame (z up) unless a docstring says otherwise.
"""
import math
from typing import Callable, Iterable, Optional, Sequence, Tuple

import numpy as np

from ..kinematics import Pose, cross_2d, matrix_from_rpy, rotation_matrix
from ..files.meshes.mesh_file import load_mesh
from ..files.world_types import Shape, World

LIFT_TOLERANCE = 0.001   # m: a floor at most this above the requested z leaves the pose as given
SOLID_INSET = 0.001      # m: a buried robot's span is probed this far inside its root and top
TILE_STEP = 0.01         # m: solids whose tops differ at most this are one floor (its tiles)
BURIED_DEPTH = 100.0     # m: nothing this far below a robot: it is under the ground (see above)
OVERLAP_DEPTH = 0.01     # m: a penetration at most this deep is no overlap (resting contacts)
RING_POINTS = 12         # rays on each of the two circles about the root (and one at it)
PROPOSAL_MARGIN = 0.01   # m: the rays that find a proposed z_pos start this above the model
MAX_MODEL_NAME = 40      # characters of the model's name in the warning (160 in all at most)
FLOOR_CLEARANCE = 0.01   # m: find_obstacle: shapes wholly below this are floor coverings
DEFAULT_HEIGHT = 0.2     # m: find_obstacle: the robot's top (burger 0.191, waffle 0.141)
TILTED_SAMPLES = 21      # find_obstacle: heights at which a tilted shape is measured

Point = Tuple[float, float]


# --- landing on the floor ----------------------------------------------------------------------

def collision_points(description) -> np.ndarray:
    """(N, 3) points (m, in the root link's frame) outlining every collision shape of a robot
    (urdf_file.RobotDescription): a box's corners, 32 points on each rim of a cylinder, 26 on a
    sphere, a mesh's vertices (scaled)."""
    root = description.root_link
    out = [np.zeros((1, 3))]
    for name, link in description.links.items():
        for collision in link.collisions:
            pose = description.transform(root, name) @ collision.origin.matrix()
            local = _shape_points(collision.geometry)
            out.append(local @ pose[:3, :3].T + pose[:3, 3])
    return np.concatenate(out)


def _shape_points(geometry) -> np.ndarray:
    shape, size = geometry.shape, geometry.size
    if shape == "box":
        return np.array([(sx * size[0] / 2, sy * size[1] / 2, sz * size[2] / 2)
                         for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)])
    if shape == "cylinder":
        radius, length = size
        angles = np.linspace(0.0, 2 * math.pi, 32, endpoint=False)
        return np.array([(radius * math.cos(a), radius * math.sin(a), sz * length / 2)
                         for a in angles for sz in (-1, 1)])
    if shape == "sphere":
        steps = (-1, 0, 1)
        directions = np.array([(i, j, k) for i in steps for j in steps for k in steps
                               if (i, j, k) != (0, 0, 0)], dtype=float)
        return size[0] * directions / np.linalg.norm(directions, axis=1)[:, None]
    return np.asarray(load_mesh(geometry.filename, size).vertices, dtype=float)


def robot_extent(points: np.ndarray, orientation) -> Tuple[float, float]:
    """(top, reach) of a robot's ``collision_points`` turned by ``orientation`` (x, y, z, w):
    its highest point above the root link and its farthest from the root's vertical axis (m)."""
    turned = points @ rotation_matrix(orientation).T
    return float(turned[:, 2].max()), float(np.hypot(turned[:, 0], turned[:, 1]).max())


def footprint_points(x: float, y: float, reach: float) -> np.ndarray:
    """(N, 2) world (x, y) where the rays are cast: the root's and RING_POINTS on each of the
    circles of radius ``reach`` and ``reach`` / 2 about it."""
    angles = np.linspace(0.0, 2 * math.pi, RING_POINTS, endpoint=False)
    ring = np.stack((np.cos(angles), np.sin(angles)), axis=1)
    return np.concatenate(([(x, y)], (x, y) + reach * ring, (x, y) + reach / 2 * ring))


def landed_pose(physics, description, pose: Pose) -> Pose:
    """``pose`` ((x, y, z), quaternion) of a robot's root link, with z raised to the top of
    the floor under the robot where that lies above z, or of the solid floor the robot is
    inside (the landing rule, above); ``pose`` itself where neither is. ``physics``: the
    engine's WorldPhysics."""
    (x, y, z), orientation = pose
    top, reach = robot_extent(collision_points(description), orientation)
    if not top > LIFT_TOLERANCE:
        return pose
    points = footprint_points(x, y, reach)
    # one cast on down to BURIED_DEPTH below z: only a floor above z lifts the robot, and a
    # cast that meets nothing at all says the robot is under the ground
    floors = physics.surfaces_below(points, z + top, z - BURIED_DEPTH)
    if np.all(np.isnan(floors)):
        grounds = physics.surfaces_below(points, z + BURIED_DEPTH, z + top, lowest=True)
        if not np.all(np.isnan(grounds)):          # under the ground: onto it
            return (x, y, float(np.nanmax(grounds))), orientation
        return pose
    floor = float(np.nanmax(floors))
    if floor > z + LIFT_TOLERANCE:
        return (x, y, floor), orientation
    solid_top = buried_floor_top(physics, points, z, top)
    if solid_top is not None:                      # inside a solid floor: onto its top
        return (x, y, solid_top), orientation
    return pose


def buried_floor_top(physics, points: np.ndarray, z: float, top: float) -> Optional[float]:
    """The top (m) of the solid floor that a robot whose root is at z and whose top is ``top``
    above it lies inside over its whole footprint ``points`` ((N, 2) world x, y, the root's
    first), None where it does not (the landing rule, "Inside a solid floor")."""
    low, high = z + SOLID_INSET, z + max(top - SOLID_INSET, SOLID_INSET)

    def held(xy: np.ndarray) -> list:
        """The solid colliders that hold each vertical segment low..high at ``xy``, whole."""
        n = len(xy)
        holders = physics.solids_at(np.concatenate((np.column_stack((xy, np.full(n, low))),
                                                    np.column_stack((xy, np.full(n, high))))))
        return [holders[i] & holders[n + i] for i in range(n)]

    (root,) = held(points[:1])            # the root's column first: most poses end here
    if not root:
        return None
    others = held(points[1:])
    if not all(others):
        return None
    tops = physics.surfaces_below(points, z + BURIED_DEPTH, high, lowest=True)
    if np.any(np.isnan(tops)):
        return None
    if not root.intersection(*others) and np.ptp(tops) > TILE_STEP:
        return None                       # in two solids of other heights: a floor and a wall
    return float(np.max(tops))


# --- overlap -------------------------------------------------------------------------------------

def overlap_warning(physics, body: int, description, pose: Pose,
                    model_of: Callable[[int], Optional[str]]) -> Optional[str]:
    """One line (at most 160 characters) when the robot ``body``, placed at ``pose``, overlaps
    a model (``model_of``: the name of the model a body id belongs to, None for none): the
    deepest, with a z_pos that stands the robot on it; None when it overlaps nothing."""
    for uid, _, depth, model_top in physics.overlaps(body, OVERLAP_DEPTH):
        name = model_of(uid)
        if name is None:
            continue
        (x, y, z), orientation = pose
        _, reach = robot_extent(collision_points(description), orientation)
        tops = physics.surfaces_below(footprint_points(x, y, reach),
                                      model_top + PROPOSAL_MARGIN, z, static_only=False)
        proposal = float(np.nanmax(tops)) if not np.all(np.isnan(tops)) else model_top
        if len(name) > MAX_MODEL_NAME:
            name = name[:MAX_MODEL_NAME - 3] + "..."
        return ("at (%s, %s, %s) it overlaps %s by %.3f m, spawned as Gazebo would: move it, "
                "or give z_pos %.3f to stand on top" % (_number(x), _number(y), _number(z),
                                                        name, depth, proposal))
    return None


def model_of_body(models) -> Callable[[int], Optional[str]]:
    """The name of the model of a ModelRegistry ``models`` that a pybullet body id belongs to
    (None for a body of no model), as a function."""
    owners = {part.body.uid: model.name for model in models.models() for part in model.parts}
    return owners.get


# --- a world file's shapes in plan ---------------------------------------------------------------

def find_obstacle(world: World, x: float, y: float, footprint_radius: float, z: float = 0.0,
                  height: float = DEFAULT_HEIGHT) -> Optional[Tuple[Shape, float]]:
    """The nearest collision shape within ``footprint_radius`` of (x, y) in plan, over the
    heights z + FLOOR_CLEARANCE .. z + height, with its distance (m; <= 0 when (x, y) is inside
    a primitive; a mesh has no inside here: an open mesh has none, so its nearest triangle is
    measured); None if there is none."""
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
    heights ``band`` (negative inside a primitive); None if the shape lies wholly above or
    below."""
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
    heights ``band``; None if none does."""
    z = triangles[:, :, 2]
    near = triangles[(z.max(axis=1) > band[0]) & (z.min(axis=1) < band[1])]
    if not len(near):
        return None
    return float(_plan_triangle_distances(near[:, :, :2], np.array((x, y))).min())


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
