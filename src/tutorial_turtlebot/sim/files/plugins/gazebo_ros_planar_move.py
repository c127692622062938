"""``libgazebo_ros_planar_move.so``: a model plugin with no wheels. At every physics step it
sets the model's velocity to the command (linear.x, linear.y m/s in the base's heading, angular.z
rad/s about the world's z; z velocity 0), zeroed ``cmdTimeout`` s of sim time after the last
command (a negative one: never); every 1 / odometryRate s it publishes the model's world pose on
``odometryTopic`` (twist: the pose's change since the last, in the base frame) and the odom ->
base TF. Read into ``PlanarMovePlugin`` with gazebo_ros_planar_move's defaults. No ROS, no
pybullet. Units: m, s, rad, Hz.
"""
from dataclasses import dataclass

from .drive_values import TIMEOUT

PLANAR_MOVE = "libgazebo_ros_planar_move.so"
MODEL_FILES = (PLANAR_MOVE,)
HOSTS = ("robot", "world")
DRIVE = True
PARAMS = frozenset({"robotNamespace", "commandTopic", "odometryTopic", "odometryFrame",
                    "robotBaseFrame", "odometryRate", "cmdTimeout", "alwaysOn"})
# gazebo_ros_planar_move's fixed pose covariance diagonal (x, y, z, roll, pitch, yaw)
POSE_COVARIANCE = (1e-5, 1e-5, 1e12, 1e12, 1e12, 1e-3)


@dataclass(frozen=True)
class PlanarMovePlugin:
    """``libgazebo_ros_planar_move.so`` (a model plugin)."""

    name: str
    command_topic: str = "cmd_vel"
    odometry_topic: str = "odom"
    odometry_frame: str = "odom"
    robot_base_frame: str = "base_footprint"
    odometry_rate: float = 20.0           # Hz of sim time; 0 = no odometry at all
    cmd_timeout: float = -1.0             # s of sim time; negative: a command is kept
    robot_namespace: str = ""
    model: str = ""                       # an SDF model's name (a robot's drive: "")

    publish_odom_tf = True                # the odom -> base TF, with every odometry
    pose_covariance = POSE_COVARIANCE


def read(reader, elem, model: str, links, joints) -> PlanarMovePlugin:
    """The planar move of the <plugin> ``elem`` (a robot's or an SDF model's, its
    parameters checked already)."""
    return PlanarMovePlugin(
        name=elem.get("name", "").strip(),
        command_topic=reader.topic(elem, "commandTopic", "cmd_vel"),
        odometry_topic=reader.topic(elem, "odometryTopic", "odom"),
        odometry_frame=reader.text(elem, "odometryFrame", "odom"),
        robot_base_frame=reader.text(elem, "robotBaseFrame", "base_footprint"),
        odometry_rate=reader.rate(elem, "odometryRate", 20.0, elem),
        cmd_timeout=reader.bounded(elem, "cmdTimeout", -1.0, elem, TIMEOUT),
        robot_namespace=reader.topic(elem, "robotNamespace", ""),
        model=model if reader.host == "world" else "")
