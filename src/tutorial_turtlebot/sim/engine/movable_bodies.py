"""The bodies of models that are not ``<static>``: one per tree of joined links (files.model_tree).
Knows nothing of ROS.

A lone link is one movable rigid body of the link's ``<inertial>`` mass and inertia, holding all
its collisions and visuals (box, cylinder, sphere, mesh) and its collisions' friction; a mesh
collides as its convex hull (Bullet's moving bodies are convex). Its frame is the link's centre
of mass, its axes the principal axes of inertia (``link_com_pose``).
Links joined by joints are one pybullet multibody (``jointed_body``): the base is the tree's
root link, framed as a lone link is (a massless fixed base at the joint where a joint from the
world turns or slides it); every other link's frame is its joint's frame (the pivot: SDF's
joint <pose> in the child link), in which world_models keeps the link's own frame
(``body_link_frames`` says where each was built).
Joint limits, damping and friction (a velocity motor of that force holding it, as the URDF
models' joints are held) are set as the file says; a ball joint is pybullet's spherical one.
Units: metres, kilograms, kg m^2; poses ((x, y, z), (qx, qy, qz, qw)) in the world frame.
"""
import math
import tempfile
from typing import Dict, List, Optional, Sequence, Tuple

import numpy as np

from . import bullet_shapes, collision_filters, view_culling
from .bodies import NO_STOP, Body, BuiltJoint
from .bullet import pybullet
from .client import Client
from .collision_groups import (MOVABLE_COLLISION_GROUP, MOVABLE_COLLISION_MASK, MOVABLE_KINDS,
                               WORLD_FRICTION, WORLD_RESTITUTION)
from .rendering import egl_enabled
from .visual_files import box_visual_file, mesh_part_files, obj_file, part_colour, unseen_visual
from ...errors import WorldError
from ..kinematics import pose_from_xyz_rpy, quat_from_matrix
from ..files.meshes.mesh_file import load_mesh
from ..files.meshes.mesh_types import Mesh, MeshPart
from ..files.meshes.obj_writer import write_obj_parts
from ..files import limits
from ..files.model_tree import BodyLink, Tree, link_by_name, trees
from ..files.world_types import Inertial, Joint, Link, Shape, World

Pose = Tuple[Tuple[float, float, float], Tuple[float, float, float, float]]


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
    moments, axes = principal_axes([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]])
    return quat_from_matrix(np.array(axes)), moments


JACOBI_SWEEPS = 50   # at most; a 3x3 tensor takes five or six


def principal_axes(tensor) -> Tuple[Tuple[float, float, float], List[List[float]]]:
    """(moments ascending, axes: a right-handed rotation whose columns are the principal axes)
    of a symmetric 3x3 inertia ``tensor`` (kg m^2), by Jacobi's rotations in plain floats.
    Not numpy's eigh: LAPACK's last bits differ between numpy's builds (1.24 and 2.x gave
    principal frames 3e-15 apart), and the robots' paths are chaotic enough to make that a
    millimetre in five seconds; these operations round alike on every build."""
    a = [[float(v) for v in row] for row in tensor]
    v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
    for _ in range(JACOBI_SWEEPS):
        for p, q in ((0, 1), (0, 2), (1, 2)):
            apq = a[p][q]
            if abs(apq) <= 1e-17 * (abs(a[p][p]) + abs(a[q][q])):   # below rounding
                a[p][q] = a[q][p] = 0.0
                continue
            theta = (a[q][q] - a[p][p]) / (2.0 * apq)
            t = (1.0 if theta >= 0.0 else -1.0) / (abs(theta) + math.sqrt(theta * theta + 1.0))
            c = 1.0 / math.sqrt(t * t + 1.0)
            s = t * c
            for k in range(3):      # A J, then V J
                a[k][p], a[k][q] = c * a[k][p] - s * a[k][q], s * a[k][p] + c * a[k][q]
                v[k][p], v[k][q] = c * v[k][p] - s * v[k][q], s * v[k][p] + c * v[k][q]
            for k in range(3):      # J^T (A J)
                a[p][k], a[q][k] = c * a[p][k] - s * a[q][k], s * a[p][k] + c * a[q][k]
            a[p][q] = a[q][p] = 0.0
        if a[0][1] == a[0][2] == a[1][2] == 0.0:
            break
    order = sorted(range(3), key=lambda i: a[i][i])
    axes = [[v[row][i] for i in order] for row in range(3)]
    det = (axes[0][0] * (axes[1][1] * axes[2][2] - axes[1][2] * axes[2][1])
           - axes[0][1] * (axes[1][0] * axes[2][2] - axes[1][2] * axes[2][0])
           + axes[0][2] * (axes[1][0] * axes[2][1] - axes[1][1] * axes[2][0]))
    if det < 0.0:
        for row in axes:
            row[2] = -row[2]
    return (a[order[0]][order[0]], a[order[1]][order[1]], a[order[2]][order[2]]), axes


def movable_body(link: Link, shapes: List[Shape], client: Client, mesh_dir: str) -> int:
    """One movable rigid body for a lone ``link``: its collisions and visuals placed around its
    centre of mass, its mass and principal moments of inertia, its first collision's friction."""
    com_pos, com_orn = link_com_pose(link)
    col, vis = _link_shapes(shapes, pybullet.invertTransform(com_pos, com_orn), client, mesh_dir)
    body = client.createMultiBody(baseMass=link.inertial.mass, baseCollisionShapeIndex=col,
                                  baseVisualShapeIndex=vis, basePosition=com_pos,
                                  baseOrientation=com_orn)
    if body < 0:
        raise WorldError("%s: pybullet could not build this link" % link.scoped)
    _set_up_link(client, body, -1, _principal(link.inertial)[1], shapes)
    if egl_enabled(client):   # never left out of a camera image, nor what shares its drawing
        view_culling.note_drawn_groups(client, body, [s for s in shapes if not s.collision])
    return body


def _link_shapes(shapes: Sequence[Shape], to_frame, client: Client, mesh_dir: str):
    """(collision shape, visual shape) of a link's ``shapes`` placed in the link's body frame
    ``to_frame`` (world -> frame); -1 for no collision; an unseen visual for none (collisions
    alone are not drawn)."""
    for s in shapes:
        if s.kind not in MOVABLE_KINDS:
            raise WorldError("%s: a %s cannot be part of a model that is not <static> (movable "
                             "models are made of %s)" % (s.name, s.kind, ", ".join(MOVABLE_KINDS)))
    collisions = [s for s in shapes if s.collision]
    visuals = [s for s in shapes if not s.collision]
    col = -1
    if collisions:
        col = bullet_shapes.collision_shape_array(
            client, **_shape_arrays(collisions, to_frame, client, mesh_dir, visual=False))
    if visuals:
        vis = client.createVisualShapeArray(
            **_shape_arrays(visuals, to_frame, client, mesh_dir, visual=True))
    else:
        vis = unseen_visual(client, mesh_dir)
    return col, vis


def _set_up_link(client: Client, body: int, index: int, moments, shapes: Sequence[Shape]) -> None:
    """A movable link as Gazebo moves one: its principal ``moments`` (kg m^2; None: a link of
    no mass), its first collision's friction, no damping, never asleep, colliding with the
    world and other movable bodies if it has a collision."""
    collisions = [s for s in shapes if s.collision]
    mu = collisions[0].mu if collisions else WORLD_FRICTION
    inertia = {"localInertiaDiagonal": moments} if moments is not None else {}
    if inertia and index >= 0:     # given with the settings below, pybullet drops a jointed
        client.changeDynamics(body, index, **inertia)   # link's inertia (keeps its shapes')
        inertia = {}
    client.changeDynamics(body, index, lateralFriction=mu, restitution=WORLD_RESTITUTION,
                          linearDamping=0.0, angularDamping=0.0,
                          activationState=pybullet.ACTIVATION_STATE_DISABLE_SLEEPING, **inertia)
    collision_filters.set_filter(client, body, index, MOVABLE_COLLISION_GROUP,
                                 MOVABLE_COLLISION_MASK if collisions else 0)


# A two-axis joint's light link between its axes (model_tree.BodyLink with no link): enough
# mass for Featherstone's algorithm, too little to show.
LIGHT_MASS = 1e-3           # kg
LIGHT_MOMENT = 1e-6         # kg m^2
NO_LIMIT = 1e15             # rad or m: a joint limit beyond this is none (SDF: 1e16)
_JOINT_TYPES = {"revolute": pybullet.JOINT_REVOLUTE, "continuous": pybullet.JOINT_REVOLUTE,
                "universal": pybullet.JOINT_REVOLUTE, "revolute2": pybullet.JOINT_REVOLUTE,
                "prismatic": pybullet.JOINT_PRISMATIC, "ball": pybullet.JOINT_SPHERICAL}


def body_link_frames(tree: Tree, links: Dict[str, Link]) -> List[Pose]:
    """World pose of the body frame of each of ``tree.body_links()`` (model_tree), as built:
    the root link's centre of mass for a free or fixed base, the anchor joint's frame for an
    anchor's base, each joined link's joint frame."""
    frames = []
    for entry in tree.body_links():
        if entry.joint is None:
            frames.append(link_com_pose(links[tree.root]) if entry.link is not None
                          else _pose(pose_from_xyz_rpy(tree.anchor.pose)))
        else:
            frames.append(_pose(pose_from_xyz_rpy(entry.joint.pose)))
    return frames


def _pose(pose) -> Pose:
    return tuple(pose[0]), tuple(pose[1])


def jointed_body(tree: Tree, links: Dict[str, Link], shapes: Dict[str, List[Shape]],
                 client: Client, mesh_dir: str) -> int:
    """One multibody of the links of ``tree`` joined by its joints (the module's docstring);
    ``shapes``: each link's collisions and visuals (scoped link name -> shapes)."""
    entries = tree.body_links()
    frames = body_link_frames(tree, links)
    built = []    # (collision, visual, mass, inertial pose in the body frame, moments)
    for entry, frame in zip(entries, frames):
        to_frame = pybullet.invertTransform(*frame)
        own = shapes.get(entry.link, []) if entry.link is not None else []
        col, vis = _link_shapes(own, to_frame, client, mesh_dir)
        if entry.link is None:
            mass = 0.0 if entry.joint is None else LIGHT_MASS
            built.append((col, vis, mass, ((0, 0, 0), (0, 0, 0, 1)), (LIGHT_MOMENT,) * 3))
            continue
        link = links[entry.link]
        inertial = pybullet.multiplyTransforms(*to_frame, *link_com_pose(link))
        built.append((col, vis, link.inertial.mass, inertial, _principal(link.inertial)[1]))
    base, rest = built[0], built[1:]
    base_mass = 0.0 if tree.fixed_base else base[2]
    kwargs = {"linkMasses": [], "linkCollisionShapeIndices": [], "linkVisualShapeIndices": [],
              "linkPositions": [], "linkOrientations": [], "linkInertialFramePositions": [],
              "linkInertialFrameOrientations": [], "linkParentIndices": [],
              "linkJointTypes": [], "linkJointAxis": []}
    for entry, frame, (col, vis, mass, inertial, _) in zip(entries[1:], frames[1:], rest):
        parent = frames[entry.parent + 1]
        pos, orn = pybullet.multiplyTransforms(*pybullet.invertTransform(*parent), *frame)
        axis = entry.joint.axis if entry.axis == 1 else entry.joint.axis2
        local_axis = np.asarray(pybullet.getMatrixFromQuaternion(frame[1])).reshape(3, 3).T \
            @ np.asarray(axis)
        kwargs["linkMasses"].append(mass)
        kwargs["linkCollisionShapeIndices"].append(col)
        kwargs["linkVisualShapeIndices"].append(vis)
        kwargs["linkPositions"].append(pos)
        kwargs["linkOrientations"].append(orn)
        kwargs["linkInertialFramePositions"].append(inertial[0])
        kwargs["linkInertialFrameOrientations"].append(inertial[1])
        kwargs["linkParentIndices"].append(entry.parent + 1)
        kwargs["linkJointTypes"].append(_JOINT_TYPES.get(entry.joint.kind, pybullet.JOINT_FIXED))
        kwargs["linkJointAxis"].append(tuple(float(v) for v in local_axis))
    body = client.createMultiBody(baseMass=base_mass, baseCollisionShapeIndex=base[0],
                                  baseVisualShapeIndex=base[1], basePosition=frames[0][0],
                                  baseOrientation=frames[0][1], **kwargs)
    if body < 0:
        raise WorldError("%s: pybullet could not build its jointed links" % tree.root)
    joints = []
    for index, (entry, (_, _, mass, _, moments)) in enumerate(zip(entries, built), start=-1):
        own = shapes.get(entry.link, []) if entry.link is not None else []
        _set_up_link(client, body, index, moments if mass > 0 else None, own)
        if index >= 0:
            joints.append(_built_joint(entry))
    client.built_joints[body] = tuple(joints)
    # each link's friction in a call of its own, once every link is set up: in one call with
    # the settings above pybullet leaves a jointed link at its default 0.5 and gives the base
    # the last link's (as it does for URDF bodies too)
    for index, entry in enumerate(entries, start=-1):
        own = [s for s in shapes.get(entry.link, []) if s.collision] if entry.link else []
        client.changeDynamics(body, index, lateralFriction=own[0].mu if own else WORLD_FRICTION)
    handle = Body(client, body)
    for index, (entry, joint) in enumerate(zip(entries[1:], joints)):
        _set_up_joint(handle, index, entry.joint, joint)
    cap = _top_speed([entry.joint for entry in entries[1:]])
    if cap is not None:
        client.changeDynamics(body, -1, maxJointVelocity=cap)
    if egl_enabled(client):
        view_culling.note_drawn_groups(client, body, [s for link in tree.links
                                                      for s in shapes.get(link, [])
                                                      if not s.collision])
    return body


def _built_joint(entry: BodyLink) -> BuiltJoint:
    """The BuiltJoint of a body link's joint: the second axis of a two-axis joint is nameless
    (the world API finds the joint by its first), stops only where the joint has them."""
    joint = entry.joint
    local = entry.link.split("::", 1)[1] if entry.link else ""
    stopped = (_JOINT_TYPES.get(joint.kind) in (pybullet.JOINT_REVOLUTE, pybullet.JOINT_PRISMATIC)
               and abs(joint.lower) < NO_LIMIT and abs(joint.upper) < NO_LIMIT)
    lower, upper = (joint.lower, joint.upper) if stopped else (-NO_STOP, NO_STOP)
    return BuiltJoint(joint.name if entry.axis == 1 else "", local, joint.damping,
                      joint.friction, lower, upper)


def _top_speed(joints: List[Joint]) -> Optional[float]:
    """The one top speed pybullet keeps for all the joints of a multibody (rad/s or m/s): the
    fastest of their <limit><velocity>, where every moving joint has one; None (pybullet's
    own cap) where one has none. A joint whose limit is lower than another's of the same
    body is not held to it."""
    moving = [j for j in joints if j.kind != "fixed"]
    if not moving or any(j.velocity <= 0 for j in moving):
        return None
    return max(j.velocity for j in moving)


def _set_up_joint(body: Body, index: int, joint: Joint, built: BuiltJoint) -> None:
    """Joint ``index`` as ``joint`` says: its stops, damping (held as set_joint_properties
    holds it: Body.damp_joint), and a motor of its friction's force holding it
    (pybullet's default motors would brake every joint)."""
    client = body.client
    if built.lower > -NO_STOP:
        client.changeDynamics(body.uid, index, jointLowerLimit=built.lower,
                              jointUpperLimit=built.upper)
    if joint.damping > 0:
        body.damp_joint(index, joint.damping, limits.MAX_TIME_STEP)
    if joint.kind == "ball":
        client.setJointMotorControlMultiDof(body.uid, index, pybullet.POSITION_CONTROL,
                                            targetPosition=[0, 0, 0, 1], positionGain=0,
                                            velocityGain=0, force=[joint.friction] * 3)
    elif _JOINT_TYPES.get(joint.kind) is not None:
        client.setJointMotorControl2(body.uid, index, pybullet.VELOCITY_CONTROL,
                                     force=joint.friction)


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
            for path, rgba in mesh_part_files(s, mesh, client, mesh_dir) if visual else \
                    write_obj_parts(mesh, mesh_dir):
                add(pybullet.GEOM_MESH, pose, part_colour(s, rgba), mesh=path)
        elif s.kind == "box":
            half = [v / 2 for v in s.size]
            if visual and s.texture is not None:
                path, rgba = box_visual_file(s, half[0], half[1], -half[2], half[2], client,
                                             mesh_dir)
                add(pybullet.GEOM_MESH, pose, rgba, mesh=path)
            elif visual:   # a file: EGL flattens thin GEOM_BOX visuals
                hx, hy = half[0], half[1]
                add(pybullet.GEOM_MESH, pose, s.rgba, mesh=obj_file(
                    [(-hx, -hy), (hx, -hy), (hx, hy), (-hx, hy)], -half[2], half[2], mesh_dir))
            else:
                add(pybullet.GEOM_BOX, pose, s.rgba, half=half)
        elif s.kind == "cylinder":
            add(pybullet.GEOM_CYLINDER, pose, s.rgba, radius=s.size[0], length=s.size[1])
        else:
            add(pybullet.GEOM_SPHERE, pose, s.rgba, radius=s.size[0])
    return args


def model_body(world: World, client: Client) -> int:
    """The one body of the first model of ``world`` (a robot's, urdf_to_sdf): the tree of its
    first link (a lone link: ``movable_body``; joined links: ``jointed_body``), its base
    framed as ``model_base_frame`` says. Links of other trees (below a floating or planar URDF
    joint) are not part of it."""
    tree, links = _first_tree(world)
    shapes: Dict[str, List[Shape]] = {}
    for shape in world.shapes:
        if shape.link in tree.links:
            shapes.setdefault(shape.link, []).append(shape)
    with tempfile.TemporaryDirectory(prefix="tutorial_turtlebot_meshes_") as mesh_dir:
        if tree.single:
            return movable_body(links[tree.root], shapes.get(tree.root, []), client, mesh_dir)
        return jointed_body(tree, links, shapes, client, mesh_dir)


def model_base_frame(world: World) -> Tuple[str, Pose]:
    """(scoped name of the link at the base of ``model_body``'s body, world pose of the base's
    frame as built: body_link_frames)."""
    tree, links = _first_tree(world)
    return tree.root, body_link_frames(tree, links)[0]


def _first_tree(world: World) -> Tuple[Tree, Dict[str, Link]]:
    """(the tree of the first model's first link, its links by scoped name)."""
    model = world.model_specs[0]
    return trees(model)[0], link_by_name(model)


def movable_trees(world: World) -> Dict[str, Tree]:
    """Scoped link -> its tree, for every link of a movable model that is joined to another
    or anchored (a lone free link is a rigid body of its own: not listed)."""
    out = {}
    for model in world.model_specs:
        if model.static or not model.joint_specs:
            continue
        for tree in trees(model):
            if not tree.single:
                out.update((link, tree) for link in tree.links)
    return out


def place_jointed(client: Client, body: int, tree: Tree, links: Dict[str, Link],
                  world: World) -> None:
    """Put a reused multibody of ``tree`` where ``jointed_body`` builds it, every joint at 0, at
    rest, colliding as it sets it."""
    frame = body_link_frames(tree, links)[0]
    client.resetBasePositionAndOrientation(body, frame[0], frame[1])
    client.resetBaseVelocity(body, (0, 0, 0), (0, 0, 0))
    colliding = {s.link for s in world.collisions if not s.static}
    for index, entry in enumerate(tree.body_links(), start=-1):
        if index >= 0:
            if entry.joint.kind == "ball":
                client.resetJointStateMultiDof(body, index, [0, 0, 0, 1], [0, 0, 0])
            else:
                client.resetJointState(body, index, 0.0, 0.0)
        collision_filters.set_filter(client, body, index, MOVABLE_COLLISION_GROUP,
                                     MOVABLE_COLLISION_MASK if entry.link in colliding else 0)
