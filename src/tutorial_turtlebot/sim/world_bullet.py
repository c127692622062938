"""Build a loaded ``World`` (world_sdf) as fixed pybullet bodies. Knows nothing of ROS.

Every collision shape becomes one fixed body that also carries its visual twin's colour, so
contacts, rays and cameras all see it; a visual without a collision twin becomes a body that
cameras see and rays and contacts pass through. Dynamic (non-static) models are fixed too: the
TurtleBot3 worlds have none.

Units: metres; poses in the world frame (z up), as in world_sdf.
"""
import os
import tempfile
from typing import Dict, List, Sequence, Tuple


from .bullet import pybullet
from ..errors import WorldError
from .world_sdf import Shape, World

# World bodies are in collision group 4. A laser that must see the world only casts rays with
# collisionFilterMask=WORLD_COLLISION_GROUP, and other bodies (the robot) use another group.
# Bullet also tests the ray's own group (1) against a body's mask, so the mask keeps bit 1; it
# drops the world's own bit, so that static bodies never test each other (wasted work every step).
WORLD_COLLISION_GROUP = 4
WORLD_COLLISION_MASK = 0xFFFF & ~WORLD_COLLISION_GROUP

WORLD_FRICTION = 1.0        # lateral friction coefficient of every world surface
WORLD_RESTITUTION = 0.0

# A plane is a thin box with its top face on the plane (pybullet's EGL renderer crashed on
# GEOM_PLANE). Its collision box is at least PLANE_MIN_EXTENT square, as Gazebo's plane collision
# is unbounded; its visual keeps the SDF size.
PLANE_THICKNESS = 0.05      # m
PLANE_MIN_EXTENT = 100.0    # m

Point = Tuple[float, float]


def build_world(world: World, client_id: int) -> Dict[str, int]:
    """Create the world's bodies in pybullet client ``client_id``.

    Returns shape name -> body id, for every collision shape and every visual without a twin.
    A polyline that is not convex is one body whose extra pieces are links of that body.
    """
    bodies = {}
    # Box, plane and polyline visuals are mesh files, read when their body is created.
    with tempfile.TemporaryDirectory(prefix="tutorial_turtlebot_meshes_") as mesh_dir:
        for shape in world.collisions:
            bodies[shape.name] = _body(shape, client_id, mesh_dir, collide=True)
        for shape in world.visuals:
            if shape.twin is None:
                bodies[shape.name] = _body(shape, client_id, mesh_dir, collide=False)
    return bodies


def _body(shape: Shape, cid: int, mesh_dir: str, collide: bool) -> int:
    """One fixed body for ``shape``: collision and visual geometry, or visual only."""
    pieces = _pieces(shape, cid, mesh_dir, collide)
    (base_col, base_vis), links = pieces[0], pieces[1:]
    orientation = pybullet.getQuaternionFromEuler(shape.pose[3:], physicsClientId=cid)
    body = pybullet.createMultiBody(
        baseMass=0.0, baseCollisionShapeIndex=base_col, baseVisualShapeIndex=base_vis,
        basePosition=shape.pose[:3], baseOrientation=orientation,
        linkMasses=[0.0] * len(links),
        linkCollisionShapeIndices=[c for c, _ in links],
        linkVisualShapeIndices=[v for _, v in links],
        linkPositions=[(0, 0, 0)] * len(links), linkOrientations=[(0, 0, 0, 1)] * len(links),
        linkInertialFramePositions=[(0, 0, 0)] * len(links),
        linkInertialFrameOrientations=[(0, 0, 0, 1)] * len(links),
        linkParentIndices=[0] * len(links), linkJointTypes=[pybullet.JOINT_FIXED] * len(links),
        linkJointAxis=[(0, 0, 1)] * len(links), physicsClientId=cid)
    if body < 0:
        raise WorldError("%s: pybullet could not build %s" % (shape.name, shape.kind))
    for link in range(-1, len(links)) if collide else ():
        pybullet.setCollisionFilterGroupMask(body, link, WORLD_COLLISION_GROUP,
                                             WORLD_COLLISION_MASK, physicsClientId=cid)
        pybullet.changeDynamics(body, link, lateralFriction=WORLD_FRICTION,
                                restitution=WORLD_RESTITUTION, physicsClientId=cid)
    return body


def _pieces(shape: Shape, cid: int, mesh_dir: str, collide: bool) -> List[Tuple[int, int]]:
    """(collision shape id or -1, visual shape id) per convex piece of ``shape``, in its frame.

    Box and plane visuals are mesh files too (``_mesh_visual``): pybullet's EGL renderer
    tessellates a GEOM_BOX through a convex hull that flattens a box about 800 times wider than
    thick (the 100 m ground, 5 cm thick) into its middle plane, with one triangle missing.
    """
    rgba = shape.rgba
    if shape.kind == "polyline":
        polygons = [shape.points] if _is_convex(shape.points) else _triangulate(shape)
        return [_prism(polygon, shape.size[0], rgba, cid, mesh_dir, collide)
                for polygon in polygons]
    if shape.kind in ("box", "plane"):
        if shape.kind == "box":
            half = [s / 2 for s in shape.size]
            col_args = {"halfExtents": half}
            z_range = (-half[2], half[2])
        else:
            half = [s / 2 for s in shape.size] + [PLANE_THICKNESS / 2]
            col_args = {"halfExtents": [max(s, PLANE_MIN_EXTENT) / 2 for s in shape.size]
                        + [half[2]], "collisionFramePosition": (0, 0, -half[2])}
            z_range = (-PLANE_THICKNESS, 0.0)
        col = (pybullet.createCollisionShape(pybullet.GEOM_BOX, physicsClientId=cid, **col_args)
               if collide else -1)
        hx, hy = half[0], half[1]
        rectangle = [(-hx, -hy), (hx, -hy), (hx, hy), (-hx, hy)]
        return [(col, _mesh_visual(rectangle, *z_range, rgba, cid, mesh_dir))]
    kind = {"cylinder": pybullet.GEOM_CYLINDER, "sphere": pybullet.GEOM_SPHERE}[shape.kind]
    if shape.kind == "cylinder":
        col_args = {"radius": shape.size[0], "height": shape.size[1]}
        vis_args = {"radius": shape.size[0], "length": shape.size[1]}
    else:
        col_args = vis_args = {"radius": shape.size[0]}
    col = pybullet.createCollisionShape(kind, physicsClientId=cid, **col_args) if collide else -1
    vis = pybullet.createVisualShape(kind, rgbaColor=rgba, physicsClientId=cid, **vis_args)
    return [(col, vis)]


def _prism(polygon: Sequence[Point], height: float, rgba, cid: int, mesh_dir: str,
           collide: bool) -> Tuple[int, int]:
    """A convex counter-clockwise polygon extruded from z 0 to ``height``: a convex-hull collision
    shape (pybullet inflates it by its 1 mm collision margin) and a flat-shaded visual mesh of the
    same solid."""
    corners = [(x, y, z) for z in (0.0, height) for x, y in polygon]
    col = (pybullet.createCollisionShape(pybullet.GEOM_MESH, vertices=corners,
                                         physicsClientId=cid) if collide else -1)
    return col, _mesh_visual(polygon, 0.0, height, rgba, cid, mesh_dir)


def _mesh_visual(polygon: Sequence[Point], z0: float, z1: float, rgba, cid: int,
                 mesh_dir: str) -> int:
    """Visual shape of a convex counter-clockwise polygon extruded from ``z0`` to ``z1``,
    flat-shaded, written as a Wavefront file in ``mesh_dir`` (read when its body is created).

    A file, because pybullet's EGL renderer draws no mesh given as vertex lists, and flattens
    thin boxes; both renderers draw a file as it is.
    """
    n = len(polygon)
    normals = [(0.0, 0.0, 1.0), (0.0, 0.0, -1.0)]
    for i in range(n):
        (x0, y0), (x1, y1) = polygon[i], polygon[(i + 1) % n]
        length = ((x1 - x0) ** 2 + (y1 - y0) ** 2) ** 0.5
        normals.append(((y1 - y0) / length, (x0 - x1) / length, 0.0))
    # .obj indices count from 1: bottom corners 1..n, top corners n+1..2n; normal 1 up, 2 down,
    # 3+i the side from corner i to corner i+1. Faces are counter-clockwise seen from outside.
    faces = [[(n + 1 + i, 1) for i in range(n)], [(1 + i, 2) for i in reversed(range(n))]]
    for i in range(n):
        j = (i + 1) % n
        faces.append([(1 + i, 3 + i), (1 + j, 3 + i), (n + 1 + j, 3 + i), (n + 1 + i, 3 + i)])
    lines = ["v %.9g %.9g %.9g" % (x, y, z) for z in (z0, z1) for x, y in polygon]
    lines += ["vn %.9g %.9g %.9g" % v for v in normals]
    lines += ["f " + " ".join("%d//%d" % corner for corner in face) for face in faces]
    fd, path = tempfile.mkstemp(suffix=".obj", prefix="visual_", dir=mesh_dir)
    with os.fdopen(fd, "w") as f:
        f.write("\n".join(lines) + "\n")
    return pybullet.createVisualShape(pybullet.GEOM_MESH, fileName=path, rgbaColor=rgba,
                                      physicsClientId=cid)


def _cross(o: Point, a: Point, b: Point) -> float:
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])


def _is_convex(polygon: Sequence[Point]) -> bool:
    """Whether a counter-clockwise polygon turns left at every corner."""
    n = len(polygon)
    return all(_cross(polygon[i - 1], polygon[i], polygon[(i + 1) % n]) > 0 for i in range(n))


def _triangulate(shape: Shape) -> List[Tuple[Point, Point, Point]]:
    """Ear clipping of a polyline's simple counter-clockwise polygon into counter-clockwise
    triangles."""
    remaining = list(shape.points)
    triangles = []
    while len(remaining) > 3:
        n = len(remaining)
        for i in range(n):
            a, b, c = remaining[i - 1], remaining[i], remaining[(i + 1) % n]
            if _cross(a, b, c) <= 0:
                continue                                  # a reflex corner is no ear
            others = (p for p in remaining if p not in (a, b, c))
            if any(_cross(a, b, p) >= 0 and _cross(b, c, p) >= 0 and _cross(c, a, p) >= 0
                   for p in others):
                continue                                  # another corner lies inside
            triangles.append((a, b, c))
            del remaining[i]
            break
        else:
            raise WorldError("%s: its polyline cannot be split into triangles" % shape.name)
    triangles.append(tuple(remaining))
    return triangles
