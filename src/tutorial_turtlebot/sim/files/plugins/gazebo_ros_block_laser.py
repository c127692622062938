"""``libgazebo_ros_block_laser.so`` on a ``<sensor type="ray">``: one sensor_msgs/PointCloud a
tick of every ray, horizontal and vertical, in the sensor frame (devices.block_laser). Read into
sensor_types.BlockLaserSensor with gazebo_ros_block_laser's defaults: topic and frame "/world",
no noise. Its rate is the sensor's update_rate (the plugin's updateRate is read and not used,
as in Gazebo). Runs on world models and on robots (world.robot_sensors). Units: m, rad,
Hz.
"""
from .sensor_reader import NOISE
from .sensor_types import BLOCK_LASER, BlockLaserSensor

SENSORS = {BLOCK_LASER: "ray"}
HOSTS = ("robot", "world")
PARAMS = frozenset({"robotNamespace", "topicName", "frameName", "gaussianNoise",
                    "hokuyoMinIntensity", "updateRate", "alwaysOn"})


def read(reader, sensor, plugin, link: str) -> BlockLaserSensor:
    """The block laser of ``sensor`` on ``link`` with its ``plugin``."""
    reader.check_params(plugin, BLOCK_LASER, PARAMS)
    rays = reader.ray_scan(sensor)
    reader.rate(plugin, "updateRate", 0.0, plugin)        # read, unused (Gazebo's FIXME)
    reader.number(plugin, "hokuyoMinIntensity", 101.0, plugin)   # read, unused
    return BlockLaserSensor(
        name=sensor.get("name"), link=link, rays=rays,
        topic=reader.topic(plugin, "topicName", "/world"),
        frame=reader.frame(plugin, link, "/world"),
        gaussian_noise=reader.bounded(plugin, "gaussianNoise", 0.0, plugin, NOISE),
        rate=reader.rate(sensor, "update_rate", 0.0, sensor),
        plugin=plugin.get("name", "").strip(),
        robot_namespace=reader.topic(plugin, "robotNamespace", ""),
        pose=reader.sensor_pose(sensor))
