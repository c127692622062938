"""The data of the ray sensor plugins that the world's sensors run (world_sensors), on a world
model's link or a robot's: gazebo_ros_range and gazebo_ros_block_laser, with the rays of their
``<sensor type="ray">``.
Plain data: no ROS, no pybullet, no file reading (the plugin modules beside it read them).
Topic names are as written (relative ones resolve in ``robot_namespace``); frames as written,
without a leading "/" (tf's resolve drops it). Units: m, rad, Hz.
"""
from dataclasses import dataclass
from typing import Union

from ...kinematics import ZERO_XYZ_RPY, XyzRpy
from .robot_plugin_types import CameraSensor, LaserSensor

RANGE = "libgazebo_ros_range.so"
BLOCK_LASER = "libgazebo_ros_block_laser.so"


@dataclass(frozen=True)
class RayScan:
    """The rays of a ``<ray>``, as Gazebo's MultiRayShape casts them: ``samples`` x
    ``vertical_samples`` rays from ``range_min`` to ``range_max`` (m) along the sensor's x, turned
    by a yaw in min_angle..max_angle and a pitch in vertical_min_angle..vertical_max_angle (rad; a
    positive pitch looks up; one sample: angle 0). ``resolution`` (and ``vertical_resolution``)
    times the samples is how many readings a plugin interpolates from them."""

    samples: int = 640
    resolution: float = 1.0
    min_angle: float = 0.0
    max_angle: float = 0.0
    vertical_samples: int = 1
    vertical_resolution: float = 1.0
    vertical_min_angle: float = 0.0
    vertical_max_angle: float = 0.0
    range_min: float = 0.0
    range_max: float = 1.0

    @property
    def ray_count(self) -> int:
        return self.samples * self.vertical_samples


@dataclass(frozen=True)
class RangeSensor:
    """A ``<sensor type="ray">`` with ``libgazebo_ros_range.so``: one sensor_msgs/Range a tick,
    the nearest of its rays (gazebo_ros_range's defaults for what the plugin leaves out).
    ``rate``: Hz of sim time, the smaller of the sensor's update_rate and the plugin's
    updateRate that are not 0 (0: every physics step)."""

    name: str
    link: str                               # the scoped link: "model::link"
    rays: RayScan
    topic: str = "/range"                   # topicName
    frame: str = "world"                    # frameName ("/world")
    radiation: str = "ultrasound"           # ultrasound, else infrared
    fov: float = 0.05                       # rad, <fov>: field_of_view as written
    gaussian_noise: float = 0.0             # m, gaussianNoise
    rate: float = 0.0
    plugin: str = ""                        # the plugin's name
    robot_namespace: str = ""
    pose: XyzRpy = ZERO_XYZ_RPY             # the sensor's <pose> in its link
    plugin_file: str = RANGE


@dataclass(frozen=True)
class BlockLaserSensor:
    """A ``<sensor type="ray">`` with ``libgazebo_ros_block_laser.so``: one sensor_msgs/PointCloud
    a tick of (samples x resolution) x (vertical samples x resolution) points in the sensor frame
    (gazebo_ros_block_laser's defaults for what the plugin leaves out). ``rate``: the sensor's
    update_rate, Hz of sim time (0: every physics step; the plugin's updateRate is not used,
    as in Gazebo)."""

    name: str
    link: str
    rays: RayScan
    topic: str = "/world"                   # topicName
    frame: str = "world"                    # frameName ("/world")
    gaussian_noise: float = 0.0             # m, gaussianNoise, on each coordinate
    rate: float = 0.0
    plugin: str = ""
    robot_namespace: str = ""
    pose: XyzRpy = ZERO_XYZ_RPY
    plugin_file: str = BLOCK_LASER


# What a world model's <sensor> with a gazebo_ros plugin becomes (World.sensors).
WorldSensor = Union[LaserSensor, CameraSensor, RangeSensor, BlockLaserSensor]
