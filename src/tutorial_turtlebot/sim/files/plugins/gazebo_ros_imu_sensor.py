"""``libgazebo_ros_imu_sensor.so`` on a ``<sensor type="imu">``: one sensor_msgs/Imu a tick of
the sensor's link (orientation in the world, REP 145; angular velocity and linear acceleration
with gravity's reaction, +9.8 m/s^2 up at rest, in the sensor frame), read into
``ImuSensorPlugin`` with gazebo_ros_imu_sensor's defaults: topic "imu_data" in <robotNamespace>
(else "/<model>"; a robot's: "" here, world.robot_sensors puts in the spawn's namespace or
"/<model>"), updateRateHZ 1, gaussianNoise 0 (on every field, the quaternion's too),
rpyOffset 0 (turns the orientation); the sensor's own ``<imu>`` noise (per axis: mean, stddev,
bias_mean, bias_stddev) on the rates and the acceleration. Without <frameName> the plugin does
not load (one warning), as in Gazebo. Runs on world models and on robots. Units: rad,
rad/s, m/s^2, Hz.
"""
from dataclasses import dataclass
from typing import Optional, Tuple

from .. import limits
from ...kinematics import ZERO_XYZ_RPY, XyzRpy
from .gazebo_ros_range import rate_of
from .sensor_reader import NOISE, NOISE_MEAN, NOISE_TYPES

IMU_SENSOR = "libgazebo_ros_imu_sensor.so"
SENSORS = {IMU_SENSOR: "imu"}
HOSTS = ("robot", "world")
PARAMS = frozenset({"robotNamespace", "topicName", "frameName", "updateRateHZ",
                    "gaussianNoise", "xyzOffset", "rpyOffset", "initialOrientationAsReference",
                    "alwaysOn", "updateRate"})


@dataclass(frozen=True)
class AxisNoise:
    """An ``<imu>`` axis' ``<noise>``: white noise N(mean, stddev) at each reading, and a bias
    drawn once, N(bias_mean, bias_stddev) with a random sign (rad/s or m/s^2)."""

    mean: float = 0.0
    stddev: float = 0.0
    bias_mean: float = 0.0
    bias_stddev: float = 0.0


NO_NOISE = (AxisNoise(),) * 3


@dataclass(frozen=True)
class ImuSensorPlugin:
    """An imu sensor with gazebo_ros_imu_sensor. ``rate``: Hz of sim time, the smaller of the
    sensor's update_rate and the plugin's updateRateHZ that are not 0 (0: every step)."""

    name: str
    link: str                               # the scoped link: "model::link"
    frame: str                              # frameName, as written (the header's frame_id)
    topic: str = "imu_data"                 # topicName
    robot_namespace: str = ""               # robotNamespace, else "/<model>"
    rate: float = 1.0
    gaussian_noise: float = 0.0             # gaussianNoise
    rpy_offset: Tuple[float, float, float] = (0.0, 0.0, 0.0)   # rad, rpyOffset
    rate_noise: Tuple[AxisNoise, ...] = NO_NOISE     # <imu><angular_velocity> x y z
    accel_noise: Tuple[AxisNoise, ...] = NO_NOISE    # <imu><linear_acceleration> x y z
    plugin: str = ""
    pose: XyzRpy = ZERO_XYZ_RPY
    plugin_file: str = IMU_SENSOR


def read(reader, sensor, plugin, link: str) -> Optional[ImuSensorPlugin]:
    """The IMU of ``sensor`` on ``link`` with its ``plugin``; None (one warning) without a
    <frameName>."""
    reader.check_params(plugin, IMU_SENSOR, PARAMS)
    if plugin.find("frameName") is None:
        reader.skip_plugin(plugin, sensor, "%s is not simulated here: it has no <frameName>, "
                                           "and gazebo_ros_imu_sensor does not load without one;"
                                           " %s" % (reader.describe(plugin), reader.without))
        return None
    imu = sensor.find("imu")
    rpy = (0.0, 0.0, 0.0)
    if plugin.find("rpyOffset") is not None:
        rpy = tuple(reader.floats(plugin.find("rpyOffset"), 3, plugin))
        problem = limits.angles_problem("rpyOffset", rpy)
        if problem:
            reader.fail(plugin.find("rpyOffset"), problem, plugin)
    return ImuSensorPlugin(
        name=sensor.get("name"), link=link,
        frame=reader.text(plugin, "frameName", ""),
        topic=reader.topic(plugin, "topicName", "imu_data"),
        robot_namespace=(reader.topic(plugin, "robotNamespace", "")
                         if plugin.find("robotNamespace") is not None
                         else "/" + link.split("::", 1)[0] if reader.host == "world" else ""),
        rate=rate_of(reader.rate(sensor, "update_rate", 0.0, sensor),
                     reader.rate(plugin, "updateRateHZ", 1.0, plugin)),
        gaussian_noise=reader.bounded(plugin, "gaussianNoise", 0.0, plugin, NOISE),
        rpy_offset=tuple(rpy),
        rate_noise=_axes(reader, imu, "angular_velocity", sensor),
        accel_noise=_axes(reader, imu, "linear_acceleration", sensor),
        plugin=plugin.get("name", "").strip(),
        pose=reader.sensor_pose(sensor))


def _axes(reader, imu, tag: str, sensor) -> Tuple[AxisNoise, ...]:
    """The x, y, z noises of ``<imu><tag>``; none where there is none."""
    group = imu.find(tag) if imu is not None else None
    return tuple(_noise(reader, group.find(axis) if group is not None else None, sensor)
                 for axis in "xyz")


def _noise(reader, axis, sensor) -> AxisNoise:
    noise = axis.find("noise") if axis is not None else None
    if noise is None:
        return AxisNoise()
    kind = noise.get("type", "none").strip()
    if kind not in NOISE_TYPES:
        reader.fail(noise, "type must be one of %s, got %r" % (", ".join(NOISE_TYPES), kind),
                    sensor)
    if kind == "none":
        return AxisNoise()
    return AxisNoise(reader.bounded(noise, "mean", 0.0, sensor, NOISE_MEAN),
                     reader.bounded(noise, "stddev", 0.0, sensor, NOISE),
                     reader.bounded(noise, "bias_mean", 0.0, sensor, NOISE_MEAN),
                     reader.bounded(noise, "bias_stddev", 0.0, sensor, NOISE))
