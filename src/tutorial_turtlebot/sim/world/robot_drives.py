"""The drives besides the diff drive (sim_robot runs a robot's itself, model_drives an SDF
model's): what each gazebo_ros drive plugin does to the body at its control ticks, and the
odometry it reports, written once for any model: a URDF robot's (SimRobot, on its RobotBody)
and an SDF model's (model_drives.DriveRunner, on an engine.drive_body.DriveBody, which answers
the same calls; the base frame there is the model frame). One small interface, each drive a
class:

  ``wheels`` (RobotBody's and DriveBody's wheel_joints, wheel_torque, wheel_sides, free_wheels),
  ``control_rate(step_rate)`` and ``odom_rate(step_rate)`` (Hz; 0: no odometry), ``reset()``,
  ``set_command(x, y, yaw_rate, now)`` (m/s, m/s, rad/s in the base frame; s of sim time),
  ``tick(body, now, dt)`` (one control tick's actuation), ``odom_tick(body, now)`` (at each
  odometry tick) and ``odom(body)`` ((position, orientation, linear, angular): the root link
  in the world, the twist in the base frame); ``joint_names``: the joints whose states it
  publishes (() for none).

Knows nothing of ROS. Units: m, s, rad, N*m.
"""
import math
from typing import Optional

from .. import kinematics
from ..devices.force_based_move import push
from ..devices.planar_move import PlanarMoveController, PoseOdometry, world_velocity
from ..devices.skid_steer import SIDES, SkidSteerController
from ..devices.tricycle import TricycleController
from ..devices.wheel_odometry import WheelOdometry
from ..files.plugins.gazebo_ros_force_based_move import ForceBasedMovePlugin
from ..files.plugins.gazebo_ros_planar_move import PlanarMovePlugin
from ..files.plugins.gazebo_ros_skid_steer_drive import SkidSteerPlugin
from ..files.plugins.gazebo_ros_tricycle_drive import TricyclePlugin


def _every(rate: float, step_rate: float) -> float:
    """A plugin's rate (Hz; 0: every physics step), at most the physics' own."""
    return min(rate or step_rate, step_rate)


def _world_odom(body):
    """The root link's world pose and the chassis' twist in the base's heading (Gazebo's
    skid steer: the world velocity turned by the yaw; angular z of the world)."""
    position, orientation = body.footprint_pose()
    linear, angular = body.velocity()
    yaw = kinematics.yaw_from_quat(orientation)
    c, s = math.cos(yaw), math.sin(yaw)
    return (position, orientation, (c * linear[0] + s * linear[1],
                                    c * linear[1] - s * linear[0], 0.0),
            (0.0, 0.0, angular[2]))


class SkidSteerDrive:
    """libgazebo_ros_skid_steer_drive: four wheels, each side at one speed, no ramp; stopped,
    the wheels are braked (RobotBody.brake, as the diff drive's)."""

    def __init__(self, plugin: SkidSteerPlugin):
        self.plugin = plugin
        self.wheels = (plugin.wheel_joints, plugin.torque, SIDES, ())
        self.joint_names = ()
        self.controller = SkidSteerController(plugin.wheel_separation,
                                              plugin.wheel_diameter / 2.0)

    def control_rate(self, step_rate: float) -> float:
        return _every(self.plugin.update_rate, step_rate)

    def odom_rate(self, step_rate: float) -> float:
        return self.control_rate(step_rate)

    def reset(self) -> None:
        self.controller.reset()

    def set_command(self, x: float, y: float, yaw_rate: float, now: float) -> None:
        self.controller.set_command(x, yaw_rate)

    def tick(self, body, now: float, dt: float) -> None:
        if self.controller.stopped:
            body.brake()
        else:
            body.set_wheel_velocities(*self.controller.update(dt))

    def odom_tick(self, body, now: float) -> None:
        pass

    def odom(self, body):
        return _world_odom(body)


class PlanarMoveDrive:
    """libgazebo_ros_planar_move: the base's velocity set at every physics step."""

    def __init__(self, plugin: PlanarMovePlugin):
        self.plugin = plugin
        self.wheels = ((), 0.0, None, ())
        self.joint_names = ()
        self.controller = PlanarMoveController(plugin.cmd_timeout)
        self.odometry = PoseOdometry()

    def control_rate(self, step_rate: float) -> float:
        return step_rate

    def odom_rate(self, step_rate: float) -> float:
        rate = self.plugin.odometry_rate
        return min(rate, step_rate) if rate > 0 else 0.0

    def reset(self) -> None:
        self.controller.reset()
        self.odometry.reset()

    def set_command(self, x: float, y: float, yaw_rate: float, now: float) -> None:
        self.controller.set_command(x, y, yaw_rate, now)

    def tick(self, body, now: float, dt: float) -> None:
        _, orientation = body.footprint_pose()
        yaw = kinematics.yaw_from_quat(orientation)
        body.set_velocity(*world_velocity(*self.controller.command(now), yaw))

    def odom_tick(self, body, now: float) -> None:
        (x, y, _), orientation = body.footprint_pose()
        self.odometry.update(x, y, kinematics.yaw_from_quat(orientation), now,
                             self.controller.command(now)[2])

    def odom(self, body):
        position, orientation = body.footprint_pose()
        odometry = self.odometry
        return (position, orientation, (*odometry.linear, 0.0), (0.0, 0.0, odometry.angular))


class TricycleDrive:
    """libgazebo_ros_tricycle_drive: the actuated wheel's speed (braked when stopped) and the
    steering joint's angle (a position motor of the wheel torque: Gazebo sets the angle) or
    speed; odometry from the world, or from the encoder wheels (as the diff drive's encoders,
    REP 103's left and right)."""

    def __init__(self, plugin: TricyclePlugin):
        self.plugin = plugin
        self.wheels = ((plugin.actuated_wheel_joint,), plugin.wheel_torque, (0,),
                       (plugin.encoder_wheel_left_joint, plugin.encoder_wheel_right_joint))
        # publishWheelJointState: the plugin's four joints, in its order
        self.joint_names = ((plugin.steering_joint, plugin.actuated_wheel_joint,
                             plugin.encoder_wheel_left_joint, plugin.encoder_wheel_right_joint)
                            if plugin.publish_wheel_joint_state else ())
        self.controller = TricycleController(
            plugin.actuated_wheel_diameter / 2.0, plugin.wheel_acceleration,
            plugin.wheel_deceleration, plugin.wheel_speed_tolerance, plugin.steering_speed,
            plugin.steering_angle_tolerance)
        self.encoders = WheelOdometry(plugin.encoder_wheel_separation,
                                      plugin.encoder_wheel_diameter / 2.0)
        self._last_odom: Optional[float] = None

    def control_rate(self, step_rate: float) -> float:
        return _every(self.plugin.update_rate, step_rate)

    def odom_rate(self, step_rate: float) -> float:
        return self.control_rate(step_rate)

    def reset(self) -> None:
        self.controller.reset()
        self.encoders.reset()
        self._last_odom = None

    def set_command(self, x: float, y: float, yaw_rate: float, now: float) -> None:
        self.controller.set_command(x, yaw_rate)

    def tick(self, body, now: float, dt: float) -> None:
        plugin, controller = self.plugin, self.controller
        speed = controller.wheel_speed(body.joint_state(plugin.actuated_wheel_joint)[1], dt)
        if controller.stopped and speed == 0.0:
            body.brake()
        else:
            body.set_wheel_velocities(speed, speed)
        angle, rate = controller.steering(body.joint_state(plugin.steering_joint)[0])
        if angle is not None:
            body.steer(plugin.steering_joint, angle, plugin.wheel_torque)
        else:
            body.set_joint_speed(plugin.steering_joint, rate, plugin.wheel_torque)

    def odom_tick(self, body, now: float) -> None:
        if self.plugin.odometry_source == "encoders":
            left = body.joint_state(self.plugin.encoder_wheel_left_joint)[0]
            right = body.joint_state(self.plugin.encoder_wheel_right_joint)[0]
            dt = 0.0 if self._last_odom is None else now - self._last_odom
            self.encoders.update(left, right, dt)
            self._last_odom = now

    def odom(self, body):
        if self.plugin.odometry_source != "encoders":
            return _world_odom(body)
        e = self.encoders
        return ((e.x, e.y, 0.0), kinematics.quat_from_yaw(e.yaw), (e.linear, 0.0, 0.0),
                (0.0, 0.0, e.angular))


class ForceBasedMoveDrive:
    """libgazebo_ros_force_based_move: at every physics step, a force and a torque on the
    chassis toward the commanded velocity (devices.force_based_move.push)."""

    def __init__(self, plugin: ForceBasedMovePlugin):
        self.plugin = plugin
        self.wheels = ((), 0.0, None, ())
        self.joint_names = ()
        self.command = (0.0, 0.0, 0.0)
        self._inertia: Optional[tuple] = None   # (kg, kg m^2), read at the first tick

    def control_rate(self, step_rate: float) -> float:
        return step_rate

    def odom_rate(self, step_rate: float) -> float:
        rate = self.plugin.odometry_rate
        return min(rate, step_rate) if rate > 0 else 0.0

    def reset(self) -> None:
        self.command = (0.0, 0.0, 0.0)

    def set_command(self, x: float, y: float, yaw_rate: float, now: float) -> None:
        self.command = (x, y, yaw_rate)

    def tick(self, body, now: float, dt: float) -> None:
        if self._inertia is None:
            self._inertia = body.mass_and_yaw_inertia()
        plugin = self.plugin
        _, orientation = body.footprint_pose()
        linear, angular = body.velocity()
        yaw = kinematics.yaw_from_quat(orientation)
        c, s = math.cos(yaw), math.sin(yaw)
        in_base = (c * linear[0] + s * linear[1], c * linear[1] - s * linear[0])
        fx, fy, torque = push(self.command, in_base, angular[2],
                              (plugin.x_velocity_p_gain, plugin.y_velocity_p_gain,
                               plugin.yaw_velocity_p_gain), *self._inertia, dt)
        body.push((c * fx - s * fy, s * fx + c * fy, 0.0), (0.0, 0.0, torque))

    def odom_tick(self, body, now: float) -> None:
        pass

    def odom(self, body):
        """The world pose; the twist's linear.x and angular.z (the plugin's two)."""
        position, orientation, linear, angular = _world_odom(body)
        return position, orientation, (linear[0], 0.0, 0.0), angular


DRIVES = {SkidSteerPlugin: SkidSteerDrive, PlanarMovePlugin: PlanarMoveDrive,
          TricyclePlugin: TricycleDrive, ForceBasedMovePlugin: ForceBasedMoveDrive}


def make_drive(plugin) -> Optional[object]:
    """The drive of a drive plugin's data; None for the diff drive (or none)."""
    kind = DRIVES.get(type(plugin))
    return kind(plugin) if kind else None
