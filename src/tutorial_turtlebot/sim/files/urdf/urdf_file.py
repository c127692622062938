"""Read a URDF file into plain dataclasses, with neither ROS nor pybullet.

Units: metres, kilograms, kg*m^2, radians. An ``Origin`` is a child frame's origin in its parent
frame: ``xyz`` then ``rpy`` as URDF defines it (fixed axes: R = Rz(yaw) * Ry(pitch) * Rx(roll)).
Every problem with the file raises ``UrdfError`` whose message is xml_reader's one line:
``<file>:<line>: <element at fault>: <what is wrong>``; a DOCTYPE is refused, as in SDF. The
``<gazebo>`` blocks (plugins and sensors) are read by ``robot_plugins.read_plugins`` into
``RobotDescription.plugins``.
A ``<mesh filename>`` (``package://``, ``file://``, absolute, or relative to the URDF's folder;
for a URDF given as text, to the working directory) is found and checked while reading: it must
name an STL, Collada (.dae) or OBJ file; ``Geometry.filename`` is then its absolute path and
``Geometry.uri`` the filename as written. A visual or collision whose file is found nowhere is
left out with one warning line (``RobotDescription.warnings``), as Gazebo loads the link without
it (urdf_gazebo); a file that is no mesh, or a bad scale, is refused. The file's triangles are
read later, by ``mesh_file.load_mesh``, when a body is built.
What Gazebo's URDF conversion adds (urdf_gazebo): a reference-less ``<gazebo>`` block's
``<static>`` (``RobotDescription.static``), and a root link named ``world``, to which the model is
joined (``model_links``; urdf_to_sdf converts a URDF into the SDF model Gazebo makes).
"""
import os
from dataclasses import dataclass, field
from typing import Dict, List, Optional, Tuple

import numpy as np

from ....errors import UrdfError, UserError
from .. import limits
from .. import xml_reader
from ..asset_uri import AssetNotFound, resolve_uri
from ...kinematics import Vector3, transform_from_xyz_rpy
from ..meshes.mesh_file import load_mesh
from ....robot_models import urdf_path
from ..plugins.robot_plugin_types import RobotPlugins
from ..plugins.robot_plugins import read_plugins
from ..xml_reader import Element, XmlReader
from .urdf_gazebo import WORLD_LINK, MissingMeshes, read_static

REEXPORTED = (urdf_path,)  # re-exported: the sim and the tests import urdf_path from here

NAMED = ("robot", "link", "joint", "material")  # elements that errors call by name
JOINT_TYPES = ("fixed", "continuous", "revolute", "prismatic", "floating", "planar")
LUMP = "_fixed_joint_lump__"


@dataclass(frozen=True)
class Origin:
    """A URDF ``<origin>``: a child frame in its parent frame as written, xyz (m) and
    fixed-axis roll, pitch, yaw (rad); kinematics converts it."""

    xyz: Vector3 = (0.0, 0.0, 0.0)
    rpy: Vector3 = (0.0, 0.0, 0.0)

    def matrix(self) -> np.ndarray:
        """4x4 homogeneous transform T with p_parent = T @ p_child."""
        return transform_from_xyz_rpy(self.xyz, self.rpy)


@dataclass(frozen=True)
class Geometry:
    """A shape in its own frame. ``size``: box (x, y, z); cylinder (radius, length) along z;
    sphere (radius,); mesh (scale x, y, z: the factors the file's coordinates are multiplied
    by), with ``filename`` the mesh file's absolute path and ``uri`` its filename as written."""

    shape: str
    size: Tuple[float, ...]
    filename: str = ""
    uri: str = ""


@dataclass(frozen=True)
class Collision:
    """A collision shape placed at ``origin`` in its link frame; ``name``: its name attribute
    ("" if it has none)."""

    origin: Origin
    geometry: Geometry
    name: str = ""


@dataclass(frozen=True)
class Visual:
    """A visual shape placed at ``origin`` in its link frame.

    ``rgba`` is in 0..1, None if uncoloured; ``name``: its name attribute ("" if none).
    """

    origin: Origin
    geometry: Geometry
    material: str = ""
    rgba: Optional[Tuple[float, float, float, float]] = None
    name: str = ""


@dataclass(frozen=True)
class Inertial:
    """Mass (kg) and inertia tensor (kg*m^2: ixx, ixy, ixz, iyy, iyz, izz) about ``origin``."""

    mass: float
    inertia: Tuple[float, float, float, float, float, float]
    origin: Origin = Origin()


@dataclass(frozen=True)
class Link:
    """A URDF link; ``inertial`` is None for a bare frame (base_footprint, imu_link, cameras)."""

    name: str
    inertial: Optional[Inertial] = None
    collisions: Tuple[Collision, ...] = ()
    visuals: Tuple[Visual, ...] = ()

    @property
    def mass(self) -> float:
        """kg; 0 for a link without an inertial."""
        return self.inertial.mass if self.inertial else 0.0


@dataclass(frozen=True)
class Joint:
    """A URDF joint: ``origin`` is the child frame in the parent frame at joint position 0;
    ``axis`` is a unit-free direction in the child (= joint) frame."""

    name: str
    type: str
    parent: str
    child: str
    origin: Origin = Origin()
    axis: Vector3 = (1.0, 0.0, 0.0)
    friction: float = 0.0          # N m (N): the <dynamics> friction that holds it still
    damping: float = 0.0           # N m s/rad (N s/m): <dynamics> damping (a robot: not simulated)


@dataclass(frozen=True)
class RobotDescription:
    """A whole robot: links and joints by name, in file order. The tree is checked on reading:
    every joint names known links, each link has at most one parent, there is one root.
    ``plugins``: what its ``<gazebo>`` blocks declare. ``path``: the file, or for a URDF read
    from text the name its errors give (e.g. "spawn_urdf_model tb3_3"). ``root``: the parsed
    ``<robot>`` element it was read from (xml_reader), for whoever writes the URDF out again,
    without the visuals and collisions left out (a copy then); copy it before changing it.
    ``static``: its ``<gazebo><static>`` (urdf_gazebo.read_static). ``warnings``: one line
    each, what was left out (a mesh file found nowhere) or overridden."""

    name: str
    path: str
    links: Dict[str, Link]
    joints: Dict[str, Joint]
    _parent_joint: Dict[str, Joint] = field(init=False, repr=False, compare=False)
    plugins: RobotPlugins = RobotPlugins()
    root: Optional[Element] = field(default=None, repr=False, compare=False)
    static: bool = False
    warnings: Tuple[str, ...] = ()

    def __post_init__(self):
        object.__setattr__(self, "_parent_joint", {j.child: j for j in self.joints.values()})

    @property
    def root_link(self) -> str:
        """Name of the one link that is no joint's child (base_footprint on a TurtleBot3)."""
        return next(name for name in self.links if name not in self._parent_joint)

    def _lumped(self, link: str) -> bool:
        """Whether Gazebo lumps ``link`` into its parent: its joint is fixed, and the parent is
        not a root ``world`` (that joint joins the model to the world)."""
        joint = self._parent_joint.get(link)
        return joint is not None and joint.type == "fixed" and not (
            joint.parent == WORLD_LINK == self.root_link)

    def model_links(self) -> List[str]:
        """The links Gazebo's model has (get_model_properties' body_names), in file order:
        every link not lumped into its parent by a fixed joint; a root ``world`` is none."""
        return [link for link in self.links if not self._lumped(link)
                and not link == WORLD_LINK == self.root_link]

    @property
    def mass(self) -> float:
        """Total mass of all links, kg."""
        return sum(link.mass for link in self.links.values())

    def parent_joint(self, link: str) -> Optional[Joint]:
        """The joint whose child is ``link``; None for the root."""
        self._check_link(link)
        return self._parent_joint.get(link)

    def transform(self, frame: str, target: str) -> np.ndarray:
        """4x4 pose of link ``target`` in link ``frame`` (p_frame = T @ p_target), every joint at
        position 0. Translation in m is ``T[:3, 3]``, rotation ``T[:3, :3]``."""
        return np.linalg.inv(self._pose_in_root(frame)) @ self._pose_in_root(target)

    def _pose_in_root(self, link: str) -> np.ndarray:
        self._check_link(link)
        pose = np.eye(4)
        while link in self._parent_joint:
            joint = self._parent_joint[link]
            pose = joint.origin.matrix() @ pose
            link = joint.parent
        return pose

    def _check_link(self, link: str) -> None:
        if link not in self.links:
            raise KeyError("no link %r in %s" % (link, self.path))

    def collision_names(self) -> Dict[str, List[str]]:
        """Gazebo's names of the collisions (get_model_properties' geom_names), by the link
        that holds them once fixed joints are lumped, as gazebo_ros's URDF to SDF conversion
        (sdformat's parser_urdf) names them: a link takes its own collisions, then those of
        its fixed-jointed children (depth first, children in joint-name order, as urdfdom
        keeps them; a root ``world`` is no link and lumps none); the i-th (from 0) is called
        ``<name>_collision`` plus ``_<i>`` when i > 0, where <name> is the collision's own
        name attribute or else the link it came from, and a name that does not start with the
        holding link's name is prefixed ``<link>_fixed_joint_lump__``. A TurtleBot3 Burger:
        base_footprint holds ``base_footprint_fixed_joint_lump__base_link_collision``,
        ``..._caster_back_link_collision_1`` and ``..._base_scan_collision_2``; each wheel
        link ``wheel_left_link_collision``."""
        children: Dict[str, List[Tuple[str, str]]] = {}
        for joint in self.joints.values():
            if self._lumped(joint.child):
                children.setdefault(joint.parent, []).append((joint.name, joint.child))

        def lumped(link: str) -> List[str]:
            names = [c.name or link for c in self.links[link].collisions]
            for _, child in sorted(children.get(link, ())):
                names += lumped(child)
            return names

        out: Dict[str, List[str]] = {}
        for link in self.model_links():
            names = []
            for i, base in enumerate(lumped(link)):
                geom = base + "_collision" + ("_%d" % i if i else "")
                names.append(geom if geom.startswith(link) else link + LUMP + geom)
            out[link] = names
        return out


def read_urdf(path) -> RobotDescription:
    """Read and check the URDF file at ``path``; any problem raises a one-line UrdfError.
    Relative mesh filenames are taken from the file's folder."""
    path = str(path)
    root = xml_reader.parse_file(path, "URDF file", UrdfError)
    return read_urdf_element(root, path, os.path.dirname(os.path.abspath(path)))


def read_urdf_text(xml: str, source: str, base_dir: Optional[str] = None) -> RobotDescription:
    """Read and check a URDF given as text (e.g. a spawn_urdf_model request); ``source`` names
    it in the one-line UrdfError that any problem raises, and is the result's ``path``.
    Relative mesh filenames are taken from ``base_dir`` (default: the working directory)."""
    if not isinstance(xml, (str, bytes)):
        raise UrdfError("%s: the URDF must be text, not %s" % (source, type(xml).__name__))
    return read_urdf_element(xml_reader.parse(xml, source, UrdfError), source, base_dir)


def read_urdf_element(root: Element, source: str,
                      base_dir: Optional[str] = None) -> RobotDescription:
    """Read and check a URDF already parsed by xml_reader (its ``<robot>`` element); ``source``
    names it in errors and is the result's ``path``; relative mesh filenames are taken from
    ``base_dir`` (default: the working directory)."""
    return _Reader(source, base_dir or os.getcwd()).read(root)


def mesh_path(uri: str, base_dir: str, scale=(1.0, 1.0, 1.0)) -> str:
    """The absolute path of the mesh file a URDF ``<mesh filename>`` names (relative to
    ``base_dir``), read once here with its ``scale`` (mesh_file caches it); UserError (one
    line, without file or element) if it cannot be found, is not a mesh this simulator reads,
    or reaches beyond the world once scaled."""
    path = resolve_uri(uri, base_dir)
    load_mesh(path, scale)
    return path


def mesh_scale(text: Optional[str]) -> Optional[Tuple[float, float, float]]:
    """A ``<mesh scale>`` as three non-zero factors within +-limits.MAX_SCALE ((1, 1, 1)
    when absent); None if it is not that (a negative factor mirrors the mesh, as in Gazebo)."""
    if text is None:
        return (1.0, 1.0, 1.0)
    values = xml_reader.numbers(text, 3, finite=False)
    if values is None or limits.scale_problem(values):
        return None
    return values


class _Reader(XmlReader):
    """One pass over one parsed URDF; every error names the file and the element's line."""

    def __init__(self, path: str, base_dir: str = ""):
        super().__init__(path, UrdfError)
        self.path = path
        self.base_dir = base_dir
        self.missing = MissingMeshes(path)

    def read(self, root: Element) -> RobotDescription:
        if root.tag != "robot":
            self.fail(root, "the root element must be <robot>")
        name = self._name(root)
        materials = {}
        for elem in root.findall("material"):
            rgba = self._rgba(elem, "material %r" % self._name(elem))
            if rgba is not None:
                materials[elem.get("name")] = rgba
        links: Dict[str, Link] = {}
        for elem in root.findall("link"):
            link = self._link(elem, materials)
            if link.name in links:
                self.fail(elem, "defined twice")
            links[link.name] = link
        if not links:
            self.fail(root, "no <link> in robot %r" % name)
        if len(links) > limits.MAX_URDF_LINKS:
            self.fail(root, "robot %r has %d links, more than the %d one URDF may have"
                      % (name, len(links), limits.MAX_URDF_LINKS))
        joints: Dict[str, Joint] = {}
        parent_of: Dict[str, Element] = {}
        for elem in root.findall("joint"):
            joint = self._joint(elem, links)
            if joint.name in joints:
                self.fail(elem, "defined twice")
            if joint.child in parent_of:
                first = parent_of[joint.child]
                self.fail(elem, "link %r already has a parent, joint %r (line %s)"
                          % (joint.child, first.get("name"), first.line))
            joints[joint.name] = joint
            parent_of[joint.child] = elem
        self._check_tree(root, links, joints)
        plugins = read_plugins(root, links, {j.name: j.type for j in joints.values()},
                               self.path)
        static, warnings = read_static(root, self.path)
        return RobotDescription(name, self.path, links, joints, plugins,
                                self.missing.trimmed(root), static,
                                tuple(warnings + self.missing.warnings()))

    def _check_tree(self, root, links, joints) -> None:
        children = {j.child for j in joints.values()}
        roots = [name for name in links if name not in children]
        if not roots:
            self.fail(root, "no root link: every link is the child of a joint (a loop)")
        if len(roots) > 1:
            self.fail(root, "%d root links (%s): links must form one tree joined by joints"
                      % (len(roots), ", ".join(roots)))
        below: Dict[str, List[str]] = {}
        for joint in joints.values():
            below.setdefault(joint.parent, []).append(joint.child)
        depth = {roots[0]: 0}
        todo = [roots[0]]
        while todo:
            parent = todo.pop()
            for child in below.get(parent, ()):
                if child not in depth:
                    depth[child] = depth[parent] + 1
                    if depth[child] > limits.MAX_URDF_DEPTH:
                        self.fail(root, "link %r is %d joints from root link %r: a chain may "
                                  "be at most %d deep" % (child, depth[child], roots[0],
                                                          limits.MAX_URDF_DEPTH))
                    todo.append(child)
        reached = depth
        moving = sum(1 for joint in joints.values() if joint.type != "fixed")
        if moving > limits.MAX_MOVING_JOINTS:
            self.fail(root, "%d joints that move: pybullet builds at most %d in one body"
                      % (moving, limits.MAX_MOVING_JOINTS))
        if len(reached) < len(links):
            lost = [name for name in links if name not in reached]
            self.fail(root, "links %s form a loop cut off from root link %r"
                      % (", ".join(lost), roots[0]))

    def _link(self, elem, materials) -> Link:
        name = self._name(elem)
        owner = "link %r" % name
        inertial = None
        inertial_elem = elem.find("inertial")
        if inertial_elem is not None:
            mass_elem = self.child(inertial_elem, "mass", owner)
            mass = self._numbers(mass_elem, "value", 1, owner, finite=False)[0]
            problem = limits.mass_problem(mass, allow_zero=True)   # 0: a bare frame
            if problem:
                self.fail(mass_elem, problem, owner)
            inertia_elem = self.child(inertial_elem, "inertia", owner)
            inertia = tuple(self._numbers(inertia_elem, key, 1, owner, finite=False)[0]
                            for key in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz"))
            ixx, ixy, ixz, iyy, iyz, izz = inertia
            problem = limits.inertia_problem((ixx, iyy, izz), (ixy, ixz, iyz), allow_zero=True)
            if problem:
                self.fail(inertia_elem, problem, owner)
            inertial = Inertial(mass, inertia, self._origin(inertial_elem, owner))
        collisions = []
        for c in elem.findall("collision"):
            geometry = self._geometry(c, owner)
            if geometry is not None:      # None: its mesh is left out
                collisions.append(Collision(self._origin(c, owner), geometry, c.get("name") or ""))
        visuals = [self._visual(v, owner, materials) for v in elem.findall("visual")]
        return Link(name, inertial, tuple(collisions), tuple(v for v in visuals if v))

    def _visual(self, elem, owner, materials) -> Optional[Visual]:
        geometry = self._geometry(elem, owner)
        if geometry is None:
            return None
        visual = Visual(self._origin(elem, owner), geometry, name=elem.get("name") or "")
        material = elem.find("material")
        if material is None:
            return visual
        name = material.get("name", "")
        rgba = self._rgba(material, owner)
        if rgba is None and name:
            if name not in materials:
                self.fail(material, "has no <color> and no robot-level definition", owner)
            rgba = materials[name]
        return Visual(visual.origin, visual.geometry, name, rgba, visual.name)

    def _rgba(self, material, owner):
        color = material.find("color")
        if color is None:
            return None
        rgba = self._numbers(color, "rgba", 4, owner)
        if not all(0.0 <= c <= 1.0 for c in rgba):
            self.fail(color, "rgba %r must be four numbers from 0 to 1" % color.get("rgba"), owner)
        return rgba

    def _geometry(self, elem, owner) -> Optional[Geometry]:
        """The shape of a <visual> or <collision> ``elem``; None if its mesh file is found
        nowhere (left out, with a warning: MissingMeshes)."""
        geometry = self.child(elem, "geometry", owner)
        shapes = list(geometry)
        if len(shapes) != 1:
            self.fail(geometry, "needs exactly one of <box>, <cylinder>, <sphere>, <mesh>", owner)
        shape = shapes[0]
        if shape.tag in ("box", "cylinder", "sphere"):
            keys = {"box": ("size",), "cylinder": ("radius", "length"),
                    "sphere": ("radius",)}[shape.tag]
            size = ()
            for key in keys:
                values = self._numbers(shape, key, 3 if key == "size" else 1, owner,
                                       finite=False)
                problem = limits.size_problem(key, values)
                if problem:
                    self.fail(shape, problem, owner)
                size += values
        elif shape.tag == "mesh":
            uri = self.attr(shape, "filename", owner)
            scale = mesh_scale(shape.get("scale"))
            if scale is None:
                self.fail(shape, "scale=%r is not three non-zero numbers (x y z factors)"
                          % shape.get("scale"), owner)
            try:
                path = mesh_path(uri, self.base_dir, scale)
            except AssetNotFound as err:
                self.missing.add(elem, shape, owner, uri.strip(), err)
                return None
            except UserError as err:
                self.fail(shape, str(err), owner)
            return Geometry("mesh", scale, path, uri)
        else:
            self.fail(shape, "unknown shape: use <box>, <cylinder>, <sphere> or <mesh>", owner)
        return Geometry(shape.tag, size)

    def _joint(self, elem, links) -> Joint:
        name = self._name(elem)
        owner = "joint %r" % name
        kind = self.attr(elem, "type", owner)
        if kind not in JOINT_TYPES:
            self.fail(elem, "type %r is not one of %s" % (kind, ", ".join(JOINT_TYPES)), owner)
        ends = []
        for tag in ("parent", "child"):
            end = self.child(elem, tag, owner)
            link = self._name(end, "link")
            if link not in links:
                self.fail(end, "link %r is not defined in this file" % link, owner)
            ends.append(link)
        if ends[0] == ends[1]:
            self.fail(elem, "parent and child are the same link %r" % ends[0], owner)
        if kind in ("revolute", "prismatic"):
            self.child(elem, "limit", owner)
        limit = elem.find("limit")
        for key, low, high, unit in (
                ("lower", -limits.MAX_JOINT_POSITION, limits.MAX_JOINT_POSITION, "rad or m"),
                ("upper", -limits.MAX_JOINT_POSITION, limits.MAX_JOINT_POSITION, "rad or m"),
                ("effort", 0.0, limits.MAX_FORCE, "N m or N"),
                ("velocity", 0.0, limits.MAX_ANGULAR_SPEED, "rad/s or m/s")):
            if limit is not None and key in limit.attrib:
                problem = limits.outside(key, self._number(limit, key, owner), low, high, unit)
                if problem:
                    self.fail(limit, problem, owner)
        axis = (1.0, 0.0, 0.0)
        axis_elem = elem.find("axis")
        if axis_elem is not None:
            axis = self._numbers(axis_elem, "xyz", 3, owner)
            if not any(axis):
                self.fail(axis_elem, "axis must not be zero", owner)
            problem = limits.symmetric("xyz", axis, limits.MAX_POSITION, "")
            if problem:   # a direction: its length must not overflow
                self.fail(axis_elem, problem, owner)
        friction = damping = 0.0
        dynamics = elem.find("dynamics")
        if dynamics is not None:
            for key, high, unit in (("friction", limits.MAX_FORCE, "N m or N"),
                                    ("damping", limits.MAX_DAMPING, "N m s/rad or N s/m")):
                if key in dynamics.attrib:
                    value = self._number(dynamics, key, owner)
                    problem = limits.outside("dynamics " + key, value, 0.0, high, unit)
                    if problem:
                        self.fail(dynamics, problem, owner)
                    if key == "friction":
                        friction = value
                    else:
                        damping = value
        return Joint(name, kind, ends[0], ends[1], self._origin(elem, owner), axis,
                     friction, damping)

    def _origin(self, elem, owner) -> Origin:
        origin = elem.find("origin")
        if origin is None:
            return Origin()
        xyz = self._numbers(origin, "xyz", 3, owner) if "xyz" in origin.attrib else (0.0,) * 3
        rpy = self._numbers(origin, "rpy", 3, owner) if "rpy" in origin.attrib else (0.0,) * 3
        problem = limits.position_problem("xyz", xyz) or limits.angles_problem("rpy", rpy)
        if problem:
            self.fail(origin, problem, owner)
        return Origin(xyz, rpy)

    def _numbers(self, elem, key, count, owner, finite: bool = True) -> tuple:
        return self.attr_floats(elem, key, count, owner, finite)

    def _number(self, elem, key, owner) -> float:
        return self.attr_floats(elem, key, 1, owner)[0]

    def _name(self, elem, key: str = "name") -> str:
        """The required attribute ``key`` naming a robot, link, joint or material: at most
        limits.MAX_NAME characters (refused before any message repeats it)."""
        name = elem.get(key, "").strip()
        problem = limits.name_problem(key, name)
        if problem:
            self.fail_bare(elem, "<%s>: %s" % (elem.tag, problem))
        return self.attr(elem, key)

    def describe(self, elem) -> str:
        """``link 'a'`` for a named robot, link, joint or material, else ``<tag>``."""
        name = elem.get("name")
        return "%s %r" % (elem.tag, name) if name and elem.tag in NAMED else "<%s>" % elem.tag
