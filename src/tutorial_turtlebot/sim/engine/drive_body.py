"""The body a drive of world.robot_drives moves when it sits on a model built from SDF (a world
file's or a spawned one): the calls robot_drives makes on a RobotBody (``footprint_pose``,
``velocity``, ``set_wheel_velocities``, ``brake``, ``joint_state``, ``steer``,
``set_joint_speed``, ``set_velocity``, ``push``, ``mass_and_yaw_inertia``), made on the model's
canonical body (``base``, a bodies.Body: a lone link's rigid body or a multibody of joined
links, engine.movable_bodies) and on its joints found by name.

The drive's reference frame is the model frame (``in_model``: the base's frame in it), as
Gazebo's drives read the model's pose. The wheels' friction is the SDF's (their collisions'
<surface>), not a robot's. Units: m, s, rad, kg, N, N*m. Quaternions (x, y, z, w).
"""
from typing import Mapping, Optional, Sequence, Tuple

from . import collision_filters
from .bodies import Body, moment_about_z
from .bullet import pybullet
from .robot_body import BRAKE_MOVED, BRAKE_POSITION_GAIN

Pose = Tuple[Tuple[float, float, float], Tuple[float, float, float, float]]
JointRef = Tuple[Body, int]      # (body, joint index)


class DriveBody:
    """robot_drives' body interface on an SDF model's bodies."""

    def __init__(self, base: Body, in_model: Pose, joints: Mapping[str, JointRef],
                 wheel_joints: Sequence[str] = (), wheel_torque: float = 0.0,
                 wheel_sides: Optional[Sequence[int]] = None, free_wheels: Sequence[str] = ()):
        """``base``: the model's canonical body, whose base frame is at ``in_model`` in the
        model frame; ``joints``: the model's movable joints by name (KeyError for a wheel the
        model does not simulate); the wheels as RobotBody takes them (``free_wheels``, with
        no motor, turn freely already: an SDF joint's motor is its friction)."""
        self.base = base
        self.joints = dict(joints)
        self.wheels = tuple(self.joints[name] for name in wheel_joints)
        missing = [name for name in free_wheels if name not in self.joints]
        if missing:
            raise KeyError(missing[0])
        self.wheel_torque = wheel_torque
        self._sides = tuple(wheel_sides) if wheel_sides is not None else (0, 1)
        self._base_in_model = in_model[1]
        self._model_in_base = pybullet.invertTransform(*in_model)
        self._held: Optional[Tuple[float, ...]] = None   # wheel angles the brake holds
        self._anchored: Optional[bool] = None           # unknown: set at the first call

    # --- the model's state ----------------------------------------------------------------------

    def footprint_pose(self) -> Pose:
        """World pose of the model frame."""
        position, orientation = pybullet.multiplyTransforms(*self.base.pose(),
                                                            *self._model_in_base)
        return tuple(position), tuple(orientation)

    def velocity(self):
        """World-frame (linear m/s of the base's centre of mass, angular rad/s)."""
        return self.base.twist()

    def joint_state(self, name: str) -> Tuple[float, float]:
        """(angle rad or m, rate rad/s or m/s) of joint ``name``."""
        body, index = self.joints[name]
        return body.joint_state(index)

    def mass_and_yaw_inertia(self) -> Tuple[float, float]:
        """(kg of every link of the base's body, kg m^2 of the base about the model frame's z
        axis through its centre of mass: the base's frame is along its principal axes)."""
        base = self.base
        mass = sum(base.inertial(link).mass for link in range(-1, base.joint_count()))
        return mass, moment_about_z(base.inertial(-1).moments, self._base_in_model)

    # --- commands -------------------------------------------------------------------------------

    def set_wheel_velocities(self, left: float, right: float) -> None:
        """Wheel velocity targets in rad/s (each wheel its side's), reached with at most the
        wheel torque; releases the brake."""
        if self.wheels:
            self._held = None
            self._anchor_wheels(False)
            speeds = (left, right)
            for (body, index), side in zip(self.wheels, self._sides):
                body.set_joint_motor(index, speeds[side], self.wheel_torque)

    def brake(self) -> None:
        """Hold the wheels at the angles where they stopped (a position motor of at most the
        wheel torque) and anchor their contacts, as RobotBody.brake does (its docstring
        says why a velocity target of 0 creeps); call it at every control tick while
        stopped."""
        if not self.wheels:
            return
        angles = tuple(body.joint_state(index)[0] for body, index in self.wheels)
        if self._held is None or any(abs(a - h) > BRAKE_MOVED
                                     for a, h in zip(angles, self._held)):
            self._held = angles
            for (body, index), angle in zip(self.wheels, angles):
                body.set_joint_target(index, angle, self.wheel_torque, BRAKE_POSITION_GAIN)
        self._anchor_wheels(True)

    def _anchor_wheels(self, anchored: bool) -> None:
        """Anchor the wheels' contacts, or not; anchoring renews them (their filter set again,
        as it is), as RobotBody's brake does."""
        if anchored == self._anchored:
            return
        for body, index in self.wheels:
            client = body.client
            client.changeDynamics(body.uid, index, frictionAnchor=int(anchored))
            group_mask = collision_filters.colliders(client).get((body.uid, index))
            if anchored and group_mask is not None:
                collision_filters.set_filter(client, body.uid, index, *group_mask)
        self._anchored = anchored

    def steer(self, name: str, angle: float, torque: float) -> None:
        """Drive joint ``name`` to ``angle`` (rad) with at most ``torque`` N*m."""
        body, index = self.joints[name]
        body.set_joint_target(index, angle, torque)

    def set_joint_speed(self, name: str, rate: float, torque: float) -> None:
        """Drive joint ``name`` at ``rate`` (rad/s) with at most ``torque`` N*m."""
        body, index = self.joints[name]
        body.set_joint_motor(index, rate, torque)

    def set_velocity(self, linear, angular) -> None:
        """Set the base's world-frame velocity (m/s, rad/s): a planar move's."""
        self.base.set_twist((tuple(linear), tuple(angular)))

    def push(self, force, torque) -> None:
        """Apply a world-frame ``force`` (N) at the base's centre of mass and a world-frame
        ``torque`` (N*m) to it during the next step (pybullet clears them after it)."""
        base = self.base
        position, _ = base.pose()
        base.client.applyExternalForce(base.uid, -1, tuple(force), tuple(position),
                                       pybullet.WORLD_FRAME)
        base.client.applyExternalTorque(base.uid, -1, tuple(torque), pybullet.WORLD_FRAME)
