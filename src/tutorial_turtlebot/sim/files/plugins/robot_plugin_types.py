"""The data a URDF's ``<gazebo>`` plugins become: the gazebo_ros plugin file names and one
frozen dataclass per plugin or sensor the simulator makes, with Gazebo's defaults (gazebo_plugins'
``getParameter`` defaults) for what the block leaves out. Plain data: no ROS, no pybullet, no file
reading (robot_plugins reads them). Topic names are as written (relative ones resolve in the
robot's namespace); frames are link names, unprefixed. Units: m, s, rad, Hz, N*m, m/s^2.
"""
import math
from dataclasses import dataclass
from typing import Optional, Tuple, Union

from ...kinematics import ZERO_XYZ_RPY, XyzRpy
from .gazebo_ros_force_based_move import ForceBasedMovePlugin
from .gazebo_ros_planar_move import PlanarMovePlugin
from .gazebo_ros_skid_steer_drive import SkidSteerPlugin
from .gazebo_ros_tricycle_drive import TricyclePlugin

DIFF_DRIVE = "libgazebo_ros_diff_drive.so"
LASER = "libgazebo_ros_laser.so"
GPU_LASER = "libgazebo_ros_gpu_laser.so"
IMU = "libgazebo_ros_imu.so"
CAMERA = "libgazebo_ros_camera.so"
OPENNI_KINECT = "libgazebo_ros_openni_kinect.so"


@dataclass(frozen=True)
class LaserConfig:
    """Fields of the published LaserScan and the value used where there is no valid reading."""

    name: str
    angle_min: float
    angle_max: float
    angle_increment: float
    samples: int = 360
    range_min: float = 0.12
    range_max: float = 3.5
    noise_sigma: float = 0.01     # m, gaussian
    no_return: float = math.inf   # nothing within range_max
    too_close: float = -math.inf  # something at or inside range_min
    rate: float = 5.0             # Hz, sim time


@dataclass(frozen=True)
class CameraSpec:
    """What a camera renders: image size, horizontal field of view (rad), rate (Hz of sim
    time), clip planes (m), whether it also gives depth, and gazebo_ros' hackBaseline (m:
    P[3] = -f * baseline)."""

    width: int
    height: int
    hfov: float
    rate: float
    near: float = 0.03
    far: float = 100.0
    depth: bool = False
    baseline: float = 0.0


@dataclass(frozen=True)
class DiffDrivePlugin:
    """``libgazebo_ros_diff_drive.so`` (a model plugin)."""

    name: str
    command_topic: str = "cmd_vel"
    odometry_topic: str = "odom"
    odometry_frame: str = "odom"
    robot_base_frame: str = "base_footprint"
    odometry_source: str = "world"        # "world" (ground truth) or "encoders" (Gazebo: encoder)
    publish_tf: bool = True               # odometry on odometry_topic (and its TF), at all
    publish_wheel_tf: bool = False        # not simulated (robot_state_publisher does it)
    publish_wheel_joint_state: bool = False
    update_rate: float = 100.0            # Hz of sim time; 0 = every physics step
    left_joint: str = "left_joint"
    right_joint: str = "right_joint"
    wheel_separation: float = 0.34        # m
    wheel_diameter: float = 0.15          # m
    wheel_acceleration: float = 0.0       # m/s^2 at the rim; 0 = no ramp
    wheel_torque: float = 5.0             # N*m
    robot_namespace: str = ""             # <robotNamespace>; "" = the spawn's namespace
    publish_odom_tf: bool = True          # <publishOdomTF>: the odom TF, when publish_tf is on

    @property
    def wheel_radius(self) -> float:
        """m."""
        return self.wheel_diameter / 2.0


# A robot's drive: the diff drive or another drive of table (a module with DRIVE).
Drive = Union[DiffDrivePlugin, SkidSteerPlugin, PlanarMovePlugin, TricyclePlugin,
              ForceBasedMovePlugin]


@dataclass(frozen=True)
class LaserSensor:
    """A ``<sensor type="ray">`` with ``libgazebo_ros_laser.so``: the ray geometry and noise in
    ``laser`` (angle_increment = (max - min) / (samples - 1), as Gazebo publishes; ``rate`` =
    the sensor's update_rate), where it sits and where it publishes."""

    name: str                              # the sensor's name
    link: str                              # the <gazebo reference=...> link
    laser: LaserConfig
    topic: str = "/world"                  # topicName (gazebo_ros_laser's default)
    frame: str = "/world"                  # frameName
    plugin: str = ""                       # the plugin's name
    robot_namespace: str = ""
    plugin_file: str = LASER               # or GPU_LASER on a gpu_ray sensor
    pose: XyzRpy = ZERO_XYZ_RPY            # the sensor's <pose> in its link: x y z roll pitch yaw
    range_resolution: float = 0.0          # m, <range><resolution> (not simulated)


@dataclass(frozen=True)
class ImuPlugin:
    """``libgazebo_ros_imu.so`` (a model plugin reading link ``body_name``)."""

    name: str
    body_name: str                         # the link it reads
    frame_name: str = ""                   # header.frame_id; "" = body_name
    topic: str = "imu"                     # topicName
    service_name: str = "imu_service"
    update_rate: float = 0.0               # Hz; 0 = every physics step
    gaussian_noise: float = 0.0
    robot_namespace: str = ""

    @property
    def frame(self) -> str:
        return self.frame_name or self.body_name


@dataclass(frozen=True)
class CameraSensor:
    """A ``<sensor type="camera">`` with ``libgazebo_ros_camera.so`` or a
    ``<sensor type="depth">`` with ``libgazebo_ros_openni_kinect.so``. Topics are relative to
    ``camera_name`` (itself relative to the robot's namespace); ``spec.depth`` is True for the
    depth sensor; ``spec.rate`` is the plugin's updateRate (else the sensor's update_rate);
    ``image_format`` Gazebo's <format> (R8G8B8, L8, ...), ``lens`` the image's <distortion>
    (None: none), ``info_distortion`` CameraInfo's D (k1, k2, t1, t2, k3)."""

    name: str
    link: str
    spec: CameraSpec
    plugin_file: str = CAMERA
    camera_name: str = "camera"
    frame: str = "camera_rgb_optical_frame"     # frameName
    image_topic: str = "image_raw"
    info_topic: str = "camera_info"
    depth_image_topic: str = "depth/image_raw"
    depth_info_topic: str = "depth/camera_info"
    point_cloud_topic: str = "depth/points"
    point_cloud_cutoff: float = 0.4              # m
    robot_namespace: str = ""
    pose: XyzRpy = ZERO_XYZ_RPY                  # the sensor's <pose> in its link
    point_cloud_cutoff_max: float = 5.0          # m
    image_format: str = "R8G8B8"
    lens: Optional[object] = None                # a camera_types.LensDistortion
    info_distortion: Tuple[float, ...] = (0.0,) * 5


@dataclass(frozen=True)
class RobotPlugins:
    """Everything one URDF's <gazebo> blocks declare that this simulator makes. Every laser
    and every camera is simulated (``lasers``, ``cameras`` in file order; ``laser`` and
    ``camera`` are the first of each, or None); ``warnings`` names (one line each) every
    plugin or sensor that is not, and the robot runs without it."""

    drive: Optional[Drive] = None
    laser: Optional[LaserSensor] = None
    imu: Optional[ImuPlugin] = None
    camera: Optional[CameraSensor] = None
    warnings: Tuple[str, ...] = ()
    model_plugins: Tuple = ()     # p3d, joint_state_publisher, hector's (plugins.table)
    lasers: Tuple[LaserSensor, ...] = ()
    cameras: Tuple[CameraSensor, ...] = ()
    # the sensors SimRobot does not make itself, run as a world model's are (world_sensors):
    # range, block laser, bumper, depth, multi- and triggered cameras, imu sensor; file order
    sensors: Tuple = ()

    def __post_init__(self):
        """The first of each list and the list agree, whichever of them was given."""
        for one, many in (("laser", "lasers"), ("camera", "cameras")):
            first, listed = getattr(self, one), tuple(getattr(self, many))
            if not listed and first is not None:
                listed = (first,)
            object.__setattr__(self, many, listed)
            object.__setattr__(self, one, listed[0] if listed else None)
