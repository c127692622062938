"""Build a loaded ``World`` (world_sdf) as pybullet bodies. Knows nothing of ROS.

Static models: every collision shape becomes one fixed body that also carries its visual twin
(same geometry and pose), so contacts, rays and cameras all see it; a collision without a twin
is not drawn (cameras see visuals only, as in Gazebo: a collision box around a textured mesh
would hide it); a visual without a collision twin becomes a body that cameras see and rays and
contacts pass through. A static mesh collides with its triangles themselves.
Models that are not ``<static>``: every link becomes one movable rigid body of the link's
``<inertial>`` mass and inertia, holding all its collisions and visuals (box, cylinder, sphere,
mesh) and its collisions' friction; a mesh collides as its convex hull (Bullet's moving bodies
are convex). Its frame is the link's centre of mass (see ``link_com_pose``).
Mesh visuals are drawn part by part, each in its SDF ``<material>`` colour, or where the visual
has none, in the mesh file's own colour of that part, and with its texture where it has one
(obj_writer.write_obj_parts, each image halved as texture_budget says; a texture that cannot
be used leaves the part in its colour, else grey, with one warning). A visual with an SDF
``<material>`` is drawn in that colour alone, textures left out.
A box or plane whose ``<material>`` script has a texture image (world_sdf ``Shape.texture``,
material_scripts) is drawn with it, tinted by its colour, the same way (``_box_visual_file``):
the whole image once across its top face, upright seen from above with +x to the right and +y
up (u along +x, v along +y, as Gazebo maps a plane); a box shows it on each side face too.
A deleted model's bodies parked for reuse (body_pool) are taken back as ``build_world`` would
build them (``reused_world_bodies``, ``place_world_bodies``).

Units: metres; poses in the world frame (z up), as in world_sdf.
"""
import os
import tempfile
from typing import Dict, List, Optional, Sequence, Tuple

import numpy as np

from . import bullet_shapes, collision_filters, texture_budget, view_culling
from ..files import mesh_cache
from .bullet import pybullet
from .client import Client
from .rendering import egl_enabled, note_textures
from ...errors import UserError, WorldError
from ..kinematics import cross_2d, pose_from_xyz_rpy, quat_from_matrix
from ..files.mesh_file import load_mesh
from ..files.mesh_types import Mesh, MeshPart
from ..files.obj_writer import write_obj_parts
from ..files.texture_images import texture_info
from ..files.world_types import Inertial, Link, Shape, World

# World bodies are in collision group 4. A laser that must see the world only casts rays with
# collisionFilterMask=WORLD_COLLISION_GROUP, and other bodies (the robot) use another group.
# Bullet also tests the ray's own group (1) against a body's mask, so the mask keeps bit 1; it
# drops the world's own bit, so that static bodies never test each other (wasted work every step).
# Robots (robot_body.RobotBody) take one bit each of the higher ones, up to
# ALL_COLLISION_GROUPS.
WORLD_COLLISION_GROUP = 4
ALL_COLLISION_GROUPS = (1 << 28) - 1
WORLD_COLLISION_MASK = ALL_COLLISION_GROUPS & ~WORLD_COLLISION_GROUP
# Movable bodies: in the world's group (the laser sees them) and one of their own, which the
# static bodies' mask keeps, so that they rest on the floor and hit walls.
MOVABLE_COLLISION_GROUP = WORLD_COLLISION_GROUP | 8
MOVABLE_COLLISION_MASK = ALL_COLLISION_GROUPS
MOVABLE_KINDS = ("box", "cylinder", "sphere", "mesh")

WORLD_FRICTION = 1.0        # lateral friction coefficient of every world surface
WORLD_RESTITUTION = 0.0

# A plane is a thin box with its top face on the plane (pybullet's EGL renderer crashed on
# GEOM_PLANE). Its collision box is at least PLANE_MIN_EXTENT square, as Gazebo's plane collision
# is unbounded; its visual keeps the SDF size.
PLANE_THICKNESS = 0.05      # m
PLANE_MIN_EXTENT = 100.0    # m

Point = Tuple[float, float]


def build_world(world: World, client: Client,
                warnings: Optional[List[str]] = None) -> Dict[str, int]:
    """Create the world's bodies in pybullet ``client``.

    Returns shape name -> body id, for every collision shape and every visual without a twin of
    a static model (a polyline that is not convex is one body whose extra pieces are links of
    that body), and for every shape of a movable link (all of one link's shapes share its body).
    ``warnings``: where to add one line (at most 200 characters) for each texture that is not
    drawn as its file is, and why (the texture budget halved it, it cannot be read now).
    """
    bodies: Dict[str, int] = {}
    try:
        _plan_textures(world, client, warnings if warnings is not None else [])
        _build(world, client, bodies)
    except BaseException:   # a spawn that cannot be built leaves no body behind
        for body in set(bodies.values()):
            client.removeBody(body)
            collision_filters.forget_body(client, body)
        raise
    return bodies


def _build(world: World, client: Client, bodies: Dict[str, int]) -> None:
    """build_world's work: each body into ``bodies`` as soon as it exists."""
    movable: Dict[str, List[Shape]] = {}
    # Box, plane and polyline visuals are mesh files, read when their body is created.
    with tempfile.TemporaryDirectory(prefix="tutorial_turtlebot_meshes_") as mesh_dir:
        for shape in world.collisions:
            if shape.static:
                bodies[shape.name] = _body(shape, client, mesh_dir, collide=True)
            else:
                movable.setdefault(shape.link, []).append(shape)
        for shape in world.visuals:
            if not shape.static:
                movable.setdefault(shape.link, []).append(shape)
            elif shape.twin is None:
                bodies[shape.name] = _body(shape, client, mesh_dir, collide=False)
        links = {link.scoped: link for model in world.model_specs for link in model.links}
        for scoped, shapes in movable.items():
            body = _movable_body(links[scoped], shapes, client, mesh_dir)
            bodies.update((shape.name, body) for shape in shapes)


def _drawn_textures(shape: Shape) -> List[str]:
    """The texture files a drawn shape is drawn with: its mesh file's own (a mesh visual
    without an SDF <material>, or its collision twin), or its script's image (a box or plane);
    [] if none. A mesh that cannot be read gives [] (its body's building says why)."""
    if shape.kind == "mesh":
        if not shape.mesh_colours:
            return []
        try:
            mesh = load_mesh(shape.mesh, shape.size)
        except UserError:
            return []
        return [p.texture for p in mesh.parts if p.texture is not None]
    if shape.kind in ("box", "plane") and shape.texture is not None:
        return [shape.texture]
    return []


def _plan_textures(world: World, client: Client, warnings: List[str]) -> None:
    """Tell texture_budget the texture images the world's visuals are drawn with (each image
    once, with how many visuals use it), and add to ``warnings`` its line, if it halves any,
    and one line for each texture that cannot be read now (drawn in its colour)."""
    drawn = [s for s in world.collisions if s.static and s.twin is not None]
    drawn += [s for s in world.visuals if not s.static or s.twin is None]
    uses: Dict[str, texture_budget.TextureUse] = {}
    for shape in drawn:
        for texture in _drawn_textures(shape):
            info = texture_info(texture)
            if info is None:
                line = ("%s: texture %s not drawn (its file is no usable image now); drawn in "
                        "its colour" % (shape.name[-80:], os.path.basename(texture)[-60:]))
                if line not in warnings:
                    warnings.append(line)
            elif info.digest in uses:
                uses[info.digest].visuals += 1
            else:
                uses[info.digest] = texture_budget.TextureUse(texture, info.width, info.height)
    if uses:
        line = texture_budget.plan(client, uses, per_visual=not egl_enabled(client))
        if line is not None:
            warnings.append(line)


def link_com_pose(link: Link):
    """World pose ((x, y, z), (qx, qy, qz, qw)) of a movable link's body frame: the centre of
    mass, its axes along the principal axes of inertia."""
    com_in_link = _com_frame(link.inertial)
    return pybullet.multiplyTransforms(*pose_from_xyz_rpy(link.pose), *com_in_link)


def _com_frame(inertial: Inertial):
    """(position, quaternion) of the principal-axes centre-of-mass frame in the link frame, and
    nothing else: see ``_principal``."""
    rotation, _ = _principal(inertial)
    pos, orn = pose_from_xyz_rpy(inertial.pose)
    return pybullet.multiplyTransforms(pos, orn, (0, 0, 0), rotation)


def _principal(inertial: Inertial):
    """(quaternion of the principal axes in the inertial frame, principal moments)."""
    ixx, iyy, izz, ixy, ixz, iyz = inertial.inertia
    if ixy == ixz == iyz == 0.0:
        return (0.0, 0.0, 0.0, 1.0), (ixx, iyy, izz)
    tensor = np.array([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]])
    moments, axes = np.linalg.eigh(tensor)
    if np.linalg.det(axes) < 0:
        axes[:, 2] = -axes[:, 2]
    return quat_from_matrix(axes), tuple(float(m) for m in moments)


def _movable_body(link: Link, shapes: List[Shape], client: Client, mesh_dir: str) -> int:
    """One movable rigid body for ``link``: its collisions and visuals placed around its centre
    of mass, its mass and principal moments of inertia, its first collision's friction."""
    com_pos, com_orn = link_com_pose(link)
    to_com = pybullet.invertTransform(com_pos, com_orn)
    collisions = [s for s in shapes if s.collision]
    visuals = [s for s in shapes if not s.collision]
    for s in shapes:
        if s.kind not in MOVABLE_KINDS:
            raise WorldError("%s: a %s cannot be part of a model that is not <static> (movable "
                             "models are made of %s)" % (s.name, s.kind, ", ".join(MOVABLE_KINDS)))
    col = -1
    if collisions:
        col = bullet_shapes.collision_shape_array(
            client, **_shape_arrays(collisions, to_com, client, mesh_dir, visual=False))
    if visuals:
        vis = client.createVisualShapeArray(
            **_shape_arrays(visuals, to_com, client, mesh_dir, visual=True))
    else:
        vis = _unseen_visual(client, mesh_dir)     # collisions alone are not drawn
    _, moments = _principal(link.inertial)
    body = client.createMultiBody(baseMass=link.inertial.mass, baseCollisionShapeIndex=col,
                                  baseVisualShapeIndex=vis, basePosition=com_pos,
                                  baseOrientation=com_orn)
    if body < 0:
        raise WorldError("%s: pybullet could not build this link" % link.scoped)
    mu = collisions[0].mu if collisions else WORLD_FRICTION
    client.changeDynamics(body, -1, localInertiaDiagonal=moments, lateralFriction=mu,
                          restitution=WORLD_RESTITUTION, linearDamping=0.0, angularDamping=0.0,
                          activationState=pybullet.ACTIVATION_STATE_DISABLE_SLEEPING)
    collision_filters.set_filter(client, body, -1, MOVABLE_COLLISION_GROUP,
                                 MOVABLE_COLLISION_MASK if collisions else 0)
    if egl_enabled(client):   # never left out of a camera image, nor what shares its drawing
        view_culling.note_drawn_groups(client, body, visuals)
    return body


def _shape_arrays(shapes: List[Shape], to_com, client: Client, mesh_dir: str, visual: bool) -> dict:
    """Keyword arguments of createVisualShapeArray (``visual``) or createCollisionShapeArray for
    ``shapes`` placed in the body frame ``to_com``; mesh files are written in ``mesh_dir``."""
    frame = "visualFrame" if visual else "collisionFrame"
    args = {"shapeTypes": [], "halfExtents": [], "radii": [], "lengths": [], "fileNames": [],
            "meshScales": [], frame + "Positions": [], frame + "Orientations": []}
    if visual:
        args["rgbaColors"] = []

    def add(kind, pose, rgba, half=(0.0, 0.0, 0.0), radius=0.0, length=0.0, mesh=""):
        args["shapeTypes"].append(kind)
        args[frame + "Positions"].append(pose[0])
        args[frame + "Orientations"].append(pose[1])
        args["halfExtents"].append(list(half))
        args["radii"].append(radius)
        args["lengths"].append(length)
        args["fileNames"].append(mesh)
        args["meshScales"].append([1.0, 1.0, 1.0])
        if visual:
            args["rgbaColors"].append(rgba)

    for s in shapes:
        pose = pybullet.multiplyTransforms(*to_com, *pose_from_xyz_rpy(s.pose))
        if s.kind == "mesh":
            mesh = load_mesh(s.mesh, s.size)
            if not visual:   # one file of every triangle: pybullet collides with its hull
                mesh = Mesh(mesh.path, mesh.vertices, (MeshPart(mesh.faces, None),))
            for path, rgba in _visual_files(s, mesh, client, mesh_dir) if visual else \
                    write_obj_parts(mesh, mesh_dir):
                add(pybullet.GEOM_MESH, pose, _part_colour(s, rgba), mesh=path)
        elif s.kind == "box":
            half = [v / 2 for v in s.size]
            if visual and s.texture is not None:
                path, rgba = _box_visual_file(s, half[0], half[1], -half[2], half[2], client,
                                              mesh_dir)
                add(pybullet.GEOM_MESH, pose, rgba, mesh=path)
            elif visual:   # a file: EGL flattens thin GEOM_BOX visuals
                hx, hy = half[0], half[1]
                add(pybullet.GEOM_MESH, pose, s.rgba, mesh=_obj_file(
                    [(-hx, -hy), (hx, -hy), (hx, hy), (-hx, hy)], -half[2], half[2], mesh_dir))
            else:
                add(pybullet.GEOM_BOX, pose, s.rgba, half=half)
        elif s.kind == "cylinder":
            add(pybullet.GEOM_CYLINDER, pose, s.rgba, radius=s.size[0], length=s.size[1])
        else:
            add(pybullet.GEOM_SPHERE, pose, s.rgba, radius=s.size[0])
    return args


def _visual_files(shape: Shape, mesh: Mesh, client: Client, mesh_dir: str):
    """write_obj_parts of a visual mesh: with its textures where the file's own colours are
    drawn (no SDF <material>), or where it is a box or plane of a script's texture
    (``_box_mesh``), each image halved as the client's texture budget says (texture_budget);
    tells the camera when the client gets a texture."""
    own = shape.mesh_colours or shape.kind in ("box", "plane")
    halvings: Dict[str, int] = {}    # texture file -> times halved
    for texture in {p.texture for p in mesh.parts if p.texture is not None} if own else ():
        info = texture_info(texture)
        if info is not None:
            use = texture_budget.TextureUse(texture, info.width, info.height)
            halvings[texture] = texture_budget.halvings(client, info.digest, use,
                                                        per_visual=not egl_enabled(client))
    if halvings:
        note_textures(client)
    # written once for this content, kept in the mesh cache (mesh_cache.obj_parts)
    return mesh_cache.visual_obj_parts(mesh, mesh_dir, halvings or None)


def _part_colour(shape: Shape, rgba) -> Tuple[float, float, float, float]:
    """The colour a mesh part is drawn in: the SDF material's, else the file's, else grey."""
    return tuple(rgba) if shape.mesh_colours and rgba is not None else shape.rgba


def _body(shape: Shape, client: Client, mesh_dir: str, collide: bool) -> int:
    """One fixed body for ``shape``: collision and visual geometry, or visual only. A collision
    without a visual twin is not drawn (cameras see visuals only), nor is a piece of a mesh
    collision beyond its visual parts."""
    pieces = _pieces(shape, client, mesh_dir, collide, draw=not collide or shape.twin is not None)
    unseen = None
    for i, (col, vis) in enumerate(pieces):
        if col != -1 and vis == -1:
            unseen = _unseen_visual(client, mesh_dir) if unseen is None else unseen
            pieces[i] = (col, unseen)
    (base_col, base_vis), links = pieces[0], pieces[1:]
    position, orientation = pose_from_xyz_rpy(shape.pose)
    body = client.createMultiBody(
        baseMass=0.0, baseCollisionShapeIndex=base_col, baseVisualShapeIndex=base_vis,
        basePosition=position, baseOrientation=orientation,
        linkMasses=[0.0] * len(links),
        linkCollisionShapeIndices=[c for c, _ in links],
        linkVisualShapeIndices=[v for _, v in links],
        linkPositions=[(0, 0, 0)] * len(links), linkOrientations=[(0, 0, 0, 1)] * len(links),
        linkInertialFramePositions=[(0, 0, 0)] * len(links),
        linkInertialFrameOrientations=[(0, 0, 0, 1)] * len(links),
        linkParentIndices=[0] * len(links), linkJointTypes=[pybullet.JOINT_FIXED] * len(links),
        linkJointAxis=[(0, 0, 1)] * len(links),
        useMaximalCoordinates=_static_rigid(shape, collide, links))
    if body < 0:
        raise WorldError("%s: pybullet could not build %s" % (shape.name, shape.kind))
    if egl_enabled(client) and (not collide or shape.twin is not None):
        view_culling.note_static_body(client, body, shape)   # left out of images it cannot show
    for link in range(-1, len(links)) if collide else ():
        collision_filters.set_filter(client, body, link, WORLD_COLLISION_GROUP,
                                     WORLD_COLLISION_MASK)
        client.changeDynamics(body, link, lateralFriction=WORLD_FRICTION,
                              restitution=WORLD_RESTITUTION)
    if _static_rigid(shape, collide, links):   # asleep: Bullet skips its bounds every step
        client.changeDynamics(body, -1, activationState=(
            pybullet.ACTIVATION_STATE_ENABLE_SLEEPING | pybullet.ACTIVATION_STATE_SLEEP))
    return body


def _static_rigid(shape: Shape, collide: bool, links: list) -> bool:
    """Whether a fixed body is made a plain static rigid body (pybullet's maximal coordinates)
    rather than a multibody, and asleep: a static mesh collision of one piece, and every visual
    of one piece without a collision. Bullet updates every multibody every step, fixed or not
    and colliding or not, and the bounds of every static body that is awake: the 171 bodies of
    bench/mesh_world.py cost 2.7 times turtlebot3_world's physics CPU per sim second as
    multibodies, 1.9 times as static rigid bodies, 1.35 times asleep, and the same as
    turtlebot3_world once its 41 visual-only bodies were asleep too (a body still collides
    asleep and moves when set). Colliding primitive shapes stay multibodies (turtlebot3_world's
    contacts, and so its robot's path, stay as they were)."""
    return not links and (not collide or shape.kind == "mesh")


def _pieces(shape: Shape, client: Client, mesh_dir: str, collide: bool,
            draw: bool = True) -> List[Tuple[int, int]]:
    """(collision shape id or -1, visual shape id or -1) per convex piece of ``shape``, in its
    frame; without ``draw``, no visual shape is made.

    Box and plane visuals are mesh files too (``_mesh_visual``): pybullet's EGL renderer
    tessellates a GEOM_BOX through a convex hull that flattens a box about 800 times wider than
    thick (the 100 m ground, 5 cm thick) into its middle plane, with one triangle missing.
    """
    rgba = shape.rgba
    if shape.kind == "mesh":
        return _mesh_pieces(shape, client, mesh_dir, collide, draw)
    if shape.kind == "polyline":
        polygons = [shape.points] if _is_convex(shape.points) else _triangulate(shape)
        return [_prism(polygon, shape.size[0], rgba, client, mesh_dir, collide, draw)
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
        col = (bullet_shapes.collision_shape(client, pybullet.GEOM_BOX, **col_args)
               if collide else -1)
        hx, hy = half[0], half[1]
        if not draw:
            return [(col, -1)]
        if shape.texture is not None:
            path, rgba = _box_visual_file(shape, hx, hy, *z_range, client, mesh_dir)
            return [(col, client.createVisualShape(pybullet.GEOM_MESH, fileName=path,
                                                   rgbaColor=rgba))]
        rectangle = [(-hx, -hy), (hx, -hy), (hx, hy), (-hx, hy)]
        return [(col, _mesh_visual(rectangle, *z_range, rgba, client, mesh_dir))]
    kind = {"cylinder": pybullet.GEOM_CYLINDER, "sphere": pybullet.GEOM_SPHERE}[shape.kind]
    if shape.kind == "cylinder":
        col_args = {"radius": shape.size[0], "height": shape.size[1]}
        vis_args = {"radius": shape.size[0], "length": shape.size[1]}
    else:
        col_args = vis_args = {"radius": shape.size[0]}
    col = bullet_shapes.collision_shape(client, kind, **col_args) if collide else -1
    vis = (client.createVisualShape(kind, rgbaColor=rgba, **vis_args)
           if draw else -1)
    return [(col, vis)]


# Triangles of one concave collision shape: pybullet refuses more than 131,072 vertices or
# 524,287 indices in one (a static mesh beyond that is split; 40,000 triangles use at most
# 120,000 vertices).
TRIMESH_CHUNK = 40_000


def _mesh_pieces(shape: Shape, client: Client, mesh_dir: str, collide: bool,
                 draw: bool = True) -> List[Tuple[int, int]]:
    """A static mesh: its triangles as concave collision shapes of TRIMESH_CHUNK triangles or
    fewer (a fixed body collides with the triangles themselves) and, with ``draw``, a visual
    per colour part; the pieces after the first are links of its body."""
    mesh = load_mesh(shape.mesh, shape.size)
    collisions = []
    if collide:   # pybullet takes a concave mesh of at most 131,072 vertices: in chunks
        faces = mesh.faces
        for start in range(0, len(faces), TRIMESH_CHUNK):
            chunk = faces[start:start + TRIMESH_CHUNK]
            used, local = np.unique(chunk, return_inverse=True)
            collisions.append(bullet_shapes.collision_shape(
                client, pybullet.GEOM_MESH, vertices=mesh.vertices[used].tolist(),
                indices=local.reshape(-1).tolist(), flags=pybullet.GEOM_FORCE_CONCAVE_TRIMESH))
    visuals = [client.createVisualShape(pybullet.GEOM_MESH, fileName=path,
                                        rgbaColor=_part_colour(shape, rgba))
               for path, rgba in (_visual_files(shape, mesh, client, mesh_dir) if draw else ())]
    count = max(len(collisions), len(visuals))
    collisions += [-1] * (count - len(collisions))
    visuals += [-1] * (count - len(visuals))
    return list(zip(collisions, visuals))


def _prism(polygon: Sequence[Point], height: float, rgba, client: Client, mesh_dir: str,
           collide: bool, draw: bool = True) -> Tuple[int, int]:
    """A convex counter-clockwise polygon extruded from z 0 to ``height``: a convex-hull collision
    shape (pybullet inflates it by its 1 mm collision margin) and, with ``draw``, a flat-shaded
    visual mesh of the same solid."""
    corners = [(x, y, z) for z in (0.0, height) for x, y in polygon]
    col = (bullet_shapes.collision_shape(client, pybullet.GEOM_MESH, vertices=corners)
           if collide else -1)
    return col, (_mesh_visual(polygon, 0.0, height, rgba, client, mesh_dir) if draw else -1)


def _unseen_visual(client: Client, mesh_dir: str) -> int:
    """A visual shape that draws nothing (one triangle of no area, a file in ``mesh_dir``). A
    body or link without a visual shape is drawn by pybullet's renderers as its collision shape
    (white, or EGL's link colours); Gazebo's cameras never see collisions."""
    path = os.path.join(mesh_dir, "unseen.obj")
    if not os.path.isfile(path):
        with open(path, "w") as f:
            f.write("# one triangle of no area: nothing drawn\nv 0 0 0\nv 0 0 0\nv 0 0 0\n"
                    "f 1 2 3\n")
    return client.createVisualShape(pybullet.GEOM_MESH, fileName=path)


def _mesh_visual(polygon: Sequence[Point], z0: float, z1: float, rgba, client: Client,
                 mesh_dir: str) -> int:
    """Visual shape of a convex counter-clockwise polygon extruded from ``z0`` to ``z1``,
    flat-shaded, written as a Wavefront file in ``mesh_dir`` (read when its body is created).

    A file, because pybullet's EGL renderer draws no mesh given as vertex lists, and flattens
    thin boxes; both renderers draw a file as it is.
    """
    return client.createVisualShape(pybullet.GEOM_MESH, rgbaColor=rgba,
                                    fileName=_obj_file(polygon, z0, z1, mesh_dir))


def _obj_file(polygon: Sequence[Point], z0: float, z1: float, mesh_dir: str) -> str:
    """Path of a Wavefront file in ``mesh_dir`` of the convex counter-clockwise polygon extruded
    from ``z0`` to ``z1``, flat-shaded."""
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
    return path


def _box_mesh(shape: Shape, hx: float, hy: float, z0: float, z1: float) -> Mesh:
    """A box or plane visual of a script's texture as a Mesh of one textured part (tinted by
    ``shape.rgba``): x in -hx..hx, y in -hy..hy, z in z0..z1 (m, the shape's frame). Its top
    and bottom faces map the image by x and y (u = 0..1 along +x, v = 0..1 along +y: upright
    seen from above with +x to the right); a box's side faces each show the whole image upright
    (v along +z) seen from outside, a plane's sides the image's edge beside them."""
    corners = [(-hx, -hy), (hx, -hy), (hx, hy), (-hx, hy)]          # counter-clockwise
    vertices = np.array([(x, y, z) for z in (z0, z1) for x, y in corners], dtype=np.float64)

    def above(i):
        x, y = corners[i % 4]
        return ((x + hx) / (2 * hx), (y + hy) / (2 * hy))

    faces = [(4, 5, 6), (4, 6, 7), (0, 2, 1), (0, 3, 2)]           # top, bottom
    for i in range(4):
        j = (i + 1) % 4
        faces += [(i, j, 4 + j), (i, 4 + j, 4 + i)]                 # a side, from outside
    uvs = [[above(v) for v in face] for face in faces[:4]]
    upright = (((0.0, 0.0), (1.0, 0.0), (1.0, 1.0)), ((0.0, 0.0), (1.0, 1.0), (0.0, 1.0)))
    for k, face in enumerate(faces[4:]):
        uvs.append(upright[k % 2] if shape.kind == "box" else [above(v) for v in face])
    part = MeshPart(np.array(faces, dtype=np.int64), tuple(shape.rgba),
                    np.array(uvs, dtype=np.float64), shape.texture)
    return Mesh(shape.kind, vertices, (part,))


def _box_visual_file(shape: Shape, hx: float, hy: float, z0: float, z1: float, client: Client,
                     mesh_dir: str) -> Tuple[str, Tuple[float, float, float, float]]:
    """(Wavefront file, colour to draw it in) of ``_box_mesh``: textured as ``_visual_files``
    allows, else in ``shape.rgba``."""
    [(path, rgba)] = _visual_files(shape, _box_mesh(shape, hx, hy, z0, z1), client, mesh_dir)
    return path, tuple(rgba) if rgba is not None else shape.rgba


def _is_convex(polygon: Sequence[Point]) -> bool:
    """Whether a counter-clockwise polygon turns left at every corner."""
    n = len(polygon)
    return all(cross_2d(polygon[i - 1], polygon[i], polygon[(i + 1) % n]) > 0 for i in range(n))


def _triangulate(shape: Shape) -> List[Tuple[Point, Point, Point]]:
    """Ear clipping of a polyline's simple counter-clockwise polygon into counter-clockwise
    triangles."""
    remaining = list(shape.points)
    triangles = []
    while len(remaining) > 3:
        n = len(remaining)
        for i in range(n):
            a, b, c = remaining[i - 1], remaining[i], remaining[(i + 1) % n]
            if cross_2d(a, b, c) <= 0:
                continue                                  # a reflex corner is no ear
            others = (p for p in remaining if p not in (a, b, c))
            if any(cross_2d(a, b, p) >= 0 and cross_2d(b, c, p) >= 0 and cross_2d(c, a, p) >= 0
                   for p in others):
                continue                                  # another corner lies inside
            triangles.append((a, b, c))
            del remaining[i]
            break
        else:
            raise WorldError("%s: its polyline cannot be split into triangles" % shape.name)
    triangles.append(tuple(remaining))
    return triangles


# --- a deleted model's parked bodies (body_pool) built again -----------------------------------

def reused_world_bodies(world: World, bodies: Sequence[int]) -> Dict[str, int]:
    """``build_world``'s answer for ``world`` made of ``bodies``: those it built for the same
    text (under any model name), one per body, in the order it built them."""
    groups: Dict[str, List[str]] = {}   # body by body, in build order: its shape names
    for s in world.collisions:
        if s.static:
            groups[s.name] = [s.name]
    for s in world.visuals:
        if s.static and s.twin is None:
            groups[s.name] = [s.name]
    for s in world.collisions + world.visuals:
        if not s.static:
            groups.setdefault("link " + s.link, []).append(s.name)
    if len(groups) != len(bodies):
        raise WorldError("the parked bodies do not fit this model")
    return {name: body for names, body in zip(groups.values(), bodies) for name in names}


def place_world_bodies(world: World, bodies: Dict[str, int], client: Client) -> None:
    """Put reused bodies where ``build_world`` builds them for ``world``, at rest, colliding
    as it sets them."""
    links = {link.scoped: link for model in world.model_specs for link in model.links}
    for shape in world.collisions + world.visuals:
        body = bodies.get(shape.name)
        if body is None:    # a static visual drawn by its collision twin's body
            continue
        if shape.static:
            pos, orn = pose_from_xyz_rpy(shape.pose)
        else:
            pos, orn = link_com_pose(links[shape.link])
        client.resetBasePositionAndOrientation(body, pos, orn)
        client.resetBaseVelocity(body, (0, 0, 0), (0, 0, 0))
        for link in range(-1, client.getNumJoints(body)):
            if shape.static and shape.collision:
                collision_filters.set_filter(client, body, link, WORLD_COLLISION_GROUP,
                                             WORLD_COLLISION_MASK)
            elif not shape.static:
                has_collision = any(s.collision and s.link == shape.link
                                    for s in world.collisions)
                collision_filters.set_filter(
                    client, body, link, MOVABLE_COLLISION_GROUP,
                    MOVABLE_COLLISION_MASK if has_collision else 0)
