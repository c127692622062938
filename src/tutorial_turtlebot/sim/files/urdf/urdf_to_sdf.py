"""A URDF ``<robot>`` converted into an SDF ``<model>`` as Gazebo 11 converts it (sdformat 9's
parser_urdf, which gazebo_ros's spawn services and Gazebo's loader use), so that a URDF model is
then read as any SDF model is (sdf/world_sdf.load_model_xml): each feature is written once. No
ROS, no pybullet. Units: metres, kilograms, kg m^2, radians; poses are x y z roll pitch yaw.

``urdf_to_sdf(description)`` takes what urdf_file read and checked (meshes found, those found
nowhere already left out with their warning; limits and ``<gazebo>`` blocks are read from its
``root``) and returns an ``<sdf version="1.7">`` element holding one ``<model>``, each element
at the line of the URDF element it came from, with warning lines. The rules, parser_urdf's:

- Fixed-joint lumping: a link joined to its parent by a fixed joint is merged into it, unless
  a ``<gazebo reference="JOINT">`` says ``<preserveFixedJoint>`` (the fixed joint is kept) or
  ``<disableFixedJointLumping>`` (it becomes a revolute joint held at 0). Children first, depth
  first, children in joint-name order (urdfdom keeps joints by name). Merged: masses added, the
  centre of mass their weighted mean, inertias moved to it (parallel axes), kept in the
  parent's inertial orientation; collisions and visuals moved into the parent's frame; the
  joints below re-parented; the link's ``<gazebo>`` blocks moved to the parent (a
  ``<sensor>``'s ``<pose>`` replaced by where the merged link stood, as Gazebo 11 does: its own
  pose is dropped, with one warning); a plugin's ``<bodyName>``/``<frameName>`` naming the link
  and a contact sensor's ``<collision>`` ``<link>_collision`` renamed as Gazebo renames them.
  A fixed joint from a root link ``world`` is never lumped.
- Links: every link that is not lumped, in that depth-first order, at its pose in the model
  frame (the joint chain composed; the root link is the model frame), with its ``<inertial>``
  (pose, mass, inertia). A link without mass (no ``<inertial>``, or mass 0) is not modelled,
  nor anything below it (one warning names what is left out).
- Collisions and visuals: the i-th (from 0) of a link is named ``<name>_collision`` (or
  ``_visual``) plus ``_<i>`` when i > 0, <name> its own name attribute, else the link it came
  from; a name that does not start with the link's is prefixed ``<link>_fixed_joint_lump__``
  (``base_footprint_fixed_joint_lump__base_link_collision``: bumpers' contacts use these
  names). Geometry: box, cylinder, sphere, mesh (its file, absolute, and scale). A URDF
  ``<material>`` colour is not converted (sdformat 9 drops it: Gazebo 11 draws URDF models
  grey, or a mesh in its file's colours), a ``<gazebo>`` ``<material>`` is.
- Joints: revolute and continuous are ``revolute`` (a continuous one without limits),
  prismatic, fixed; floating and planar make no joint (their child is a free link). The joint
  frame is the child link's frame; ``<axis><xyz>`` in it; ``<limit>`` lower/upper (swapped if
  lower > upper, with a warning), effort, velocity; ``<dynamics>`` damping, friction. A root
  link named ``world`` is no link: the joints from it join the model to the world.
- ``<gazebo>`` blocks: without ``reference`` into the model (``<static>``: the last such block
  decides; plugins and anything else as written); with ``reference=LINK`` into that link
  (``<turnGravityOff>`` as ``<gravity>``, ``<dampingFactor>`` as ``<velocity_decay>``,
  ``<selfCollide>``, sensors and anything else as written), its collisions' ``<surface>``
  (``<mu1>``, ``<mu2>``, ``<fdir1>``, ``<kp>``, ``<kd>``, ``<maxVel>``, ``<minDepth>``, and a
  ``<collision>`` block's contents), its visuals (``<material>`` as a Gazebo script name, and a
  ``<visual>`` block's contents); with ``reference=JOINT`` into that joint
  (``<provideFeedback>``, ``<implicitSpringDamper>``, ``<stopCfm>``, ``<stopErp>``,
  ``<springReference>``, ``<springStiffness>``, ``<fudgeFactor>``). (A reference to nothing in
  the model is refused earlier, by urdf_file's plugin reading.) What the SDF reader then does
  with each element is sdf_elements' rule, as for any SDF model.
"""
import math
from typing import Dict, List, Optional, Sequence, Tuple

import numpy as np

from ...kinematics import matrix_from_rpy, rpy_from_matrix
from ..sdf.sdf_elements import one_line
from ..world_types import WORLD_LINK
from ..xml_reader import Element, element, numbers
from .urdf_file import Geometry, RobotDescription

LUMP = "_fixed_joint_lump__"
NO_MASS = 1e-6            # kg: a link of no more mass is not modelled (ignition::math::equal)
SDF_VERSION = "1.7"
GAZEBO_MATERIAL_SCRIPT = "file://media/materials/scripts/gazebo.material"
# <gazebo reference> values written into a link's collisions: (under <surface>, SDF tag)
COLLISION_KEYS = {"mu1": ("friction", "mu"), "mu2": ("friction", "mu2"),
                  "fdir1": ("friction", "fdir1"), "kp": ("contact", "kp"),
                  "kd": ("contact", "kd"), "maxVel": ("contact", "max_vel"),
                  "minDepth": ("contact", "min_depth"), "laserRetro": ("", "laser_retro"),
                  "maxContacts": ("", "max_contacts")}
# ... and into a joint: (where, SDF tag)
JOINT_KEYS = {"stopCfm": ("limit", "cfm"), "stopErp": ("limit", "erp"),
              "springReference": ("dynamics", "spring_reference"),
              "springStiffness": ("dynamics", "spring_stiffness"),
              "fudgeFactor": ("ode", "fudge_factor")}
JOINT_FLAGS = {"provideFeedback": "provide_feedback", "implicitSpringDamper":
               "implicit_spring_damper", "cfmDamping": "implicit_spring_damper"}
SDF_JOINT = {"revolute": "revolute", "continuous": "revolute", "prismatic": "prismatic",
             "fixed": "fixed"}


def _text(node: Element) -> str:
    """A <gazebo> entry's value: its ``value`` attribute, else its text (trimmed)."""
    return (node.get("value") if node.get("value") is not None else node.text or "").strip()


def _true(node: Element) -> bool:
    value = _text(node)
    return value.lower() in ("true", "yes") or value == "1"


def _vector(node: Optional[Element], scale: float = 1.0) -> np.ndarray:
    values = numbers(_text(node), 3) if node is not None else None
    return np.array(values if values is not None else (0.0, 0.0, 0.0)) * scale


def _pose_text(t: np.ndarray) -> str:
    return " ".join(repr(float(v) + 0.0) for v in tuple(t[:3, 3]) + rpy_from_matrix(t[:3, :3]))


def _node(tag: str, line: int, text: Optional[str] = None, attrib: Optional[dict] = None,
          children: Sequence[Element] = ()) -> Element:
    node = element(tag, attrib or {}, line, children)
    node.text = text
    return node


def _copy(node: Element) -> Element:
    """A deep copy of ``node``, lines kept (the URDF's own elements stay as they are)."""
    out = element(node.tag, node.attrib, node.line, [_copy(child) for child in node])
    out.text, out.tail = node.text, node.tail
    return out


def _child(parent: Element, tag: str) -> Element:
    """``parent``'s first ``<tag>``, made (at its line) if it has none."""
    found = parent.find(tag)
    if found is None:
        found = _node(tag, parent.line)
        parent.append(found)
    return found


def _set(parent: Element, tag: str, text: str) -> None:
    """``<tag>text</tag>`` in ``parent`` in place of any earlier one (AddKeyValue: the last
    value wins)."""
    for old in parent.findall(tag):
        parent.remove(old)
    parent.append(_node(tag, parent.line, text))


class _Extension:
    """One ``<gazebo>`` block, read as parser_urdf reads it; ``old_link`` its reference as
    written, ``reduction`` where the merged link stood in the link it was moved to."""

    def __init__(self, block: Element, ref: str):
        self.old_link = ref
        self.line = block.line
        self.gravity = True
        self.damping: Optional[str] = None
        self.self_collide: Optional[bool] = None
        self.material = ""
        self.values: Dict[str, str] = {}
        self.flags: Dict[str, bool] = {}
        self.collision_blobs: List[Element] = []
        self.visual_blobs: List[Element] = []
        self.blobs: List[Element] = []
        self.reduction = np.eye(4)
        self.lumped = False      # moved into a parent link already (its sensors' poses too)
        for child in block:
            tag = child.tag
            if tag == "material":
                self.material = _text(child)
            elif tag in ("collision", "visual"):
                blobs = self.collision_blobs if tag == "collision" else self.visual_blobs
                blobs.extend([_copy(node) for node in child])
            elif tag == "turnGravityOff":
                value = _text(child)
                self.gravity = value.lower() in ("false", "no") or value == "0"
            elif tag == "dampingFactor":
                self.damping = _text(child)
            elif tag == "selfCollide":
                self.self_collide = _true(child)
            elif tag in COLLISION_KEYS or tag in JOINT_KEYS:
                self.values[tag] = _text(child)
            elif tag in JOINT_FLAGS:
                self.flags[JOINT_FLAGS[tag]] = _true(child)
            elif tag not in ("static", "canonicalBody", "disableFixedJointLumping",
                             "preserveFixedJoint"):
                self.blobs.append(_copy(child))


class _Link:
    """A link being converted: inertial (mass, 4x4 pose of its centre of mass in the link,
    3x3 inertia in that frame) or None, shapes as [name, 4x4 pose in the link, Geometry]."""

    def __init__(self, name: str, description: RobotDescription, line: int):
        self.name = name
        self.line = line
        link = description.links[name]
        self.inertial = None
        if link.inertial is not None:
            i = link.inertial
            ixx, ixy, ixz, iyy, iyz, izz = i.inertia
            self.inertial = (i.mass, i.origin.matrix(),
                             np.array([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]]))
        self.collisions = [[c.name, c.origin.matrix(), c.geometry] for c in link.collisions]
        self.visuals = [[v.name, v.origin.matrix(), v.geometry] for v in link.visuals]
        self.children: List[str] = []


class _Converter:
    def __init__(self, description: RobotDescription, source: str):
        self.d = description
        self.source = source
        self.warnings: List[str] = []
        root = description.root
        self.root_line = root.line if root is not None else 0
        lines = {}
        self.joint_elems: Dict[str, Element] = {}
        for node in (root if root is not None else ()):
            if node.tag in ("link", "joint"):
                lines.setdefault((node.tag, node.get("name", "").strip()), node.line)
            if node.tag == "joint":
                self.joint_elems.setdefault(node.get("name", "").strip(), node)
        self.joint_line = {name: lines.get(("joint", name), self.root_line)
                           for name in description.joints}
        self.links = {name: _Link(name, description, lines.get(("link", name), self.root_line))
                      for name in description.links}
        self.joint_of = {j.child: j for j in description.joints.values()}
        self.origin = {j.name: j.origin.matrix() for j in description.joints.values()}
        self.parent = {j.child: j.parent for j in description.joints.values()}
        for joint in sorted(description.joints.values(), key=lambda j: j.name):
            self.links[joint.parent].children.append(joint.child)
        self.extensions: Dict[str, List[_Extension]] = {}
        self.preserved, self.revolute = set(), set()
        for block in (root.findall("gazebo") if root is not None else ()):
            ref = block.get("reference", "").strip()
            self.extensions.setdefault(ref, []).append(_Extension(block, ref))
            for child in block:
                if child.tag == "preserveFixedJoint" and _true(child):
                    self.preserved.add(ref)
                elif child.tag == "disableFixedJointLumping" and _true(child):
                    self.revolute.add(ref)
        self.revolute -= self.preserved

    def _warn(self, line: int, message: str) -> None:
        self.warnings.append(one_line(self.source, line, message))

    def reduced(self, link: str) -> bool:
        """Whether the joint above ``link`` is a fixed joint that is lumped (FixedJoint
        ShouldBeReduced), its parent not ``world``."""
        joint = self.joint_of.get(link)
        return (joint is not None and joint.type == "fixed" and joint.name not in self.preserved
                and joint.name not in self.revolute and joint.parent != WORLD_LINK)

    # --- lumping (ReduceFixedJoints) -----------------------------------------------------------

    def reduce(self, name: str) -> None:
        link = self.links[name]
        for child in link.children:
            if self.reduced(child):
                self.reduce(child)
        if self.reduced(name):
            self._lump(link, self.links[self.parent[name]], self.joint_of[name])
        for child in link.children:
            if not self.reduced(child):
                self.reduce(child)

    def _lump(self, link: _Link, parent: _Link, joint) -> None:
        t = self.origin[joint.name]
        self._move_extensions(link, parent, t)
        if link.inertial is not None:
            parent.inertial = _merged(parent.inertial, link.inertial, t)
        for shapes, into in ((link.collisions, parent.collisions),
                             (link.visuals, parent.visuals)):
            for shape in shapes:
                into.append([shape[0] if LUMP in shape[0] else (shape[0] or link.name),
                             t @ shape[1], shape[2]])
        for child in link.children:        # ReduceJointsToParent: the parent above the lumps
            if not self.reduced(child):
                above = link.name
                while above in self.joint_of and self.reduced(above):
                    above = self.parent[above]
                self.parent[child] = above

    def _move_extensions(self, link: _Link, parent: _Link, t: np.ndarray) -> None:
        moved = self.extensions.pop(link.name, [])
        for ext in moved:
            ext.reduction = t @ ext.reduction
            first, ext.lumped = not ext.lumped, True
            for blob in ext.blobs:
                if blob.tag == "sensor":
                    for pose in blob.findall("pose"):
                        values = numbers(_text(pose), 6)
                        if first and (values is None or any(values)):
                            self._warn(pose.line, "<sensor> %r: its <pose> in link %r is "
                                       "dropped when the link is lumped into %r, as Gazebo 11 "
                                       "drops it; it stands where the link stood"
                                       % (blob.get("name", ""), link.name, parent.name))
                        blob.remove(pose)
                    blob.append(_node("pose", blob.line, _pose_text(ext.reduction)))
        self.extensions.setdefault(parent.name, []).extend(moved)
        for exts in self.extensions.values():     # ReduceSDFExtensionFrameReplace
            for ext in exts:
                for blob in ext.blobs:
                    _frame_replace(blob, link.name, parent.name, ext.reduction, self.origin[
                        self.joint_of[link.name].name])

    # --- writing (CreateSDF) -------------------------------------------------------------------

    def model(self) -> Element:
        root = self.d.root_link
        model = _node("model", self.root_line, attrib={"name": self.d.name})
        if root == WORLD_LINK:
            for child in self.links[root].children:
                self.create(model, child)
        else:
            self.create(model, root)
        for ext in self.extensions.get("", ()):
            model.extend(ext.blobs)
        if "" in self.extensions:
            _set(model, "static", "true" if self.d.static else "false")
        origin = self.d.root.find("origin") if self.d.root is not None else None
        if origin is not None:
            t = np.eye(4)
            t[:3, :3] = matrix_from_rpy(*_vector(_attr_node(origin, "rpy")))
            t[:3, 3] = _vector(_attr_node(origin, "xyz"))
            model.append(_node("pose", origin.line, _pose_text(t)))
        return _node("sdf", self.root_line, attrib={"version": SDF_VERSION}, children=[model])

    def create(self, model: Element, name: str) -> None:
        link = self.links[name]
        if link.inertial is None or abs(link.inertial[0]) <= NO_MASS:
            lost = [n for n in self._below(name) if not self.reduced(n)]
            if lost:
                self._warn(link.line, "link%s %s left out, with %s joint%s: link %r has no "
                           "mass (no <inertial>, or mass 0), and Gazebo models nothing from "
                           "it down" % ("s" if len(lost) > 1 else "", ", ".join(lost),
                                        "their" if len(lost) > 1 else "its",
                                        "s" if len(lost) > 1 else "", name))
            return
        if not self.reduced(name):
            joint = self.joint_of.get(name)
            if joint is not None:
                self.joint(model, joint)
            model.append(self.link(link))
        for child in link.children:
            self.create(model, child)

    def _below(self, name: str) -> List[str]:
        out = [name]
        for link in out:
            out.extend(self.links[link].children)
        return out

    def link(self, link: _Link) -> Element:
        node = _node("link", link.line, attrib={"name": link.name})
        node.append(_node("pose", link.line, _pose_text(self.d.transform(self.d.root_link,
                                                                         link.name))))
        mass, com, inertia = link.inertial
        values = [_node(tag, link.line, repr(float(inertia[i, j]))) for tag, i, j in (
            ("ixx", 0, 0), ("ixy", 0, 1), ("ixz", 0, 2), ("iyy", 1, 1), ("iyz", 1, 2),
            ("izz", 2, 2))]
        node.append(_node("inertial", link.line, children=[
            _node("pose", link.line, _pose_text(com)), _node("mass", link.line, repr(float(mass))),
            _node("inertia", link.line, children=values)]))
        exts = self.extensions.get(link.name, ())
        for kind, shapes in (("collision", link.collisions), ("visual", link.visuals)):
            for i, (own, pose, geometry) in enumerate(shapes):
                name = (own or link.name) + "_" + kind + ("_%d" % i if i else "")
                if not name.startswith(link.name):
                    name = link.name + LUMP + name
                shape = _node(kind, link.line, attrib={"name": name}, children=[
                    _node("pose", link.line, _pose_text(pose)), _geometry(geometry, link.line)])
                for ext in exts:
                    if _applies(ext, link.name, name, kind):
                        (_collision_extension if kind == "collision" else _visual_extension)(
                            shape, ext)
                node.append(shape)
        for ext in exts:
            _set(node, "gravity", "true" if ext.gravity else "false")
            decay = _node("velocity_decay", ext.line)
            if ext.damping is not None:
                decay.extend([_node("linear", ext.line, ext.damping),
                              _node("angular", ext.line, ext.damping)])
            node.append(decay)
            if ext.self_collide is not None:
                _set(node, "self_collide", "1" if ext.self_collide else "0")
            node.extend(ext.blobs)
        return node

    def joint(self, model: Element, joint) -> None:
        kind = SDF_JOINT.get(joint.type)
        if kind is None:             # floating, planar: no joint, a free link
            return
        line = self.joint_line[joint.name]
        revolute = joint.type == "fixed" and joint.name in self.revolute
        node = _node("joint", line, attrib={"name": joint.name,
                                            "type": "revolute" if revolute else kind})
        node.extend([_node("parent", line, self.parent[joint.child]),
                     _node("child", line, joint.child)])
        if revolute:
            node.append(_node("axis", line, children=[
                _node("limit", line, children=[_node("lower", line, "0"),
                                               _node("upper", line, "0")]),
                _node("dynamics", line, children=[_node("damping", line, "0"),
                                                  _node("friction", line, "0")])]))
        elif kind != "fixed":
            axis = _node("axis", line, children=[
                _node("xyz", line, " ".join(repr(float(v)) for v in joint.axis))])
            axis.append(self._limit(joint, line))
            dynamics = _node("dynamics", line)
            elem = self.joint_elems.get(joint.name)
            if elem is not None and elem.find("dynamics") is not None:
                dynamics.extend([_node("damping", line, repr(joint.damping)),
                                 _node("friction", line, repr(joint.friction))])
            axis.append(dynamics)
            node.append(axis)
        for ext in self.extensions.get(joint.name, ()):
            _joint_extension(node, ext)
        model.append(node)

    def _limit(self, joint, line: int) -> Element:
        limit = _node("limit", line)
        elem = self.joint_elems.get(joint.name)
        urdf = elem.find("limit") if elem is not None else None
        if urdf is None or joint.type == "continuous":
            return limit
        value = {key: float(urdf.get(key, "0")) for key in ("lower", "upper")}
        value.update((key, float(urdf.get(key))) for key in ("effort", "velocity")
                     if urdf.get(key) is not None)
        if value["lower"] > value["upper"]:
            self._warn(urdf.line, "joint %r: lower limit %g > upper limit %g: swapped, as "
                                  "Gazebo swaps them" % (joint.name, value["lower"],
                                                         value["upper"]))
            value["lower"], value["upper"] = value["upper"], value["lower"]
        limit.extend(_node(key, line, repr(value[key])) for key in ("lower", "upper", "effort",
                                                                    "velocity") if key in value)
        return limit


def _attr_node(origin: Element, key: str) -> Optional[Element]:
    """A stand-in element holding ``origin``'s attribute ``key`` as text (None if absent)."""
    return None if origin.get(key) is None else _node(key, origin.line, origin.get(key))


def _merged(parent, child, t: np.ndarray):
    """The inertial of a parent link with a child's merged in (ReduceInertialToParent):
    ``child`` placed by ``t`` (the child frame in the parent's); each (mass, 4x4 centre-of-mass
    pose in its link, 3x3 inertia in that frame); the result keeps the parent's orientation."""
    if parent is None:
        parent = (0.0, np.eye(4), np.zeros((3, 3)))
    parts = []
    for mass, pose, inertia in (parent, (child[0], t @ child[1], child[2])):
        r = pose[:3, :3]
        parts.append((mass, pose[:3, 3], r @ inertia @ r.T))
    total = parts[0][0] + parts[1][0]
    com = (sum(m * c for m, c, _ in parts) / total) if total > 0 else np.zeros(3)
    moment = np.zeros((3, 3))
    for mass, c, inertia in parts:
        d = c - com
        moment += inertia + mass * (np.dot(d, d) * np.eye(3) - np.outer(d, d))
    pose = np.eye(4)
    pose[:3, :3] = parent[1][:3, :3]
    pose[:3, 3] = com
    r = pose[:3, :3]
    return total, pose, r.T @ moment @ r


def _geometry(geometry: Geometry, line: int) -> Element:
    size = [repr(float(v)) for v in geometry.size]
    if geometry.shape == "box":
        children = [_node("size", line, " ".join(size))]
    elif geometry.shape == "cylinder":
        children = [_node("length", line, size[1]), _node("radius", line, size[0])]
    elif geometry.shape == "sphere":
        children = [_node("radius", line, size[0])]
    else:
        children = [_node("scale", line, " ".join(size)),
                    _node("uri", line, geometry.filename)]
    return _node("geometry", line, children=[_node(geometry.shape, line, children=children)])


def _applies(ext: _Extension, link: str, name: str, kind: str) -> bool:
    """Whether the extension ``ext`` of ``link`` goes into its collision or visual ``name``: a
    link's own ones into those not lumped, a lumped link's into those lumped from it."""
    if link == ext.old_link:
        return LUMP not in name
    return LUMP + ext.old_link + "_" + kind in name


def _collision_extension(shape: Element, ext: _Extension) -> None:
    surface = shape.find("surface")
    for blob in ext.collision_blobs:
        if blob.tag == "surface" and surface is not None:
            shape.remove(surface)
        shape.append(_copy(blob))
        if blob.tag == "surface":
            surface = shape.findall("surface")[-1]
    surface = surface if surface is not None else _child(shape, "surface")
    for under in ("contact", "friction"):
        _child(_child(surface, under), "ode")
    for key, (under, tag) in COLLISION_KEYS.items():
        if key in ext.values:
            into = shape if not under else _child(_child(surface, under), "ode")
            _set(into, tag, ext.values[key])


def _visual_extension(shape: Element, ext: _Extension) -> None:
    material = shape.find("material")
    for blob in ext.visual_blobs:
        if blob.tag == "material" and material is not None:
            shape.remove(material)
        shape.append(_copy(blob))
        if blob.tag == "material":
            material = shape.findall("material")[-1]
    if ext.material:
        material = material if material is not None else _child(shape, "material")
        script = _child(material, "script")
        _set(script, "name", ext.material)
        _set(script, "uri", GAZEBO_MATERIAL_SCRIPT)


def _joint_extension(joint: Element, ext: _Extension) -> None:
    physics = _child(joint, "physics")
    ode = _child(physics, "ode")
    dynamics = _child(_child(joint, "axis"), "dynamics")
    where = {"limit": _child(ode, "limit"), "dynamics": dynamics, "ode": ode}
    for key, (under, tag) in JOINT_KEYS.items():
        if key in ext.values:
            _set(where[under], tag, ext.values[key])
    for tag, value in ext.flags.items():
        text = "true" if value else "false"
        if tag == "provide_feedback":
            _set(physics, tag, text)
        else:
            _set(ode, "cfm_damping", text)
        _set(ode, tag, text)
    joint.extend(ext.blobs)


def _frame_replace(blob: Element, link: str, parent: str, reduction: np.ndarray,
                   joint_origin: np.ndarray) -> None:
    """What parser_urdf renames in an extension's ``blob`` when ``link`` is lumped into
    ``parent``: a contact sensor's <collision> ``<link>_collision`` (to
    ``<parent>_collision_<link>``), a plugin's <bodyName> and <frameName> naming the link (its
    <xyzOffset>, <rpyOffset> (read in degrees) moved as Gazebo moves them), a <joint>'s
    <parent> and <child>."""
    if blob.tag == "sensor":
        collision = blob.find("contact/collision")
        if collision is not None and _text(collision) == link + "_collision":
            collision.text = parent + "_collision_" + link
    elif blob.tag == "plugin":
        for key in ("bodyName", "frameName"):
            node = blob.find(key)
            if node is None or _text(node) != link:
                continue
            blob.remove(node)
            blob.append(_node(key, node.line, parent))
            t = reduction.copy()
            xyz, rpy = blob.find("xyzOffset"), blob.find("rpyOffset")
            if xyz is not None:
                t[:3, 3] = _vector(xyz)
                blob.remove(xyz)
            if rpy is not None:
                t[:3, :3] = matrix_from_rpy(*_vector(rpy, math.pi / 180.0))
                blob.remove(rpy)
            back = joint_origin[:3, :3].T          # inverseTransformToParentFrame
            moved = np.eye(4)
            moved[:3, 3] = back @ t[:3, 3] - joint_origin[:3, 3]
            moved[:3, :3] = back @ t[:3, :3]
            blob.append(_node("xyzOffset", node.line, " ".join(
                repr(float(v)) for v in moved[:3, 3])))
            blob.append(_node("rpyOffset", node.line, " ".join(
                repr(float(v)) for v in rpy_from_matrix(moved[:3, :3]))))
    elif blob.tag == "joint":
        for key in ("parent", "child"):
            node = blob.find(key)
            if node is not None and _text(node) == link:
                node.text = parent


def urdf_to_sdf(description: RobotDescription,
                source: Optional[str] = None) -> Tuple[Element, List[str]]:
    """(``<sdf>`` holding the ``<model>`` Gazebo 11 makes of ``description``, warning lines,
    each naming ``source`` (default: the description's path) and a line of the URDF)."""
    converter = _Converter(description, source or description.path)
    converter.reduce(description.root_link)
    return converter.model(), converter.warnings
