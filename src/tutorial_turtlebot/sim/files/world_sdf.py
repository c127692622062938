"""Worlds: the catalogue of this package's SDF worlds and a loader for the SDF subset they use.

No ROS and no pybullet here: a world becomes plain data (``World``, ``Shape``) that
``world_bullet`` turns into bodies.

The subset: a ``<world>`` (or bare ``<model>`` elements) holding static or dynamic models, nested
models and links, whose collisions and visuals have a ``box``, ``cylinder``, ``sphere``, ``plane``,
one extruded ``polyline`` or a ``mesh`` (Collada, STL, OBJ: ``mesh_file``) geometry; ``<pose>`` as
"x y z roll pitch yaw" (``degrees="true"`` allowed); visual ``<material>`` colours, and the
colour and texture image of a ``<script>`` material of a model's own ``.material`` files
(material_scripts); ``<include>`` of a model folder found as Gazebo finds it (``asset_uri``:
``model://`` through GAZEBO_MODEL_PATH and the package's own ``models/``, which has Gazebo's
``ground_plane`` and ``sun``), with its ``<name>``, ``<pose>`` and ``<static>`` overrides,
nested to any depth up to MAX_INCLUDE_DEPTH; what an include or a mesh names is read only
from a regular file (``file_read``). A model's links keep their ``<inertial>`` (SDF's defaults where absent: 1 kg, inertia 1 kg m^2
about each axis) and each collision its ``<surface><friction><ode><mu>`` (default 1), so that a
model that is not ``<static>`` can be a movable rigid body. The world's ``<light>``s and those of
its ``<include>``s of a light model (``model://sun``) are kept in ``World.lights``
(``world_lights.Light``: they light nothing, the world API reads and sets them). Other
elements that do not shape the world (physics, scene, gui, plugin, sensor, joint ...) are
skipped. Anything else that would carry geometry (a heightmap, a mesh's ``<submesh>``, an
actor) is an error, never a silent gap.

Tolerated as Gazebo tolerates them, each with one line in ``World.warnings`` (file, line, what
was left out; the node logs them): an ``<include>`` whose model is found nowhere (the model is
left out), a ``<mesh>`` whose file is found nowhere or is a Collada file that cannot be read
(the link loads without that collision or visual), a material script that cannot be read or
is malformed, or whose texture cannot be used (the visual is drawn in its colour, else grey), a
light's value that cannot be read (it keeps SDF's default). A static model's ``<inertial>``
numbers are not checked (Gazebo never uses them; its building editor writes mass 0 and
inertia nan).

Units: metres, radians. Poses are in the world frame (z up), kept as SDF writes them
(kinematics.XyzRpy: x, y, z, then SDF's fixed-axis roll, pitch, yaw: R = Rz(yaw) Ry(pitch)
Rx(roll)); kinematics.pose_from_xyz_rpy makes them quaternion poses. Errors are xml_reader's
one line: file, line, what is wrong.
"""
import math
import os
from dataclasses import dataclass, replace
from typing import Dict, List, NamedTuple, Optional, Sequence, Tuple

from ...errors import UserError, WorldError
from . import limits
from . import xml_reader
from .asset_uri import AssetError, AssetNotFound, model_sdf_file, resolve_uri
from .file_read import not_regular
from .material_scripts import MaterialScripts
from .world_lights import Light, light_of, light_pose
from ..kinematics import ZERO_XYZ_RPY, XyzRpy, compose_xyz_rpy, cross_2d, rpy_from_matrix
from ...package_data import data_dir
from .xml_reader import Element, XmlReader

Rgba = Tuple[float, float, float, float]
Spawn = Tuple[float, float, float]                       # x, y (m), yaw (rad) of base_footprint
KINDS = ("box", "cylinder", "sphere", "plane", "polyline", "mesh")
MAX_INCLUDE_DEPTH = 16        # <include>s nested deeper than this are refused (a model including itself)
# What one document may expand to, includes and all (a 155-character request of three local
# models once fanned out to 10,000 boxes): reading stops with one line beyond these.
MAX_WORLD_SHAPES = 100_000   # collisions and visuals
MAX_INCLUDES = 10_000
DEFAULT_RGBA: Rgba = (0.7, 0.7, 0.7, 1.0)   # a visual without material: Gazebo's light grey

# The colour of each common Gazebo/<Name> material of Gazebo 11's gazebo.material: its diffuse
# colour; for a textured one the mean colour of its texture (approximate); a few whose look
# comes from their ambient term (SkyBlue) take that. Transparent and glowing ones are drawn
# opaque. A name not here is drawn grey (DEFAULT_RGBA).
GAZEBO_MATERIALS: Dict[str, Rgba] = {
    "Gazebo/White": (1.0, 1.0, 1.0, 1.0),
    "Gazebo/Grey": (0.7, 0.7, 0.7, 1.0),
    "Gazebo/Gray": (0.7, 0.7, 0.7, 1.0),
    "Gazebo/DarkGrey": (0.175, 0.175, 0.175, 1.0),
    "Gazebo/DarkGray": (0.175, 0.175, 0.175, 1.0),
    "Gazebo/FlatBlack": (0.1, 0.1, 0.1, 1.0),
    "Gazebo/Black": (0.0, 0.0, 0.0, 1.0),
    "Gazebo/Red": (1.0, 0.0, 0.0, 1.0),
    "Gazebo/RedBright": (0.87, 0.26, 0.07, 1.0),
    "Gazebo/Green": (0.0, 1.0, 0.0, 1.0),
    "Gazebo/Blue": (0.0, 0.0, 1.0, 1.0),
    "Gazebo/SkyBlue": (0.13, 0.44, 0.70, 1.0),
    "Gazebo/Yellow": (1.0, 1.0, 0.0, 1.0),
    "Gazebo/ZincYellow": (0.9725, 0.9529, 0.2078, 1.0),
    "Gazebo/DarkYellow": (0.7, 0.7, 0.0, 1.0),
    "Gazebo/Purple": (1.0, 0.0, 1.0, 1.0),
    "Gazebo/Turquoise": (0.0, 1.0, 1.0, 1.0),
    "Gazebo/Orange": (1.0, 0.5088, 0.0468, 1.0),
    "Gazebo/Indigo": (0.33, 0.0, 0.5, 1.0),
    "Gazebo/Gold": (0.8, 0.4974, 0.0071, 1.0),
    "Gazebo/Chrome": (0.7, 0.7, 0.72, 1.0),
    "Gazebo/WhiteGlow": (1.0, 1.0, 1.0, 1.0),
    "Gazebo/RedGlow": (1.0, 0.0, 0.0, 1.0),
    "Gazebo/GreenGlow": (0.0, 1.0, 0.0, 1.0),
    "Gazebo/BlueGlow": (0.0, 0.0, 1.0, 1.0),
    "Gazebo/YellowGlow": (1.0, 1.0, 0.0, 1.0),
    "Gazebo/PurpleGlow": (1.0, 0.0, 1.0, 1.0),
    "Gazebo/TurquoiseGlow": (0.0, 1.0, 1.0, 1.0),
    "Gazebo/BlueLaser": (0.0, 0.0, 1.0, 1.0),
    "Gazebo/RedTransparent": (1.0, 0.0, 0.0, 1.0),
    "Gazebo/GreenTransparent": (0.0, 1.0, 0.0, 1.0),
    "Gazebo/BlueTransparent": (0.0, 0.0, 1.0, 1.0),
    "Gazebo/YellowTransparent": (1.0, 1.0, 0.0, 1.0),
    "Gazebo/OrangeTransparent": (1.0, 0.44, 0.0, 1.0),
    "Gazebo/GreyTransparent": (0.5, 0.5, 0.5, 1.0),
    "Gazebo/BlackTransparent": (0.0, 0.0, 0.0, 1.0),
    "Gazebo/DarkMagentaTransparent": (0.6, 0.0, 0.6, 1.0),
    "Gazebo/Shadow": (0.2, 0.2, 0.2, 1.0),          # a see-through dark grey in Gazebo
    # textured: the mean colour of the texture
    "Gazebo/Wood": (0.62, 0.45, 0.28, 1.0),
    "Gazebo/WoodFloor": (0.55, 0.38, 0.22, 1.0),
    "Gazebo/WoodPallet": (0.66, 0.53, 0.37, 1.0),
    "Gazebo/LightWood": (0.80, 0.66, 0.47, 1.0),
    "Gazebo/Bricks": (0.58, 0.33, 0.26, 1.0),
    "Gazebo/CeilingTiled": (0.80, 0.80, 0.78, 1.0),
    "Gazebo/PaintedWall": (0.85, 0.83, 0.78, 1.0),
    "Gazebo/Rockwall": (0.45, 0.42, 0.38, 1.0),
    "Gazebo/Grass": (0.33, 0.47, 0.20, 1.0),
    "Gazebo/Leaf": (0.24, 0.40, 0.12, 1.0),
    "Gazebo/Trunk": (0.35, 0.35, 0.35, 1.0),         # the road texture of OSM trunk roads
    "Gazebo/Road": (0.35, 0.35, 0.35, 1.0),
    "Gazebo/Asphalt": (0.30, 0.30, 0.30, 1.0),
    "Gazebo/Residential": (0.38, 0.38, 0.38, 1.0),
    "Gazebo/Tertiary": (0.38, 0.38, 0.38, 1.0),
    "Gazebo/Secondary": (0.38, 0.38, 0.38, 1.0),
    "Gazebo/Primary": (0.35, 0.35, 0.35, 1.0),
    "Gazebo/Motorway": (0.33, 0.33, 0.33, 1.0),
    "Gazebo/Footway": (0.60, 0.58, 0.55, 1.0),
    "Gazebo/Pedestrian": (0.60, 0.58, 0.55, 1.0),
    "Gazebo/Lanes": (0.35, 0.35, 0.35, 1.0),
    "Gazebo/CloudySky": (0.62, 0.70, 0.82, 1.0),
}

# World elements that carry geometry this loader cannot build.
_UNSUPPORTED_WORLD = ("actor", "population", "road")


@dataclass(frozen=True)
class Shape:
    """One collision or visual element, placed in the world.

    The shape's own frame sits at ``pose``: box, cylinder and sphere are centred on it (a cylinder's
    axis is its z); a plane's surface is its x-y plane with the normal along its z; a polyline is
    the polygon ``points`` in its x-y plane extruded from z 0 up to its height.
    """

    name: str                # scoped as in Gazebo: "model::link::element" (nested models add parts)
    kind: str                # one of KINDS
    pose: XyzRpy             # world pose of the shape's frame
    size: Tuple[float, ...]  # box (x, y, z); cylinder (radius, length); sphere (radius,);
    #                          plane (x, y); polyline (height,); mesh (scale x, y, z)
    points: Tuple[Tuple[float, float], ...] = ()  # polyline corners (x, y), counter-clockwise
    rgba: Rgba = DEFAULT_RGBA  # a visual's colour; a collision takes its twin's (else its link's)
    static: bool = True      # from <static> of the model or of any model around it
    collision: bool = True   # True: a <collision>; False: a <visual>
    twin: Optional[str] = None  # the element of the other kind in the same link with the same
    #                             geometry and pose (a collision's visual, a visual's collision)
    link: str = ""           # scoped name of its link ("model::link")
    mu: float = 1.0          # a collision's friction coefficient (<surface><friction><ode><mu>)
    mesh: str = ""           # a mesh's file, absolute (read by mesh_file.load_mesh with ``size``)
    mesh_colours: bool = False  # a mesh visual without <material>: the file's own colours
    texture: Optional[str] = None  # absolute path of the PNG or JPEG image of its <material>'s
    #                               script (material_scripts; a collision: its twin's); drawn on
    #                               a box or plane, the whole image once across its top face


@dataclass(frozen=True)
class Inertial:
    """A link's mass properties; SDF's defaults where the file gives none."""

    mass: float = 1.0                                    # kg
    pose: XyzRpy = ZERO_XYZ_RPY                                # centre of mass in the link frame
    inertia: Tuple[float, ...] = (1.0, 1.0, 1.0, 0.0, 0.0, 0.0)  # ixx iyy izz ixy ixz iyz, kg m^2


@dataclass(frozen=True)
class Link:
    """One link of a model: where it is and what it weighs; its shapes carry ``link=scoped``."""

    name: str                # the link's own name (Gazebo's body_names)
    scoped: str              # "model::link" (nested models add parts), as /gazebo/link_states
    pose: XyzRpy             # world pose of the link frame
    inertial: Inertial = Inertial()


@dataclass(frozen=True)
class Model:
    """A top-level model of a world file, as /gazebo/model_states lists it."""

    name: str
    pose: XyzRpy             # world pose of the model frame
    static: bool
    links: Tuple[Link, ...]
    joints: Tuple[str, ...] = ()
    joint_types: Tuple[str, ...] = ()    # each joint's <joint type> (revolute, fixed ...)


@dataclass(frozen=True)
class World:
    """A loaded world file: its shapes in file order."""

    name: str                   # <world name="...">, or the file's stem for a bare model file
    path: str
    models: Tuple[str, ...]     # top-level model names in file order (as /gazebo/model_states)
    shapes: Tuple[Shape, ...]
    model_specs: Tuple[Model, ...] = ()   # the same models with their links, in file order
    warnings: Tuple[str, ...] = ()        # one line each: what was left out, and why
    lights: Tuple[Light, ...] = ()        # the world's lights in file order (world_lights)

    def model(self, name: str) -> Model:
        """The top-level model called ``name``; KeyError if there is none."""
        for m in self.model_specs:
            if m.name == name:
                return m
        raise KeyError(name)

    def model_shapes(self, name: str) -> Tuple[Shape, ...]:
        """The collisions and visuals of model ``name`` (nested models included)."""
        prefix = name + "::"
        return tuple(s for s in self.shapes if s.name.startswith(prefix))

    @property
    def collisions(self) -> Tuple[Shape, ...]:
        return tuple(s for s in self.shapes if s.collision)

    @property
    def visuals(self) -> Tuple[Shape, ...]:
        return tuple(s for s in self.shapes if not s.collision)

    def shape(self, name: str) -> Shape:
        """The collision called ``name``, else the visual; KeyError if neither exists."""
        for s in self.collisions + self.visuals:
            if s.name == name:
                return s
        raise KeyError(name)


# --- catalogue ----------------------------------------------------------------------------------

class WorldEntry(NamedTuple):
    """A world this package ships: its file in ``WORLD_DIR`` and where the robot spawns."""

    file: str
    spawn: Spawn


WORLD_DIR = data_dir("worlds")

# The spawn poses of the turtlebot3_gazebo launch files (doc/turtlebot3.md 4.1); the robot faces +x.
_CATALOGUE = (
    ("empty", WorldEntry("empty.world", (0.0, 0.0, 0.0))),
    ("turtlebot3_world", WorldEntry("turtlebot3_world.world", (-2.0, -0.5, 0.0))),
    ("turtlebot3_house", WorldEntry("turtlebot3_house.world", (-3.0, 1.0, 0.0))),
    ("turtlebot3_autorace", WorldEntry("turtlebot3_autorace.world", (0.245, -1.787, 0.0))),
    # The learning stages of turtlebot3_machine_learning (doc/turtlebot3.md 4.6).
    ("turtlebot3_stage_1", WorldEntry("turtlebot3_stage_1.world", (0.0, 0.0, 0.0))),
    ("turtlebot3_stage_2", WorldEntry("turtlebot3_stage_2.world", (0.0, 0.0, 0.0))),
    ("turtlebot3_stage_3", WorldEntry("turtlebot3_stage_3.world", (0.0, 0.0, 0.0))),
    ("turtlebot3_stage_4", WorldEntry("turtlebot3_stage_4.world", (-0.7, 0.0, 0.0))),
)
WORLDS: Dict[str, WorldEntry] = {name: entry for name, entry in _CATALOGUE
                                 if os.path.isfile(os.path.join(WORLD_DIR, entry.file))}
WORLD_SUFFIXES = (".world", ".sdf")


def world_from_command_line(world: str, environ=os.environ) -> str:
    """``world`` with a relative file path made absolute against the directory the user typed
    the command in (roslaunch runs the sim in ~/.ros, but leaves the shell's $PWD as it was)."""
    if world.endswith(WORLD_SUFFIXES) and not os.path.isabs(os.path.expanduser(world)):
        return os.path.join(environ.get("PWD") or os.getcwd(), world)
    return world


def resolve_world(name_or_path: str) -> Tuple[str, Optional[Spawn]]:
    """(absolute path, spawn) for a catalogue name or a path to a .world/.sdf file.

    A path to a catalogue file gets that world's spawn; any other path gets None.
    """
    if name_or_path in WORLDS:
        entry = WORLDS[name_or_path]
        return os.path.join(WORLD_DIR, entry.file), entry.spawn
    if not name_or_path.endswith(WORLD_SUFFIXES):
        raise WorldError("unknown world %r: valid worlds are %s, or a path to a %s file"
                         % (name_or_path, ", ".join(WORLDS), " or ".join(WORLD_SUFFIXES)))
    path = os.path.abspath(os.path.expanduser(name_or_path))
    if not os.path.isfile(path):
        raise WorldError("world file not found: %s" % path)
    for entry in WORLDS.values():
        known = os.path.join(WORLD_DIR, entry.file)
        if os.path.isfile(known) and os.path.samefile(known, path):
            return path, entry.spawn
    return path, None


# --- XML with line numbers ----------------------------------------------------------------------

def _parse_xml(path: str) -> Element:
    """The root element of the SDF file at ``path``; WorldError (file, line) if it cannot."""
    return xml_reader.parse_file(path, "world file", WorldError)


def parse_xml(data, source: str) -> Element:
    """The root element of the XML text ``data`` (str or bytes): xml_reader.parse, raising
    WorldError."""
    return xml_reader.parse(data, source, WorldError)


def _normal_pose(n: Sequence[float]) -> XyzRpy:
    """A rotation taking +z onto the unit vector ``n`` (the shortest one)."""
    axis = (-n[1], n[0], 0.0)                    # z x n
    s, c = math.hypot(axis[0], axis[1]), n[2]
    if s < 1e-12:
        return ZERO_XYZ_RPY if c > 0 else (0.0, 0.0, 0.0, math.pi, 0.0, 0.0)
    ux, uy = axis[0] / s, axis[1] / s
    t = 1.0 - c                                  # Rodrigues with a horizontal unit axis (ux, uy, 0)
    m = ((c + ux * ux * t, ux * uy * t, uy * s),
         (ux * uy * t, c + uy * uy * t, -ux * s),
         (-uy * s, ux * s, c))
    return (0.0, 0.0, 0.0) + rpy_from_matrix(m)


# --- polygon checks for polylines ---------------------------------------------------------------

def _segments_cross(p1, p2, q1, q2) -> bool:
    d1, d2 = cross_2d(q1, q2, p1), cross_2d(q1, q2, p2)
    d3, d4 = cross_2d(p1, p2, q1), cross_2d(p1, p2, q2)
    return d1 * d2 < 0 and d3 * d4 < 0


def _clean_polygon(points: List[Tuple[float, float]]) -> Optional[Tuple[Tuple[float, float], ...]]:
    """Counter-clockwise corners without repeats (a closing repeat of the first included) or
    straight-through points; None if the polygon is degenerate or crosses itself."""
    pts = list(points)
    changed = True
    while changed and len(pts) >= 3:
        changed = False
        for i in range(len(pts)):
            a, b, c = pts[i - 1], pts[i], pts[(i + 1) % len(pts)]
            if abs(cross_2d(a, b, c)) < 1e-12:
                del pts[i]
                changed = True
                break
    if len(pts) < 3:
        return None
    n = len(pts)
    edges = [(pts[i], pts[(i + 1) % n]) for i in range(n)]
    for i in range(n):
        for j in range(i + 2, n):
            if (j + 1) % n != i and _segments_cross(*edges[i], *edges[j]):
                return None
    area = sum(cross_2d((0.0, 0.0), pts[i - 1], pts[i]) for i in range(n))
    return tuple(pts if area > 0 else pts[::-1])


# --- the loader ---------------------------------------------------------------------------------

class _Loader(XmlReader):
    """Walks one SDF document; every error names the file and the line of the element at fault."""

    def __init__(self, path: str, base_dir: Optional[str] = None, depth: int = 0):
        """``path`` names the document in errors; relative URIs are read from ``base_dir``
        (default: the document's folder); ``depth`` counts the includes around it."""
        super().__init__(path, WorldError)
        self.path = path
        self.base_dir = base_dir if base_dir is not None else os.path.dirname(path)
        self.depth = depth
        self.shapes: List[Shape] = []
        self._links: List[Link] = []
        self._joints: List[Tuple[str, str]] = []    # (name, type)
        self.warnings: List[str] = []               # shared with the loaders of includes
        self.budget = {"shapes": MAX_WORLD_SHAPES, "includes": MAX_INCLUDES}   # shared too
        self.material_scripts = MaterialScripts()   # each script file read once; shared too
        self.lights: List[Light] = []               # the world's, in file order

    def warn(self, node: Element, message: str) -> None:
        """Note ``message`` about ``node`` ("file:line: message"), once."""
        line = "%s:%d: %s" % (self.path, node.line, message)
        if line not in self.warnings:
            self.warnings.append(line)

    # numbers

    def positive(self, parent: Element, tag: str, count: int, default: Tuple[float, ...]):
        node = parent.child(tag)
        if node is None:
            return default
        values = self.floats(node, count, finite=False)
        problem = limits.size_problem("<%s>" % tag, values)
        if problem:
            self.fail_bare(node, problem)
        return values

    def pose(self, parent: Element) -> XyzRpy:
        node = parent.child("pose")
        if node is None or not node.value:
            return ZERO_XYZ_RPY
        for frame in ("relative_to", "frame"):
            if node.attrib.get(frame):
                self.fail_bare(node, "<pose %s=...> is not supported: give poses relative to "
                                     "the parent element" % frame)
        if node.attrib.get("rotation_format", "euler_rpy") != "euler_rpy":
            self.fail_bare(node, "<pose rotation_format=...> is not supported: use euler_rpy")
        x, y, z, roll, pitch, yaw = self.floats(node, 6)
        if node.attrib.get("degrees", "false").lower() in ("true", "1"):
            roll, pitch, yaw = (math.radians(a) for a in (roll, pitch, yaw))
        problem = (limits.position_problem("<pose>", (x, y, z))
                   or limits.angles_problem("<pose>", (roll, pitch, yaw)))
        if problem:
            self.fail_bare(node, problem)
        return (x, y, z, roll, pitch, yaw)

    # structure

    def document(self, root: Element) -> World:
        if root.tag != "sdf":
            self.fail_bare(root, "not an SDF file: the root element is <%s>, not <sdf>" % root.tag)
        world = root.child("world")
        if world is None:
            if not root.all("model"):
                self.fail_bare(root, "no <world> or <model> in this file")
            world, name = root, os.path.splitext(os.path.basename(self.path))[0]
        else:
            name = world.attrib.get("name", "default")
        return self.models_of(world, name)

    def models_of(self, world: Element, name: str, parent: XyzRpy = ZERO_XYZ_RPY) -> World:
        """The World made of ``world``'s top-level models and includes, placed in ``parent``."""
        models: List[Model] = []
        saved = _saved_poses(world)
        for node in world.children:
            if node.tag in ("model", "include"):
                node = _with_saved_pose(node, saved)
            if node.tag == "model":
                models.append(self.top_model(node, parent))
            elif node.tag == "include":
                models.extend(self.include(node, parent, ""))
            elif node.tag == "light" and world.tag == "world":
                self.lights.append(light_of(node, self.warn))
            elif node.tag in _UNSUPPORTED_WORLD:
                self.fail_bare(node, "<%s> is not supported: build it from models" % node.tag)
        return World(name, self.path, tuple(m.name for m in models), tuple(self.shapes),
                     tuple(models), tuple(self.warnings), tuple(self.lights))

    def top_model(self, node: Element, parent: XyzRpy) -> Model:
        self._links: List[Link] = []
        self._joints: List[Tuple[str, str]] = []
        name = self.model(node, parent, "", False)
        pose = compose_xyz_rpy(parent, self.pose(node))
        return Model(name, pose, self.flag(node, "static", False), tuple(self._links),
                     tuple(n for n, _ in self._joints), tuple(t for _, t in self._joints))

    def include(self, node: Element, parent: XyzRpy, scope: str,
                parent_static: bool = False) -> List[Model]:
        """The model an <include> adds, read from the folder or file its <uri> names, with the
        include's <name>, <pose> and <static> in place of the model's own. At the top level it
        is a Model of the world; inside a model (``scope``) its links join that model. An SDF
        of lights only (model://sun) adds no model; at the top level its lights join the
        world's."""
        uri_node = node.child("uri")
        uri = uri_node.value if uri_node is not None else ""
        if not uri:
            self.fail_bare(node, "<include> needs a <uri>")
        if self.depth >= MAX_INCLUDE_DEPTH:
            self.fail_bare(node, "<include> of %s: includes nested more than %d deep (does a "
                                 "model include itself?)" % (uri, MAX_INCLUDE_DEPTH))
        self.budget["includes"] -= 1
        if self.budget["includes"] < 0:
            self.fail_bare(node, "<include> of %s: more than %d includes in all (do includes "
                                 "fan out?)" % (uri, MAX_INCLUDES))
        try:
            found = resolve_uri(uri, self.base_dir)
        except AssetNotFound as err:     # Gazebo (sdformat) skips it: "Unable to find uri"
            self.warn(node, "<include> left out: %s" % err)
            return []
        except AssetError as err:
            self.fail_bare(node, "<include>: %s" % err)
        try:
            sdf = model_sdf_file(found, parse_xml) if os.path.isdir(found) else found
        except AssetError as err:
            self.fail_bare(node, "<include>: %s" % err)
        why = not_regular(sdf)     # /dev/stdin or a FIFO would wait for ever, /dev/zero fill
        if why is not None:        # the memory (file_read)
            self.fail_bare(node, "<include> of %s: %s: %s" % (uri, sdf, why))
        root = _parse_xml(sdf)
        models = root.all("model")
        if len(models) != 1:
            if not models and root.all("light"):
                if not scope:
                    self.light_model(node, sdf, root)
                return []
            self.fail_bare(node, "<include> of %s: %s must hold one <model>, it holds %d"
                           % (uri, sdf, len(models)))
        model = models[0]
        children = list(model.children)
        for tag in ("pose", "static"):
            override = node.child(tag)
            if override is not None:
                children = [c for c in children if c.tag != tag] + [override]
        name_node = node.child("name")
        attrib = dict(model.attrib)
        if name_node is not None and name_node.value:
            attrib["name"] = name_node.value
        model = xml_reader.element("model", attrib, model.line, children)
        inner = _Loader(sdf, depth=self.depth + 1)
        inner.shapes, inner.warnings, inner.budget = self.shapes, self.warnings, self.budget
        inner.material_scripts = self.material_scripts
        if not scope:
            return [inner.top_model(model, parent)]
        inner._links, inner._joints = self._links, self._joints
        inner.model(model, parent, scope, parent_static)
        return []

    def light_model(self, include: Element, sdf: str, root: Element) -> None:
        """Keep the lights of the light model ``root`` (read from ``sdf``) that ``include``
        adds to the world, with the include's <name> (a model of one light) and <pose> in
        place of their own."""
        lights = root.all("light")
        name_node = include.child("name")
        name = name_node.value if name_node is not None and len(lights) == 1 else None
        override = include.child("pose")
        pose = light_pose(override, self.warn) if override is not None else None
        inner = _Loader(sdf, depth=self.depth + 1)   # its warnings name the light's file
        inner.warnings = self.warnings
        self.lights.extend(light_of(elem, inner.warn, name, pose) for elem in lights)

    def model(self, node: Element, parent: XyzRpy, scope: str, parent_static: bool) -> str:
        name = self.name(node)
        pose = compose_xyz_rpy(parent, self.pose(node))
        static = parent_static or self.flag(node, "static", False)
        scope += name + "::"
        for child in node.children:
            if child.tag == "link":
                self.link(child, pose, scope, static)
            elif child.tag == "model":
                self.model(child, pose, scope, static)
            elif child.tag == "include":
                self.include(child, pose, scope, static)
            elif child.tag == "joint":
                self._joints.append((self.name(child), child.attrib.get("type", "")))
        return name

    def name(self, node: Element) -> str:
        name = node.attrib.get("name", "")
        if not name:
            self.fail_bare(node, "<%s> needs a name attribute" % node.tag)
        problem = limits.name_problem("<%s> name" % node.tag, name)
        if problem:
            self.fail_bare(node, problem)
        return name

    def link(self, node: Element, parent: XyzRpy, scope: str, static: bool) -> None:
        pose = compose_xyz_rpy(parent, self.pose(node))
        own = self.name(node)
        link = scope + own
        scope = link + "::"
        shapes = []
        for child in node.children:
            if child.tag in ("collision", "visual"):
                shape = self.element(child, pose, scope, static)
                if shape is not None:
                    shapes.append(replace(shape, link=link))
        self.shapes.extend(self.pair_twins(shapes))
        if len(self.shapes) > self.budget["shapes"]:
            self.fail_bare(node, "more than %d collisions and visuals in all (do includes fan "
                                 "out?)" % self.budget["shapes"])
        self._links.append(Link(own, link, pose,
                                self.inertial(node.child("inertial"), static)))

    def inertial(self, node: Optional[Element], static: bool = False) -> Inertial:
        """A link's <inertial>, SDF's defaults for what it leaves out.

        Only a movable link's mass and inertia are checked. Gazebo 11 gives a static link no
        physics body at all (ODELink::UpdateMass returns at once without one), so a static
        model's numbers are never used: Gazebo's building editor writes mass 0 and inertia
        nan there. Here such a link keeps SDF's defaults (nothing uses them either). On a
        movable link Gazebo repairs nothing: ODELink::UpdateMass throws "Setting custom link
        ... mass to zero!" for a mass that is not > 0 (nan included), and ODE's dBodySetMass
        asserts a positive definite inertia (gzserver ends with "ODE INTERNAL ERROR ...
        dMassCheck"). So those stay refused here, with the line at fault."""
        if node is None:
            return Inertial()
        mass = Inertial.mass
        mass_node = node.child("mass")
        problems = []
        if mass_node is not None:
            mass = self.floats(mass_node, 1, finite=False)[0]
            problems.append((mass_node, limits.mass_problem(mass, field="<mass>"),
                             not mass > 0))
        inertia = list(Inertial.inertia)
        inertia_node = node.child("inertia")
        if inertia_node is not None:
            for i, tag in enumerate(limits.INERTIA_NAMES):
                value = inertia_node.child(tag)
                if value is not None:
                    inertia[i] = self.floats(value, 1, finite=False)[0]
            problems.append((inertia_node, limits.inertia_problem(
                inertia[:3], inertia[3:],
                names=tuple("<inertia> %s" % n for n in limits.INERTIA_NAMES)),
                not all(v > 0 for v in inertia[:3])))
        pose = self.pose(node)           # a pose is checked in any model: nan is garbage
        for at, problem, not_positive in problems:
            if problem and static:
                return Inertial(pose=pose)
            if problem:
                self.fail_bare(at, problem + (" (Gazebo refuses it on a link that is not static)"
                                              if not_positive else ""))
        return Inertial(mass, pose, tuple(inertia))

    def friction(self, collision: Element) -> float:
        """<surface><friction><ode><mu> of a collision (SDF's default 1)."""
        node = collision
        for tag in ("surface", "friction", "ode", "mu"):
            node = node.child(tag)
            if node is None:
                return 1.0
        mu = self.floats(node, 1, finite=False)[0]
        problem = limits.outside("<mu>", mu, 0.0, limits.MAX_FRICTION)
        if problem:
            self.fail_bare(node, problem)
        return mu

    def element(self, node: Element, parent: XyzRpy, scope: str, static: bool) -> Optional[Shape]:
        """A collision or visual as a Shape; None for an empty geometry."""
        name = scope + self.name(node)
        geometry = node.child("geometry")
        if geometry is None or not geometry.children or geometry.children[0].tag == "empty":
            return None
        if len(geometry.children) > 1:
            self.fail_bare(geometry.children[1], "<geometry> of %s holds more than one shape "
                                                 "(one <polyline> at most)" % name)
        geo = geometry.children[0]
        pose = compose_xyz_rpy(parent, self.pose(node))
        points: Tuple[Tuple[float, float], ...] = ()
        if geo.tag == "box":
            size = self.positive(geo, "size", 3, (1.0, 1.0, 1.0))
        elif geo.tag == "cylinder":
            size = (self.positive(geo, "radius", 1, (1.0,))[0],
                    self.positive(geo, "length", 1, (1.0,))[0])
        elif geo.tag == "sphere":
            size = self.positive(geo, "radius", 1, (1.0,))
        elif geo.tag == "plane":
            size = self.positive(geo, "size", 2, (1.0, 1.0))
            normal_node = geo.child("normal")
            normal = self.floats(normal_node, 3) if normal_node is not None else (0.0, 0.0, 1.0)
            length = math.hypot(*normal)     # no overflow for 1e200
            if length == 0:
                self.fail_bare(normal_node, "<normal> must not be zero")
            pose = compose_xyz_rpy(pose, _normal_pose([v / length for v in normal]))
        elif geo.tag == "polyline":
            size = self.positive(geo, "height", 1, (1.0,))
            points = self.polygon(geo)
        elif geo.tag == "mesh":
            found = self.mesh(geo, name)
            if found is None:
                return None
            size, mesh = found
        else:
            self.fail_bare(geo, "unsupported geometry <%s> in %s (supported: %s)"
                           % (geo.tag, name, ", ".join(KINDS)))
        collision = node.tag == "collision"
        rgba, texture = (DEFAULT_RGBA, None) if collision else self.look(node.child("material"))
        mu = self.friction(node) if collision else 1.0
        mesh_colours = geo.tag == "mesh" and not collision and node.child("material") is None
        if mesh_colours:
            self.texture_warnings(geo, mesh, size)
        return Shape(name, geo.tag, pose, tuple(size), points, rgba, static, collision, mu=mu,
                     mesh=mesh if geo.tag == "mesh" else "", mesh_colours=mesh_colours,
                     texture=texture)

    def mesh(self, geo: Element, name: str) -> Optional[Tuple[Tuple[float, ...], str]]:
        """(scale, absolute file) of a <mesh>, its file read once here so that a bad one is
        refused with this line. None, with a warning, for a file found nowhere or a Collada
        file that cannot be read: Gazebo loads the link without that geometry."""
        from .mesh_file import MeshUnreadable, load_mesh
        uri_node = geo.child("uri")
        if uri_node is None or not uri_node.value:
            self.fail_bare(geo, "<mesh> of %s needs a <uri>" % name)
        if geo.child("submesh") is not None:
            self.fail_bare(geo.child("submesh"), "<submesh> is not supported: give the part "
                                                 "its own mesh file")
        scale = (1.0, 1.0, 1.0)
        scale_node = geo.child("scale")
        if scale_node is not None:
            scale = self.floats(scale_node, 3, finite=False)
            problem = limits.scale_problem(scale, "<scale>")
            if problem:
                self.fail_bare(scale_node, problem)
        try:
            path = resolve_uri(uri_node.value, self.base_dir)
            load_mesh(path, scale)
        except (AssetNotFound, MeshUnreadable) as err:
            if not any(w.endswith(str(err)) for w in self.warnings):   # once per file
                self.warn(uri_node, "%s left out: %s" % (name, err))
            return None
        except UserError as err:
            self.fail_bare(uri_node, str(err))
        return scale, path

    def texture_warnings(self, geo: Element, path: str, scale) -> None:
        """A warning (once per line) for each texture of the drawn mesh ``path`` that is not
        used: its part is drawn in its colour."""
        from .mesh_file import load_mesh
        for part in load_mesh(path, scale).parts:
            problem = part.texture_problem
            if problem and not any(w.endswith(problem) for w in self.warnings):
                self.warn(geo.child("uri"), problem)

    def polygon(self, polyline: Element) -> Tuple[Tuple[float, float], ...]:
        points = [self.floats(p, 2) for p in polyline.all("point")]
        for node, point in zip(polyline.all("point"), points):
            problem = limits.position_problem("<point>", point)
            if problem:
                self.fail_bare(node, problem)
        cleaned = _clean_polygon([(x, y) for x, y in points])
        if cleaned is None:
            self.fail_bare(polyline, "<polyline> must be a simple polygon of at least 3 corners "
                                     "(not crossing itself)")
        return cleaned

    def colour(self, material: Optional[Element]) -> Rgba:
        """Explicit <diffuse>, else <ambient>, else a known Gazebo script name, else the
        colour of the script's own material (material_scripts), else grey."""
        return self.look(material)[0]

    def look(self, material: Optional[Element]) -> Tuple[Rgba, Optional[str]]:
        """(colour, texture image or None) of a visual's <material>: ``colour``'s, and the
        image of a script's own material where it has one. A bad script is a warning (its
        file and line), never an error: the visual is drawn grey."""
        if material is None:
            return DEFAULT_RGBA, None
        for tag in ("diffuse", "ambient"):
            node = material.child(tag)
            if node is not None:
                values = node.value.split()
                rgba = self.floats(node, 4 if len(values) == 4 else 3)
                if not all(0.0 <= v <= 1.0 for v in rgba):
                    self.fail_bare(node, "<%s> values must lie in 0..1, got %r" % (tag, node.value))
                return tuple(rgba) + (1.0,) * (4 - len(rgba)), None
        script = material.child("script")
        script_name = script.child("name") if script is not None else None
        if script_name is None:
            return DEFAULT_RGBA, None
        if script_name.value in GAZEBO_MATERIALS:
            return GAZEBO_MATERIALS[script_name.value], None
        return self.script_look(script, script_name)

    def script_look(self, script: Element, name: Element) -> Tuple[Rgba, Optional[str]]:
        """(colour, texture or None) of a material the <script>'s own <uri> folders define;
        (grey, None) where none does. A <uri> found nowhere is passed over, as Gazebo does
        (its error line is not a warning here); each problem of the scripts is one warning."""
        places = []
        for uri in script.all("uri"):
            try:
                places.append(resolve_uri(uri.value, self.base_dir))
            except AssetError:
                continue
        found, problems = self.material_scripts.material(name.value, places)
        for problem in problems:
            if not any(w.endswith(problem) for w in self.warnings):   # once per world
                self.warn(name, problem)
        if found is None:
            return DEFAULT_RGBA, None
        return found.rgba or DEFAULT_RGBA, found.texture

    def pair_twins(self, shapes: List[Shape]) -> List[Shape]:
        """Link each collision to the visual with the same geometry and pose, and colour it:
        by its twin, else by the link's first visual."""
        visuals = [s for s in shapes if not s.collision]
        taken = set()
        twins: Dict[str, str] = {}
        for c in (s for s in shapes if s.collision):
            for v in visuals:
                if v.name not in taken and _same_geometry(c, v):
                    twins[c.name], twins[v.name] = v.name, c.name
                    taken.add(v.name)
                    break
        by_name = {v.name: v for v in visuals}
        out = []
        for s in shapes:
            twin = twins.get(s.name)
            if s.collision:
                source = by_name.get(twin) if twin else (visuals[0] if visuals else None)
                rgba = source.rgba if source else DEFAULT_RGBA
                own = bool(source and source.mesh_colours and source.mesh == s.mesh)
                texture = source.texture if twin else None     # the same face to draw it on
                s = replace(s, rgba=rgba, twin=twin, mesh_colours=own, texture=texture)
            elif twin:
                s = replace(s, twin=twin)
            out.append(s)
        return out


def _saved_poses(world: Element) -> Dict[str, Element]:
    """The ``<pose>`` of each model in the world's first ``<state>`` (a world saved by Gazebo),
    by model name. Gazebo starts the world in that state: a model it names stands there, not
    where its own ``<pose>`` puts it; models the state names that are not in the world, its
    links' poses and its sim time are not used here."""
    state = world.child("state")
    if state is None:
        return {}
    poses = {}
    for model in state.all("model"):
        pose = model.child("pose")
        if model.attrib.get("name") and pose is not None and pose.value:
            poses[model.attrib["name"]] = pose
    return poses


def _with_saved_pose(node: Element, saved: Dict[str, Element]) -> Element:
    """A top-level ``<model>`` or named ``<include>`` with its pose from the saved state."""
    if node.tag == "model":
        name = node.attrib.get("name", "")
    else:
        name_node = node.child("name")
        name = name_node.value if name_node is not None else ""
    pose = saved.get(name) if name else None
    if pose is None:
        return node
    children = [c for c in node.children if c.tag != "pose"] + [pose]
    return xml_reader.element(node.tag, node.attrib, node.line, children)


def _same_geometry(a: Shape, b: Shape, tol: float = 1e-9) -> bool:
    return (a.kind == b.kind and a.mesh == b.mesh and len(a.points) == len(b.points)
            and all(abs(u - v) <= tol for u, v in zip(a.size + a.pose, b.size + b.pose))
            and all(abs(u - v) <= tol for p, q in zip(a.points, b.points) for u, v in zip(p, q)))


def _check_names(world: World) -> None:
    seen: Dict[str, Shape] = {}
    for s in world.shapes:
        other = seen.get(s.name)
        if other is not None and other.twin != s.name:
            kind = "collision" if s.collision else "visual"
            raise WorldError("%s: two elements are named %s (the second a %s): names must be "
                             "unique within a link" % (world.path, s.name, kind))
        seen[s.name] = s


def load_world(path: str) -> World:
    """Parse the SDF file at ``path``; WorldError (one line: file, line, fault) if it cannot.
    Its mesh files are first converted in parallel into the disk cache (mesh_cache)."""
    from .mesh_cache import convert_world
    convert_world(lambda: _Loader(path).document(_parse_xml(path)), path)
    loader = _Loader(path)
    world = loader.document(_parse_xml(path))
    _check_names(world)
    return world


def load_model_xml(root, source: str, name: str, pose: XyzRpy = ZERO_XYZ_RPY,
                   max_shapes: int = None) -> World:
    """The one ``<model>`` of an SDF document (a spawn request's model_xml): ``root`` is its
    root element as xml_reader parsed it (changed here), or its text, parsed here. The model is
    renamed ``name`` and placed with its own <pose> composed onto ``pose``; WorldError (one
    line with the line number) if it is not that, or if it holds more than ``max_shapes``
    (default MAX_WORLD_SHAPES) collisions and visuals: reading stops there."""
    if not isinstance(root, Element):
        root = parse_xml(root, source)
    loader = _Loader(source, base_dir=os.getcwd())
    if max_shapes is not None:
        loader.budget["shapes"] = max_shapes
    if root.tag not in ("sdf", "gazebo"):
        loader.fail_bare(root, "the root element is <%s>: an SDF model starts with <sdf>"
                         % root.tag)
    models = root.all("model")
    if len(models) != 1:
        loader.fail_bare(root, "<sdf> must hold exactly one <model>, it holds %d" % len(models))
    models[0].set("name", name)
    world = loader.models_of(xml_reader.element(root.tag, {}, root.line, models), name, pose)
    _check_names(world)
    return world
