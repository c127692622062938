"""The sensors of the world's models, running: what each gazebo_ros sensor plugin of a world
file's (or a spawned SDF model's) link computes, at its rate, from where its link is now; and a
URDF robot's sensors that SimRobot does not make itself (robot_sensors), the same way. Knows
nothing of ROS: the node asks for a reading only when someone subscribes to it.

``WorldSensors`` follows the models of the world (world_models.ModelRegistry): each SDF model
brings the sensors its document read (World.sensors of its links), a robot those of its URDF
(robot_sensors.robot_sensor_specs: on its RobotModel's links, ``namespace`` its spawn's), a
deleted model takes its own along. ``due(now)`` says which are due at a physics step (each at
its rate, Hz of sim time; 0: every step); each ``RunningSensor`` then gives its reading on
demand:
  LaserRunner.scan()          LaserScan ranges (devices.lidar, as a robot's laser)
  RangeRunner.reading()       Range's range (devices.range_sensor)
  BlockLaserRunner.cloud()    PointCloud's points and channel (devices.block_laser)
  CameraRunner.image()        an image in its <format>, distorted by its lens
                              (engine.rendering, devices.image_formats, devices.lens_distortion),
                              ``intrinsics`` its CameraInfo; ``frame(depth=True)`` with depth
  DepthCameraRunner           a CameraRunner whose topics ask for depth too
  TriggeredCameraRunner       a CameraRunner due once at the step after each ``trigger()``
  MultiCameraRunner.images()  its cameras' images (CameraRunners), drawn at one tick
  BumperRunner.contacts()     ContactsState's states: each pair's points, wrenches on the
                              sensor's link (engine.contacts, contact_names)
  ImuSensorRunner.reading(t)  Imu's orientation, rates, acceleration (devices.imu)
A world model's rays see the world and every robot; a robot's rays see the world and every
other robot, never the robot itself, as its lasers' (SimRobot.scan; Gazebo's would see its other
links). Poses: the sensor's <pose> in its link, the link where
the model's bodies are (WorldModel.link_states: a static model's link is fixed). Frames: world
(z up); a sensor looks along its x, a camera's optical frame along z (x right, y down).
Units: m, s, rad.
"""
import math
import operator
import threading
from dataclasses import replace
from typing import Callable, Dict, List, NamedTuple, Optional, Tuple

import numpy as np

from .. import kinematics
from ..devices.block_laser import block_cloud
from ..devices.camera import CameraIntrinsics
from ..devices.imu import Accelerometer, AxisNoises, imu_axes
from ..devices.image_formats import CameraOutput
from ..devices.lidar import ranges_from_distances, ray_directions
from ..devices.range_sensor import radiation_type, range_reading
from ..devices.ray_grid import gazebo_ranges, ray_grid
from ..engine.contacts import gravity, link_contacts
from ..engine.physics import ROBOT_GROUPS, WorldPhysics
from ..engine.rendering import CameraRenderer, validate_spec
from ..engine.world_bullet import WORLD_COLLISION_GROUP
from ..files.plugins.robot_plugin_types import CameraSensor, LaserSensor
from ..files.plugins.camera_types import WorldCamera
from ..files.plugins.gazebo_ros_bumper import BumperSensor
from ..files.plugins.gazebo_ros_imu_sensor import ImuSensorPlugin
from ..files.plugins.sensor_types import BlockLaserSensor, RangeSensor
from . import reference_frames as rf
from .contact_names import ContactNames, collision_link, name_in
from .robot_sensors import robot_sensor_specs
from .schedule import RateSchedule, seconds_to_ns
from .sim_robot import LINK_TO_OPTICAL

WORLD_SENSORS = "world_sensors"        # the world output Simulation.step reports them by
RAY_MASK = WORLD_COLLISION_GROUP | ROBOT_GROUPS     # what a world sensor's rays see
Vec = Tuple[float, float, float]


def model_of(link: str) -> str:
    """The top-level model of a scoped link name ("model::inner::link" -> "model")."""
    return link.split("::", 1)[0]


class RunningSensor:
    """One sensor of a world model: its data (``spec``, a WorldSensor), the model it is on,
    its schedule, its own noise; on a robot, the robot's ``namespace`` (normalize_namespace's
    form; "" on a world model) and its ``ray_mask`` (RobotBody.ray_mask)."""

    kind = ""
    namespace = ""
    ray_mask = RAY_MASK

    def __init__(self, spec, model, physics: WorldPhysics, rate: float,
                 rng: np.random.Generator):
        """``rate``: Hz of sim time, 0 for every physics step (at most that)."""
        self.spec = spec
        self.model = model
        self.physics = physics
        self.in_link = kinematics.pose_from_xyz_rpy(spec.pose)
        step_rate = 1.0 / physics.time_step
        self.schedule = RateSchedule(min(rate or step_rate, step_rate))
        self.rng = rng

    @property
    def name(self) -> str:
        """"model::link::sensor", as Gazebo scopes a sensor."""
        return "%s::%s" % (self.spec.link, self.spec.name)

    def pose(self) -> Tuple[np.ndarray, np.ndarray]:
        """World (position, 3x3 rotation) of the sensor frame now; KeyError if its link is
        no longer in its model."""
        for scoped, link_pose, _ in self.model.link_states():
            if scoped == self.spec.link:
                position, orientation = rf.compose(link_pose, self.in_link)
                return np.array(position), kinematics.rotation_matrix(orientation)
        raise KeyError(self.spec.link)

    def _cast(self, directions: np.ndarray, start: float, end: float) -> np.ndarray:
        """Distances (m) from ``start`` m out along each sensor-frame unit direction to the
        first surface before ``end`` m; inf where there is none."""
        origin, rotation = self.pose()
        world = directions @ rotation.T
        return self.physics.ray_distances(origin + world * start, world, end - start,
                                          self.ray_mask)


class LaserRunner(RunningSensor):
    """gazebo_ros_laser (gpu_laser): the horizontal plane's ranges, as a robot's laser."""

    kind = "laser"

    def __init__(self, spec: LaserSensor, model, physics, rng):
        super().__init__(spec, model, physics, spec.laser.rate, rng)
        self.laser = spec.laser
        self._rays = ray_directions(self.laser)

    def scan(self) -> np.ndarray:
        """LaserScan.ranges (float32; +inf nothing within range_max, -inf at or inside
        range_min)."""
        distances = self._cast(self._rays, 0.0, self.laser.range_max)
        return ranges_from_distances(self.laser, distances, self.rng)


class _GridRunner(RunningSensor):
    """A plugin reading every ray of its sensor, Gazebo's way (ray_grid)."""

    def __init__(self, spec, model, physics, rng):
        super().__init__(spec, model, physics, spec.rate, rng)
        self._rays = ray_grid(spec.rays)

    def ranges(self) -> np.ndarray:
        """Every ray's range (m), Gazebo's order: range_max where it meets nothing."""
        rays = self.spec.rays
        return gazebo_ranges(rays, self._cast(self._rays, rays.range_min, rays.range_max))


class RangeRunner(_GridRunner):
    """gazebo_ros_range: the nearest of the rays."""

    kind = "range"

    @property
    def radiation_type(self) -> int:
        return radiation_type(self.spec.radiation)

    def reading(self) -> float:
        """Range.range (m): range_max exactly when nothing is hit."""
        spec = self.spec
        return range_reading(self.ranges(), spec.rays.range_max, spec.gaussian_noise, self.rng)


class BlockLaserRunner(_GridRunner):
    """gazebo_ros_block_laser: a point per (interpolated) ray."""

    kind = "block_laser"

    def cloud(self) -> Tuple[np.ndarray, np.ndarray]:
        """(points (N, 3) float32 in the sensor frame, channel (N,) float32)."""
        spec = self.spec
        return block_cloud(spec.rays, self.ranges(), spec.gaussian_noise, self.rng)


class CameraRunner(RunningSensor):
    """gazebo_ros_camera: images in the camera's format (and lens), rendered only when asked
    for; a depth camera's with its depth."""

    kind = "camera"

    def __init__(self, spec: CameraSensor, model, physics, rng):
        super().__init__(spec, model, physics, spec.spec.rate, rng)
        # the renderer's rate is the schedule's (0 in the file: every physics step)
        self.camera_spec = replace(spec.spec, rate=self.schedule.rate_hz)
        validate_spec(self.camera_spec)
        self.intrinsics = CameraIntrinsics.from_spec(self.camera_spec)
        self.output = CameraOutput(spec.image_format, spec.lens, self.camera_spec.width,
                                   self.camera_spec.height)
        self.image_format = spec.image_format
        self.encoding, self.pixel_bytes = self.output.encoding, self.output.pixel_bytes
        if isinstance(spec, WorldCamera):
            self.intrinsics = replace(self.intrinsics, distortion=spec.info_distortion)
            self.in_link = rf.compose(self.in_link,
                                      kinematics.pose_from_xyz_rpy(spec.lens_pose))
        self._renderer: Optional[CameraRenderer] = None

    def frame(self, depth: bool = False) -> Tuple[np.ndarray, Optional[np.ndarray]]:
        """(the image's pixels seen now (image_formats.converted, distorted by the lens),
        depth float32 (height, width) m along the optical axis, +inf for nothing, or None)."""
        if self._renderer is None:
            physics = self.physics
            self._renderer = CameraRenderer(physics.client, self.camera_spec,
                                            use_egl=physics.egl or physics.gui)
        position, rotation = self.pose()
        rgb, metres = self._renderer.render(position, rotation @ LINK_TO_OPTICAL, depth=depth)
        return self.output.pixels(rgb), metres

    def image(self) -> np.ndarray:
        """The image's pixels seen now: (height, width, 3) uint8 for rgb8."""
        return self.frame()[0]


class DepthCameraRunner(CameraRunner):
    """gazebo_ros_depth_camera: an image, a depth image and a point cloud of one render."""

    kind = "depth_camera"


class TriggeredCameraRunner(CameraRunner):
    """gazebo_ros_triggered_camera: one image at the physics step after each ``trigger()``."""

    kind = "triggered_camera"

    def __init__(self, spec: CameraSensor, model, physics, rng):
        super().__init__(spec, model, physics, rng)
        self.schedule = TriggerSchedule(seconds_to_ns(physics.time_step))

    def trigger(self) -> None:
        """One more image (any thread)."""
        self.schedule.trigger()


class MultiCameraRunner(RunningSensor):
    """gazebo_ros_multicamera: its cameras (left, right) drawn at one tick."""

    kind = "multicamera"

    def __init__(self, spec: CameraSensor, model, physics, rng):
        super().__init__(spec, model, physics, spec.spec.rate, rng)
        self.cameras = [CameraRunner(camera, model, physics, rng) for camera in spec.cameras]

    def images(self, wanted) -> List[Optional[np.ndarray]]:
        """Each camera's pixels seen now, None for those ``wanted`` (one bool a camera) is
        False for."""
        return [camera.image() if want else None for camera, want in zip(self.cameras, wanted)]


class TriggerSchedule:
    """A triggered camera's schedule: due at one physics step for each trigger, looked at
    every step (``step_ns``); triggers come from any thread."""

    rate_hz = 0.0

    def __init__(self, step_ns: int):
        self.step_ns = step_ns
        self.next_ns = 0
        self._pending = 0
        self._lock = threading.Lock()

    def trigger(self) -> None:
        with self._lock:
            self._pending += 1

    def reset(self, now_ns: int) -> None:
        self.next_ns = now_ns

    def due(self, now_ns: int) -> bool:
        self.next_ns = now_ns + self.step_ns
        with self._lock:
            if self._pending == 0:
                return False
            self._pending -= 1
            return True


class ContactState(NamedTuple):
    """One pair's contact (gazebo_msgs/ContactState): the sensor's collision first; per point
    the (force N, torque N m) on the sensor's link in that link's frame (the torque about its
    origin), the position (m, world), the normal (world, from the other collider into the
    sensor's) and the depth (m)."""

    collision1: str
    collision2: str
    wrenches: List[Tuple[Vec, Vec]]
    positions: List[Vec]
    normals: List[Vec]
    depths: List[float]


class BumperRunner(RunningSensor):
    """gazebo_ros_bumper on a contact sensor: what its collisions touch at the last step,
    one ContactState per pair of collisions, as Gazebo's ContactSensor groups them."""

    kind = "bumper"
    names: Optional[ContactNames] = None       # the world's (WorldSensors sets it)

    def __init__(self, spec: BumperSensor, model, physics, rng):
        super().__init__(spec, model, physics, spec.rate, rng)
        self._where: List[tuple] = []
        self._built = None
        missing = [c for c in spec.collisions if collision_link(model, c) is None]
        self.warning = ("contact sensor %r on link %r: the link has no collision %s; no "
                        "contact of it is reported, as in Gazebo"
                        % (spec.name, spec.link, ", ".join(repr(c) for c in missing))
                        if missing else "")

    def where(self) -> List[tuple]:
        """(collision, its link, body, link index) of each collision the engine has."""
        built = self.model.body_ids()
        if built != self._built:
            found = ((c, collision_link(self.model, c)) for c in self.spec.collisions)
            self._where = [(c,) + f for c, f in found if f is not None and f[1] is not None]
            self._built = built
        return self._where

    def contacts(self) -> List[ContactState]:
        """The contacts of the sensor's collisions at the last physics step."""
        states: Dict[Tuple[str, str], ContactState] = {}
        poses = {scoped: pose for scoped, pose, _ in self.model.link_states()}
        names = self.names.current() if self.names is not None else {}
        for collision, link, body, index in self.where():
            origin, orientation = poses[link]
            for point in link_contacts(self.physics.client, body.uid, index):
                other = name_in(names, point.other_body, point.other_link)
                state = states.setdefault((collision, other),
                                          ContactState(collision, other, [], [], [], []))
                lever = np.subtract(point.position, origin)
                torque = np.cross(lever, point.force)
                state.wrenches.append((kinematics.to_body(orientation, point.force),
                                       kinematics.to_body(orientation, torque)))
                state.positions.append(point.position)
                state.normals.append(point.normal)
                state.depths.append(point.depth)
        return list(states.values())


class ImuReading(NamedTuple):
    orientation: Tuple[float, float, float, float]   # sensor in the world (x, y, z, w)
    angular_velocity: Vec                            # rad/s, sensor frame
    linear_acceleration: Vec                         # m/s^2, sensor frame, gravity's reaction in


class ImuSensorRunner(RunningSensor):
    """gazebo_ros_imu_sensor on an imu sensor: the sensor frame's orientation (turned by
    rpyOffset), the link's rates and its mean acceleration since the last reading with
    gravity's reaction, the sensor's <imu> noise, then the plugin's gaussianNoise on each
    field. The link's velocity is its centre of mass's (the sensor's lever arm left out)."""

    kind = "imu_sensor"

    def __init__(self, spec: ImuSensorPlugin, model, physics, rng):
        super().__init__(spec, model, physics, spec.rate, rng)
        self.accelerometer = Accelerometer()
        self.rate_noise = AxisNoises(spec.rate_noise, rng)
        self.accel_noise = AxisNoises(spec.accel_noise, rng)
        self.offset = kinematics.quat_from_rpy(*spec.rpy_offset)

    def restart(self) -> None:
        """The next reading's acceleration starts over (a reset moved the link by hand)."""
        self.accelerometer.reset()

    def reading(self, now_ns: int) -> ImuReading:
        """What the IMU reads at sim time ``now_ns``."""
        for scoped, link_pose, twist in self.model.link_states():
            if scoped == self.spec.link:
                break
        else:
            raise KeyError(self.spec.link)
        orientation = rf.compose(link_pose, self.in_link)[1]
        linear, angular = twist
        accel = self.accelerometer.acceleration(now_ns / 1e9, linear)
        rates, felt = imu_axes(orientation, angular, accel, gravity(self.physics.client))
        rates, felt = self.rate_noise.applied(rates), self.accel_noise.applied(felt)
        turned = np.array(rf.multiply(self.offset, orientation))
        sigma = self.spec.gaussian_noise
        if sigma > 0:
            turned, rates, felt = (v + self.rng.normal(0.0, sigma, len(v))
                                   for v in (turned, rates, felt))
        return ImuReading(tuple(map(float, turned)), tuple(map(float, rates)),
                          tuple(map(float, felt)))


def runner_for(spec) -> type:
    """The RunningSensor class of a WorldSensor."""
    if isinstance(spec, WorldCamera):
        if spec.cameras:
            return MultiCameraRunner
        if spec.trigger_topic:
            return TriggeredCameraRunner
        if spec.spec.depth:
            return DepthCameraRunner
    return next(r for kind, r in RUNNERS if isinstance(spec, kind))


RUNNERS: Tuple[Tuple[type, Callable], ...] = (
    (LaserSensor, LaserRunner), (RangeSensor, RangeRunner),
    (BlockLaserSensor, BlockLaserRunner), (CameraSensor, CameraRunner),
    (BumperSensor, BumperRunner), (ImuSensorPlugin, ImuSensorRunner))


class WorldSensors:
    """The running sensors of the world's models, in the models' order."""

    def __init__(self, physics: WorldPhysics, models, seed: int = 0, robots=None):
        """``models``: the world's ModelRegistry, followed at every output time; ``robots``:
        the SimRobots by model name (Simulation.robots, filled as robots come)."""
        self.physics = physics
        self.registry = models
        self.robots = robots if robots is not None else {}
        self.seed = seed
        self.sensors: List[RunningSensor] = []
        self.due_now: List[RunningSensor] = []     # those due at the last step that had any
        self.generation = 0                          # counts the changes of ``sensors``
        self.next_ns = math.inf
        self._models: List[object] = []
        self._made = 0                               # sensors made so far (their seeds)
        self.warnings: List[str] = []                # one line each, as sensors are made
        self.contact_names = ContactNames(models)    # what bumpers' contacts touch
        self.sync(0)

    def sync(self, now_ns: int) -> bool:
        """Follow the registry: the sensors of models added since, less those of models gone;
        True if that changed anything. New sensors are due at ``now_ns`` first."""
        models = self.registry.models()
        if len(models) == len(self._models) and all(map(operator.is_, models, self._models)):
            return False
        present = {id(m) for m in models}
        kept = [s for s in self.sensors if id(s.model) in present]
        known = {id(s.model) for s in self.sensors} | {id(m) for m in self._models}
        for model in models:
            if id(model) not in known:
                kept.extend(self._made_for(model, now_ns))
        changed = len(kept) != len(self.sensors) or any(map(operator.is_not, kept,
                                                            self.sensors))
        self._models = models
        if changed:
            self.sensors = kept
            self.generation += 1
            self.next_ns = min((s.schedule.next_ns for s in kept), default=math.inf)
        return changed

    def _made_for(self, model, now_ns: int) -> List[RunningSensor]:
        """The running sensors of ``model``'s links (an SdfModel's document's, a robot's
        URDF's)."""
        robot = self.robots.get(model.name)
        if robot is not None and getattr(model, "robot_body", None) is robot.body:
            specs = robot_sensor_specs(model.name, robot.namespace, robot.description,
                                       robot.options.camera)
        else:
            robot = None
            specs = getattr(getattr(model, "world", None), "sensors", ())
        made = []
        for spec in specs:
            if model_of(spec.link) != model.name:
                continue
            runner = runner_for(spec)
            sensor = runner(spec, model, self.physics,
                            np.random.default_rng([self.seed, self._made]))
            if robot is not None:
                sensor.namespace, sensor.ray_mask = robot.namespace, robot.body.ray_mask
            self._made += 1
            sensor.schedule.reset(now_ns)
            if isinstance(sensor, BumperRunner):
                sensor.names = self.contact_names
            if getattr(sensor, "warning", ""):
                self.warnings.append(sensor.warning)
            made.append(sensor)
        return made

    def due(self, now_ns: int) -> bool:
        """After a physics step: whether the node has world sensors to publish at ``now_ns``
        (``due_now``), or sensors to advertise or take back (``generation`` changed)."""
        changed = self.sync(now_ns)
        if now_ns < self.next_ns and not changed:
            return False
        self.due_now = [s for s in self.sensors if s.schedule.due(now_ns)]
        self.next_ns = min((s.schedule.next_ns for s in self.sensors), default=math.inf)
        return bool(self.due_now) or changed

    def reset(self, now_ns: int) -> None:
        """Every schedule starts over at ``now_ns`` (reset_world, reset_simulation)."""
        for sensor in self.sensors:
            sensor.schedule.reset(now_ns)
            if isinstance(sensor, ImuSensorRunner):
                sensor.restart()
        self.next_ns = now_ns if self.sensors else math.inf
