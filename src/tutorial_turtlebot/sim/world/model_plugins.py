"""The model plugins of the world's models, running: what gazebo_ros_p3d,
gazebo_ros_joint_state_publisher and hector's imu and gps (files.plugins.table) compute,
each at its rate, from where its model's links and joints are now. Knows nothing of ROS: the
node asks for a reading only when someone subscribes to it.

``ModelPlugins`` follows the models of the world (world_models.ModelRegistry): an SDF model
brings the plugins its document read (World.model_plugins naming it), a robot those of its
URDF (RobotPlugins.model_plugins, its namespace its SimRobot's); a deleted model takes its own
along. ``due(now)`` says which are due at a physics step (each at its rate, Hz of sim time; 0:
every step); each ``RunningPlugin`` then gives its reading on demand:
  P3dRunner.odometry()              Odometry's pose, twist and variance
  JointStateRunner.joint_states()   JointState's names, positions and velocities
  HectorImuRunner.imu(now_ns)       Imu's orientation, rates, acceleration and covariances
  HectorGpsRunner.fix(now_ns)       NavSatFix's latitude, longitude, altitude, covariance and
                                    the velocity
  DiffDriveRunner.odometry()        a drive's odom -> robotBaseFrame pose and base-frame
  DriveRunner.odometry()            twist (an SDF model's: model_drives; a robot's is its
                                    SimRobot)
A plugin that acts does it at its tick (``tick(now_ns)``, in ``due``): a drive's wheel motors
(or its push, its velocity) toward its command (``command``), as the physics step after it
sees them. RunningPlugin and Odometry are plugin_runner's.
Frames: world (z up) unless said; a link's twist is in the world frame. Units: m, s, rad, deg
(latitude, longitude), m/s^2.
"""
import math
import operator
from typing import Callable, Dict, List, NamedTuple, Optional, Sequence, Tuple

import numpy as np

from .. import kinematics
from ..files.plugins.gazebo_ros_joint_state_publisher import JointStatePublisherPlugin
from ..files.plugins.gazebo_ros_p3d import P3dPlugin
from ..files.plugins.hector_gazebo_ros_gps import HectorGpsPlugin
from ..files.plugins.hector_gazebo_ros_imu import ErrorModel, HectorImuPlugin
from . import model_drives
from . import reference_frames as rf
from .model_drives import DiffDriveRunner, DriveRunner
from .plugin_runner import NS_PER_S, Odometry, RunningPlugin, Vec

MODEL_PLUGINS = "model_plugins"      # the world output Simulation.step reports them by
EQUATORIAL_RADIUS = 6378137.0        # m, WGS84
FLATTENING = 1.0 / 298.257223563     # WGS84
ECCENTRICITY2 = 2.0 * FLATTENING - FLATTENING ** 2


class ImuReading(NamedTuple):
    orientation: Tuple[float, float, float, float]    # of the link in the world, with errors
    angular_velocity: Vec                             # rad/s, link frame
    linear_acceleration: Vec                          # m/s^2, link frame, gravity's reaction in
    orientation_covariance: Tuple[float, ...]         # 9, row-major
    angular_velocity_covariance: Tuple[float, ...]
    linear_acceleration_covariance: Tuple[float, ...]


class GpsFix(NamedTuple):
    latitude: float                      # deg
    longitude: float                     # deg
    altitude: float                      # m
    position_covariance: Tuple[float, ...]   # 9, row-major (m^2), diagonal known
    velocity: Vec                        # m/s: x north, y west at heading 0 (hector's)


def diagonal(values: Sequence[float]) -> Tuple[float, ...]:
    """The row-major 3x3 matrix with ``values`` on its diagonal."""
    return (values[0], 0.0, 0.0, 0.0, values[1], 0.0, 0.0, 0.0, values[2])


def fix_of(spec: HectorGpsPlugin, position: Sequence[float]) -> Tuple[float, float, float]:
    """(latitude deg, longitude deg, altitude m) of world ``position`` (m), as hector's gps
    places the world frame on the WGS84 ellipsoid (x north, y west at heading 0)."""
    lat0 = math.radians(spec.reference_latitude)
    heading = math.radians(spec.reference_heading)
    temp = 1.0 / (1.0 - ECCENTRICITY2 * math.sin(lat0) ** 2)
    prime_vertical = EQUATORIAL_RADIUS * math.sqrt(temp)
    radius_north = prime_vertical * (1.0 - ECCENTRICITY2) * temp
    radius_east = prime_vertical * math.cos(lat0)
    x, y, z = position
    north = math.cos(heading) * x + math.sin(heading) * y
    west = -math.sin(heading) * x + math.cos(heading) * y
    return (float(spec.reference_latitude + math.degrees(north / radius_north)),
            float(spec.reference_longitude - math.degrees(west / radius_east)),
            float(spec.reference_altitude + z))


class ErrorState:
    """hector's SensorModel running: its drift (a Gauss-Markov process) and the last error."""

    def __init__(self, model: ErrorModel, rng: np.random.Generator):
        self.model = model
        self.rng = rng
        self.drift = np.zeros(3)
        self.error = np.zeros(3)

    def reset(self) -> None:
        self.drift = np.zeros(3)
        self.error = np.zeros(3)

    def update(self, dt: float) -> np.ndarray:
        """The error after ``dt`` s: offset + drift + white noise, per axis."""
        m = self.model
        freq = np.array(m.drift_frequency)
        kick = self.rng.normal(0.0, 1.0, 3) * np.sqrt(2.0 * np.abs(freq)) * np.array(m.drift)
        self.drift = self.drift - dt * (self.drift * freq + kick)
        noise = self.rng.normal(0.0, 1.0, 3) * np.array(m.gaussian_noise)
        self.error = np.array(m.offset) + self.drift + noise
        return self.error


class P3dRunner(RunningPlugin):
    """gazebo_ros_p3d: the body's pose and twist in the world or in the reference link, the
    way the plugin turns them (its rotation composed as it composes it)."""

    kind = "p3d"

    def odometry(self) -> Odometry:
        spec: P3dPlugin = self.spec
        (position, orientation), (linear, angular) = self.link(spec.body_name)
        if spec.reference_link:
            (f_position, f_orientation), (f_linear, f_angular) = self.link(spec.reference_link)
            position = rf.rotate(rf.conjugate(f_orientation),
                                 np.subtract(position, f_position))
            orientation = rf.multiply(orientation, rf.conjugate(f_orientation))
            linear = rf.rotate(f_orientation, np.subtract(linear, f_linear))
            angular = rf.rotate(f_orientation, np.subtract(angular, f_angular))
        position = tuple(float(p + o) for p, o in zip(position, spec.xyz_offset))
        orientation = rf.multiply(kinematics.quat_from_rpy(*spec.rpy_offset), orientation)
        norm = math.sqrt(sum(c * c for c in orientation)) or 1.0
        orientation = tuple(float(c / norm) for c in orientation)
        sigma = spec.gaussian_noise
        noise = self.rng.normal(0.0, sigma, 6) if sigma > 0 else np.zeros(6)
        return Odometry(position, orientation,
                        tuple(float(v + n) for v, n in zip(linear, noise[:3])),
                        tuple(float(v + n) for v, n in zip(angular, noise[3:])), sigma * sigma)


class JointStateRunner(RunningPlugin):
    """gazebo_ros_joint_state_publisher: each named joint's position and rate; a joint the
    model lists but does not simulate (an SDF model's) at 0 and still, as get_joint_properties
    says."""

    kind = "joint_states"

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self._found: Dict[str, Tuple[object, int]] = {}
        self._bodies: List[object] = []

    def _joints(self) -> Dict[str, Tuple[object, int]]:
        bodies = [p.body for p in self.model.parts if p.movable]
        if len(bodies) != len(self._bodies) or any(map(operator.is_not, bodies, self._bodies)):
            found = {}
            for body in bodies:
                for joint in body.joints():
                    if joint.movable and joint.name not in found:
                        found[joint.name] = (body, joint.index)
            self._found, self._bodies = found, bodies
        return self._found

    def joint_states(self) -> Tuple[Tuple[str, ...], List[float], List[float]]:
        """(names, positions rad or m, velocities rad/s or m/s), in <jointName>'s order."""
        spec: JointStatePublisherPlugin = self.spec
        found = self._joints()
        positions, velocities = [], []
        for name in spec.joint_names:
            body, index = found.get(name, (None, -1))
            position, rate = body.joint_state(index) if body is not None else (0.0, 0.0)
            positions.append(float(position))
            velocities.append(float(rate))
        return spec.joint_names, positions, velocities


class HectorImuRunner(RunningPlugin):
    """hector_gazebo_ros_imu: the acceleration from the change of the link's velocity since
    the last reading, less gravity, in the link frame; the rates the link's; with hector's
    error models (the orientation turned by the accel and heading errors, a pseudo AHRS)."""

    kind = "hector_imu"

    def __init__(self, spec: HectorImuPlugin, *args, **kwargs):
        super().__init__(spec, *args, **kwargs)
        if spec.seed is not None:
            self.rng = np.random.default_rng(spec.seed)
        self.errors = [ErrorState(m, self.rng) for m in (spec.accel, spec.rate, spec.heading)]
        self.restart()

    def restart(self) -> None:
        self._last: Optional[Tuple[int, np.ndarray]] = None    # (time ns, world velocity)
        for error in self.errors:
            error.reset()

    def imu(self, now_ns: int) -> ImuReading:
        spec: HectorImuPlugin = self.spec
        (_, orientation), (linear, angular) = self.link(spec.body_name)
        velocity = np.array(linear, dtype=float)
        dt = 0.0 if self._last is None else (now_ns - self._last[0]) / NS_PER_S
        accel_world = (velocity - self._last[1]) / dt if dt > 0 else np.zeros(3)
        self._last = (now_ns, velocity)
        gravity = np.array(self.gravity(), dtype=float)
        gravity_body = np.array(kinematics.to_body(orientation, gravity))
        accel = np.array(kinematics.to_body(orientation, accel_world)) - gravity_body
        rate = np.array(kinematics.to_body(orientation, angular))
        accel_error, rate_error, heading_error = (e.update(dt) for e in self.errors)
        accel = accel + accel_error
        rate = rate + rate_error
        turned = rf.multiply(rf.multiply(self._attitude_error(gravity_body, accel_error),
                                         orientation),
                             (0.0, 0.0, math.sin(heading_error[0] / 2.0),
                              math.cos(heading_error[0] / 2.0)))
        g2 = float(gravity @ gravity)
        a_noise, r_noise = spec.accel.gaussian_noise, spec.rate.gaussian_noise
        tilt = ([a_noise[0] ** 2 / g2, a_noise[1] ** 2 / g2] if g2 > 0 else [-1.0, -1.0])
        return ImuReading(
            tuple(float(c) for c in turned), tuple(float(v) for v in rate),
            tuple(float(v) for v in accel),
            diagonal(tilt + [spec.heading.gaussian_noise[0] ** 2]),
            diagonal([n * n for n in r_noise]), diagonal([n * n for n in a_noise]))

    @staticmethod
    def _attitude_error(gravity_body: np.ndarray, error: np.ndarray):
        """The tilt the accel error gives the orientation (hector's pseudo AHRS); none
        without gravity or error."""
        tilted = gravity_body + error
        scale = float(np.linalg.norm(tilted) * np.linalg.norm(gravity_body))
        if scale == 0.0 or not error.any():
            return (0.0, 0.0, 0.0, 1.0)
        cos_alpha = float(tilted @ gravity_body) / scale
        normal = np.cross(gravity_body, error) * math.sqrt(abs((1 - cos_alpha) / 2)) / scale
        return (float(normal[0]), float(normal[1]), float(normal[2]),
                math.sqrt(abs((1 + cos_alpha) / 2)))


class HectorGpsRunner(RunningPlugin):
    """hector_gazebo_ros_gps: the link's world position on the ellipsoid, with hector's
    position and velocity error models (the velocity's error drives the position's drift)."""

    kind = "hector_gps"

    def __init__(self, spec: HectorGpsPlugin, *args, **kwargs):
        super().__init__(spec, *args, **kwargs)
        self.position_error = ErrorState(spec.position, self.rng)
        self.velocity_error = ErrorState(spec.velocity, self.rng)
        self.restart()

    def restart(self) -> None:
        self._last_ns: Optional[int] = None
        self.position_error.reset()
        self.velocity_error.reset()

    def fix(self, now_ns: int) -> GpsFix:
        spec: HectorGpsPlugin = self.spec
        (position, _), (linear, _) = self.link(spec.body_name)
        dt = 0.0 if self._last_ns is None else (now_ns - self._last_ns) / NS_PER_S
        self._last_ns = now_ns
        velocity = np.array(linear, dtype=float) + self.velocity_error.update(dt)
        self.position_error.drift = (self.position_error.drift
                                     + self.velocity_error.error * dt)
        position = np.array(position, dtype=float) + self.position_error.update(dt)
        latitude, longitude, altitude = fix_of(spec, position)
        heading = math.radians(spec.reference_heading)
        c, s = math.cos(heading), math.sin(heading)
        model = spec.position
        variance = [d * d + n * n for d, n in zip(model.drift, model.gaussian_noise)]
        return GpsFix(latitude, longitude, altitude, diagonal(variance),
                      (float(c * velocity[0] + s * velocity[1]),
                       float(-s * velocity[0] + c * velocity[1]), float(velocity[2])))


RUNNERS = ((P3dPlugin, P3dRunner), (JointStatePublisherPlugin, JointStateRunner),
           (HectorImuPlugin, HectorImuRunner), (HectorGpsPlugin, HectorGpsRunner)
           ) + model_drives.RUNNERS


def namespace_of(spec, model_name: str, robot_namespace: str) -> str:
    """The namespace a plugin's topics are in: its <robotNamespace>, else the robot's (the
    spawn's, which spawn_model writes into every plugin), else "" (the node's); the joint
    state publisher's default is the model's name."""
    namespace = spec.robot_namespace or robot_namespace
    if not namespace and isinstance(spec, JointStatePublisherPlugin):
        namespace = model_name
    return namespace


class ModelPlugins:
    """The running model plugins of the world's models and robots, in the models' order."""

    def __init__(self, time_step: Callable[[], float], models, robots: Dict[str, object],
                 seed: int = 0, gravity: Callable[[], Vec] = lambda: (0.0, 0.0, -9.8)):
        """``time_step()``: the physics step (s); ``models``: the world's ModelRegistry;
        ``robots``: the Simulation's SimRobots by name (followed at every output time);
        ``gravity()``: the world's (m/s^2)."""
        self.time_step = time_step
        self.registry = models
        self.robots = robots
        self.seed = seed
        self.gravity = gravity
        self.plugins: List[RunningPlugin] = []
        self.due_now: List[RunningPlugin] = []
        self.generation = 0
        self.next_ns = math.inf
        self._models: List[object] = []
        self._made = 0
        self.sync(0)
        self._due_generation = self.generation

    def sync(self, now_ns: int) -> bool:
        """Follow the registry: the plugins of models added since, less those of models gone;
        True if that changed anything. New plugins are due at ``now_ns`` first."""
        models = self.registry.models()
        if len(models) == len(self._models) and all(map(operator.is_, models, self._models)):
            return False
        present = {id(m) for m in models}
        kept = [p for p in self.plugins if id(p.model) in present]
        known = {id(p.model) for p in self.plugins} | {id(m) for m in self._models}
        for model in models:
            if id(model) not in known:
                kept.extend(self._made_for(model, now_ns))
        changed = len(kept) != len(self.plugins) or any(map(operator.is_not, kept,
                                                            self.plugins))
        self._models = models
        if changed:
            self.plugins = kept
            self.generation += 1
            self.next_ns = min((p.schedule.next_ns for p in kept), default=math.inf)
        return changed

    def _specs(self, model) -> Tuple[Sequence[object], str]:
        """(the model plugins of ``model``, its robot's namespace or "")."""
        robot = self.robots.get(model.name)
        if robot is not None and getattr(robot, "description", None) is not None:
            return robot.description.plugins.model_plugins, robot.namespace
        world = getattr(model, "world", None)
        return [p for p in getattr(world, "model_plugins", ()) if p.model == model.name], ""

    def _made_for(self, model, now_ns: int) -> List[RunningPlugin]:
        specs, robot_namespace = self._specs(model)
        made = []
        for spec in specs:
            runner = next(r for kind, r in RUNNERS if isinstance(spec, kind))
            plugin = runner(spec, model, namespace_of(spec, model.name, robot_namespace),
                            1.0 / self.time_step(),
                            np.random.default_rng([self.seed, 1, self._made]), self.gravity)
            self._made += 1
            plugin.schedule.reset(now_ns)
            made.append(plugin)
        return made

    def due(self, now_ns: int) -> bool:
        """After a physics step: whether there are plugins to publish at ``now_ns``
        (``due_now``), or plugins to advertise or take back (``generation`` changed)."""
        changed = self.sync(now_ns) or self.generation != self._due_generation
        self._due_generation = self.generation     # (a sync of drives() since reported here)
        if now_ns < self.next_ns and not changed:
            return False
        self.due_now = [p for p in self.plugins if p.schedule.due(now_ns)]
        for plugin in self.due_now:
            plugin.tick(now_ns)
        self.next_ns = min((p.schedule.next_ns for p in self.plugins), default=math.inf)
        return bool(self.due_now) or changed

    def drives(self, now_ns: int) -> List[RunningPlugin]:
        """The drives of the SDF models now (DiffDriveRunner, DriveRunner: the registry
        followed first)."""
        self.sync(now_ns)
        return [p for p in self.plugins if isinstance(p, (DiffDriveRunner, DriveRunner))]

    def reset(self, now_ns: int) -> None:
        """Every schedule starts over at ``now_ns``, every plugin's state as loaded."""
        for plugin in self.plugins:
            plugin.schedule.reset(now_ns)
            plugin.restart()
        self.next_ns = now_ns if self.plugins else math.inf
