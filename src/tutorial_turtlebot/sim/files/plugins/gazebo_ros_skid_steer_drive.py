"""``libgazebo_ros_skid_steer_drive.so``: a model plugin driving four wheel joints, each side's
two at one rim speed (linear.x -/+ angular.z * wheelSeparation / 2, m/s, over the wheel's
radius), with at most ``torque`` N*m, every 1 / updateRate s of sim time; odometry is the
model's world pose (``odometryTopic`` in ``odometryFrame``, child ``robotBaseFrame``), with the
odom -> base TF only with ``broadcastTF``. Read into ``SkidSteerPlugin`` with
gazebo_ros_skid_steer_drive's defaults. No ROS, no pybullet. Units: m, s, rad, Hz, N*m.
"""
from dataclasses import dataclass
from typing import Optional

from .drive_values import COVARIANCE, TORQUE, WHEEL
from .model_plugin_values import joints_found

SKID_STEER = "libgazebo_ros_skid_steer_drive.so"
MODEL_FILES = (SKID_STEER,)
HOSTS = ("robot", "world")
DRIVE = True
PARAMS = frozenset({
    "robotNamespace", "broadcastTF", "leftFrontJoint", "rightFrontJoint", "leftRearJoint",
    "rightRearJoint", "wheelSeparation", "wheelDiameter", "torque", "commandTopic",
    "odometryTopic", "odometryFrame", "robotBaseFrame", "updateRate", "covariance_x",
    "covariance_y", "covariance_yaw", "alwaysOn"})

# the joints it names (tag: Gazebo's default)
JOINTS = {"leftFrontJoint": "left_front_joint", "rightFrontJoint": "right_front_joint",
          "leftRearJoint": "left_rear_joint", "rightRearJoint": "right_rear_joint"}


@dataclass(frozen=True)
class SkidSteerPlugin:
    """``libgazebo_ros_skid_steer_drive.so`` (a model plugin)."""

    name: str
    left_front_joint: str = "left_front_joint"
    right_front_joint: str = "right_front_joint"
    left_rear_joint: str = "left_rear_joint"
    right_rear_joint: str = "right_rear_joint"
    wheel_separation: float = 0.4         # m
    wheel_diameter: float = 0.15          # m
    torque: float = 5.0                   # N*m, each wheel
    command_topic: str = "cmd_vel"
    odometry_topic: str = "odom"
    odometry_frame: str = "odom"
    robot_base_frame: str = "base_footprint"
    update_rate: float = 100.0            # Hz of sim time; 0 = every physics step
    covariance_x: float = 0.0001          # the odometry's pose and twist covariance diagonal
    covariance_y: float = 0.0001
    covariance_yaw: float = 0.01
    broadcast_tf: bool = False            # the odom -> base TF
    robot_namespace: str = ""
    model: str = ""                       # an SDF model's name (a robot's drive: "")

    @property
    def wheel_joints(self):
        """(left front, right front, left rear, right rear) joint names."""
        return (self.left_front_joint, self.right_front_joint, self.left_rear_joint,
                self.right_rear_joint)

    @property
    def publish_odom_tf(self) -> bool:
        return self.broadcast_tf

    @property
    def pose_covariance(self):
        """The odometry's pose covariance diagonal (x, y, z, roll, pitch, yaw)."""
        return (self.covariance_x, self.covariance_y, 1e12, 1e12, 1e12, self.covariance_yaw)


def read(reader, elem, model: str, links, joints) -> Optional[SkidSteerPlugin]:
    """The skid steer of the <plugin> ``elem`` (a robot's or an SDF model's, its
    parameters checked already)."""
    if reader.host == "world" and not joints_found(reader, elem, model, joints, JOINTS):
        return None
    number = reader.bounded
    return SkidSteerPlugin(
        name=elem.get("name", "").strip(),
        left_front_joint=reader.wheel_joint(elem, "leftFrontJoint", "left_front_joint"),
        right_front_joint=reader.wheel_joint(elem, "rightFrontJoint", "right_front_joint"),
        left_rear_joint=reader.wheel_joint(elem, "leftRearJoint", "left_rear_joint"),
        right_rear_joint=reader.wheel_joint(elem, "rightRearJoint", "right_rear_joint"),
        wheel_separation=number(elem, "wheelSeparation", 0.4, elem, WHEEL),
        wheel_diameter=number(elem, "wheelDiameter", 0.15, elem, WHEEL),
        torque=number(elem, "torque", 5.0, elem, TORQUE),
        command_topic=reader.topic(elem, "commandTopic", "cmd_vel"),
        odometry_topic=reader.topic(elem, "odometryTopic", "odom"),
        odometry_frame=reader.text(elem, "odometryFrame", "odom"),
        robot_base_frame=reader.text(elem, "robotBaseFrame", "base_footprint"),
        update_rate=reader.rate(elem, "updateRate", 100.0, elem),
        covariance_x=number(elem, "covariance_x", 0.0001, elem, COVARIANCE),
        covariance_y=number(elem, "covariance_y", 0.0001, elem, COVARIANCE),
        covariance_yaw=number(elem, "covariance_yaw", 0.01, elem, COVARIANCE),
        broadcast_tf=reader.flag(elem, "broadcastTF", False, elem),
        robot_namespace=reader.topic(elem, "robotNamespace", ""),
        model=model if reader.host == "world" else "")
