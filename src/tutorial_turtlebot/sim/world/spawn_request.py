"""A spawn request's model_xml, checked and turned into what the world builder builds. No ROS.

Three kinds, as Gazebo's spawn services take them:
- SDF: ``<sdf>`` (or ``<gazebo>``) holding one ``<model>`` as world_sdf reads a world's (boxes,
  cylinders, spheres, planes, polylines, meshes, includes): it becomes a ``World`` of that one
  model, renamed and placed;
- URDF: ``<robot>`` of links and joints, read and checked by urdf_file as a robot's is (one
  ``RobotDescription``, ``description``), with no robot plugins: converted into an SDF model as
  Gazebo converts it (files/urdf/urdf_to_sdf: fixed joints lumped, ``<gazebo>`` blocks as
  extensions, mesh filenames as the absolute paths of their files: ``package://``,
  ``file://``, or a path, a relative one from the working directory) and then read as an SDF
  spawn is: a ``World`` of that one model (``world``), the conversion's warnings ``notes``;
- a robot: a URDF whose ``<gazebo>`` blocks hold plugins: ``robot`` is its text as given, and
  the simulation builds it from ``description`` with its plugins (``Simulation.add_robot``).
The text is parsed once (xml_reader) and checked once; everything downstream uses what that
gives. Refused, with one line saying why (a RequestError whose text is the service's status
message): text over ``MAX_XML_BYTES``, anything xml_reader refuses (malformed XML with its line,
a DOCTYPE, nesting deeper than xml_reader.MAX_DEPTH), an unknown root, anything urdf_file or
world_sdf refuses (a mesh file of an unknown kind, a bad mesh scale, any number beyond the limits
of ``limits``), an initial pose beyond them. A URDF's visual or collision whose mesh file is found
nowhere is left out, with a warning (``RobotDescription.warnings``), as an SDF's is.

``prepare_spawn`` does all of that outside the stepping loop (the world API calls it from the
service's own thread), holds the spawn to the MAX_SPAWN_* budgets of what the loop may build,
and reads every mesh once, so that the loop only makes the pybullet bodies.
"""
import hashlib
import os
import threading
import time
from dataclasses import dataclass
from typing import Optional, Tuple

from ...errors import RequestError
from . import reference_frames as rf
from ..files import limits
from ..files import xml_reader
from ..kinematics import xyz_rpy_from_pose
from ..files.urdf.urdf_file import RobotDescription, read_urdf_element
from ..files.urdf.urdf_to_sdf import urdf_to_sdf
from ..engine.world_bullet import MOVABLE_KINDS
from .world_models import spawn_failure, spawn_refusal
from ..files.sdf.world_sdf import load_model_xml
from ..files.world_types import World
from ..files.xml_reader import Element, element

MAX_XML_BYTES = 1_000_000
# What one spawn may cost the loop (it builds the bodies between two steps, while physics,
# /clock and every other request wait): refused before anything is built.
# collisions and visuals, a polyline's triangles and a mesh's colour parts counted one each
# (the house world holds ~600)
MAX_SPAWN_SHAPES = 1000
MAX_POLYLINE_POINTS = 256       # corners of one polyline (cut into triangles, one body each)
# the mesh triangles of one spawn, after their files are read (a static one of 180,000 takes
# the loop 1.2 s to build)
MAX_SPAWN_TRIANGLES = 200_000
MAX_MOVABLE_MESH_VERTICES = 100_000  # a movable mesh collides as the hull of its vertices
PREPARE_SECONDS = 30.0          # wall s to read and check a spawn's text and files
_PREPARE_LOCK = threading.Lock()   # one spawn is read at a time (the mesh caches are shared)


@dataclass
class SpawnRequest:
    """A parsed spawn: ``world`` (SDF, or a plain URDF converted to SDF) or ``robot`` (a URDF
    robot's text as given) is set; ``description`` is a URDF's, read once; ``notes``: what the
    conversion of a plain URDF warns of."""

    name: str
    world: Optional[World] = None
    robot: Optional[str] = None
    description: Optional[RobotDescription] = None
    digest: str = ""    # sha256 of the text it was read from: the key of its parked bodies
    notes: Tuple[str, ...] = ()


def _check_size(xml: str) -> None:
    if len(xml) > MAX_XML_BYTES:
        raise spawn_failure("model_xml is %d characters, more than the %d allowed"
                            % (len(xml), MAX_XML_BYTES))
    if not xml.strip():
        raise spawn_failure("model_xml is empty")


def parse_spawn(name: str, xml: str, pose: rf.Pose = rf.IDENTITY,
                kind: str = "sdf", robot_namespace: str = "") -> SpawnRequest:
    """Check and parse a spawn of ``xml`` as model ``name`` at world ``pose``. ``kind`` is the
    service called: "sdf" takes SDF or URDF (as Gazebo's spawn_sdf_model does), "urdf" only
    URDF. A robot's errors name it "model_xml of <name>", others "model_xml". An SDF model's
    plugins without a <robotNamespace> get ``robot_namespace`` (add_robot_namespace). The
    request carries the text's digest (the key of its bodies once deleted)."""
    request = _parse(name, xml, pose, kind, robot_namespace)
    request.digest = hashlib.sha256(xml.encode("utf-8", "surrogatepass")).hexdigest()
    return request


def _parse(name: str, xml: str, pose: rf.Pose, kind: str,
           robot_namespace: str = "") -> SpawnRequest:
    _check_size(xml)
    with spawn_refusal():
        root = xml_reader.parse(xml, "model_xml")
        if root.tag == "robot":
            return _urdf_request(name, xml, root, pose)
    if kind == "urdf":
        raise spawn_failure("spawn_urdf_model needs a <robot> root element, got <%s>"
                            % root.tag)
    if root.tag not in ("sdf", "gazebo"):
        raise spawn_failure("model_xml: the root element is <%s>: expected <sdf> or "
                            "<robot>" % root.tag)
    add_robot_namespace(root, robot_namespace)
    return SpawnRequest(name, world=_sdf_world(root, name, pose))


def add_robot_namespace(root: Element, namespace: str) -> None:
    """A spawn's robot_namespace given to the SDF it brings, as gazebo_ros' spawn service gives
    it: every <plugin> anywhere under ``root`` that has no <robotNamespace> gets one of
    ``namespace`` (none when it is ""). A URDF robot's plugins take it as the robot's."""
    if not namespace:
        return
    for plugin in root.iter("plugin"):
        if plugin.find("robotNamespace") is None:
            child = element("robotNamespace", {}, plugin.line)
            child.text = namespace
            plugin.append(child)


def _sdf_world(root: Element, name: str, pose: rf.Pose) -> World:
    """The World of the one SDF model of ``root`` (world_sdf.load_model_xml), named ``name``
    and placed at ``pose``; RequestError if it cannot be read or built."""
    with spawn_refusal():
        world = load_model_xml(root, "model_xml", name, xyz_rpy_from_pose(pose),
                               max_shapes=MAX_SPAWN_SHAPES)
    for shape in world.shapes:
        if not shape.static and shape.kind not in MOVABLE_KINDS:
            raise spawn_failure("%s: a %s cannot be part of a model that is not "
                                "<static>" % (shape.name, shape.kind))
    return world


def prepare_spawn(name: str, xml: str, pose: rf.Pose = rf.IDENTITY, kind: str = "sdf",
                  seconds: float = PREPARE_SECONDS, robot_namespace: str = "") -> SpawnRequest:
    """Everything of a spawn but building it, for any thread: parse_spawn, its cost held to the
    MAX_SPAWN_* budgets, and every mesh it names read and converted once (mesh_file's
    caches), so that building it in the loop does little more than pybullet calls. RequestError
    (one line) over a budget, or when the reading took more than ``seconds``: nothing is built
    then."""
    with _PREPARE_LOCK:
        deadline = time.monotonic() + seconds
        request = parse_spawn(name, xml, pose, kind, robot_namespace)
        _check_time(deadline, seconds)
        if request.world is not None:
            _prepare_world(request.world, deadline, seconds)
        else:
            _prepare_urdf(request, deadline, seconds)
        return request


def _check_time(deadline: float, seconds: float) -> None:
    if time.monotonic() > deadline:
        raise spawn_failure("reading model_xml and its files took more than %g s; "
                            "nothing was spawned" % seconds)


def _over(what: str, count: int, limit: int) -> RequestError:
    return spawn_failure("%s: %d, more than the %d one spawn may build; nothing was "
                         "spawned" % (what, count, limit))


def _prepare_world(world: World, deadline: float, seconds: float) -> None:
    from ..files.meshes.mesh_file import load_mesh      # trimesh and pycollada only for meshes
    pieces = triangles = 0
    for shape in world.shapes:
        pieces += 1
        if shape.kind == "polyline":
            if len(shape.points) > MAX_POLYLINE_POINTS:
                raise _over("%s: polyline points" % shape.name, len(shape.points),
                            MAX_POLYLINE_POINTS)
            pieces += max(0, len(shape.points) - 3)
        elif shape.kind == "mesh":
            with spawn_refusal():
                mesh = load_mesh(shape.mesh, shape.size)
            triangles += sum(len(part.faces) for part in mesh.parts)
            pieces += len(mesh.parts) - 1
            if not shape.static and len(mesh.vertices) > MAX_MOVABLE_MESH_VERTICES:
                raise _over("%s: vertices of a movable mesh" % shape.name, len(mesh.vertices),
                            MAX_MOVABLE_MESH_VERTICES)
            if triangles > MAX_SPAWN_TRIANGLES:
                raise _over("mesh triangles", triangles, MAX_SPAWN_TRIANGLES)
            _check_time(deadline, seconds)
        if pieces > MAX_SPAWN_SHAPES:
            raise _over("shapes (collisions, visuals, polyline triangles, mesh parts)", pieces,
                        MAX_SPAWN_SHAPES)


def _prepare_urdf(request: SpawnRequest, deadline: float, seconds: float) -> None:
    """A robot's budgets, its meshes read (mesh_file keeps them for the build)."""
    from ..files.urdf.urdf_meshes import mesh_triangles
    description = request.description
    shapes = sum(len(link.visuals) + len(link.collisions)
                 for link in description.links.values())
    if shapes > MAX_SPAWN_SHAPES:
        raise _over("shapes (links' collisions and visuals)", shapes, MAX_SPAWN_SHAPES)
    with spawn_refusal():
        triangles, hull_vertices = mesh_triangles(description)
        if triangles > MAX_SPAWN_TRIANGLES:
            raise _over("mesh triangles", triangles, MAX_SPAWN_TRIANGLES)
        if hull_vertices > MAX_MOVABLE_MESH_VERTICES:
            raise _over("vertices of a collision mesh (it collides as their hull)",
                        hull_vertices, MAX_MOVABLE_MESH_VERTICES)
    _check_time(deadline, seconds)


def _urdf_request(name: str, xml: str, root: Element, pose: rf.Pose) -> SpawnRequest:
    """The request of a URDF (``root``: its parsed ``<robot>``), read and checked by urdf_file,
    relative mesh filenames from the working directory; UserError if it cannot be. A plain one
    (no plugins) is converted to SDF (urdf_to_sdf) and read as an SDF spawn at ``pose``."""
    is_robot = any(gazebo.find(".//plugin") is not None for gazebo in root.iter("gazebo"))
    source = "model_xml of %s" % name if is_robot else "model_xml"
    description = read_urdf_element(root, source, os.getcwd())
    if is_robot:
        return SpawnRequest(name, robot=xml, description=description)
    sdf, notes = urdf_to_sdf(description)
    return SpawnRequest(name, world=_sdf_world(sdf, name, pose), description=description,
                        notes=tuple(notes))


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
