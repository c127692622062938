"""``libgazebo_ros_force_based_move.so`` (hector_gazebo_plugins): a model plugin with no wheels.
At every physics step it pushes the base toward the command: a force in the base frame of
(linear.x - vx) * x_velocity_p_gain, (linear.y - vy) * y_velocity_p_gain (N; v in m/s in the
base frame) and a torque about z of (angular.z - wz) * yaw_velocity_p_gain (N*m); every
1 / odometryRate s it publishes the model's world pose and its base-frame twist (linear.x,
angular.z) on ``odometryTopic``, with the odom -> base TF unless publishOdometryTf is false.
Read into ``ForceBasedMovePlugin`` with the plugin's defaults. No ROS, no pybullet.
Units: m, s, rad, Hz, N, N*m.
"""
from dataclasses import dataclass

from .. import limits

FORCE_BASED_MOVE = "libgazebo_ros_force_based_move.so"
MODEL_FILES = (FORCE_BASED_MOVE,)
HOSTS = ("robot", "world")
DRIVE = True
PARAMS = frozenset({"robotNamespace", "commandTopic", "odometryTopic", "odometryFrame",
                    "robotBaseFrame", "odometryRate", "publishOdometryTf",
                    "yaw_velocity_p_gain", "x_velocity_p_gain", "y_velocity_p_gain",
                    "alwaysOn"})
GAIN = (0.0, limits.MAX_FORCE)       # N per m/s, N*m per rad/s
# The plugin's pose covariance diagonal while the base turns (|wz| >= 1e-4 rad/s: yaw 100)
# and while it does not (yaw 0.01).
POSE_COVARIANCE = (1e-3, 1e-3, 1e12, 1e12, 1e12, 0.01)


@dataclass(frozen=True)
class ForceBasedMovePlugin:
    """``libgazebo_ros_force_based_move.so`` (a model plugin)."""

    name: str
    command_topic: str = "cmd_vel"
    odometry_topic: str = "odom"
    odometry_frame: str = "odom"
    robot_base_frame: str = "base_footprint"
    odometry_rate: float = 20.0             # Hz of sim time; 0 = no odometry at all
    publish_odometry_tf: bool = True
    yaw_velocity_p_gain: float = 100.0      # N*m per rad/s
    x_velocity_p_gain: float = 10000.0      # N per m/s
    y_velocity_p_gain: float = 10000.0      # N per m/s
    robot_namespace: str = ""
    model: str = ""                       # an SDF model's name (a robot's drive: "")

    pose_covariance = POSE_COVARIANCE

    @property
    def publish_odom_tf(self) -> bool:
        return self.publish_odometry_tf


def read(reader, elem, model: str, links, joints) -> ForceBasedMovePlugin:
    """The force-based move of the <plugin> ``elem`` (a robot's or an SDF model's, its
    parameters checked already)."""
    return ForceBasedMovePlugin(
        name=elem.get("name", "").strip(),
        command_topic=reader.topic(elem, "commandTopic", "cmd_vel"),
        odometry_topic=reader.topic(elem, "odometryTopic", "odom"),
        odometry_frame=reader.text(elem, "odometryFrame", "odom"),
        robot_base_frame=reader.text(elem, "robotBaseFrame", "base_footprint"),
        odometry_rate=reader.rate(elem, "odometryRate", 20.0, elem),
        publish_odometry_tf=reader.flag(elem, "publishOdometryTf", True, elem),
        yaw_velocity_p_gain=reader.bounded(elem, "yaw_velocity_p_gain", 100.0, elem, GAIN),
        x_velocity_p_gain=reader.bounded(elem, "x_velocity_p_gain", 10000.0, elem, GAIN),
        y_velocity_p_gain=reader.bounded(elem, "y_velocity_p_gain", 10000.0, elem, GAIN),
        robot_namespace=reader.topic(elem, "robotNamespace", ""),
        model=model if reader.host == "world" else "")
