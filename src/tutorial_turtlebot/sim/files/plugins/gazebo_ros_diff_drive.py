"""``libgazebo_ros_diff_drive.so``: the one reading of the diff drive (``read_diff_drive``),
a model plugin and a drive (``table``): a URDF robot's (its drive, its wheel joints checked as
the robot's) and an SDF model's (a world file's or a spawned one), with Gazebo's defaults
(gazebo_ros_diff_drive's getParameter ones) and every number held to its limit. An SDF model's
wheels are its joints that <leftJoint> and <rightJoint> name (defaults left_joint,
right_joint); one the model does not have is one warning and the plugin does not run (Gazebo's
stops loading). Units: m, s, Hz, N*m, m/s^2.
"""
from dataclasses import dataclass, fields
from typing import Collection, Optional

from .. import limits
from .model_plugin_values import joints_found
from .robot_plugin_types import DIFF_DRIVE, DiffDrivePlugin
from .sensor_reader import Bounds

MODEL_FILES = (DIFF_DRIVE,)
HOSTS = ("robot", "world")
DRIVE = True
# What gazebo_ros_diff_drive reads (or Gazebo reads and the sim has no use for)
PARAMS = frozenset({
    "robotNamespace", "commandTopic", "odometryTopic", "odometryFrame", "robotBaseFrame",
    "odometrySource", "publishTf", "publishOdomTF", "publishWheelTF",
    "publishWheelJointState", "updateRate", "leftJoint", "rightJoint", "wheelSeparation",
    "wheelDiameter", "wheelAcceleration", "wheelTorque", "legacyMode", "rosDebugLevel",
    "alwaysOn"})
DEFAULT_JOINTS = {"leftJoint": "left_joint", "rightJoint": "right_joint"}
# the bounds of its numbers (limits.outside's arguments)
WHEEL = Bounds(limits.MIN_WHEEL_SIZE, limits.MAX_SIZE, "m")   # a diameter, a separation
ACCELERATION = Bounds(0.0, limits.MAX_ACCELERATION, "m/s^2")
TORQUE = Bounds(0.0, limits.MAX_FORCE, "N m", low_open=True)


@dataclass(frozen=True)
class ModelDiffDrive(DiffDrivePlugin):
    """The diff drive of SDF model ``model`` (its wheel joints named as the model lists them)."""

    model: str = ""


def read_diff_drive(reader, elem, name: str, wheel_joint) -> DiffDrivePlugin:
    """The settings in ``elem`` (its parameters checked already). ``reader``: a
    sensor_reader.SensorReader; ``wheel_joint(elem, tag, default)``: the joint a
    <leftJoint>/<rightJoint> names, checked as its host checks it."""
    source_elem = elem.find("odometrySource")
    source = "world"
    if source_elem is not None:
        source = reader.text(elem, "odometrySource", "world")
        if source not in ("world", "encoder"):
            reader.fail(source_elem, "must be world or encoder, got %r" % source, elem)
    number = reader.bounded
    return DiffDrivePlugin(
        name=name,
        command_topic=reader.topic(elem, "commandTopic", "cmd_vel"),
        odometry_topic=reader.topic(elem, "odometryTopic", "odom"),
        odometry_frame=reader.text(elem, "odometryFrame", "odom"),
        robot_base_frame=reader.text(elem, "robotBaseFrame", "base_footprint"),
        odometry_source="encoders" if source == "encoder" else "world",
        publish_tf=reader.flag(elem, "publishTf", True, elem),
        publish_wheel_tf=reader.flag(elem, "publishWheelTF", False, elem),
        publish_wheel_joint_state=reader.flag(elem, "publishWheelJointState", False, elem),
        update_rate=reader.rate(elem, "updateRate", 100.0, elem),
        left_joint=wheel_joint(elem, "leftJoint", "left_joint"),
        right_joint=wheel_joint(elem, "rightJoint", "right_joint"),
        wheel_separation=number(elem, "wheelSeparation", 0.34, elem, WHEEL),
        wheel_diameter=number(elem, "wheelDiameter", 0.15, elem, WHEEL),
        wheel_acceleration=number(elem, "wheelAcceleration", 0.0, elem, ACCELERATION),
        wheel_torque=number(elem, "wheelTorque", 5.0, elem, TORQUE),
        robot_namespace=reader.topic(elem, "robotNamespace", ""),
        publish_odom_tf=reader.flag(elem, "publishOdomTF", True, elem))


def read(reader, plugin, model: str, links: Collection[str],
         joints: Collection[str]) -> Optional[DiffDrivePlugin]:
    """A robot's diff drive (``reader.host`` "robot": robot_plugins' reader, whose
    ``wheel_joint`` refuses a wrong wheel joint), or an SDF model's, or None (one warning) when
    a wheel joint is not a joint of the model (its parameters checked already)."""
    if reader.host == "robot":
        return read_diff_drive(reader, plugin, plugin.get("name", "").strip(),
                               reader.wheel_joint)
    if not joints_found(reader, plugin, model, joints, DEFAULT_JOINTS):
        return None
    drive = read_diff_drive(reader, plugin, plugin.get("name", "").strip(), reader.wheel_joint)
    return ModelDiffDrive(model=model, **{f.name: getattr(drive, f.name)
                                          for f in fields(DiffDrivePlugin)})
