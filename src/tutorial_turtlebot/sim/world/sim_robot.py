"""One robot in the simulation, made from what its URDF's ``<gazebo>`` blocks declare.

A ``SimRobot`` is what Gazebo's plugins make of one spawned URDF: the diff drive (command ramp,
odometry, joint states), the laser, the IMU and the camera, each at its own rate, reading one
``RobotBody`` in the shared ``WorldPhysics``. Knows nothing of ROS. Frames are the URDF's link
names, unprefixed (the ROS side adds the namespace prefix). Units: m, s, rad.
"""
import math
from dataclasses import dataclass, replace
from typing import Dict, List, Optional, Tuple

import numpy as np

from .. import kinematics
from ..files import limits
from ..devices.camera import CameraIntrinsics
from ..engine.rendering import CameraRenderer, validate_spec
from ..devices.diff_drive import (SAFE_ANGULAR, SAFE_LINEAR, DiffDriveController,
                                  sanitize_command)
from ..devices.lidar import (LaserConfig, as_real_driver, laser_config, ranges_from_distances,
                             ray_directions)
from ..kinematics import Pose
from ..engine.physics import GRAVITY, WorldPhysics
from ..engine.robot_body import RobotBody
from ..files.robot_plugin_types import CameraSensor, LaserSensor, RobotPlugins
from .schedule import NS_PER_S, RateSchedule
from ..files.urdf_file import RobotDescription
from ..files.urdf_meshes import texture_warnings
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
    odom_source: Optional[str] = None    # "world" or "encoders"
    camera: bool = True                  # False: the declared camera is not simulated
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
        self.warnings: List[str] = list(plugins.warnings)
        self.drive_plugin = plugins.drive
        self.imu_plugin = plugins.imu
        self.laser_sensor: Optional[LaserSensor] = plugins.laser
        self.laser: Optional[LaserConfig] = self._laser_config(plugins.laser)
        self.camera_sensor: Optional[CameraSensor] = plugins.camera if options.camera else None
        self.camera_spec = self.camera_sensor.spec if self.camera_sensor else None
        self.camera_intrinsics: Optional[CameraIntrinsics] = None   # CameraInfo's numbers
        if self.camera_spec is not None:
            validate_spec(self.camera_spec)
            self.camera_intrinsics = CameraIntrinsics.from_spec(self.camera_spec)
        drive = self.drive_plugin
        self.odom_source = (options.odom_source or drive.odometry_source) if drive else "world"
        self.body = RobotBody(physics, description, spawn_pose,
                              (drive.left_joint, drive.right_joint) if drive else (),
                              drive.wheel_torque if drive else 0.0)
        self.warnings += texture_warnings(description)   # textures drawn as plain colours
        try:   # a robot that cannot be completed leaves no body behind
            self._set_up(physics, now_ns, seed)
        except BaseException:
            self.body.remove()
            raise

    def _set_up(self, physics: WorldPhysics, now_ns: int, seed: int) -> None:
        """Everything of the robot after its body: camera, drive, schedules, rays, state."""
        drive = self.drive_plugin
        self.camera = (CameraRenderer(physics.client, self.camera_spec,
                                      use_egl=physics.egl or physics.gui)
                       if self.camera_spec else None)
        step_rate = 1.0 / physics.time_step
        separation = drive.wheel_separation if drive else 1.0
        radius = drive.wheel_radius if drive else 1.0
        self.drive = DiffDriveController(separation, radius,
                                         drive.wheel_acceleration if drive else 0.0)
        self.encoders = WheelOdometry(separation, radius)
        self.control = RateSchedule(min(drive.update_rate or step_rate, step_rate)
                                    if drive else 1.0)
        self.schedules: Dict[str, RateSchedule] = {}
        if drive and drive.publish_tf:     # publishTf false: no odometry at all (Gazebo)
            self.schedules["odom"] = RateSchedule(self.control.rate_hz)
        if drive and drive.publish_wheel_joint_state:
            self.schedules["joint_states"] = RateSchedule(self.control.rate_hz)
        if self.laser:
            self.schedules["scan"] = RateSchedule(min(self.laser.rate or step_rate, step_rate))
            self._rays = ray_directions(self.laser)
            self._laser_pose = _sensor_pose(self.body, self.laser_sensor.link,
                                            self.laser_sensor.pose)
        if self.imu_plugin:
            self.schedules["imu"] = RateSchedule(
                min(self.imu_plugin.update_rate or step_rate, step_rate))
        if self.camera:
            self.schedules["camera"] = RateSchedule(min(self.camera_spec.rate, step_rate))
            self._camera_pose = _sensor_pose(self.body, self.camera_sensor.link,
                                             self.camera_sensor.pose)
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

    def command(self, linear: float, angular: float) -> List[str]:
        """A new cmd_vel. NaN/inf raise ValueError (the command is ignored); values beyond the
        limits are clamped and described in the returned list."""
        limits = self.options.limits or (SAFE_LINEAR, SAFE_ANGULAR)
        linear, angular, problems = sanitize_command(linear, angular, *limits)
        self.drive.set_command(linear, angular)
        return problems

    def before_step(self, now_ns: int) -> None:
        """The diff drive's control tick, when due: the ramp toward the command; stopped, the
        brake (RobotBody.brake: an idle robot stands still)."""
        if self.drive_plugin and now_ns >= self.control.next_ns and self.control.due(now_ns):
            left, right = self.drive.update(1.0 / self.control.rate_hz)
            if self.drive.stopped:
                self.body.brake()
            else:
                self.body.set_wheel_velocities(left, right)

    def next_tick_ns(self) -> float:
        """When before_step next has something to do (ns; inf for a robot with no drive)."""
        return self.control.next_ns if self.drive_plugin else math.inf

    def due(self, now_ns: int) -> List[str]:
        """The outputs due at ``now_ns`` (odom, joint_states, scan, imu, camera) after a step;
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
        return due

    # --- sensors ---------------------------------------------------------------------------------

    def odom(self) -> OdomState:
        """Odometry as ``odom_source`` says: ``world`` is the ground truth pose (starting at the
        spawn pose, as Gazebo); ``encoders`` is integrated from the wheels (starting at 0)."""
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
        """((left, right) wheel angles rad, (left, right) wheel velocities rad/s)."""
        return self.body.wheel_states()

    def reseed(self, seed: int) -> None:
        """Draw the sensors' noise (laser, IMU) anew from ``seed``: the same seed, the same
        noise from here on."""
        self._rng = np.random.default_rng(seed)

    def scan(self) -> np.ndarray:
        """The ranges of the laser as its LaserConfig publishes them (float32); the rays see
        the world and every other robot, never this one."""
        origin, rotation = self.body.pose_in_world(self._laser_pose)
        distances = self.body.physics.ray_distances(origin, self._rays @ rotation.T,
                                                    self.laser.range_max, self.body.ray_mask)
        return ranges_from_distances(self.laser, distances, self._rng)

    def imu(self) -> ImuState:
        """What the IMU reads now (orientation absolute in the world, yaw 0 facing +x)."""
        if self._imu_state_ns != self.time_ns:
            self._sample_imu()
        return self._imu_state

    def camera_pose(self) -> Tuple[np.ndarray, np.ndarray]:
        """World (position, 3x3 rotation) of what the camera renders from: its sensor's pose
        in its link, turned from the link's x forward to the optical frame's z forward."""
        position, rotation = self.body.pose_in_world(self._camera_pose)
        return position, rotation @ LINK_TO_OPTICAL

    def camera_image(self, depth: bool = False):
        """(rgb uint8 HxWx3, depth float32 HxW metres or None) seen by the camera now."""
        return self.camera.render(*self.camera_pose(), depth=depth)

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
