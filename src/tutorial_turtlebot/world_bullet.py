"""Build a loaded ``World`` (world_sdf) as fixed pybullet bodies. Knows nothing of ROS.

Every collision shape becomes one fixed body that also carries its visual twin's colour, so
contacts, rays and cameras all see it; a visual without a collision twin becomes a body that
cameras see and rays and contacts pass through. Dynamic (non-static) models are fixed too: the
TurtleBot3 worlds have none.

Units: metres; poses in the world frame (z up), as in world_sdf.
"""
from typing import Dict, List, Sequence, Tuple

import pybullet

from .errors import WorldError
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
    for shape in world.collisions:
        bodies[shape.name] = _body(shape, client_id, collide=True)
    for shape in world.visuals:
        if shape.twin is None:
            bodies[shape.name] = _body(shape, client_id, collide=False)
    return bodies


def _body(shape: Shape, cid: int, collide: bool) -> int:
    """One fixed body for ``shape``: collision and visual geometry, or visual only."""
    pieces = _pieces(shape, cid, collide)
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


def _pieces(shape: Shape, cid: int, collide: bool) -> List[Tuple[int, int]]:
    """(collision shape id or -1, visual shape id) per convex piece of ``shape``, in its frame."""
    rgba = shape.rgba
    if shape.kind == "polyline":
        polygons = [shape.points] if _is_convex(shape.points) else _triangulate(shape)
        return [_prism(polygon, shape.size[0], rgba, cid, collide) for polygon in polygons]
    kind = {"box": pybullet.GEOM_BOX, "cylinder": pybullet.GEOM_CYLINDER,
            "sphere": pybullet.GEOM_SPHERE, "plane": pybullet.GEOM_BOX}[shape.kind]
    if shape.kind == "box":
        col_args = vis_args = {"halfExtents": [s / 2 for s in shape.size]}
    elif shape.kind == "cylinder":
        col_args = {"radius": shape.size[0], "height": shape.size[1]}
        vis_args = {"radius": shape.size[0], "length": shape.size[1]}
    elif shape.kind == "sphere":
        col_args = vis_args = {"radius": shape.size[0]}
    else:
        half = PLANE_THICKNESS / 2
        col_args = {"halfExtents": [max(s, PLANE_MIN_EXTENT) / 2 for s in shape.size] + [half],
                    "collisionFramePosition": (0, 0, -half)}
        vis_args = {"halfExtents": [s / 2 for s in shape.size] + [half],
                    "visualFramePosition": (0, 0, -half)}
    col = pybullet.createCollisionShape(kind, physicsClientId=cid, **col_args) if collide else -1
    vis = pybullet.createVisualShape(kind, rgbaColor=rgba, physicsClientId=cid, **vis_args)
    return [(col, vis)]


def _prism(polygon: Sequence[Point], height: float, rgba, cid: int,
           collide: bool) -> Tuple[int, int]:
    """A convex counter-clockwise polygon extruded from z 0 to ``height``: a convex-hull collision
    shape (pybullet inflates it by its 1 mm collision margin) and a flat-shaded triangle mesh of
    the same solid."""
    bottom = [(x, y, 0.0) for x, y in polygon]
    top = [(x, y, height) for x, y in polygon]
    col = (pybullet.createCollisionShape(pybullet.GEOM_MESH, vertices=bottom + top,
                                         physicsClientId=cid) if collide else -1)
    vertices, normals, indices = [], [], []

    def face(corners, normal):
        first = len(vertices)
        vertices.extend(corners)
        normals.extend([normal] * len(corners))
        for i in range(1, len(corners) - 1):            # a fan, counter-clockwise from outside
            indices.extend((first, first + i, first + i + 1))

    face(top, (0.0, 0.0, 1.0))
    face(bottom[::-1], (0.0, 0.0, -1.0))
    n = len(polygon)
    for i in range(n):
        (x0, y0), (x1, y1) = polygon[i], polygon[(i + 1) % n]
        length = ((x1 - x0) ** 2 + (y1 - y0) ** 2) ** 0.5
        face([bottom[i], bottom[(i + 1) % n], top[(i + 1) % n], top[i]],
             ((y1 - y0) / length, (x0 - x1) / length, 0.0))
    vis = pybullet.createVisualShape(pybullet.GEOM_MESH, vertices=vertices, normals=normals,
                                     indices=indices, rgbaColor=rgba, physicsClientId=cid)
    return col, vis


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
