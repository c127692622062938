"""The data a world file becomes: shapes, links, models, actors, the world. Plain data: no ROS,
no pybullet (engine.world_bullet builds it), no file reading (world_sdf reads it).

Units: metres, radians, seconds, kilograms. Poses are kinematics.XyzRpy (x, y, z, then SDF's
fixed-axis roll, pitch, yaw: R = Rz(yaw) Ry(pitch) Rx(roll)) in the world frame unless a field
says otherwise.
"""
from dataclasses import dataclass
from typing import Optional, Tuple

from ..kinematics import ZERO_XYZ_RPY, XyzRpy
from .plugins.sensor_types import WorldSensor
from .sdf.world_lights import Light

Rgba = Tuple[float, float, float, float]
KINDS = ("box", "cylinder", "sphere", "plane", "polyline", "mesh")
DEFAULT_RGBA: Rgba = (0.7, 0.7, 0.7, 1.0)   # a visual without material: Gazebo's light grey


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


# SDF's joint types (sdformat 9): those simulated, and those approximated (model_tree).
JOINT_KINDS = ("revolute", "continuous", "prismatic", "fixed", "ball", "universal",
               "revolute2", "screw", "gearbox")
WORLD_LINK = "world"    # a joint's <parent> that anchors its model to the world
UNLIMITED = 1e16        # SDF's default <lower>/<upper> magnitude: no limit


@dataclass(frozen=True)
class Joint:
    """A ``<joint>`` of a model that is not static, placed in the world as the model was loaded
    (every joint at position 0). Links are scoped ("model::link"); ``parent`` is WORLD_LINK for
    a joint that anchors the model. Axes are unit vectors in the world frame; limits in rad
    (angular) or m (prismatic), -+UNLIMITED when the file sets none; ``effort`` N m or N and
    ``velocity`` rad/s or m/s, -1 = none (SDF's default)."""

    name: str                # its own name, as get_model_properties lists it
    kind: str                # one of JOINT_KINDS
    parent: str
    child: str
    pose: XyzRpy             # world pose of the joint frame (SDF: its <pose> in the child link)
    axis: Tuple[float, float, float] = (0.0, 0.0, 1.0)
    axis2: Tuple[float, float, float] = (0.0, 1.0, 0.0)   # universal, revolute2: the second
    lower: float = -UNLIMITED
    upper: float = UNLIMITED
    effort: float = -1.0
    velocity: float = -1.0
    damping: float = 0.0     # N m s/rad or N s/m, <axis><dynamics><damping>
    friction: float = 0.0    # N m or N, <axis><dynamics><friction>: what holds it still


@dataclass(frozen=True)
class Model:
    """A top-level model of a world file, as /gazebo/model_states lists it."""

    name: str
    pose: XyzRpy             # world pose of the model frame
    static: bool
    links: Tuple[Link, ...]
    joints: Tuple[str, ...] = ()
    joint_types: Tuple[str, ...] = ()    # each joint's <joint type> (revolute, fixed ...)
    joint_specs: Tuple[Joint, ...] = ()  # the joints simulated (a movable model's; a loop's
    #                                      closing joint left out: model_tree)


@dataclass(frozen=True)
class Waypoint:
    """One ``<waypoint>`` of an actor's trajectory."""

    time: float              # s from the start of its trajectory
    pose: XyzRpy             # world pose of the actor frame at that time


@dataclass(frozen=True)
class Trajectory:
    """One ``<trajectory>`` of an actor's ``<script>``, as Gazebo 11 keeps it (Actor::LoadScript):
    its waypoints in time order, one per time (the last written wins), the first moved to time
    0; it lasts until its last waypoint."""

    id: int
    type: str
    tension: float           # of the position spline: 0 Catmull-Rom .. 1 (gz::math::Spline)
    waypoints: Tuple[Waypoint, ...]

    @property
    def duration(self) -> float:
        """s: the time of its last waypoint (0 without waypoints)."""
        return self.waypoints[-1].time if self.waypoints else 0.0


@dataclass(frozen=True)
class Actor:
    """An ``<actor>``: a model moved by its script, not by physics. Its shapes (its links'
    visuals and its skin, or the box standing in for the skin) are visuals only, as Gazebo 11
    enables no collision of an actor: lasers, contacts and the robot pass through it."""

    name: str
    pose: XyzRpy             # its <pose>: where it stands until its script moves it
    trajectories: Tuple[Trajectory, ...] = ()   # in id order (equal ids in file order)
    loop: bool = True        # <script><loop>
    delay_start: float = 0.0  # s, <script><delay_start>: waited before each run of the script
    auto_start: bool = True  # <script><auto_start>: False: it stands at ``pose``
    skin: str = ""           # the skin's mesh file drawn (absolute), "" if a box stands in


@dataclass(frozen=True)
class World:
    """A loaded world file: its shapes in file order."""

    name: str                   # <world name="...">, or the file's stem for a bare model file
    path: str
    models: Tuple[str, ...]     # top-level model names as /gazebo/model_states lists them: the
    #                             models in file order, then the actors in file order
    shapes: Tuple[Shape, ...]
    model_specs: Tuple[Model, ...] = ()   # the same models (actors too) with their links
    warnings: Tuple[str, ...] = ()        # one line each: what was left out, and why
    lights: Tuple[Light, ...] = ()        # the world's lights in file order (world_lights)
    actors: Tuple[Actor, ...] = ()        # the world's <actor>s in file order (their shapes and
    #                                       Model are in ``shapes`` and ``model_specs`` too)
    sensors: Tuple[WorldSensor, ...] = ()  # its models' links' sensors with a gazebo_ros plugin
    #                                       that runs here, in file order (world_sensor_reading)
    gravity: Tuple[float, float, float] = (0.0, 0.0, -9.8)   # m/s^2, world frame: <gravity>
    model_plugins: Tuple[object, ...] = ()   # its models' model plugins that run here, in file
    #                                          order (plugins.table), each naming its model

    def model(self, name: str) -> Model:
        """The top-level model called ``name``; KeyError if there is none."""
        for m in self.model_specs:
            if m.name == name:
                return m
        raise KeyError(name)

    def actor(self, name: str) -> Actor:
        """The actor called ``name``; KeyError if there is none."""
        for a in self.actors:
            if a.name == name:
                return a
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
