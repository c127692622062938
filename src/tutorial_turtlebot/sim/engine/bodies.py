"""A pybullet body as the world above the engine sees it: poses, twists, links and joints.

``Body`` is a handle (engine.client.Client, body id) whose methods are the only pybullet calls
the world (world_models, world_control) needs; equal handles name the same body. Poses are
((x, y, z), (qx, qy, qz, qw)) in the world frame; twists ((vx, vy, vz), (wx, wy, wz)) in m/s and
rad/s, world frame. A link index of -1 is the base, whose frame is the body's centre of mass;
a jointed link's index is its joint's.
"""
import math
from typing import List, NamedTuple, Tuple

from . import collision_filters
from .bullet import pybullet
from .client import Client

Pose = Tuple[Tuple[float, float, float], Tuple[float, float, float, float]]
Twist = Tuple[Tuple[float, float, float], Tuple[float, float, float]]

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

    def root_link(self) -> str:
        """The name of the URDF's root link (of a body loaded from a URDF)."""
        return self.client.getBodyInfo(self.uid)[0].decode()

    def com_in_root(self) -> Pose:
        """The base's frame (centre of mass, principal axes) in the root link's frame."""
        info = self.client.getDynamicsInfo(self.uid, -1)
        return tuple(info[3]), tuple(info[4])

    # --- links and joints ------------------------------------------------------------------------

    def joints(self) -> List[Joint]:
        """Every joint, in index order (fixed ones too: a multibody's links)."""
        client = self.client
        out = []
        for j in range(client.getNumJoints(self.uid)):
            info = client.getJointInfo(self.uid, j)
            out.append(Joint(j, info[1].decode(), JOINT_KINDS.get(info[2], "revolute"),
                             float(info[6]), info[12].decode()))
        return out

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

    # --- lifecycle -------------------------------------------------------------------------------

    def remove(self) -> None:
        """Take the body out of the physics for good."""
        self.client.removeBody(self.uid)
        collision_filters.forget_body(self.client, self.uid)
