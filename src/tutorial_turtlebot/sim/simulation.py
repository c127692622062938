"""The simulated TurtleBot3 as Gazebo and its ROS plugins present it, without ROS.

``Simulation`` owns the physics, the diff-drive controller, the sim clock (integer ns) and the
sensor models, and answers "what would the sensors read now". The ROS node only converts.
Frames: odometry is ``base_footprint`` in ``odom``; the scan is in ``base_scan``; the IMU in
``imu_link``. Units: m, s, rad.
"""
import math
from dataclasses import dataclass, replace
from typing import List, Optional, Tuple

import numpy as np

from . import kinematics
from .camera import CameraRenderer, validate_spec
from .diff_drive import SAFE_ANGULAR, SAFE_LINEAR, DiffDriveController, sanitize_command
from ..errors import UserError
from .lidar import LaserConfig, laser_config, ranges_from_distances, ray_directions
from .physics import GRAVITY, TurtleBotPhysics
from .physics_properties import OdeConfig, PhysicsProperties, bullet_parameters
from .world_models import ModelRegistry, model_of_urdf_body, models_of_world, robot_model_name
from .robot_models import CameraSpec, get_model
from .spawn_check import check_spawn, footprint_radius
from .schedule import NS_PER_S, RateSchedule, seconds_to_ns
from .urdf_file import read_urdf, urdf_path
from .wheel_odometry import WheelOdometry
from .bullet import pybullet
from .world_sdf import load_world, resolve_world

ODOM_SOURCES = ("world", "encoders")
CAMERA_FRAME = "camera_rgb_optical_frame"  # every camera message's frame, as Gazebo's plugins
CONTROL_RATE = 30.0  # Hz: the Gazebo diff-drive plugin's updateRate (ramp, odom, joint states)
# s: low-pass time constant of the IMU's acceleration, like the MPU-9250's digital low-pass
# filter; without it the wheel and caster contacts' chatter reads as +-2 m/s^2 noise.
IMU_ACCEL_TIME_CONSTANT = 0.02


@dataclass
class SimConfig:
    """Everything that picks what is simulated. Rates in Hz of sim time."""

    model: str = "burger"
    world: str = "turtlebot3_world"      # a catalogue name or a path to an SDF file
    x: Optional[float] = None            # spawn of base_footprint; None = the world's spawn
    y: Optional[float] = None
    z: float = 0.0
    yaw: Optional[float] = None
    camera: Optional[bool] = None        # None: the model's own camera, if it has one;
                                         # True on a burger: the AutoRace camera
    lidar_model: str = "gazebo"
    odom_source: str = "world"
    clamp_cmd_vel: bool = True           # hold commands to the model's limits, as the firmware
    gui: bool = False                    # pybullet's own window (needs a display)
    time_step: float = 0.0025            # s of sim time per physics step
    solver_iterations: int = 20
    odom_rate: float = CONTROL_RATE
    joint_states_rate: float = CONTROL_RATE
    scan_rate: float = 5.0
    imu_rate: float = 200.0
    clock_rate: float = 100.0
    seed: int = 0                        # laser noise
    robot_name: Optional[str] = None     # the robot's model name; None = turtlebot3_gazebo's
    lidar_samples: int = 360             # rays per scan (the DQN agent of the stages wants 24)

    def validate(self) -> None:
        """Raise UserError (one line) for any value that cannot be simulated."""
        if self.odom_source not in ODOM_SOURCES:
            raise UserError("unknown odom_source %r: valid are %s"
                            % (self.odom_source, ", ".join(ODOM_SOURCES)))
        if not 0.0001 <= self.time_step <= 0.01:
            raise UserError("max_step_size %r s is outside 0.0001..0.01" % self.time_step)
        for name in ("odom_rate", "joint_states_rate", "scan_rate", "imu_rate", "clock_rate"):
            rate = getattr(self, name)
            if not (isinstance(rate, (int, float)) and 0 < rate <= 1.0 / self.time_step):
                raise UserError("%s %r Hz must be > 0 and at most the physics rate %g Hz"
                                % (name, rate, 1.0 / self.time_step))
        for name in ("x", "y", "z", "yaw"):
            value = getattr(self, name)
            if value is not None and not (isinstance(value, (int, float))
                                          and math.isfinite(value)):
                raise UserError("spawn %s must be a finite number, got %r" % (name, value))
        if not (isinstance(self.lidar_samples, int) and 2 <= self.lidar_samples <= 3600):
            raise UserError("lidar_samples must be an integer in 2..3600, got %r"
                            % (self.lidar_samples,))
        if self.robot_name is not None and (not self.robot_name.strip() or "::" in self.robot_name):
            raise UserError("robot_name %r must be non-empty and without '::'" % self.robot_name)
        if not (isinstance(self.solver_iterations, int) and self.solver_iterations > 0):
            raise UserError("solver_iterations must be a positive integer, got %r"
                            % (self.solver_iterations,))


def _with_samples(laser: LaserConfig, samples: int) -> LaserConfig:
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
    """imu_link: orientation in the world (x, y, z, w), angular velocity (rad/s) and linear
    acceleration including gravity (m/s^2), both in imu_link."""

    orientation: Tuple[float, float, float, float]
    angular_velocity: Tuple[float, float, float]
    linear_acceleration: Tuple[float, float, float]


class Simulation:
    """A TurtleBot3 in a world, stepped one physics step at a time."""

    def __init__(self, config: SimConfig):
        config.validate()
        self.config = config
        self.spec = get_model(config.model)
        self.laser: LaserConfig = _with_samples(laser_config(config.lidar_model),
                                                config.lidar_samples)
        world_path, world_spawn = resolve_world(config.world)
        self.world = load_world(world_path)
        spawn = self._spawn(world_spawn)
        self.description = read_urdf(urdf_path(config.model, bool(config.camera)))
        check_spawn(self.world, spawn[0], spawn[1], footprint_radius(self.description),
                    z=spawn[2])
        self.camera_spec = self._camera_spec()
        self.physics = TurtleBotPhysics(self.spec, self.description, self.world, spawn,
                                        config.time_step, config.solver_iterations,
                                        config.gui, egl=self.camera_spec is not None)
        self.camera = (CameraRenderer(self.physics.client, self.camera_spec,
                                      use_egl=self.physics.egl or config.gui)
                       if self.camera_spec else None)
        self.spawn = spawn
        self.models = ModelRegistry()
        for model in models_of_world(self.world, self.physics.world_bodies, self.physics.client):
            self.models.add(model)
        self.robot_name = config.robot_name or robot_model_name(
            config.world if not config.world.endswith((".world", ".sdf")) else "", config.model)
        self.models.add(model_of_urdf_body(self.robot_name, self.physics.robot,
                                           self.physics.client, "robot",
                                           reset_hook=self.physics.reset_robot))
        self.physics_properties = PhysicsProperties.for_factor(
            config.time_step, 1.0, OdeConfig(sor_pgs_iters=config.solver_iterations),
            (0.0, 0.0, -GRAVITY))
        self.step_ns = seconds_to_ns(config.time_step)
        self.drive = DiffDriveController(self.spec.wheel_separation, self.spec.wheel_radius,
                                         self.spec.wheel_acceleration)
        self.encoders = WheelOdometry(self.spec.wheel_separation, self.spec.wheel_radius)
        self.control = RateSchedule(CONTROL_RATE)
        self.schedules = {
            "clock": RateSchedule(config.clock_rate),
            "odom": RateSchedule(config.odom_rate),
            "joint_states": RateSchedule(config.joint_states_rate),
            "scan": RateSchedule(config.scan_rate),
            "imu": RateSchedule(config.imu_rate),
        }
        if self.camera:
            self.schedules["camera"] = RateSchedule(self.camera_spec.rate)
        self._rays = ray_directions(self.laser)
        self._rng = np.random.default_rng(config.seed)
        self.time_ns = 0
        self._reset_state()

    def _camera_spec(self) -> Optional[CameraSpec]:
        """The camera simulated: the model's own (waffle, waffle_pi) or, on a burger, the
        AutoRace camera; None with camera off. UserError if it cannot be rendered."""
        if self.config.camera is None:
            spec = self.spec.camera
        elif self.config.camera:
            spec = self.spec.camera or self.spec.optional_camera
        else:
            return None
        if spec is not None:
            validate_spec(spec)
        return spec

    def _spawn(self, world_spawn) -> Tuple[float, float, float, float]:
        default = world_spawn if world_spawn else (0.0, 0.0, 0.0)
        x, y, yaw = (default[i] if value is None else value
                     for i, value in enumerate((self.config.x, self.config.y, self.config.yaw)))
        return (x, y, self.config.z, yaw)

    def _reset_state(self) -> None:
        self.drive.reset()
        self.encoders.reset()
        self._last_control_ns = None
        self._imu_velocity = ((0.0, 0.0, 0.0), self.time_ns)
        self._imu_accel = (0.0, 0.0, 0.0)
        self._imu_state: Optional[ImuState] = None
        self._imu_state_ns: Optional[int] = None  # sim time of _imu_state
        for schedule in list(self.schedules.values()) + [self.control]:
            schedule.reset(self.time_ns)
        self._next_output_ns = self.time_ns

    # --- time and control --------------------------------------------------------------------

    @property
    def time(self) -> float:
        """Sim time in seconds."""
        return self.time_ns / NS_PER_S

    def command(self, linear: float, angular: float) -> List[str]:
        """A new cmd_vel. NaN/inf raise ValueError (the command is ignored); values beyond the
        limits are clamped and described in the returned list."""
        if self.config.clamp_cmd_vel:
            limits = (self.spec.max_linear, self.spec.max_angular)
        else:
            limits = (SAFE_LINEAR, SAFE_ANGULAR)
        linear, angular, problems = sanitize_command(linear, angular, *limits)
        self.drive.set_command(linear, angular)
        return problems

    def step(self) -> List[str]:
        """One physics step; returns the names of the outputs due at the new time (clock, odom,
        joint_states, scan, imu, camera), in that order."""
        if self.time_ns >= self.control.next_ns and self.control.due(self.time_ns):
            left, right = self.drive.update(1.0 / CONTROL_RATE)
            self.physics.set_wheel_velocities(left, right)
        self.physics.step()
        self.time_ns += self.step_ns
        if self.time_ns < self._next_output_ns:
            return []
        due = [name for name, s in self.schedules.items() if s.due(self.time_ns)]
        self._next_output_ns = min(s.next_ns for s in self.schedules.values())
        if "imu" in due:
            self._sample_imu()
        if self.config.odom_source == "encoders" and ("odom" in due or "joint_states" in due):
            self._update_encoders()
        return due

    def reset_world(self) -> None:
        """Every model (the robot, the world's movable models, spawned ones) back to its spawn
        pose at rest; time runs on (Gazebo's reset_world)."""
        self.models.reset()
        self._reset_state()

    def add_schedule(self, name: str, rate: float) -> None:
        """Report ``name`` from step() at ``rate`` Hz of sim time from now on."""
        self.schedules[name] = RateSchedule(rate)
        self.schedules[name].reset(self.time_ns)
        self._next_output_ns = self.time_ns

    def set_physics_properties(self, props: PhysicsProperties) -> None:
        """Apply a validated PhysicsProperties: the step, gravity and Bullet's counterparts of
        the ODE fields; the real-time factor is the caller's pacer's."""
        cid = self.physics.client
        pybullet.setTimeStep(props.time_step, physicsClientId=cid)
        pybullet.setGravity(*props.gravity, physicsClientId=cid)
        pybullet.setPhysicsEngineParameter(physicsClientId=cid, **bullet_parameters(props.ode))
        self.physics.time_step = props.time_step
        self.config.time_step = props.time_step
        self.step_ns = seconds_to_ns(props.time_step)
        self.physics_properties = props

    def reset_simulation(self) -> None:
        """Robot back to spawn and sim time back to 0 (Gazebo's reset_simulation)."""
        self.time_ns = 0
        self.reset_world()

    # --- sensors ---------------------------------------------------------------------------------

    def odom(self) -> OdomState:
        """Odometry as ``odom_source`` says: ``world`` is the ground truth pose (starting at the
        spawn pose, as Gazebo); ``encoders`` is integrated from the wheels (starting at 0)."""
        if self.config.odom_source == "encoders":
            e = self.encoders
            return OdomState((e.x, e.y, 0.0), kinematics.quat_from_yaw(e.yaw),
                             (e.linear, 0.0, 0.0), (0.0, 0.0, e.angular))
        pos, orn = self.physics.footprint_pose()
        lin, ang = self.physics.velocity()
        lin_body = kinematics.to_body(orn, lin)
        return OdomState(pos, orn, (lin_body[0], lin_body[1], 0.0), (0.0, 0.0, ang[2]))

    def ground_truth(self):
        """World pose of base_footprint ((x, y, z), (qx, qy, qz, qw)), whatever odom_source."""
        return self.physics.footprint_pose()

    def joint_states(self):
        """((left, right) wheel angles rad, (left, right) wheel velocities rad/s)."""
        return self.physics.wheel_states()

    def scan(self) -> np.ndarray:
        """The 360 ranges of the LDS-01 as the chosen lidar_model publishes them (float32)."""
        origin, rot = self.physics.frame_pose("base_scan")
        distances = self.physics.ray_distances(origin, self._rays @ rot.T, self.laser.range_max)
        return ranges_from_distances(self.laser, distances, self._rng)

    def imu(self) -> ImuState:
        """What the IMU reads now (orientation absolute in the world, yaw 0 facing +x)."""
        if self._imu_state_ns != self.time_ns:
            self._sample_imu(filter_acceleration=False)
        return self._imu_state

    def camera_image(self, depth: bool = False):
        """(rgb uint8 HxWx3, depth float32 HxW metres or None) seen from
        camera_rgb_optical_frame now. Only with a camera (``self.camera``)."""
        position, rotation = self.physics.frame_pose(CAMERA_FRAME)
        return self.camera.render(position, rotation, depth=depth)

    def _sample_imu(self, filter_acceleration: bool = True) -> None:
        """Read the chassis once at an IMU tick: low-pass the acceleration (from the change of
        velocity since the last tick) and keep what the IMU reads now."""
        _, orn = self.physics.footprint_pose()
        lin, ang = self.physics.velocity()
        if filter_acceleration:
            last_lin, last_ns = self._imu_velocity
            if self.time_ns > last_ns:
                dt = (self.time_ns - last_ns) / NS_PER_S
                gain = dt / (IMU_ACCEL_TIME_CONSTANT + dt)
                self._imu_accel = tuple(a + ((v - v0) / dt - a) * gain
                                        for a, v, v0 in zip(self._imu_accel, lin, last_lin))
            self._imu_velocity = (lin, self.time_ns)
        ax, ay, az = self._imu_accel
        self._imu_state = ImuState(orn, kinematics.to_body(orn, ang),
                                   kinematics.to_body(orn, (ax, ay, az + GRAVITY)))
        self._imu_state_ns = self.time_ns

    def _update_encoders(self) -> None:
        (left, right), _ = self.physics.wheel_states()
        dt = 0.0 if self._last_control_ns is None else (self.time_ns - self._last_control_ns) / NS_PER_S
        self.encoders.update(left, right, dt)
        self._last_control_ns = self.time_ns

    def close(self) -> None:
        """Release the physics client."""
        self.physics.close()
