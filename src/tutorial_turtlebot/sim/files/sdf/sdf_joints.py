"""A movable SDF model's ``<joint>``s read into world_types.Joint, placed in the world. No ROS,
no pybullet.

As Gazebo 11 (sdformat 9) reads them:
- the joint frame is its ``<pose>`` in the child link's frame (or in the frame its
  ``relative_to`` names: sdf_frames);
- ``<axis><xyz>`` is a direction in the joint frame; in the parent model's frame where
  ``<use_parent_model_frame>`` is true (SDF 1.5, 1.6) or ``<xyz expressed_in="__model__">``
  (SDF 1.7); sdf_versions converts an older file's joints as libsdformat does (SDF 1.4 and
  older wrote axes in the model frame);
- ``<parent>``/``<child>`` name links of the model, scoped as written ("inner::link" for a nested
  model's), or ``world``; a name found nowhere is refused, as Gazebo refuses the model;
- ``<limit>``: ``<lower>``, ``<upper>`` (rad or m; SDF's default +-1e16, no limit), ``<effort>``
  and ``<velocity>`` (-1: none); ``<dynamics>``: ``<damping>``, ``<friction>``;
- a ``continuous`` joint has no limits whatever ``<limit>`` says.
Units: metres, radians, seconds, newtons.
"""
import math
from dataclasses import dataclass
from typing import Dict, List, Optional, Sequence, Tuple

import numpy as np

from ...kinematics import XyzRpy, matrix_from_rpy
from .. import limits
from ..model_tree import HELD_FIXED, forest
from ..world_types import JOINT_KINDS, UNLIMITED, WORLD_LINK, Joint, Link
from ..xml_reader import Element, XmlReader
from .sdf_frames import MODEL_FRAME, Frames

NO_LIMIT = 1e15     # a limit beyond this magnitude is no limit (SDF's default is 1e16)


@dataclass(frozen=True)
class JointNode:
    """A ``<joint>`` element noted while its model is read, with what placing it needs."""

    node: Element
    scope: str               # the scoped names of its model, with "::" ("outer::inner::")
    model_pose: XyzRpy       # world pose of that model's frame
    frames: Frames           # that model's named frames


def simulated_joints(loader, nodes: Sequence[JointNode], links: Sequence[Link]) -> Tuple:
    """The joints of a movable model (``nodes``, in file order, between its ``links``) that
    are simulated: those that would close a loop left out (model_tree.forest: one warning each
    through the ``loader``'s warn_short, the nearest tree simulated), and one warning for each
    screw or gearbox joint, held fixed."""
    joints = read_joints(loader, nodes, links)
    kept, dropped = forest(joints)
    for joint, jn in zip(joints, nodes):
        if joint in dropped:
            loader.warn_short(jn.node, "joint %s closes a loop of joints: left out, the nearest "
                                       "tree of the model is simulated" % joint.name)
        elif joint.kind in HELD_FIXED:
            loader.warn_short(jn.node, "joint %s: a %s joint is held fixed here"
                              % (joint.name, joint.kind))
    return tuple(kept)


def read_joints(reader: XmlReader, nodes: Sequence[JointNode],
                links: Sequence[Link]) -> List[Joint]:
    """The Joints of ``nodes`` (a movable model's, in file order) between ``links`` (the
    model's, world poses); ``reader``: the loader (its one-line refusals)."""
    by_name: Dict[str, Link] = {link.scoped: link for link in links}
    top = links[0].scoped.split("::", 1)[0] + "::" if links else ""
    return [_joint(reader, jn, by_name, top) for jn in nodes]


def _link(reader: XmlReader, jn: JointNode, tag: str, by_name: Dict[str, Link],
          top: str) -> str:
    node = jn.node.child(tag)
    name = node.value.strip() if node is not None else ""
    if not name:
        reader.fail_bare(node if node is not None else jn.node,
                         "<joint> %s needs a <%s> link" % (jn.node.attrib.get("name"), tag))
    if name == WORLD_LINK:
        return WORLD_LINK
    for scoped in (jn.scope + name, top + name, name):
        if scoped in by_name:
            return scoped
    reader.fail_bare(node, "<joint> %s: its %s link %r is no link of this model"
                     % (jn.node.attrib.get("name"), tag, name))


def _joint(reader: XmlReader, jn: JointNode, by_name: Dict[str, Link], top: str) -> Joint:
    node = jn.node
    name = node.attrib.get("name", "")
    kind = node.attrib.get("type", "").strip()
    if kind not in JOINT_KINDS:
        reader.fail_bare(node, "<joint> %s: type %r is not one of %s"
                         % (name, kind, ", ".join(JOINT_KINDS)))
    parent = _link(reader, jn, "parent", by_name, top)
    child = _link(reader, jn, "child", by_name, top)
    if parent == child:
        reader.fail_bare(node, "<joint> %s joins link %s to itself" % (name, child))
    if child == WORLD_LINK:
        reader.fail_bare(node, "<joint> %s: the world cannot be a joint's child" % name)
    pose = jn.frames.place(node, by_name[child].pose)
    axis_node, axis2_node = node.child("axis"), node.child("axis2")
    axis = _axis(reader, jn, axis_node, pose, (0.0, 0.0, 1.0))
    axis2 = _axis(reader, jn, axis2_node, pose, (0.0, 1.0, 0.0))
    lower, upper, effort, velocity = _limits(reader, axis_node, kind)
    damping, friction = _dynamics(reader, axis_node)
    return Joint(name, kind, parent, child, pose, axis, axis2, lower, upper, effort, velocity,
                 damping, friction)


def _axis(reader: XmlReader, jn: JointNode, axis_node: Optional[Element], pose: XyzRpy,
          default) -> Tuple[float, float, float]:
    """The unit axis of ``<axis>``/``<axis2>`` in the world frame."""
    if axis_node is None:
        xyz, in_model = default, False
    else:
        xyz_node = axis_node.child("xyz")
        xyz = reader.floats(xyz_node, 3) if xyz_node is not None else default
        in_model = reader.flag(axis_node, "use_parent_model_frame", False)
        if xyz_node is not None and xyz_node.attrib.get("expressed_in"):
            in_model = xyz_node.attrib["expressed_in"].strip() == MODEL_FRAME
        length = math.sqrt(sum(v * v for v in xyz))
        if length == 0 or not math.isfinite(length):
            reader.fail_bare(xyz_node, "<xyz> of a joint axis must be a direction, not %s"
                             % xyz_node.value)
        xyz = tuple(v / length for v in xyz)
    frame = jn.model_pose if in_model else pose
    world = matrix_from_rpy(*frame[3:]) @ np.asarray(xyz, dtype=float)
    return tuple(float(v) for v in world / np.linalg.norm(world))


def _limits(reader: XmlReader, axis_node: Optional[Element], kind: str):
    """(lower, upper, effort, velocity) of the axis' <limit>."""
    limit = axis_node.child("limit") if axis_node is not None else None
    lower = reader.number(limit, "lower", -UNLIMITED)
    upper = reader.number(limit, "upper", UNLIMITED)
    effort = reader.number(limit, "effort", -1.0)
    velocity = reader.number(limit, "velocity", -1.0)
    if kind == "continuous" or lower <= -NO_LIMIT:
        lower = -UNLIMITED
    if kind == "continuous" or upper >= NO_LIMIT:
        upper = UNLIMITED
    for key, value in (("lower", lower), ("upper", upper)):
        if abs(value) < NO_LIMIT:
            problem = limits.outside("<limit><%s>" % key, value, -limits.MAX_JOINT_POSITION,
                                     limits.MAX_JOINT_POSITION, "rad or m")
            if problem:
                reader.fail_bare(limit.child(key), problem)
    return lower, upper, effort, velocity


def _dynamics(reader: XmlReader, axis_node: Optional[Element]) -> Tuple[float, float]:
    """(damping, friction) of the axis' <dynamics>; each at least 0."""
    dynamics = axis_node.child("dynamics") if axis_node is not None else None
    out = []
    for key, high, unit in (("damping", limits.MAX_DAMPING, "N m s/rad or N s/m"),
                            ("friction", limits.MAX_FORCE, "N m or N")):
        value = reader.number(dynamics, key, 0.0)
        problem = limits.outside("<dynamics><%s>" % key, value, 0.0, high, unit)
        if problem:
            reader.fail_bare(dynamics.child(key), problem)
        out.append(value)
    return out[0], out[1]
