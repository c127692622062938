"""Build a loaded ``World`` (world_sdf) as pybullet bodies. Knows nothing of ROS.

Static models: every collision shape becomes one fixed body that also carries its visual twin
(same geometry and pose), so contacts, rays and cameras all see it; a collision without a twin
is not drawn (cameras see visuals only, as in Gazebo: a collision box around a textured mesh
would hide it); a visual without a collision twin becomes a body that cameras see and rays and
contacts pass through. A static mesh collides with its triangles themselves; a plane as an
infinite plane (a half-space, as Gazebo's ODE plane), drawn at its <size>.
Models that are not ``<static>``: each tree of joined links is one movable body, a lone link
one rigid body (movable_bodies: mass, inertia, friction; a mesh collides as its convex hull).
Visuals are drawn from files (visual_files): mesh parts in their SDF ``<material>`` colour or
the file's own colours and textures (each image halved as texture_budget says; a texture that
cannot be used leaves the part in its colour, else grey, with one warning); a box or plane whose
``<material>`` script has a texture image (world_sdf ``Shape.texture``, material_scripts) with
that image, tinted by its colour: the whole image once across its top face, upright seen from
above with +x to the right and +y up (as Gazebo maps a plane); a box shows it on each side face
too.
A deleted model's bodies parked for reuse (body_pool) are taken back as ``build_world`` would
build them (``reused_world_bodies``, ``place_world_bodies``).

Units: metres; poses in the world frame (z up), as in world_sdf.
"""
import os
import tempfile
from typing import Dict, List, Optional, Sequence, Tuple

import numpy as np

from . import bullet_shapes, collision_filters, texture_budget, view_culling
from .bullet import pybullet
from .client import Client
from .collision_groups import (ALL_COLLISION_GROUPS, MOVABLE_COLLISION_GROUP,
                               MOVABLE_COLLISION_MASK, MOVABLE_KINDS, WORLD_COLLISION_GROUP,
                               WORLD_COLLISION_MASK, WORLD_FRICTION, WORLD_RESTITUTION)
from .movable_bodies import (jointed_body, link_com_pose, movable_body, movable_trees,
                             place_jointed)
from .rendering import egl_enabled
from .visual_files import box_visual_file, mesh_part_files, mesh_visual, part_colour, unseen_visual
from ...errors import UserError, WorldError
from ..kinematics import cross_2d, pose_from_xyz_rpy
from ..files.meshes.mesh_file import load_mesh
from ..files.meshes.texture_images import texture_info
from ..files.world_types import Shape, World

# re-exported: the builders' collision groups and constants are imported from here
REEXPORTED = (ALL_COLLISION_GROUPS, MOVABLE_KINDS, link_com_pose)


# A plane collides as Bullet's infinite plane (GEOM_PLANE, a half-space: its surface through
# the shape's origin, normal along the shape's z, which world_sdf turned onto the SDF <normal>),
# as Gazebo's ODE plane does. It is drawn as a thin box of its <size>, its top face on the
# plane (pybullet's EGL renderer crashed on a GEOM_PLANE visual).
PLANE_THICKNESS = 0.05      # m: drawn

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
            client.built_joints.pop(body, None)
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
        trees, built = movable_trees(world), set()
        for scoped, shapes in movable.items():
            tree = trees.get(scoped)
            if tree is None:
                body = movable_body(links[scoped], shapes, client, mesh_dir)
            elif tree.root in built:
                continue      # built with the first of its tree's links
            else:
                built.add(tree.root)
                shapes = [s for link in tree.links for s in movable.get(link, [])]
                body = jointed_body(tree, links, movable, client, mesh_dir)
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


def _body(shape: Shape, client: Client, mesh_dir: str, collide: bool) -> int:
    """One fixed body for ``shape``: collision and visual geometry, or visual only. A collision
    without a visual twin is not drawn (cameras see visuals only), nor is a piece of a mesh
    collision beyond its visual parts."""
    pieces = _pieces(shape, client, mesh_dir, collide, draw=not collide or shape.twin is not None)
    unseen = None
    for i, (col, vis) in enumerate(pieces):
        if col != -1 and vis == -1:
            unseen = unseen_visual(client, mesh_dir) if unseen is None else unseen
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
    rather than a multibody, and asleep: a static mesh collision of one piece, a plane, and
    every visual of one piece without a collision. Bullet updates every multibody every step,
    fixed or not and colliding or not, and the bounds of every static body that is awake: the
    171 bodies of bench/mesh_world.py cost 2.7 times turtlebot3_world's physics CPU per sim
    second as multibodies, 1.9 times as static rigid bodies, 1.35 times asleep, and the same as
    turtlebot3_world once its 41 visual-only bodies were asleep too (a body still collides
    asleep and moves when set). A plane as a fixed multibody took NaN into its own pose from a
    robot whose state went NaN on it, and the robot then fell through the world; the solver
    never moves a static rigid body. Other colliding primitive shapes stay multibodies
    (turtlebot3_world's walls, and so its robot's path, stay as they were)."""
    return not links and (not collide or shape.kind in ("mesh", "plane"))


def _pieces(shape: Shape, client: Client, mesh_dir: str, collide: bool,
            draw: bool = True) -> List[Tuple[int, int]]:
    """(collision shape id or -1, visual shape id or -1) per convex piece of ``shape``, in its
    frame; without ``draw``, no visual shape is made.

    Box and plane visuals are mesh files too (``mesh_visual``): pybullet's EGL renderer
    tessellates a GEOM_BOX through a convex hull that flattens a box about 800 times wider than
    thick (the 100 m ground, 5 cm thick) into its middle plane, with one triangle missing.
    A plane collides as an infinite plane (its <size> only drawn); only static shapes come
    here: a plane in a model that is not <static> is refused (movable_bodies, spawn_request).
    """
    rgba = shape.rgba
    if shape.kind == "mesh":
        return _mesh_pieces(shape, client, mesh_dir, collide, draw)
    if shape.kind == "polyline":
        polygons = [shape.points] if _is_convex(shape.points) else _triangulate(shape)
        return [_prism(polygon, shape.size[0], rgba, client, mesh_dir, collide, draw)
                for polygon in polygons]
    if shape.kind in ("box", "plane"):
        hx, hy = shape.size[0] / 2, shape.size[1] / 2
        if shape.kind == "box":
            z_range = (-shape.size[2] / 2, shape.size[2] / 2)
            col = (bullet_shapes.collision_shape(client, pybullet.GEOM_BOX,
                                                 halfExtents=[hx, hy, z_range[1]])
                   if collide else -1)
        else:     # infinite: the <size> only bounds what is drawn
            z_range = (-PLANE_THICKNESS, 0.0)
            col = (bullet_shapes.collision_shape(client, pybullet.GEOM_PLANE,
                                                 planeNormal=(0.0, 0.0, 1.0))
                   if collide else -1)
        if not draw:
            return [(col, -1)]
        if shape.texture is not None:
            path, rgba = box_visual_file(shape, hx, hy, *z_range, client, mesh_dir)
            return [(col, client.createVisualShape(pybullet.GEOM_MESH, fileName=path,
                                                   rgbaColor=rgba))]
        rectangle = [(-hx, -hy), (hx, -hy), (hx, hy), (-hx, hy)]
        return [(col, mesh_visual(rectangle, *z_range, rgba, client, mesh_dir))]
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
                                        rgbaColor=part_colour(shape, rgba))
               for path, rgba in (mesh_part_files(shape, mesh, client, mesh_dir) if draw else ())]
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
    return col, (mesh_visual(polygon, 0.0, height, rgba, client, mesh_dir) if draw else -1)


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
    trees = movable_trees(world)
    for s in world.collisions + world.visuals:
        if not s.static:
            tree = trees.get(s.link)
            key = "link " + s.link if tree is None else "tree " + tree.root
            groups.setdefault(key, []).append(s.name)
    if len(groups) != len(bodies):
        raise WorldError("the parked bodies do not fit this model")
    return {name: body for names, body in zip(groups.values(), bodies) for name in names}


def place_world_bodies(world: World, bodies: Dict[str, int], client: Client) -> None:
    """Put reused bodies where ``build_world`` builds them for ``world``, at rest, colliding
    as it sets them."""
    links = {link.scoped: link for model in world.model_specs for link in model.links}
    trees = movable_trees(world)
    for shape in world.collisions + world.visuals:
        body = bodies.get(shape.name)
        if body is None:    # a static visual drawn by its collision twin's body
            continue
        if not shape.static and shape.link in trees:
            place_jointed(client, body, trees[shape.link], links, world)
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
