"""One robot in the simulation, made from what its URDF's ``<gazebo>`` blocks declare.

A ``SimRobot`` is what Gazebo's plugins make of one spawned URDF: the diff drive (command ramp,
odometry, joint states) or another drive (robot_drives: skid steer, planar move, tricycle,
force-based move), its lasers, the IMU and its cameras (any number of each, every one at its
own rate, pose and noise), reading one ``RobotBody`` in the shared ``WorldPhysics``. Knows
nothing of ROS. Frames are the URDF's link names, unprefixed (the ROS side adds the namespace
prefix). Units: m, s, rad.
"""
import math
from dataclasses import dataclass, replace
from typing import Dict, List, Optional, Tuple

import numpy as np

from .. import kinematics
from ..files import limits
from ..devices.camera import CameraIntrinsics
from ..devices.image_formats import CameraOutput
from ..engine.rendering import CameraRenderer, validate_spec
from ..devices.diff_drive import (SAFE_ANGULAR, SAFE_LINEAR, DiffDriveController,
                                  sanitize_command)
from ..devices.lidar import (LaserConfig, as_real_driver, laser_config, ranges_from_distances,
                             ray_directions)
from ..kinematics import Pose
from ..engine.physics import GRAVITY, WorldPhysics
from ..engine.robot_body import RobotBody
from ..files.plugins.robot_plugin_types import (CameraSensor, CameraSpec, DiffDrivePlugin,
                                                LaserSensor, RobotPlugins)
from .robot_drives import make_drive
from .schedule import NS_PER_S, RateSchedule
from ..files.urdf.urdf_file import RobotDescription
from ..files.urdf.urdf_meshes import texture_warnings
from ..devices.wheel_odometry import WheelOdometry
from ...errors import UserError
from ...ros_names import is_legal_namespace

ODOM_SOURCES = ("world", "encoders")
# s: low-pass time constant of the IMU's acceleration, like the MPU-9250's digital low-pass
# filter; without it the wheel and caster contacts' chatter reads as +-2 m/s^2 noise.
IMU_ACCEL_TIME_CONSTANT = 0.02
# A camera link looks along its +x (Gazebo); the image's optical frame looks along z with x
# right and y down. Columns: the optical axes in the link frame.
LINK_TO_OPTICAL = np.array([[0.0, 0.0, 1.0], [-1.0, 0.0, 0.0], [0.0, -1.0, 0.0]])


def output_name(kind: str, index: int) -> str:
    """The name SimRobot.due gives the output of its ``index``-th sensor of ``kind`` ("scan",
    "camera"): the first's is ``kind``, the others' ``kind:index`` ("scan:1")."""
    return kind if index == 0 else "%s:%d" % (kind, index)


def normalize_namespace(namespace: str) -> str:
    """``"tb3_0"``, ``"/tb3_0/"`` -> ``"/tb3_0/"``; ``""`` and ``"/"`` -> ``""`` (the root);
    UserError for a name ROS does not allow (graph resource names: letters, digits, _, /) or
    one longer than limits.MAX_NAME."""
    problem = limits.name_problem("robot_namespace", namespace)
    if problem:
        raise UserError(problem)
    if not is_legal_namespace(namespace):
        raise UserError("robot_namespace %r is not a legal ROS namespace (a letter, then "
                        "letters, digits and _, parts joined by /)" % (namespace,))
    parts = namespace.strip("/")
    return "/%s/" % parts if parts else ""


@dataclass
class RobotOptions:
    """What the launch args override of the URDF's declarations; None = as declared."""

    lidar_model: Optional[str] = None    # "gazebo" = as declared; "lds01" = the real driver's
    lidar_samples: Optional[int] = None  # rays per scan over the declared sweep
    # (both of the first laser only: the TurtleBot3's LDS; the others' are as declared)
    odom_source: Optional[str] = None    # "world" or "encoders"
    camera: bool = True                  # False: none of the declared cameras is simulated
    # (max linear m/s, max angular rad/s) commands are held to, as the real firmware does;
    # None: only SAFE_LINEAR / SAFE_ANGULAR (Gazebo clamps nothing)
    limits: Optional[Tuple[float, float]] = None

    def validate(self) -> None:
        """UserError (one line) for a value that cannot be simulated."""
        if self.lidar_model is not None:
            laser_config(self.lidar_model)   # UserError naming the valid ones
        if self.odom_source is not None and self.odom_source not in ODOM_SOURCES:
            raise UserError("unknown odom_source %r: valid are %s"
                            % (self.odom_source, ", ".join(ODOM_SOURCES)))
        if self.lidar_samples is not None and not (
                isinstance(self.lidar_samples, int)
                and 2 <= self.lidar_samples <= limits.MAX_LASER_SAMPLES):
            raise UserError("lidar_samples must be an integer in 2..%d, got %r"
                            % (limits.MAX_LASER_SAMPLES, self.lidar_samples))


def with_samples(laser: LaserConfig, samples: int) -> LaserConfig:
    """``laser`` with ``samples`` rays over the same sweep (Gazebo's <samples>)."""
    if samples == laser.samples:
        return laser
    span = laser.angle_increment * (laser.samples - 1)
    return replace(laser, samples=samples, angle_max=laser.angle_min + span,
                   angle_increment=span / (samples - 1))


@dataclass
class OdomState:
    """base_footprint in odom: position (m), orientation (x, y, z, w), body-frame twist."""

    position: Tuple[float, float, float]
    orientation: Tuple[float, float, float, float]
    linear: Tuple[float, float, float]    # m/s in base_footprint
    angular: Tuple[float, float, float]   # rad/s in base_footprint


@dataclass
class ImuState:
    """The IMU link: orientation in the world (x, y, z, w), angular velocity (rad/s) and linear
    acceleration including gravity (m/s^2), both in the IMU link."""

    orientation: Tuple[float, float, float, float]
    angular_velocity: Tuple[float, float, float]
    linear_acceleration: Tuple[float, float, float]


@dataclass
class RobotLaser:
    """One of a robot's lasers: its sensor, the LaserConfig it publishes, its rays (unit
    vectors in the sensor frame), its pose in the root link (4x4), its noise generator (None
    for the first laser, whose noise draws on the robot's own, shared with the IMU) and the
    name of its output (output_name)."""

    sensor: LaserSensor
    config: LaserConfig
    rays: np.ndarray
    pose: np.ndarray
    rng: Optional[np.random.Generator]
    output: str


@dataclass
class RobotCamera:
    """One of a robot's cameras: its sensor, what it renders (spec), CameraInfo's numbers, its
    renderer, its pose in the root link (4x4, link axes), the name of its output and what it
    publishes of a drawn image (its lens and <format>, as a world model's camera)."""

    sensor: CameraSensor
    spec: CameraSpec
    intrinsics: CameraIntrinsics
    renderer: CameraRenderer
    pose: np.ndarray
    output: str
    image: Optional[CameraOutput] = None     # None: the drawn rgb8 image as it is


def _intrinsics(sensor: CameraSensor) -> CameraIntrinsics:
    """CameraInfo's numbers of a robot's camera: its spec's, D the plugin's."""
    intrinsics = CameraIntrinsics.from_spec(sensor.spec)
    if not any(sensor.info_distortion):
        return intrinsics
    return replace(intrinsics, distortion=tuple(sensor.info_distortion))


def _sensor_pose(body: RobotBody, link: str, pose6) -> np.ndarray:
    """4x4 pose in the root link of a sensor at ``pose6`` (x y z roll pitch yaw) in ``link``."""
    local = body.frame_in_footprint(link)
    if not any(pose6):
        return local
    return local @ kinematics.transform_from_xyz_rpy(pose6[:3], pose6[3:])


class SimRobot:
    """One robot: its body, its plugins' state, and when each of its outputs is due."""

    def __init__(self, physics: WorldPhysics, name: str, namespace: str,
                 description: RobotDescription, spawn_pose: Pose, options: RobotOptions,
                 now_ns: int, seed: int = 0):
        """``namespace`` as normalize_namespace gives it; ``spawn_pose`` of the root link."""
        options.validate()
        self.name = name
        self.namespace = namespace
        self.description = description
        self.options = options
        plugins: RobotPlugins = description.plugins
        self.warnings: List[str] = list(description.warnings) + list(plugins.warnings)
        self.drive_plugin = plugins.drive
        self.imu_plugin = plugins.imu
        # every laser and camera is in ``lasers`` and ``cameras`` (made in _set_up); the
        # first of each is also laser_sensor, laser, camera_sensor, camera_spec, camera, ...
        self.laser_sensor: Optional[LaserSensor] = plugins.laser
        self.laser: Optional[LaserConfig] = self._laser_config(plugins.laser)
        self.camera_sensors: Tuple[CameraSensor, ...] = plugins.cameras if options.camera else ()
        self.camera_sensor: Optional[CameraSensor] = (self.camera_sensors[0]
                                                      if self.camera_sensors else None)
        self.camera_spec = self.camera_sensor.spec if self.camera_sensor else None
        self.camera_intrinsics: Optional[CameraIntrinsics] = None   # CameraInfo's numbers
        for sensor in self.camera_sensors:
            validate_spec(sensor.spec)
        if self.camera_spec is not None:
            self.camera_intrinsics = _intrinsics(self.camera_sensor)
        # the diff drive is run here; another drive (robot_drives) is ``motion``
        self.motion = make_drive(plugins.drive)
        drive = self.diff_plugin = (plugins.drive if isinstance(plugins.drive, DiffDrivePlugin)
                                    else None)
        self.odom_source = (options.odom_source or drive.odometry_source) if drive else "world"
        self.body = RobotBody(physics, description, spawn_pose,
                              *(self.motion.wheels if self.motion else (
                                  (drive.left_joint, drive.right_joint) if drive else (),
                                  drive.wheel_torque if drive else 0.0)))
        self.warnings += texture_warnings(description)   # textures drawn as plain colours
        self.warnings += self.body.notes   # what Gazebo's URDF conversion left out
        try:   # a robot that cannot be completed leaves no body behind
            self._set_up(physics, now_ns, seed)
        except BaseException:
            self.body.remove()
            raise

    def _set_up(self, physics: WorldPhysics, now_ns: int, seed: int) -> None:
        """Everything of the robot after its body: cameras, drive, schedules, rays, state."""
        drive = self.diff_plugin
        self.camera = (CameraRenderer(physics.client, self.camera_spec,
                                      use_egl=physics.egl or physics.gui)
                       if self.camera_spec else None)
        self.cameras: List[RobotCamera] = []
        for index, sensor in enumerate(self.camera_sensors):
            renderer = self.camera if index == 0 else CameraRenderer(
                physics.client, sensor.spec, use_egl=physics.egl or physics.gui)
            intrinsics = self.camera_intrinsics if index == 0 else _intrinsics(sensor)
            image = CameraOutput(sensor.image_format, sensor.lens, sensor.spec.width,
                                 sensor.spec.height)
            self.cameras.append(RobotCamera(sensor, sensor.spec, intrinsics, renderer,
                                            _sensor_pose(self.body, sensor.link, sensor.pose),
                                            output_name("camera", index),
                                            None if image.plain else image))
        step_rate = 1.0 / physics.time_step
        separation = drive.wheel_separation if drive else 1.0
        radius = drive.wheel_radius if drive else 1.0
        self.drive = DiffDriveController(separation, radius,
                                         drive.wheel_acceleration if drive else 0.0)
        self.encoders = WheelOdometry(separation, radius)
        self.control = RateSchedule(min(drive.update_rate or step_rate, step_rate)
                                    if drive else 1.0)
        self.schedules: Dict[str, RateSchedule] = {}
        if self.motion:
            self.control = RateSchedule(self.motion.control_rate(step_rate))
            if self.motion.odom_rate(step_rate) > 0:
                self.schedules["odom"] = RateSchedule(self.motion.odom_rate(step_rate))
            if self.motion.joint_names:     # a tricycle's publishWheelJointState
                self.schedules["joint_states"] = RateSchedule(self.control.rate_hz)
        if drive and drive.publish_tf:     # publishTf false: no odometry at all (Gazebo)
            self.schedules["odom"] = RateSchedule(self.control.rate_hz)
        if drive and drive.publish_wheel_joint_state:
            self.schedules["joint_states"] = RateSchedule(self.control.rate_hz)
        self.lasers: List[RobotLaser] = []
        if self.laser:
            self.schedules["scan"] = RateSchedule(min(self.laser.rate or step_rate, step_rate))
            self._rays = ray_directions(self.laser)
            self._laser_pose = _sensor_pose(self.body, self.laser_sensor.link,
                                            self.laser_sensor.pose)
            self.lasers.append(RobotLaser(self.laser_sensor, self.laser, self._rays,
                                          self._laser_pose, None, "scan"))
        for index, sensor in enumerate(self.description.plugins.lasers[1:], 1):
            laser = RobotLaser(sensor, sensor.laser, ray_directions(sensor.laser),
                               _sensor_pose(self.body, sensor.link, sensor.pose),
                               np.random.default_rng([seed, index]), output_name("scan", index))
            self.schedules[laser.output] = RateSchedule(min(laser.config.rate or step_rate,
                                                            step_rate))
            self.lasers.append(laser)
        if self.imu_plugin:
            self.schedules["imu"] = RateSchedule(
                min(self.imu_plugin.update_rate or step_rate, step_rate))
        if self.camera:
            self._camera_pose = self.cameras[0].pose
        for camera in self.cameras:
            self.schedules[camera.output] = RateSchedule(min(camera.spec.rate, step_rate))
        self._rng = np.random.default_rng(seed)
        self.reset_state(now_ns)

    def _laser_config(self, sensor: Optional[LaserSensor]) -> Optional[LaserConfig]:
        if sensor is None:
            return None
        laser = sensor.laser
        if self.options.lidar_samples is not None:
            laser = with_samples(laser, self.options.lidar_samples)
        if self.options.lidar_model == "lds01":
            laser = as_real_driver(laser)
        return laser

    def reset_state(self, now_ns: int) -> None:
        """Controller, encoders, IMU filter and every schedule start over at ``now_ns``."""
        self.time_ns = now_ns
        self.drive.reset()
        if self.motion:
            self.motion.reset()
        self.encoders.reset()
        self._last_control_ns = None
        self._imu_velocity = ((0.0, 0.0, 0.0), now_ns)
        self._imu_angular = (None, None)   # (chassis rad/s in the world, ns) at the last tick
        self._imu_accel = (0.0, 0.0, 0.0)
        self._imu_state: Optional[ImuState] = None
        self._imu_state_ns: Optional[int] = None
        for schedule in list(self.schedules.values()) + [self.control]:
            schedule.reset(now_ns)
        self.next_output_ns = now_ns

    # --- stepping ----------------------------------------------------------------------------

    def command(self, linear: float, angular: float, lateral: float = 0.0) -> List[str]:
        """A new cmd_vel (linear.x m/s, angular.z rad/s; linear.y m/s, which only a planar
        move reads). NaN/inf raise ValueError (the command is ignored); values beyond the
        limits are clamped and described in the returned list."""
        limits = self.options.limits or (SAFE_LINEAR, SAFE_ANGULAR)
        linear, angular, problems = sanitize_command(linear, angular, *limits)
        if self.motion:
            lateral, _, more = sanitize_command(lateral, 0.0, *limits)
            problems += [p.replace("linear.x", "linear.y") for p in more]
            self.motion.set_command(linear, lateral, angular, self.time_ns / NS_PER_S)
            return problems
        self.drive.set_command(linear, angular)
        return problems

    def before_step(self, now_ns: int) -> None:
        """The diff drive's control tick, when due: the ramp toward the command; stopped, the
        brake (RobotBody.brake: an idle robot stands still)."""
        if self.drive_plugin and now_ns >= self.control.next_ns and self.control.due(now_ns):
            if self.motion:
                self.motion.tick(self.body, now_ns / NS_PER_S, 1.0 / self.control.rate_hz)
                return
            left, right = self.drive.update(1.0 / self.control.rate_hz)
            if self.drive.stopped:
                self.body.brake()
            else:
                self.body.set_wheel_velocities(left, right)

    def next_tick_ns(self) -> float:
        """When before_step next has something to do (ns; inf for a robot with no drive)."""
        return self.control.next_ns if self.drive_plugin else math.inf

    def due(self, now_ns: int) -> List[str]:
        """The outputs due at ``now_ns`` (odom, joint_states, scan, imu, camera; a further
        laser's or camera's named by output_name: "scan:1") after a step;
        updates ``next_output_ns``. Samples what must be sampled at each tick."""
        self.time_ns = now_ns
        if now_ns < self.next_output_ns:
            return []
        due = [name for name, s in self.schedules.items() if s.due(now_ns)]
        self.next_output_ns = min((s.next_ns for s in self.schedules.values()),
                                  default=math.inf)
        if "imu" in due:
            self._filter_imu()
        if self.odom_source == "encoders" and ("odom" in due or "joint_states" in due):
            self._update_encoders()
        if self.motion and "odom" in due:
            self.motion.odom_tick(self.body, now_ns / NS_PER_S)
        return due

    # --- sensors ---------------------------------------------------------------------------------

    def odom(self) -> OdomState:
        """Odometry as ``odom_source`` says: ``world`` is the ground truth pose (starting at the
        spawn pose, as Gazebo); ``encoders`` is integrated from the wheels (starting at 0).
        Another drive's (``motion``) is as its plugin reports it."""
        if self.motion:
            return OdomState(*self.motion.odom(self.body))
        if self.odom_source == "encoders":
            e = self.encoders
            return OdomState((e.x, e.y, 0.0), kinematics.quat_from_yaw(e.yaw),
                             (e.linear, 0.0, 0.0), (0.0, 0.0, e.angular))
        pos, orn = self.body.footprint_pose()
        lin, ang = self.body.velocity()
        lin_body = kinematics.to_body(orn, lin)
        return OdomState(pos, orn, (lin_body[0], lin_body[1], 0.0), (0.0, 0.0, ang[2]))

    def ground_truth(self) -> Pose:
        """World pose of the root link, whatever odom_source."""
        return self.body.footprint_pose()

    def joint_states(self):
        """((left, right) wheel angles rad, (left, right) wheel velocities rad/s); another
        drive's: of its ``joint_names``."""
        if self.motion:
            states = [self.body.joint_state(name) for name in self.motion.joint_names]
            return tuple(s[0] for s in states), tuple(s[1] for s in states)
        return self.body.wheel_states()

    def reseed(self, seed: int) -> None:
        """Draw the sensors' noise (lasers, IMU) anew from ``seed``: the same seed, the same
        noise from here on."""
        self._rng = np.random.default_rng(seed)
        for index, laser in enumerate(self.lasers[1:], 1):
            laser.rng = np.random.default_rng([seed, index])

    def scan(self, index: int = 0) -> np.ndarray:
        """The ranges of laser ``index`` (of ``lasers``) as its LaserConfig publishes them
        (float32); the rays see the world and every other robot, never this one."""
        if index == 0:
            config, pose, rays, rng = self.laser, self._laser_pose, self._rays, self._rng
        else:
            laser = self.lasers[index]
            config, pose, rays, rng = laser.config, laser.pose, laser.rays, laser.rng
        origin, rotation = self.body.pose_in_world(pose)
        distances = self.body.physics.ray_distances(origin, rays @ rotation.T,
                                                    config.range_max, self.body.ray_mask)
        return ranges_from_distances(config, distances, rng)

    def imu(self) -> ImuState:
        """What the IMU reads now (orientation absolute in the world, yaw 0 facing +x)."""
        if self._imu_state_ns != self.time_ns:
            self._sample_imu()
        return self._imu_state

    def camera_pose(self, index: int = 0) -> Tuple[np.ndarray, np.ndarray]:
        """World (position, 3x3 rotation) of what camera ``index`` (of ``cameras``) renders
        from: its sensor's pose in its link, turned from the link's x forward to the optical
        frame's z forward."""
        pose = self._camera_pose if index == 0 else self.cameras[index].pose
        position, rotation = self.body.pose_in_world(pose)
        return position, rotation @ LINK_TO_OPTICAL

    def camera_image(self, depth: bool = False, index: int = 0):
        """(the image's pixels, depth float32 HxW metres or None) seen by camera ``index`` now:
        rgb uint8 HxWx3, or distorted by its lens and in its <format> (RobotCamera.image,
        image_formats.converted); the depth is undistorted."""
        renderer = self.camera if index == 0 else self.cameras[index].renderer
        rgb, metres = renderer.render(*self.camera_pose(index), depth=depth)
        image = self.cameras[index].image
        if image is None:
            return rgb, metres
        return image.pixels(rgb), metres

    def _filter_imu(self) -> None:
        """At an IMU tick: low-pass the acceleration (world frame) from the change of the
        chassis' velocity since the last tick. The reading itself is worked out when asked for
        (imu()), unless it has noise: its draws are made at every tick, asked for or not, so
        the random sequence (shared with the laser) does not depend on who subscribes."""
        lin, ang = self.body.velocity()
        last_lin, last_ns = self._imu_velocity
        if self.time_ns > last_ns:
            dt = (self.time_ns - last_ns) / NS_PER_S
            gain = dt / (IMU_ACCEL_TIME_CONSTANT + dt)
            self._imu_accel = tuple(a + ((v - v0) / dt - a) * gain
                                    for a, v, v0 in zip(self._imu_accel, lin, last_lin))
        self._imu_velocity = (lin, self.time_ns)
        self._imu_angular = (ang, self.time_ns)   # a reading at this tick needs no second read
        self._imu_state_ns = None
        if self.imu_plugin and self.imu_plugin.gaussian_noise > 0:
            self._sample_imu()

    def _sample_imu(self) -> None:
        """Keep what the IMU reads now, from the chassis and the filtered acceleration. The
        IMU link is rigidly attached to the chassis without rotation, as on every TurtleBot3."""
        _, orn = self.body.footprint_pose()
        ang, at_ns = self._imu_angular
        if at_ns != self.time_ns:
            _, ang = self.body.velocity()
        ax, ay, az = self._imu_accel
        rates = kinematics.to_body(orn, ang)
        accel = kinematics.to_body(orn, (ax, ay, az + GRAVITY))
        sigma = self.imu_plugin.gaussian_noise if self.imu_plugin else 0.0
        if sigma > 0:   # gazebo_ros_imu's gaussianNoise on the rates and the acceleration
            rates = tuple(rates + self._rng.normal(0.0, sigma, 3))
            accel = tuple(accel + self._rng.normal(0.0, sigma, 3))
        self._imu_state = ImuState(orn, rates, accel)
        self._imu_state_ns = self.time_ns

    def _update_encoders(self) -> None:
        (left, right), _ = self.body.wheel_states()
        dt = (0.0 if self._last_control_ns is None
              else (self.time_ns - self._last_control_ns) / NS_PER_S)
        self.encoders.update(left, right, dt)
        self._last_control_ns = self.time_ns
