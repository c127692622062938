"""A pybullet body as the world above the engine sees it: poses, twists, links and joints.

``Body`` is a handle (engine.client.Client, body id) whose methods are the only pybullet calls
the world (world_models, world_control) needs; equal handles name the same body. Poses are
((x, y, z), (qx, qy, qz, qw)) in the world frame; twists ((vx, vy, vz), (wx, wy, wz)) in m/s and
rad/s, world frame. A link index of -1 is the base, whose frame is the body's centre of mass;
a jointed link's index is its joint's.

A joint's damping, stops and velocity motor may be changed after the build (set_joint_damping,
set_joint_stops, set_joint_motor: set_joint_properties); pybullet cannot tell them back, so
what was set is kept in the client (``Client.joints_set``) until the body is removed or
``restore_joints`` puts them back as built.
"""
import math
from typing import Any, Dict, List, NamedTuple, Tuple

import numpy as np

from . import collision_filters
from .bullet import pybullet
from .client import Client

Pose = Tuple[Tuple[float, float, float], Tuple[float, float, float, float]]
Twist = Tuple[Tuple[float, float, float], Tuple[float, float, float]]

NO_STOP = 1e30   # rad or m: a stop this far away is none (pybullet's stops come in pairs)
ONE_AXIS = ("revolute", "prismatic")   # the joints whose damping, stops and motor are set here

JOINT_KINDS = {pybullet.JOINT_REVOLUTE: "revolute", pybullet.JOINT_PRISMATIC: "prismatic",
               pybullet.JOINT_SPHERICAL: "ball", pybullet.JOINT_PLANAR: "planar",
               pybullet.JOINT_FIXED: "fixed"}


class Joint(NamedTuple):
    """One joint of a body: its index, name, kind ("revolute", "prismatic", "ball", "planar"
    or "fixed"), damping and the name of the link it moves."""

    index: int
    name: str
    kind: str
    damping: float
    child_link: str

    @property
    def movable(self) -> bool:
        return self.kind != "fixed"


class BuiltJoint(NamedTuple):
    """A joint as its body was built, where pybullet's getJointInfo cannot say it (a body
    built from SDF: movable_bodies): its name, its child link's name, damping (N m s/rad or
    N s/m), friction (N m or N: its motor's force at rest) and stops (rad or m; -NO_STOP,
    NO_STOP: none)."""

    name: str
    child_link: str
    damping: float = 0.0
    friction: float = 0.0
    lower: float = -NO_STOP
    upper: float = NO_STOP


class Inertial(NamedTuple):
    """A link's mass (kg), its centre of mass in the link's body frame (the base: in its own
    frame, the identity) and the principal moments of inertia (kg m^2) about that frame."""

    mass: float
    com: Pose
    moments: Tuple[float, float, float]


class Body:
    """One pybullet body of ``client``, body id ``uid``."""

    __slots__ = ("client", "uid")

    def __init__(self, client: Client, uid: int):
        self.client = client
        self.uid = uid

    def __eq__(self, other) -> bool:
        return isinstance(other, Body) and (other.client, other.uid) == (self.client, self.uid)

    def __hash__(self) -> int:
        return hash((self.client, self.uid))

    def __repr__(self) -> str:
        return "Body(%d, %d)" % (self.client.id, self.uid)

    # --- the base --------------------------------------------------------------------------------

    def pose(self) -> Pose:
        """World pose of the base (the centre of mass of a movable body)."""
        pos, orn = self.client.getBasePositionAndOrientation(self.uid)
        return tuple(pos), tuple(orn)

    def twist(self) -> Twist:
        """World twist of the base."""
        lin, ang = self.client.getBaseVelocity(self.uid)
        return tuple(lin), tuple(ang)

    def set_pose(self, pose: Pose) -> None:
        self.client.resetBasePositionAndOrientation(self.uid, pose[0], pose[1])

    def set_twist(self, twist: Twist) -> None:
        self.client.resetBaseVelocity(self.uid, twist[0], twist[1])

    # --- links and joints ------------------------------------------------------------------------

    def joints(self) -> List[Joint]:
        """Every joint, in index order (fixed ones too: a multibody's links)."""
        client = self.client
        built = client.built_joints.get(self.uid)     # a body built from SDF
        out = []
        for j in range(client.getNumJoints(self.uid)):
            info = client.getJointInfo(self.uid, j)
            name, child = built[j][:2] if built else (info[1].decode(), info[12].decode())
            out.append(Joint(j, name, JOINT_KINDS.get(info[2], "revolute"),
                             self._built(j)[0], child))
        return out

    def _built(self, index: int) -> Tuple[float, float, float, float]:
        """Joint ``index`` as built: (damping, friction, lower stop, upper stop); a side
        without a stop at -NO_STOP or NO_STOP."""
        built = self.client.built_joints.get(self.uid)
        if built:
            return built[index][2:]
        info = self.client.getJointInfo(self.uid, index)
        lower, upper = (info[8], info[9]) if info[8] <= info[9] else (-NO_STOP, NO_STOP)
        return float(info[6]), float(info[7]), float(lower), float(upper)

    def joint_count(self) -> int:
        return self.client.getNumJoints(self.uid)

    def joint_state(self, index: int) -> Tuple[float, float]:
        """(position rad or m, rate rad/s or m/s) of joint ``index``."""
        position, rate = self.client.getJointState(self.uid, index)[:2]
        return position, rate

    def set_joint(self, index: int, position: float, rate: float = 0.0) -> None:
        self.client.resetJointState(self.uid, index, position, rate)

    def zero_joints(self) -> None:
        """Every joint at 0, at rest."""
        for j in range(self.joint_count()):
            self.set_joint(j, 0.0, 0.0)

    def link_frame(self, index: int) -> Tuple[Pose, Twist]:
        """World pose of jointed link ``index``'s URDF frame, and the twist of that link."""
        state = self.client.getLinkState(self.uid, index, computeLinkVelocity=1)
        return ((tuple(state[4]), tuple(state[5])), (tuple(state[6]), tuple(state[7])))

    def link_com(self, index: int) -> Tuple[float, float, float]:
        """World position of the centre of mass of link ``index`` (-1: the base)."""
        if index < 0:
            return self.pose()[0]
        return tuple(self.client.getLinkState(self.uid, index)[0])

    def finite(self) -> bool:
        """Whether the base's pose and twist and every joint's state are finite numbers."""
        client = self.client
        pos, orn = client.getBasePositionAndOrientation(self.uid)
        lin, ang = client.getBaseVelocity(self.uid)
        values = list(pos) + list(orn) + list(lin) + list(ang)
        joints = range(client.getNumJoints(self.uid))
        for state in client.getJointStates(self.uid, joints) or ():
            values.extend(state[:2])
        return all(math.isfinite(v) for v in values)

    # --- mass ------------------------------------------------------------------------------------

    def inertial(self, index: int) -> Inertial:
        """Link ``index``'s mass, centre of mass (a jointed link: in its URDF frame) and
        principal moments."""
        info = self.client.getDynamicsInfo(self.uid, index)
        com = ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0)) if index < 0 \
            else (tuple(info[3]), tuple(info[4]))
        return Inertial(float(info[0]), com, tuple(float(v) for v in info[2]))

    def set_inertial(self, index: int, mass: float, moments: Tuple[float, float, float]) -> None:
        """Link ``index``'s mass (kg) and principal moments (kg m^2, its inertia axes)."""
        self.client.changeDynamics(self.uid, index, mass=float(mass),
                                   localInertiaDiagonal=tuple(float(v) for v in moments))

    def limit_joint_rate(self, index: int, rate: float) -> None:
        """At most ``rate`` (rad/s or m/s) at joint ``index``."""
        self.client.changeDynamics(self.uid, index, maxJointVelocity=rate)

    # --- joint properties set after the build (set_joint_properties) --------------------------

    def _joint_set(self, index: int, make: bool = False) -> Dict[str, Any]:
        """What was set of joint ``index`` since the build (a new record with ``make``)."""
        key = (self.uid, index)
        joints_set = self.client.joints_set
        if make and key not in joints_set:
            joints_set[key] = {}
        return joints_set.get(key, {})

    def joint_damping(self, index: int) -> float:
        """Joint ``index``'s viscous damping (N m s/rad or N s/m): as last set, else as built."""
        damping = self._joint_set(index).get("damping")
        return self._built(index)[0] if damping is None else damping

    def joint_stops(self, index: int) -> Tuple[float, float]:
        """Joint ``index``'s (lower, upper) stops, rad or m: as last set, else as built; a side
        without a stop is at -NO_STOP or NO_STOP."""
        stops = self._joint_set(index).get("stops")
        return stops if stops is not None else self._built(index)[2:]

    def joint_motor(self, index: int) -> Tuple[float, float]:
        """Joint ``index``'s velocity motor: (target rad/s or m/s, at most N m or N), as last
        set, else as built (still, held by its URDF friction)."""
        motor = self._joint_set(index).get("motor")
        return motor if motor is not None else (0.0, self._built(index)[1])

    def set_joint_damping(self, index: int, damping: float, longest_step: float) -> float:
        """Damp one-axis joint ``index`` with ``damping`` N m s/rad (N s/m); the damping
        simulated is returned. pybullet adds -damping x rate to the joint at each step (an
        explicit torque), which adds energy once one step takes out more than the joint's rate
        (a light wheel of damping 0.02 spun up to its speed limit); so the damping simulated
        is at most what stops the joint in one step of ``longest_step`` s: a stronger damping
        stops it within a step or a few, as Gazebo's implicit damping nearly does."""
        simulated = self.damp_joint(index, damping, longest_step)
        self._joint_set(index, make=True)["damping"] = float(damping)
        return simulated

    def damp_joint(self, index: int, damping: float, longest_step: float) -> float:
        """``set_joint_damping``'s damping of joint ``index``, as a body is built (not noted as
        set): the damping simulated."""
        inverse = self._inverse_inertia(index)
        simulated = float(damping)
        if inverse > 0:
            simulated = min(simulated, 1.0 / (longest_step * inverse))
        self.client.changeDynamics(self.uid, index, jointDamping=simulated)
        return simulated

    def _inverse_inertia(self, index: int) -> float:
        """How fast an effort turns joint ``index`` at its present configuration, 1/(kg m^2)
        or 1/kg: its diagonal entry of the inverse joint-space inertia (the base and the other
        joints free to move). Where pybullet cannot work that out, the link's own (1 / its
        smallest principal moment, or 1 / its mass); infinite for a massless link."""
        positions, dof = [], None
        for joint in self.joints():
            if joint.kind in ONE_AXIS:
                if joint.index == index:
                    dof = len(positions)
                positions.append(float(self.joint_state(joint.index)[0]))
            elif joint.movable:
                positions = None   # a ball or planar joint: more than one value each
                break
        if positions is not None and dof is not None:
            try:
                matrix = np.array(self.client.calculateMassMatrix(self.uid, positions))
                inverse = np.linalg.inv(matrix)
                value = float(inverse[len(matrix) - len(positions) + dof,
                                      len(matrix) - len(positions) + dof])
                if math.isfinite(value) and value > 0:
                    return value
            except (pybullet.error, np.linalg.LinAlgError, IndexError, ValueError):
                pass
        inertial = self.inertial(index)
        prismatic = self.client.getJointInfo(self.uid, index)[2] == pybullet.JOINT_PRISMATIC
        resistance = inertial.mass if prismatic else min(inertial.moments)
        return 1.0 / resistance if resistance > 0 else math.inf

    def set_joint_stops(self, index: int, lower: float, upper: float) -> None:
        """Hold one-axis joint ``index`` within ``lower`` .. ``upper`` (rad or m, lower <=
        upper; +-NO_STOP: no stop on that side)."""
        self.client.changeDynamics(self.uid, index, jointLowerLimit=float(lower),
                                   jointUpperLimit=float(upper))
        self._joint_set(index, make=True)["stops"] = (float(lower), float(upper))

    def set_joint_motor(self, index: int, velocity: float, max_force: float) -> None:
        """Drive one-axis joint ``index`` towards ``velocity`` (rad/s or m/s) with at most
        ``max_force`` (N m or N; 0: no motor), as ODE's joint motor (vel, fmax), which also
        holds a joint by its friction; a robot's drive sets its wheels' motors again at every
        tick."""
        self.client.setJointMotorControl2(self.uid, index, pybullet.VELOCITY_CONTROL,
                                          targetVelocity=float(velocity),
                                          force=float(max_force))
        self._joint_set(index, make=True)["motor"] = (float(velocity), float(max_force))

    def set_joint_target(self, index: int, position: float, max_force: float,
                         position_gain: float = 0.1, velocity_gain: float = 1.0) -> None:
        """Drive one-axis joint ``index`` to ``position`` (rad or m) with at most ``max_force``
        (N m or N), pybullet's position motor of those gains (a drive's steering joint, a
        braked wheel); noted as a motor of rate 0 (restore_joints puts the built one back)."""
        self.client.setJointMotorControl2(self.uid, index, pybullet.POSITION_CONTROL,
                                          targetPosition=float(position), targetVelocity=0.0,
                                          force=float(max_force), positionGain=position_gain,
                                          velocityGain=velocity_gain)
        self._joint_set(index, make=True)["motor"] = (0.0, float(max_force))

    def restore_joints(self) -> None:
        """Every joint's damping, stops and motor as built (a body parked for reuse)."""
        client = self.client
        for key in [k for k in client.joints_set if k[0] == self.uid]:
            done = client.joints_set.pop(key)
            damping, friction, lower, upper = self._built(key[1])
            if "damping" in done:
                client.changeDynamics(self.uid, key[1], jointDamping=damping)
            if "stops" in done:
                client.changeDynamics(self.uid, key[1], jointLowerLimit=lower,
                                      jointUpperLimit=upper)
            if "motor" in done:
                client.setJointMotorControl2(self.uid, key[1], pybullet.VELOCITY_CONTROL,
                                             targetVelocity=0.0, force=friction)

    # --- lifecycle -------------------------------------------------------------------------------

    def remove(self) -> None:
        """Take the body out of the physics for good."""
        self.client.removeBody(self.uid)
        collision_filters.forget_body(self.client, self.uid)
        forget_joints(self.client, self.uid)
        self.client.built_joints.pop(self.uid, None)


def moment_about_z(moments, base_in_frame) -> float:
    """kg m^2 about a frame's z axis, through the centre of mass, of a base whose principal
    ``moments`` (kg m^2) lie along the axes of quaternion ``base_in_frame`` (the base's
    orientation in that frame): a drive's yaw inertia, whatever the principal axes."""
    z_in_base = np.array(pybullet.getMatrixFromQuaternion(base_in_frame)).reshape(3, 3)[2]
    return float(z_in_base @ (np.array(moments) * z_in_base))


def forget_joints(client: Client, uid: int) -> None:
    """Body ``uid`` was removed from ``client``: what was set of its joints is gone."""
    for key in [k for k in client.joints_set if k[0] == uid]:
        del client.joints_set[key]
