"""``libgazebo_ros_tricycle_drive.so``: a model plugin steering one joint and driving one wheel.
Its command is linear.x (m/s at the actuated wheel's rim) and angular.z, read as the steering
angle (rad, held to +-pi/2), not a yaw rate. Every 1 / updateRate s of sim time the actuated
wheel's speed moves toward the command (at most wheelAcceleration, wheelDeceleration m/s^2 when
given, held within wheelSpeedTolerance), and the steering joint goes to its angle (at
steeringSpeed rad/s when given, else at once); odometry from the world pose, or, with
odometrySource encoder, from the two encoder wheels' joints; the odom -> base TF always.
Read into ``TricyclePlugin`` with gazebo_ros_tricycle_drive's defaults. No ROS, no pybullet.
Units: m, s, rad, Hz, N*m.
"""
from dataclasses import dataclass
from typing import Optional

from .drive_values import ACCELERATION, STEERING_SPEED, TOLERANCE, TORQUE, WHEEL
from .model_plugin_values import joints_found

TRICYCLE = "libgazebo_ros_tricycle_drive.so"
MODEL_FILES = (TRICYCLE,)
HOSTS = ("robot", "world")
DRIVE = True
PARAMS = frozenset({
    "robotNamespace", "actuatedWheelDiameter", "encoderWheelDiameter", "wheelTorque",
    "commandTopic", "odometryTopic", "odometryFrame", "robotBaseFrame", "updateRate",
    "wheelAcceleration", "wheelDeceleration", "wheelSpeedTolerance", "steeringSpeed",
    "steeringAngleTolerance", "encoderWheelSeparation", "publishWheelTF",
    "publishWheelJointState", "steeringJoint", "actuatedWheelJoint", "encoderWheelLeftJoint",
    "encoderWheelRightJoint", "odometrySource", "rosDebugLevel", "alwaysOn"})
POSE_COVARIANCE = (1e-5, 1e-5, 1e12, 1e12, 1e12, 1e-3)

# the joints it names (tag: Gazebo's default)
JOINTS = {"steeringJoint": "front_steering_joint", "actuatedWheelJoint": "front_wheel_joint",
          "encoderWheelLeftJoint": "left_wheel_joint",
          "encoderWheelRightJoint": "right_wheel_joint"}


@dataclass(frozen=True)
class TricyclePlugin:
    """``libgazebo_ros_tricycle_drive.so`` (a model plugin)."""

    name: str
    steering_joint: str = "front_steering_joint"
    actuated_wheel_joint: str = "front_wheel_joint"
    encoder_wheel_left_joint: str = "left_wheel_joint"
    encoder_wheel_right_joint: str = "right_wheel_joint"
    actuated_wheel_diameter: float = 0.15   # m
    encoder_wheel_diameter: float = 0.15    # m
    encoder_wheel_separation: float = 0.5   # m
    wheel_torque: float = 5.0               # N*m, the actuated wheel's and the steering's
    wheel_acceleration: float = 0.0         # m/s^2 at the rim; 0 = no ramp
    wheel_deceleration: float = 0.0         # m/s^2; Gazebo's default: wheel_acceleration
    wheel_speed_tolerance: float = 0.01     # m/s
    steering_speed: float = 0.0             # rad/s; 0 = the angle at once
    steering_angle_tolerance: float = 0.01  # rad
    command_topic: str = "cmd_vel"
    odometry_topic: str = "odom"
    odometry_frame: str = "odom"
    robot_base_frame: str = "base_link"
    odometry_source: str = "world"          # "world" or "encoders" (Gazebo: encoder)
    update_rate: float = 100.0              # Hz of sim time; 0 = every physics step
    publish_wheel_tf: bool = False          # not simulated (robot_state_publisher does it)
    publish_wheel_joint_state: bool = False
    robot_namespace: str = ""
    model: str = ""                         # an SDF model's name (a robot's drive: "")

    publish_odom_tf = True
    pose_covariance = POSE_COVARIANCE


def read(reader, elem, model: str, links, joints) -> Optional[TricyclePlugin]:
    """The tricycle of the <plugin> ``elem`` (a robot's or an SDF model's, its
    parameters checked already)."""
    if reader.host == "world" and not joints_found(reader, elem, model, joints, JOINTS):
        return None
    source = reader.text(elem, "odometrySource", "world")
    if source not in ("world", "encoder"):
        reader.fail(elem.find("odometrySource"), "must be world or encoder, got %r" % source,
                    elem)
    number = reader.bounded
    acceleration = number(elem, "wheelAcceleration", 0.0, elem, ACCELERATION)
    return TricyclePlugin(
        name=elem.get("name", "").strip(),
        steering_joint=reader.wheel_joint(elem, "steeringJoint", "front_steering_joint"),
        actuated_wheel_joint=reader.wheel_joint(elem, "actuatedWheelJoint",
                                                "front_wheel_joint"),
        encoder_wheel_left_joint=reader.wheel_joint(elem, "encoderWheelLeftJoint",
                                                    "left_wheel_joint"),
        encoder_wheel_right_joint=reader.wheel_joint(elem, "encoderWheelRightJoint",
                                                     "right_wheel_joint"),
        actuated_wheel_diameter=number(elem, "actuatedWheelDiameter", 0.15, elem, WHEEL),
        encoder_wheel_diameter=number(elem, "encoderWheelDiameter", 0.15, elem, WHEEL),
        encoder_wheel_separation=number(elem, "encoderWheelSeparation", 0.5, elem, WHEEL),
        wheel_torque=number(elem, "wheelTorque", 5.0, elem, TORQUE),
        wheel_acceleration=acceleration,
        wheel_deceleration=number(elem, "wheelDeceleration", acceleration, elem, ACCELERATION),
        wheel_speed_tolerance=number(elem, "wheelSpeedTolerance", 0.01, elem, TOLERANCE),
        steering_speed=number(elem, "steeringSpeed", 0.0, elem, STEERING_SPEED),
        steering_angle_tolerance=number(elem, "steeringAngleTolerance", 0.01, elem, TOLERANCE),
        command_topic=reader.topic(elem, "commandTopic", "cmd_vel"),
        odometry_topic=reader.topic(elem, "odometryTopic", "odom"),
        odometry_frame=reader.text(elem, "odometryFrame", "odom"),
        robot_base_frame=reader.text(elem, "robotBaseFrame", "base_link"),
        odometry_source="encoders" if source == "encoder" else "world",
        update_rate=reader.rate(elem, "updateRate", 100.0, elem),
        publish_wheel_tf=reader.flag(elem, "publishWheelTF", False, elem),
        publish_wheel_joint_state=reader.flag(elem, "publishWheelJointState", False, elem),
        robot_namespace=reader.topic(elem, "robotNamespace", ""),
        model=model if reader.host == "world" else "")
