"""The gazebo_ros sensor plugins this simulator makes, one module each, by the library file they
are loaded from, and the one reading of a ``<sensor>`` that robots (robot_plugins) and world
models (world_sensor_reading) share. No ROS, no pybullet.

Each plugin module has ``SENSORS`` ({library: the sensor type it sits on}: Gazebo loads it on
no other), ``HOSTS`` (where it runs here: "robot", "world"), ``PARAMS`` (the parameters it
reads) and ``read(reader, sensor, plugin, link)`` (its data, with the plugin's defaults; None
for a plugin that does not load, as gazebo_ros_imu_sensor without <frameName>).
Adding a plugin is one module and one line of ``MODULES``.
"""
from typing import Dict, List, Optional, Tuple

from . import (gazebo_ros_block_laser, gazebo_ros_bumper, gazebo_ros_camera,
               gazebo_ros_depth_camera, gazebo_ros_imu_sensor, gazebo_ros_laser,
               gazebo_ros_multicamera, gazebo_ros_openni_kinect, gazebo_ros_range,
               gazebo_ros_triggered_camera)

MODULES = (gazebo_ros_laser, gazebo_ros_camera, gazebo_ros_openni_kinect, gazebo_ros_range,
           gazebo_ros_block_laser, gazebo_ros_depth_camera, gazebo_ros_multicamera,
           gazebo_ros_triggered_camera, gazebo_ros_bumper, gazebo_ros_imu_sensor)
PLUGINS = {filename: module for module in MODULES for filename in module.SENSORS}


def sensor_type(filename: str) -> Optional[str]:
    """The sensor type the plugin library ``filename`` sits on; None for another library."""
    module = PLUGINS.get(filename)
    return module.SENSORS[filename] if module is not None else None


def runs_on(filename: str, host: str) -> bool:
    """Whether the plugin library ``filename`` runs on ``host`` ("robot" or "world")."""
    module = PLUGINS.get(filename)
    return module is not None and host in module.HOSTS


def plugins_of(kind: str, host: str) -> Tuple[str, ...]:
    """The plugin libraries that run on a sensor of type ``kind`` on ``host``."""
    return tuple(f for f, m in PLUGINS.items() if m.SENSORS[f] == kind and host in m.HOSTS)


def read_sensor(reader, elem, link: str) -> List[object]:
    """The data of each plugin on the <sensor> ``elem`` of ``link`` that runs on the reader's
    host (a SensorReader), in file order; a warning for each plugin that does not run
    (reader.skip_plugin), and for a sensor that no plugin here makes (reader.not_run). A sensor
    without a gazebo_ros plugin gives nothing and no warning: Gazebo publishes nothing of it on
    ROS either. On a robot (``reader.one_per_sensor``) a second plugin of a kind is warned."""
    kind = reader.attr(elem, "type")
    reader.attr(elem, "name")
    plugins = elem.findall("plugin")
    wanted = plugins_of(kind, reader.host)
    if not wanted:
        reader.not_run(elem, link, plugins)
        return []
    kept = []
    first: Dict[str, object] = {}
    for plugin in plugins:
        _, filename = reader.plugin_id(plugin)
        if filename in wanted and filename in first and reader.one_per_sensor:
            reader.second(plugin, "%s on %s" % (filename, reader.sensor_id(elem)),
                          first[filename].get("name", ""))
        elif filename in wanted:
            first.setdefault(filename, plugin)
            kept.append((filename, plugin))
        elif runs_on(filename, reader.host):
            reader.skip_plugin(plugin, elem, '%s on %s is of the wrong kind (it needs a <sensor '
                               'type="%s">); %s' % (reader.describe(plugin),
                                                    reader.sensor_id(elem),
                                                    sensor_type(filename), reader.without))
        else:
            reader.skip_plugin(plugin, elem, "%s is not simulated here; %s"
                               % (reader.describe(plugin), reader.without))
    read = (PLUGINS[filename].read(reader, elem, plugin, link) for filename, plugin in kept)
    return [data for data in read if data is not None]
