"""A spawn request's model_xml, checked and turned into what the world builder builds. No ROS.

Three kinds, as Gazebo's spawn services take them:
- SDF: ``<sdf>`` (or ``<gazebo>``) holding one ``<model>`` of primitive shapes (world_sdf's
  subset): it becomes a ``World`` of that one model, renamed and placed;
- URDF: ``<robot>`` of links and joints, read and checked by urdf_file as a robot's is (one
  ``RobotDescription``, ``description``), with box, cylinder, sphere or mesh geometry and no
  robot plugins: ``urdf`` is its text with the requested name and each mesh filename made the
  absolute path of its file (``package://``, ``file://``, or a path; a relative one from the
  working directory), which pybullet loads (meshes through urdf_meshes);
- a robot: a URDF whose ``<gazebo>`` blocks hold plugins: ``robot`` is its text as given, and
  the simulation builds it from ``description`` with its plugins (``Simulation.add_robot``).
The text is parsed once (xml_reader) and checked once; everything downstream uses what that
gives. Refused, with one line saying why (a RequestError whose text is the service's status
message): text over ``MAX_XML_BYTES``, anything xml_reader refuses (malformed XML with its line,
a DOCTYPE, nesting deeper than xml_reader.MAX_DEPTH), an unknown root, anything urdf_file or
world_sdf refuses (a mesh file that cannot be found or is of an unknown kind, a bad mesh scale,
any number beyond the limits of ``limits``), an initial pose beyond them.
"""
import os
from dataclasses import dataclass
from typing import Optional
from xml.etree import ElementTree

from ..errors import UserError
from . import reference_frames as rf
from . import limits
from . import xml_reader
from .kinematics import xyz_rpy_from_pose
from .urdf_file import RobotDescription, read_urdf_element
from .urdf_meshes import absolute_meshes, mesh_paths
from .world_bullet import MOVABLE_KINDS
from .world_models import RequestError
from .world_sdf import World, load_model_xml
from .xml_reader import Element

MAX_XML_BYTES = 1_000_000
PREFIX = "SpawnModel: Failure - "


@dataclass
class SpawnRequest:
    """A parsed spawn: ``world`` (SDF) or ``description`` (URDF, read once) is set; a URDF is
    either a plain model (``urdf``: the text pybullet loads) or a robot with plugins
    (``robot``: its text as given)."""

    name: str
    world: Optional[World] = None
    urdf: Optional[str] = None
    robot: Optional[str] = None
    description: Optional[RobotDescription] = None

    def plain_urdf(self) -> Element:
        """A copy of a plain URDF's ``<robot>`` as ``urdf`` writes it: renamed, without
        ``<gazebo>`` blocks, each mesh filename the absolute path of its file."""
        robot = absolute_meshes(self.description.root, mesh_paths(self.description))
        robot.set("name", self.name)
        for gazebo in robot.findall("gazebo"):
            robot.remove(gazebo)
        return robot


def _check_size(xml: str) -> None:
    if len(xml) > MAX_XML_BYTES:
        raise RequestError(PREFIX + "model_xml is %d characters, more than the %d allowed"
                           % (len(xml), MAX_XML_BYTES))
    if not xml.strip():
        raise RequestError(PREFIX + "model_xml is empty")


def parse_spawn(name: str, xml: str, pose: rf.Pose = rf.IDENTITY, kind: str = "sdf") -> SpawnRequest:
    """Check and parse a spawn of ``xml`` as model ``name`` at world ``pose``. ``kind`` is the
    service called: "sdf" takes SDF or URDF (as Gazebo's spawn_sdf_model does), "urdf" only
    URDF. A robot's errors name it "model_xml of <name>", others "model_xml"."""
    _check_size(xml)
    try:
        root = xml_reader.parse(xml, "model_xml")
        if root.tag == "robot":
            return _urdf_request(name, xml, root)
    except UserError as err:
        raise RequestError(PREFIX + str(err)) from None
    if kind == "urdf":
        raise RequestError(PREFIX + "spawn_urdf_model needs a <robot> root element, got <%s>"
                           % root.tag)
    if root.tag not in ("sdf", "gazebo"):
        raise RequestError(PREFIX + "model_xml: the root element is <%s>: expected <sdf> or "
                                    "<robot>" % root.tag)
    try:
        world = load_model_xml(root, "model_xml", name, xyz_rpy_from_pose(pose))
    except UserError as err:
        raise RequestError(PREFIX + str(err)) from None
    for shape in world.shapes:
        if not shape.static and shape.kind not in MOVABLE_KINDS:
            raise RequestError(PREFIX + "%s: a %s cannot be part of a model that is not "
                                        "<static>" % (shape.name, shape.kind))
    return SpawnRequest(name, world=world)


def _urdf_request(name: str, xml: str, root: Element) -> SpawnRequest:
    """The request of a URDF (``root``: its parsed ``<robot>``), read and checked by urdf_file,
    relative mesh filenames from the working directory; UserError if it cannot be."""
    is_robot = any(gazebo.find(".//plugin") is not None for gazebo in root.iter("gazebo"))
    source = "model_xml of %s" % name if is_robot else "model_xml"
    description = read_urdf_element(root, source, os.getcwd())
    if is_robot:
        return SpawnRequest(name, robot=xml, description=description)
    request = SpawnRequest(name, description=description)
    request.urdf = ElementTree.tostring(request.plain_urdf(), encoding="unicode")
    return request


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

