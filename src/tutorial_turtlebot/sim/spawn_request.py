"""A spawn request's model_xml, checked and turned into what the world builder builds. No ROS.

Three kinds, as Gazebo's spawn services take them:
- SDF: ``<sdf>`` (or ``<gazebo>``) holding one ``<model>`` of primitive shapes (world_sdf's
  subset): it becomes a ``World`` of that one model, renamed and placed;
- URDF: ``<robot>`` of links and joints with box, cylinder, sphere or mesh geometry and no
  robot plugins: it becomes URDF text with the requested name and each mesh filename made the
  absolute path of its file (``package://``, ``file://``, or a path; a relative one from the
  working directory), which pybullet loads (meshes through urdf_meshes);
- a robot: a URDF whose ``<gazebo>`` blocks hold plugins: its text as given (``robot``), which
  the simulation builds with its plugins (``Simulation.add_robot``).
Refused, with one line saying why (a RequestError whose text is the service's status message):
text over ``MAX_XML_BYTES``, nesting deeper than world_sdf.MAX_XML_DEPTH, a DOCTYPE, malformed
XML (with its line), an unknown root, a mesh file that cannot be found or is of an unknown kind,
a bad mesh scale, any number beyond the limits of ``limits`` (a URDF's read by urdf_file, as a
robot's are; an SDF's by world_sdf), an initial pose beyond them.
"""
import os
from dataclasses import dataclass
from typing import Optional
from xml.etree import ElementTree

from ..errors import UserError, WorldError
from . import reference_frames as rf
from . import limits
from .urdf_file import mesh_path, mesh_scale, read_urdf_text
from .world_bullet import MOVABLE_KINDS
from .world_models import RequestError
from .world_sdf import World, load_model_xml, parse_xml

MAX_XML_BYTES = 1_000_000
URDF_GEOMETRY = ("box", "cylinder", "sphere", "mesh")
PREFIX = "SpawnModel: Failure - "


@dataclass
class SpawnRequest:
    """A parsed spawn: exactly one of ``world`` (SDF), ``urdf`` (URDF text of a plain model)
    and ``robot`` (URDF text of a robot with plugins) is set."""

    name: str
    world: Optional[World] = None
    urdf: Optional[str] = None
    robot: Optional[str] = None


def _check_size(xml: str) -> None:
    if len(xml) > MAX_XML_BYTES:
        raise RequestError(PREFIX + "model_xml is %d characters, more than the %d allowed"
                           % (len(xml), MAX_XML_BYTES))
    if not xml.strip():
        raise RequestError(PREFIX + "model_xml is empty")


def parse_spawn(name: str, xml: str, pose: rf.Pose = rf.IDENTITY, kind: str = "sdf") -> SpawnRequest:
    """Check and parse a spawn of ``xml`` as model ``name`` at world ``pose``. ``kind`` is the
    service called: "sdf" takes SDF or URDF (as Gazebo's spawn_sdf_model does), "urdf" only
    URDF."""
    _check_size(xml)
    try:
        root = parse_xml(xml, "model_xml")
    except WorldError as err:
        raise RequestError(PREFIX + str(err)) from None
    if root.tag == "robot":
        try:
            robot = ElementTree.fromstring(xml)
        except ElementTree.ParseError as err:
            raise RequestError(PREFIX + "model_xml: malformed XML: %s" % err) from None
        if any(gazebo.find(".//plugin") is not None for gazebo in robot.iter("gazebo")):
            return SpawnRequest(name, robot=xml)
        urdf = _urdf(name, robot)
        try:   # every number checked as a robot's are (limits), before pybullet sees it
            read_urdf_text(xml, "model_xml")
        except UserError as err:
            raise RequestError(PREFIX + str(err)) from None
        return SpawnRequest(name, urdf=urdf)
    if kind == "urdf":
        raise RequestError(PREFIX + "spawn_urdf_model needs a <robot> root element, got <%s>"
                           % root.tag)
    if root.tag not in ("sdf", "gazebo"):
        raise RequestError(PREFIX + "model_xml: the root element is <%s>: expected <sdf> or "
                                    "<robot>" % root.tag)
    roll, pitch, yaw = rf.rpy_from_quat(pose[1])
    try:
        world = load_model_xml(xml, "model_xml", name, tuple(pose[0]) + (roll, pitch, yaw))
    except WorldError as err:
        raise RequestError(PREFIX + str(err)) from None
    for shape in world.shapes:
        if not shape.static and shape.kind not in MOVABLE_KINDS:
            raise RequestError(PREFIX + "%s: a %s cannot be part of a model that is not "
                                        "<static>" % (shape.name, shape.kind))
    return SpawnRequest(name, world=world)


def _urdf(name: str, robot: ElementTree.Element) -> str:
    """The URDF text of ``robot`` renamed ``name``; RequestError for what this simulator
    cannot load."""
    links = robot.findall("link")
    if not links:
        raise RequestError(PREFIX + "the URDF <robot> has no <link>")
    names = [link.get("name", "") for link in links]
    if "" in names or len(set(names)) != len(names):
        raise RequestError(PREFIX + "every URDF <link> needs a unique name")
    children = set()
    for joint in robot.findall("joint"):
        parent, child = joint.find("parent"), joint.find("child")
        for end in (parent, child):
            if end is None or end.get("link") not in names:
                raise RequestError(PREFIX + "URDF joint %r: parent and child must name links"
                                   % joint.get("name", ""))
        children.add(child.get("link"))
    roots = [n for n in names if n not in children]
    if len(roots) != 1:
        raise RequestError(PREFIX + "the URDF must have exactly one root link, it has %d"
                           % len(roots))
    for link in links:
        for element in link:
            geometry = element.find("geometry") if element.tag in ("collision", "visual") else None
            for shape in (geometry if geometry is not None else ()):
                if shape.tag not in URDF_GEOMETRY:
                    raise RequestError(PREFIX + "URDF link %r: <%s> geometry is not supported "
                                                "(only %s)" % (link.get("name"), shape.tag,
                                                               ", ".join(URDF_GEOMETRY)))
                if shape.tag == "mesh":
                    _absolute_mesh(link.get("name"), shape)
    robot.set("name", name)
    for gazebo in robot.findall("gazebo"):
        robot.remove(gazebo)
    return ElementTree.tostring(robot, encoding="unicode")


def _absolute_mesh(link: str, mesh: ElementTree.Element) -> None:
    """Check a plain URDF's ``<mesh>`` and make its filename the file's absolute path."""
    where = "URDF link %r <mesh>" % link
    if mesh_scale(mesh.get("scale")) is None:
        raise RequestError(PREFIX + "%s: scale=%r is not three non-zero numbers"
                           % (where, mesh.get("scale")))
    uri = mesh.get("filename", "").strip()
    if not uri:
        raise RequestError(PREFIX + "%s: missing attribute 'filename'" % where)
    try:
        mesh.set("filename", mesh_path(uri, os.getcwd()))
    except UserError as err:
        raise RequestError(PREFIX + "%s: %s" % (where, err)) from None


def placed(pose: rf.Pose, frame: Optional[rf.Pose]) -> rf.Pose:
    """The world pose of a spawn's ``initial_pose`` given in ``frame`` (None: the world), its
    quaternion normalised (all-zero: identity). ValueError (one line naming the field and the
    limit) for NaN or inf, or a position (given, or in the world) beyond limits.MAX_POSITION."""
    position, orientation = pose
    if not rf.finite(position, orientation):
        raise ValueError("initial_pose has NaN or infinite values")
    problem = limits.position_problem("initial_pose.position", position)
    if problem:
        raise ValueError(problem)
    pose = (tuple(float(v) for v in position),
            limits.unit_quaternion(orientation, "initial_pose.orientation"))
    if frame is None:
        return pose
    pose = rf.compose(frame, pose)
    problem = limits.position_problem("initial_pose.position (in the world)", pose[0])
    if problem:
        raise ValueError(problem)
    return pose[0], limits.unit_quaternion(pose[1])

