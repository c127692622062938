"""``libgazebo_ros_range.so`` on a ``<sensor type="ray">``: one sensor_msgs/Range a tick, the
nearest of the sensor's rays (devices.range_sensor). Read into sensor_types.RangeSensor with
gazebo_ros_range's defaults: topic "/range", frame "/world", radiation ultrasound, fov 0.05 rad,
no noise, updateRate 0 (a robot's frame: its link). Runs on world models and on robots
(world.robot_sensors). Units: m, rad, Hz.
"""
from .sensor_reader import FIELD_OF_VIEW, NOISE
from .sensor_types import RANGE, RangeSensor

SENSORS = {RANGE: "ray"}
HOSTS = ("robot", "world")
PARAMS = frozenset({"robotNamespace", "topicName", "frameName", "radiation", "fov",
                    "gaussianNoise", "updateRate", "alwaysOn"})


def rate_of(sensor_rate: float, plugin_rate: float) -> float:
    """Hz: the sensor updates at its rate, the plugin publishes at most at its own (0: no
    limit), as gazebo_ros_range and gazebo_ros_camera throttle; 0 for every physics step."""
    rates = [r for r in (sensor_rate, plugin_rate) if r > 0]
    return min(rates) if rates else 0.0


def read(reader, sensor, plugin, link: str) -> RangeSensor:
    """The range sensor of ``sensor`` on ``link`` with its ``plugin``."""
    reader.check_params(plugin, RANGE, PARAMS)
    rays = reader.ray_scan(sensor)
    rate = rate_of(reader.rate(sensor, "update_rate", 0.0, sensor),
                   reader.rate(plugin, "updateRate", 0.0, plugin))
    return RangeSensor(
        name=sensor.get("name"), link=link, rays=rays,
        topic=reader.topic(plugin, "topicName", "/range"),
        frame=reader.frame(plugin, link, "/world"),
        radiation=reader.text(plugin, "radiation", "ultrasound"),
        fov=reader.bounded(plugin, "fov", 0.05, plugin, FIELD_OF_VIEW),
        gaussian_noise=reader.bounded(plugin, "gaussianNoise", 0.0, plugin, NOISE),
        rate=rate, plugin=plugin.get("name", "").strip(),
        robot_namespace=reader.topic(plugin, "robotNamespace", ""),
        pose=reader.sensor_pose(sensor))
