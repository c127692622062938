"""The model plugins this simulator runs on any model (a world file's or a spawned SDF model, a
URDF robot's ``<gazebo>`` block; the diff drive on SDF models, a robot's being its drive), one
module each, by the library file they are loaded from, and what their readers share. No ROS,
no pybullet.

A model plugin sits on a model, not on a sensor, so it has a table of its own beside
``table`` (whose plugins are read with their ``<sensor>``): each module here has ``FILES``
(the libraries it is loaded from), ``PARAMS`` (the parameters it reads) and
``read(reader, plugin, model, links, joints)``: its frozen dataclass with the plugin's
defaults, or None when Gazebo would not run it (a missing or unknown ``<bodyName>``, ...;
one warning then). ``reader`` is a sensor_reader.SensorReader (robot_plugins' or the SDF
loader's); ``links`` and ``joints`` are the names the model knows (an SDF model's nested
ones as "inner::link"). Adding a model plugin is one module and one entry of ``MODULES``.
"""
from typing import Collection, Optional

from . import (gazebo_ros_diff_drive, gazebo_ros_joint_state_publisher, gazebo_ros_p3d,
               hector_gazebo_ros_gps, hector_gazebo_ros_imu)

MODULES = (gazebo_ros_p3d, gazebo_ros_joint_state_publisher, hector_gazebo_ros_imu,
           hector_gazebo_ros_gps, gazebo_ros_diff_drive)
MODEL_PLUGINS = {filename: module for module in MODULES for filename in module.FILES}


def is_model_plugin(filename: str) -> bool:
    """Whether the library ``filename`` (plugin_file's form) is a model plugin run here."""
    return filename in MODEL_PLUGINS


def read_model_plugin(reader, plugin, model: str, links: Collection[str],
                      joints: Collection[str]) -> Optional[object]:
    """The data of the model plugin ``plugin`` (a <plugin> element of a model of name
    ``model``), or None (one warning) where Gazebo would not run it."""
    _, filename = reader.plugin_id(plugin)
    module = MODEL_PLUGINS[filename]
    reader.check_params(plugin, filename, module.PARAMS)
    return module.read(reader, plugin, model, links, joints)
