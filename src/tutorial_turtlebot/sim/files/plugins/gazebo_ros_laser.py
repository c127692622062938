"""``libgazebo_ros_laser.so`` on a ``<sensor type="ray">`` (``libgazebo_ros_gpu_laser.so`` on a
``gpu_ray``): a sensor_msgs/LaserScan of the horizontal plane of its rays, at the sensor's
update_rate. Read into robot_plugin_types.LaserSensor (angle_increment = (max - min) /
(samples - 1), as Gazebo publishes) with gazebo_ros_laser's defaults: topic and frame "/world"
(a robot's frame: its link). Runs on robots and on world models. Units: m, rad, Hz.
"""
from .robot_plugin_types import GPU_LASER, LASER, LaserConfig, LaserSensor
from .sensor_reader import DISTANCE

SENSORS = {LASER: "ray", GPU_LASER: "gpu_ray"}     # the plugin file -> the sensor it sits on
HOSTS = ("robot", "world")
PARAMS = frozenset({"robotNamespace", "topicName", "frameName", "alwaysOn"})


def read(reader, sensor, plugin, link: str) -> LaserSensor:
    """The laser of ``sensor`` on ``link`` with its ``plugin`` (a SensorReader's elements)."""
    filename = reader.plugin_id(plugin)[1]
    reader.check_params(plugin, filename, PARAMS)
    rays = reader.ray_scan(sensor, one_plane=True)
    ranges = sensor.find("ray").find("range")
    sigma = reader.ray_noise(sensor.find("ray").find("noise"), sensor)
    rate = reader.rate(sensor, "update_rate", 0.0, sensor)
    samples = rays.samples
    increment = (rays.max_angle - rays.min_angle) / (samples - 1) if samples > 1 else 0.0
    config = LaserConfig("gazebo", rays.min_angle, rays.max_angle, increment, samples=samples,
                         range_min=rays.range_min, range_max=rays.range_max,
                         noise_sigma=sigma, rate=rate)
    return LaserSensor(
        name=sensor.get("name"), link=link, laser=config,
        topic=reader.topic(plugin, "topicName", "/world"),
        frame=reader.frame(plugin, link, "/world"),
        plugin=plugin.get("name", "").strip(),
        robot_namespace=reader.topic(plugin, "robotNamespace", ""),
        plugin_file=filename, pose=reader.sensor_pose(sensor),
        range_resolution=reader.bounded(ranges, "resolution", 0.0, sensor, DISTANCE))
