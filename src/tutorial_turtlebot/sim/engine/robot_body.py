"""One robot URDF built into a WorldPhysics: its pose, velocity, wheels and frames. Knows nothing
of ROS.

The robot's body is built as every model's is: its URDF converted into the SDF model Gazebo
makes of it (files/urdf/urdf_to_sdf: fixed joints lumped, inertias merged as Gazebo merges
them), whose links, joints and shapes movable_bodies builds (``model_body``: the base framed at
its centre of mass along its principal axes of inertia; each wheel a true cylinder).
``RobotBody`` is built on a ``bodies.Body`` (``body``, a new one after ``rebuild``): the robot's
base, joints and removal are the Body's; what is the robot's own is here: its collision group
bit, its wheels' friction, motors and brake, and its root link's frames. A robot's reference
frame is its root link (``base_footprint`` on a TurtleBot3: on the floor between the wheels, x
forward). pybullet places a body by its base frame, so every pose here is converted to and
from the root link. Units: m, s, rad, kg, N*m. Quaternions (x, y, z, w).
"""
import hashlib
from typing import Dict, List, Optional, Sequence, Tuple

import numpy as np

from . import collision_filters
from .bodies import Body, moment_about_z
from .bullet import pybullet
from ...errors import UserError
from .movable_bodies import model_base_frame, model_body
from ..kinematics import Pose
from ..files.sdf.world_sdf import load_model_xml
from ..files.urdf.urdf_file import RobotDescription
from ..files.urdf.urdf_to_sdf import urdf_to_sdf
from ..files.world_types import World
from .physics import ROBOT_GROUPS, WorldPhysics
from .collision_groups import ALL_COLLISION_GROUPS, WORLD_COLLISION_GROUP

# Tyre on floor (pybullet multiplies the two surfaces' values; the floor's is 1): enough grip
# for the 1 m/s^2 ramp with margin, little enough that a robot pushing a wall spins its wheels
# instead of climbing it (at 1.0 a Burger pressed into a corner reared up by 0.37 rad).
WHEEL_FRICTION = 0.5
BODY_FRICTION = 0.0              # chassis and caster skids slide freely
# The brake of an idle robot (RobotBody.brake): its wheels held at the angles where they stopped
# (a position motor of at most the wheel torque, pybullet's default positionGain) and their
# floor contacts anchored. A wheel found this far (rad) from its held angle was turned by
# someone else (set_model_configuration): it is held where it is now.
BRAKE_POSITION_GAIN = 0.1
BRAKE_MOVED = 0.5
SPAWN_CLEARANCE = 0.001          # m: drop the robot from just above the floor


class RobotBody:
    """One robot URDF in a WorldPhysics: its pose, velocity, wheels and frames."""

    def __init__(self, physics: WorldPhysics, description: RobotDescription, spawn_pose: Pose,
                 wheel_joints: Sequence[str] = (), wheel_torque: float = 0.0,
                 wheel_sides: Optional[Sequence[int]] = None, free_wheels: Sequence[str] = ()):
        """``spawn_pose``: the root link's world pose; ``wheel_joints``: (left, right) joint
        names driven by velocity with at most ``wheel_torque`` N*m, or () for none; more wheels
        (a skid steer's four, a tricycle's one) with ``wheel_sides``, each wheel's side: 0 turns
        at the left speed, 1 at the right (default: (0, 1)); ``free_wheels``: wheel joints
        with the tyres' grip and no motor (a tricycle's encoder wheels)."""
        self.physics = physics
        self.client = physics.client      # engine.client.Client
        self.description = description
        self.wheel_torque = wheel_torque
        self.collision_bit = physics.take_robot_bit()
        # rays of this robot's sensors: the world and every other robot
        self.ray_mask = (WORLD_COLLISION_GROUP | ROBOT_GROUPS) & ~self.collision_bit
        try:
            self.body = Body(self.client, self._load(description))
        except Exception:
            physics.give_back_robot_bit(self.collision_bit)
            raise
        self._footprint_in_com = pybullet.invertTransform(*self.com_in_root)
        try:
            self.wheels = self._wheel_indices(wheel_joints)
            self._free = self._wheel_indices(free_wheels)
        except UserError:
            self.remove()
            raise
        self._gripping = self.wheels + self._free
        self._free_wheels()
        self._sides = tuple(wheel_sides) if wheel_sides is not None else (0, 1)
        self._held: Optional[Tuple[float, float]] = None  # wheel angles the brake holds
        self._anchored = False
        self._frames: Dict[str, np.ndarray] = {}
        (x, y, z), orn = spawn_pose
        self.spawn_pose: Pose = ((x, y, z + SPAWN_CLEARANCE), tuple(orn))
        self.reset_robot()

    def _load(self, description: Optional[RobotDescription] = None) -> int:
        """Build the description's body (its SDF model kept for rebuild), or again that
        model's; a deleted robot's body of the same model is reused (body_pool)."""
        client = self.client
        if description is not None:
            # model: the World of the robot's SDF model; notes: what its conversion left out;
            # root_link: the link at the base of the body; com_in_root: the base's frame in it
            self.model, self.notes = robot_model(description)
            root, base = model_base_frame(self.model)
            self.root_link = root.split("::", 1)[1]
            self.com_in_root: Pose = (tuple(base[0]), tuple(base[1]))
            self._key = ("robot", hashlib.sha256(repr(
                (self.model.model_specs, self.model.shapes)).encode("utf-8")).hexdigest())
        pool = self.physics.body_pool
        parked = pool.take(self._pool_key())
        if parked:
            robot = parked[0]
        else:
            robot = model_body(self.model, client)
            pool.remember([robot])
        for link in range(-1, client.getNumJoints(robot)):
            collision_filters.set_filter(client, robot, link, self.collision_bit,
                                         ALL_COLLISION_GROUPS)
            client.changeDynamics(robot, link, lateralFriction=BODY_FRICTION,
                                  spinningFriction=0.0, rollingFriction=0.0, restitution=0.0,
                                  linearDamping=0.0, angularDamping=0.0,
                                  activationState=pybullet.ACTIVATION_STATE_DISABLE_SLEEPING)
        return robot

    @property
    def robot(self) -> int:
        """The pybullet id of the robot's body (``body.uid``)."""
        return self.body.uid

    def _pool_key(self) -> tuple:
        """The BodyPool key of this robot's body: the digest of the model it was built from."""
        return self._key

    def _wheel_indices(self, names: Sequence[str]) -> Tuple[int, ...]:
        client = self.client
        by_name: Dict[str, int] = {}
        for joint in self.body.joints():
            by_name.setdefault(joint.name, joint.index)
        self._joints = by_name
        for name in names:
            if name not in by_name:
                raise UserError("%s: joint %r is not simulated: it moves a link without mass, "
                                "which Gazebo leaves out" % (self.description.path, name))
        wheels = tuple(by_name[name] for name in names)
        for j in wheels:
            client.changeDynamics(self.robot, j, lateralFriction=WHEEL_FRICTION)
        return wheels

    def _free_wheels(self) -> None:
        """The free wheels turn freely: pybullet's default motor (velocity 0) off."""
        if self._free:
            self.client.setJointMotorControlArray(self.robot, self._free,
                                                  pybullet.VELOCITY_CONTROL,
                                                  forces=(0.0,) * len(self._free))

    # --- commands ------------------------------------------------------------------------------

    def set_wheel_velocities(self, left: float, right: float) -> None:
        """Joint velocity targets in rad/s, reached with at most the wheel torque; releases
        the brake."""
        if self.wheels:
            self._held = None
            self._anchor_wheels(False)
            speeds = (left, right)
            self.client.setJointMotorControlArray(
                self.robot, self.wheels, pybullet.VELOCITY_CONTROL,
                targetVelocities=tuple(speeds[side] for side in self._sides),
                forces=(self.wheel_torque,) * len(self.wheels))

    def brake(self) -> None:
        """Keep an idle robot where it is, as Gazebo's diff drive (wheel velocity 0 with the
        wheel torque) and ODE's static friction do; call it on every control tick while the
        drive is stopped (set_wheel_velocities releases it).

        A velocity target of 0 is not enough here: in a step's 20 solver iterations pybullet
        does not reconcile the motor of a light wheel (I/r^2 ~ 0.02 kg) with the ~1 kg
        chassis through the tyre's friction, and leaves the wheels rolling at ~0.008 rad/s
        whatever the torque (a Burger crept 15 cm in 10 minutes; 200 iterations without the
        solver's early exit hold it). Nothing takes that back, a velocity target has no
        memory. So the brake
        holds each wheel at the angle where it stopped (a position target, at most the wheel
        torque): the solver's error now stays an error of angle and is corrected. Held wheels
        still let the tyres' contacts creep (a Burger turned 8 mrad in 10 minutes), so the
        brake also anchors them (Bullet's friction anchors: within the friction cone a
        contact keeps its points and the solver corrects their drift; beyond it, it slides).
        Anchors alone would not do: a rolling wheel drags its anchor along.
        """
        if not self.wheels:
            return
        angles, _ = self.wheel_states()
        if self._held is None or any(abs(a - h) > BRAKE_MOVED
                                     for a, h in zip(angles, self._held)):
            self._held = angles
            self.client.setJointMotorControlArray(
                self.robot, self.wheels, pybullet.POSITION_CONTROL, targetPositions=angles,
                targetVelocities=(0.0,) * len(angles),
                forces=(self.wheel_torque,) * len(angles),
                positionGains=(BRAKE_POSITION_GAIN,) * len(angles),
                velocityGains=(1.0,) * len(angles))
        self._anchor_wheels(True)

    def _anchor_wheels(self, anchored: bool) -> None:
        """Anchor the tyres' contacts, or not. A contact made unanchored keeps its points
        unanchored while it holds (a robot stopped after driving kept creeping), so anchoring
        renews the tyres' contacts, and with them those a teleport or reset left behind:
        setting a link's collision filter (to what it is) drops its contacts in pybullet,
        and the next step makes them afresh."""
        if anchored != self._anchored:
            client = self.client
            for j in self.wheels:
                client.changeDynamics(self.robot, j, frictionAnchor=int(anchored))
                if anchored:
                    collision_filters.set_filter(client, self.robot, j, self.collision_bit,
                                                 ALL_COLLISION_GROUPS)
            self._anchored = anchored

    def reset_robot(self) -> None:
        """Put the robot back at its spawn pose, at rest, every joint at angle 0."""
        self.place(self.spawn_pose)
        self.body.zero_joints()
        # Velocity 0 with the wheel torque (brake released: its held angles are gone) until
        # the drive's next control tick brakes.
        self.restart_wheels()

    def restart_wheels(self) -> None:
        """The wheels' motors as ``reset_robot`` leaves them, for a body whose state was
        restored (WorldPhysics.restore_state): velocity 0 with the wheel torque, brake off."""
        self.set_wheel_velocities(0.0, 0.0)

    def place(self, pose: Pose) -> None:
        """Put the root link at world ``pose``, at rest."""
        self.body.set_pose(pybullet.multiplyTransforms(*pose, *self.com_in_root))
        self.body.set_twist(((0, 0, 0), (0, 0, 0)))

    def rebuild(self) -> None:
        """Replace the robot's body by a new one loaded from the same URDF, at its spawn pose
        (a body whose state went NaN cannot be repaired in place: world_models.sound)."""
        old = self.body
        self.body = Body(self.client, self._load())
        old.remove()
        for j in self._gripping:
            self.client.changeDynamics(self.robot, j, lateralFriction=WHEEL_FRICTION)
        self._free_wheels()
        self._held, self._anchored = None, False
        self.reset_robot()

    def remove(self) -> None:
        """Take the robot out of the world (parked for reuse: body_pool.BodyPool)."""
        pool = self.physics.body_pool
        if not pool.park(self._pool_key(), [self.robot]):
            self.body.remove()
            pool.forget([self.robot])
        self.physics.give_back_robot_bit(self.collision_bit)

    # --- state -----------------------------------------------------------------------------------

    def footprint_pose(self) -> Pose:
        """World pose of the root link (base_footprint): ((x, y, z), (qx, qy, qz, qw))."""
        return pybullet.multiplyTransforms(*self.body.pose(), *self._footprint_in_com)

    def velocity(self) -> Tuple[Tuple[float, float, float], Tuple[float, float, float]]:
        """World-frame (linear m/s of the centre of mass, angular rad/s) of the chassis."""
        return self.body.twist()

    def wheel_states(self) -> Tuple[Tuple[float, ...], Tuple[float, ...]]:
        """((left, right) joint angles in rad, (left, right) joint velocities in rad/s); of
        every wheel, in ``wheel_joints`` order, on a robot of more wheels."""
        states = self.client.getJointStates(self.robot, self.wheels)
        return tuple(s[0] for s in states), tuple(s[1] for s in states)

    def joint_index(self, name: str) -> int:
        """The pybullet index of the robot's joint ``name`` (a URDF joint the reader checked)."""
        return self._joints[name]

    def joint_state(self, name: str) -> Tuple[float, float]:
        """(angle rad or m, rate rad/s or m/s) of the robot's joint ``name``."""
        return self.body.joint_state(self.joint_index(name))

    def steer(self, name: str, angle: float, torque: float) -> None:
        """Drive joint ``name`` to ``angle`` (rad) with at most ``torque`` N*m (a tricycle's
        steering joint: Gazebo sets its position)."""
        self.client.setJointMotorControl2(self.robot, self.joint_index(name),
                                          pybullet.POSITION_CONTROL, targetPosition=angle,
                                          force=torque)

    def set_joint_speed(self, name: str, rate: float, torque: float) -> None:
        """Drive joint ``name`` at ``rate`` (rad/s) with at most ``torque`` N*m."""
        self.body.set_joint_motor(self.joint_index(name), rate, torque)

    def set_velocity(self, linear, angular) -> None:
        """Set the chassis' world-frame velocity (m/s, rad/s): a planar move's base."""
        self.body.set_twist((tuple(linear), tuple(angular)))

    def push(self, force, torque) -> None:
        """Apply a world-frame ``force`` (N) at the chassis' centre of mass and a world-frame
        ``torque`` (N*m) to it during the next step (pybullet clears them after it)."""
        position, _ = self.body.pose()
        self.client.applyExternalForce(self.robot, -1, tuple(force), tuple(position),
                                       pybullet.WORLD_FRAME)
        self.client.applyExternalTorque(self.robot, -1, tuple(torque), pybullet.WORLD_FRAME)

    def mass_and_yaw_inertia(self) -> Tuple[float, float]:
        """(kg of every link, kg m^2 of the chassis about the root link's z axis through its
        centre of mass)."""
        client = self.client
        mass = sum(client.getDynamicsInfo(self.robot, link)[0]
                   for link in range(-1, client.getNumJoints(self.robot)))
        moments = client.getDynamicsInfo(self.robot, -1)[2]
        return mass, moment_about_z(moments, self.com_in_root[1])

    def frame_in_footprint(self, frame: str) -> np.ndarray:
        """4x4 pose of a URDF frame (base_scan, imu_link, camera...) in the root link."""
        if frame not in self._frames:
            root = self.description.root_link
            self._frames[frame] = self.description.transform(root, frame)
        return self._frames[frame]

    def frame_pose(self, frame: str) -> Tuple[np.ndarray, np.ndarray]:
        """World (position, 3x3 rotation) of a URDF frame rigidly attached to the chassis."""
        return self.pose_in_world(self.frame_in_footprint(frame))

    def pose_in_world(self, in_root: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
        """World (position, 3x3 rotation) of a pose given as a 4x4 in the root link."""
        pos, orn = self.footprint_pose()
        rot = np.array(pybullet.getMatrixFromQuaternion(orn)).reshape(3, 3)
        return np.array(pos) + rot @ in_root[:3, 3], rot @ in_root[:3, :3]


def robot_model(description: RobotDescription) -> Tuple[World, List[str]]:
    """(the World of the one SDF model Gazebo makes of a robot's URDF (urdf_to_sdf), named
    after the robot, its root link at the origin; the conversion's warning lines). A lumped
    link's <sensor> pose is not among them: a robot's sensors are read from its URDF
    (robot_plugins), each at its own link and pose."""
    sdf, notes = urdf_to_sdf(description)
    world = load_model_xml(sdf, description.path, description.name)
    return world, [note for note in notes if "<sensor>" not in note]
