"""The drives of SDF models (a world file's or a spawned one's <plugin>), running: each a
RunningPlugin of world.model_plugins, ticked at its control rate, commanded as cmd_vel commands
it (``command(linear, angular, lateral)``: linear.x, angular.z, linear.y) and read as its
odometry topic publishes it (``odometry()``: odometryFrame -> robotBaseFrame).

``DiffDriveRunner`` is gazebo_ros_diff_drive's; ``DriveRunner`` runs every other drive of the
plugin table (skid steer, planar move, tricycle, force-based move) with the very classes a
URDF robot's SimRobot runs (world.robot_drives), on the model's body (engine.drive_body
.DriveBody: its canonical body, its joints by name). ``odometry_due`` says whether the last
tick was an odometry tick; ``joint_names`` the joints whose states it publishes. Knows nothing
of ROS. Frames: world (z up); the odometry's twist in the base frame. Units: m, s, rad, N*m.
"""
import math
import operator
from typing import List, Optional, Tuple

import numpy as np

from .. import kinematics
from ..devices.diff_drive import (SAFE_ANGULAR, SAFE_LINEAR, DiffDriveController,
                                  sanitize_command)
from ..devices.wheel_odometry import WheelOdometry
from ..engine.drive_body import DriveBody
from ..files.plugins.gazebo_ros_diff_drive import ModelDiffDrive
from .plugin_runner import NS_PER_S, Odometry, RunningPlugin, find_joints, movable_joints
from .robot_drives import DRIVES, make_drive
from .schedule import RateSchedule


class DiffDriveRunner(RunningPlugin):
    """gazebo_ros_diff_drive on an SDF model, as a robot's (SimRobot) runs it: at each tick of
    <updateRate> the command's rim speeds ramped by <wheelAcceleration> (devices.diff_drive)
    become the <leftJoint>/<rightJoint> motors' targets (rad/s, at most <wheelTorque> N*m); a
    command is held until the next. Odometry (odometrySource world) is the model frame's
    pose in the world, the twist in the model frame; encoder odometry is integrated from the
    wheel angles at each tick, from (0, 0, 0)."""

    kind = "diff_drive"

    def __init__(self, spec: ModelDiffDrive, *args, **kwargs):
        super().__init__(spec, *args, **kwargs)
        self.drive = DiffDriveController(spec.wheel_separation, spec.wheel_radius,
                                         spec.wheel_acceleration)
        self.encoders = WheelOdometry(spec.wheel_separation, spec.wheel_radius)
        self._wheels: Tuple[List[object], List[Tuple[object, int]]] = ([], [])
        self.restart()

    def restart(self) -> None:
        self.drive.reset()
        self.encoders.reset()
        self._last_ns: Optional[int] = None

    publishes_odometry = property(lambda self: self.spec.publish_tf)   # false: none at all
    odometry_due = True            # at each of its ticks
    joint_names: Tuple[str, ...] = ()

    def command(self, linear: float, angular: float, lateral: float = 0.0) -> List[str]:
        """A new cmd_vel (linear.x m/s, angular.z rad/s; linear.y, which the diff drive does
        not read), held until the next: NaN or inf raise ValueError; beyond SAFE_LINEAR /
        SAFE_ANGULAR clamped, the problems returned."""
        linear, angular, problems = sanitize_command(linear, angular, SAFE_LINEAR,
                                                     SAFE_ANGULAR)
        self.drive.set_command(linear, angular)
        return problems

    def wheels(self) -> List[Tuple[object, int]]:
        """(body, joint index) of the left and right wheel joints (found again when the
        model's bodies change: a rebuild); none where they are not simulated (a static
        model's: it does not move)."""
        bodies = [p.body for p in self.model.parts]
        if len(bodies) != len(self._wheels[0]) or any(map(operator.is_not, bodies,
                                                          self._wheels[0])):
            try:
                found = find_joints(self.model, (self.spec.left_joint, self.spec.right_joint))
            except KeyError:
                found = []
            self._wheels = (bodies, found)
        return self._wheels[1]

    def tick(self, now_ns: int) -> None:
        spec: ModelDiffDrive = self.spec
        wheels = self.wheels()
        rates = self.drive.update(1.0 / self.schedule.rate_hz)
        for (body, index), rate in zip(wheels, rates):
            body.set_joint_motor(index, rate, spec.wheel_torque)
        if spec.odometry_source == "encoders" and wheels:
            left, right = (body.joint_state(index)[0] for body, index in wheels)
            dt = 0.0 if self._last_ns is None else (now_ns - self._last_ns) / NS_PER_S
            self.encoders.update(left, right, dt)
            self._last_ns = now_ns

    def odometry(self) -> Odometry:
        """odom -> robotBaseFrame: position (m), orientation (x y z w), twist in the base
        frame (m/s, rad/s: linear x and y, angular z); variance 0 (the topic's covariance is
        the plugin's fixed one)."""
        if self.spec.odometry_source == "encoders":
            e = self.encoders
            return Odometry((e.x, e.y, 0.0), kinematics.quat_from_yaw(e.yaw),
                            (e.linear, 0.0, 0.0), (0.0, 0.0, e.angular), 0.0)
        position, orientation = self.model.pose()
        linear, angular = self.model.twist()
        part = next((p for p in self.model.parts if p.movable), None)
        if part is not None:     # the model frame's velocity, not its body's centre's
            lever = np.subtract(position, part.body.pose()[0])
            linear = tuple(np.add(linear, np.cross(angular, lever)))
        yaw = kinematics.yaw_from_quat(orientation)
        c, s = math.cos(yaw), math.sin(yaw)
        return Odometry(tuple(float(v) for v in position), tuple(orientation),
                        (float(c * linear[0] + s * linear[1]),
                         float(c * linear[1] - s * linear[0]), 0.0),
                        (0.0, 0.0, float(angular[2])), 0.0)


class DriveRunner(RunningPlugin):
    """A drive of robot_drives on an SDF model, as a robot's SimRobot runs it: its control at
    each tick (``drive.control_rate``: <updateRate>, or every physics step), its odometry
    read at each odometry tick (``drive.odom_rate``; 0: none at all). Its body is found
    again when the model's bodies change (a rebuild); a model that simulates none of its
    body or wheels (a static one) does not move and has no odometry."""

    kind = "drive"

    def __init__(self, spec, model, namespace: str, step_rate: float, *args, **kwargs):
        self.drive = make_drive(spec)
        super().__init__(spec, model, namespace, step_rate, *args, **kwargs)
        odom_rate = self.drive.odom_rate(step_rate)
        self.odometry_schedule = RateSchedule(odom_rate) if odom_rate > 0 else None
        self.joint_names: Tuple[str, ...] = tuple(self.drive.joint_names)
        self._body: Tuple[List[object], Optional[DriveBody]] = ([], None)
        self.restart()

    def rate(self, step_rate: float) -> float:
        return self.drive.control_rate(step_rate)

    @property
    def publishes_odometry(self) -> bool:
        return self.odometry_schedule is not None

    def restart(self) -> None:
        self.drive.reset()
        self._body = ([], None)        # the brake's held angles go with it
        self._odometry_from: Optional[int] = None
        self._now_ns = 0
        self.odometry_due = False

    def command(self, linear: float, angular: float, lateral: float = 0.0) -> List[str]:
        """A new cmd_vel (linear.x, linear.y m/s, angular.z rad/s), as SimRobot.command takes
        it: NaN or inf raise ValueError; beyond SAFE_LINEAR / SAFE_ANGULAR clamped, the
        problems returned."""
        linear, angular, problems = sanitize_command(linear, angular, SAFE_LINEAR,
                                                     SAFE_ANGULAR)
        lateral, _, more = sanitize_command(lateral, 0.0, SAFE_LINEAR, SAFE_ANGULAR)
        problems += [p.replace("linear.x", "linear.y") for p in more]
        self.drive.set_command(linear, lateral, angular, self._now_ns / NS_PER_S)
        return problems

    def body(self) -> Optional[DriveBody]:
        """The drive's body now (None: the model simulates not its body or not every joint
        the drive moves or reads)."""
        bodies = [p.body for p in self.model.parts]
        if len(bodies) != len(self._body[0]) or any(map(operator.is_not, bodies,
                                                        self._body[0])):
            part = next((p for p in self.model.parts if p.movable), None)
            found = None
            if part is not None:
                try:
                    found = DriveBody(part.body, part.in_model, movable_joints(self.model),
                                      *self.drive.wheels)
                    if any(name not in found.joints for name in self.joint_names):
                        found = None       # a joint whose state it publishes
                except KeyError:
                    found = None
            self._body = (bodies, found)
        return self._body[1]

    def tick(self, now_ns: int) -> None:
        self._now_ns = now_ns
        body = self.body()
        self.odometry_due = False
        if body is None:
            return
        now = now_ns / NS_PER_S
        self.drive.tick(body, now, 1.0 / self.schedule.rate_hz)
        if self.odometry_schedule is not None:
            if self._odometry_from is None:
                self.odometry_schedule.reset(now_ns)
                self._odometry_from = now_ns
            self.odometry_due = self.odometry_schedule.due(now_ns)
        if self.odometry_due:
            self.drive.odom_tick(body, now)

    def odometry(self) -> Odometry:
        """odom -> robotBaseFrame as the drive reports it (robot_drives' ``odom``): position
        (m), orientation (x y z w), twist in the base frame; variance 0 (the topic's pose
        covariance is the plugin's)."""
        position, orientation, linear, angular = self.drive.odom(self.body())
        return Odometry(tuple(float(v) for v in position), tuple(orientation),
                        tuple(float(v) for v in linear), tuple(float(v) for v in angular), 0.0)

    def joint_states(self) -> Tuple[Tuple[str, ...], List[float], List[float]]:
        """(``joint_names``, positions rad, velocities rad/s) now (0 where the model does not
        simulate them)."""
        body = self.body()
        states = [body.joint_state(name) if body is not None else (0.0, 0.0)
                  for name in self.joint_names]
        return (self.joint_names, [float(s[0]) for s in states],
                [float(s[1]) for s in states])


# the drives' data -> their runner on an SDF model
RUNNERS = ((ModelDiffDrive, DiffDriveRunner),) + tuple((kind, DriveRunner) for kind in DRIVES)
