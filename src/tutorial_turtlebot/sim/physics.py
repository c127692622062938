"""One TurtleBot3 in a world, simulated by pybullet (DIRECT, headless). Knows nothing of ROS.

Frames: ``world`` is the SDF world frame (z up); the robot's reference frame is
``base_footprint`` (on the floor between the wheels, x forward). pybullet places a body by its
centre of mass, so every pose here is converted to and from ``base_footprint``.
Units: m, s, rad, kg, N*m. Quaternions (x, y, z, w).
"""
import os
import tempfile
from typing import Dict, Sequence, Tuple
from xml.etree import ElementTree

import numpy as np

from . import gui_window
from .bullet import pybullet, quiet_output
from .camera import disable_egl, enable_egl
from .robot_models import ModelSpec
from .urdf_file import RobotDescription
from .world_bullet import WORLD_COLLISION_GROUP, build_world
from .world_sdf import World


Pose = Tuple[Tuple[float, float, float], Tuple[float, float, float, float]]

GRAVITY = 9.8                    # m/s^2, Gazebo's default
ROBOT_COLLISION_GROUP = 2        # rays test the world only, never the robot itself
WHEEL_JOINTS = ("wheel_left_joint", "wheel_right_joint")
# Tyre on floor (pybullet multiplies the two surfaces' values; the floor's is 1): enough grip
# for the 1 m/s^2 ramp with margin, little enough that a robot pushing a wall spins its wheels
# instead of climbing it (at 1.0 a Burger pressed into a corner reared up by 0.37 rad).
WHEEL_FRICTION = 0.5
BODY_FRICTION = 0.0              # chassis and caster skids slide freely
SPAWN_CLEARANCE = 0.001          # m: drop the robot from just above the floor


def _urdf_for_bullet(path: str) -> str:
    """A copy of the URDF in which bare frames (links with no inertial) weigh next to nothing.

    pybullet would give each of them 1 kg; merged into the chassis that would triple a Burger's
    mass. Returns the path of a temporary file the caller deletes.
    """
    tree = ElementTree.parse(path)
    for link in tree.getroot().iter("link"):
        if link.find("inertial") is None:
            inertial = ElementTree.SubElement(link, "inertial")
            ElementTree.SubElement(inertial, "mass", value="1e-6")
            ElementTree.SubElement(inertial, "inertia", ixx="1e-12", iyy="1e-12", izz="1e-12",
                                   ixy="0", ixz="0", iyz="0")
    fd, out = tempfile.mkstemp(suffix=".urdf", prefix="tutorial_turtlebot_")
    with os.fdopen(fd, "wb") as f:
        tree.write(f)
    return out


class TurtleBotPhysics:
    """pybullet client holding the world's static bodies and one TurtleBot3."""

    def __init__(self, spec: ModelSpec, description: RobotDescription, world: World,
                 spawn: Sequence[float], time_step: float, solver_iterations: int = 20,
                 gui: bool = False, egl: bool = False):
        """``spawn`` is (x, y, z, yaw) of base_footprint in the world; ``gui`` opens pybullet's
        own window (the caller checks that a display exists); ``egl`` loads the EGL renderer for
        cameras where it works here (see ``self.egl``)."""
        self.spec = spec
        self.description = description
        self.time_step = time_step
        self.client = gui_window.open_window() if gui else pybullet.connect(pybullet.DIRECT)
        if self.client < 0:
            raise RuntimeError("pybullet could not open its window")
        cid = self.client
        self.egl = False
        if egl and not gui:  # before any body: the plugin draws only bodies created after it
            with quiet_output():
                self.egl = enable_egl(cid)
        pybullet.setTimeStep(time_step, physicsClientId=cid)
        pybullet.setGravity(0, 0, -GRAVITY, physicsClientId=cid)
        pybullet.setPhysicsEngineParameter(numSolverIterations=solver_iterations,
                                           physicsClientId=cid)
        self.world_bodies = build_world(world, cid)
        self.robot = self._load_robot(description.path)
        self._com_in_footprint = pybullet.getDynamicsInfo(self.robot, -1, physicsClientId=cid)[3:5]
        self._footprint_in_com = pybullet.invertTransform(*self._com_in_footprint)
        self.wheels = self._wheel_indices()
        self._frames: Dict[str, np.ndarray] = {}
        x, y, z, yaw = spawn
        self.spawn_pose: Pose = ((x, y, z + SPAWN_CLEARANCE),
                                 tuple(pybullet.getQuaternionFromEuler((0.0, 0.0, yaw))))
        self.reset_robot()
        if gui:
            gui_window.look_at(cid, (x, y, z), yaw)

    def _load_robot(self, path: str) -> int:
        cid = self.client
        tmp = _urdf_for_bullet(path)
        try:
            with quiet_output():
                robot = pybullet.loadURDF(
                    tmp, flags=(pybullet.URDF_MERGE_FIXED_LINKS | pybullet.URDF_USE_INERTIA_FROM_FILE
                           | pybullet.URDF_USE_IMPLICIT_CYLINDER),
                    physicsClientId=cid)
        finally:
            os.unlink(tmp)
        for link in range(-1, pybullet.getNumJoints(robot, physicsClientId=cid)):
            pybullet.setCollisionFilterGroupMask(robot, link, ROBOT_COLLISION_GROUP, 0xFFFF,
                                                 physicsClientId=cid)
            pybullet.changeDynamics(robot, link, lateralFriction=BODY_FRICTION,
                                    spinningFriction=0.0, rollingFriction=0.0, restitution=0.0,
                                    linearDamping=0.0, angularDamping=0.0, physicsClientId=cid)
        return robot

    def _wheel_indices(self) -> Tuple[int, int]:
        cid = self.client
        by_name = {pybullet.getJointInfo(self.robot, j, physicsClientId=cid)[1].decode(): j
                   for j in range(pybullet.getNumJoints(self.robot, physicsClientId=cid))}
        wheels = tuple(by_name[name] for name in WHEEL_JOINTS)
        for j in wheels:
            pybullet.changeDynamics(self.robot, j, lateralFriction=WHEEL_FRICTION,
                                    physicsClientId=cid)
            # Free-spinning until commanded: pybullet's default velocity motor would brake.
            pybullet.setJointMotorControl2(self.robot, j, pybullet.VELOCITY_CONTROL,
                                           targetVelocity=0.0, force=self.spec.wheel_torque,
                                           physicsClientId=cid)
        return wheels

    # --- commands and stepping -----------------------------------------------------------------

    def set_wheel_velocities(self, left: float, right: float) -> None:
        """Joint velocity targets in rad/s, reached with at most the model's wheel torque."""
        pybullet.setJointMotorControlArray(
            self.robot, self.wheels, pybullet.VELOCITY_CONTROL, targetVelocities=(left, right),
            forces=(self.spec.wheel_torque,) * 2, physicsClientId=self.client)

    def step(self) -> None:
        """Advance physics by one time step."""
        pybullet.stepSimulation(physicsClientId=self.client)

    def reset_robot(self) -> None:
        """Put the robot back at its spawn pose, at rest, wheels at angle 0."""
        cid = self.client
        pos, orn = pybullet.multiplyTransforms(*self.spawn_pose, *self._com_in_footprint)
        pybullet.resetBasePositionAndOrientation(self.robot, pos, orn, physicsClientId=cid)
        pybullet.resetBaseVelocity(self.robot, (0, 0, 0), (0, 0, 0), physicsClientId=cid)
        for j in self.wheels:
            pybullet.resetJointState(self.robot, j, 0.0, 0.0, physicsClientId=cid)
        self.set_wheel_velocities(0.0, 0.0)

    # --- state -----------------------------------------------------------------------------------

    def footprint_pose(self) -> Pose:
        """World pose of base_footprint: ((x, y, z), (qx, qy, qz, qw))."""
        com = pybullet.getBasePositionAndOrientation(self.robot, physicsClientId=self.client)
        return pybullet.multiplyTransforms(*com, *self._footprint_in_com)

    def velocity(self) -> Tuple[Tuple[float, float, float], Tuple[float, float, float]]:
        """World-frame (linear m/s of the centre of mass, angular rad/s) of the chassis."""
        return pybullet.getBaseVelocity(self.robot, physicsClientId=self.client)

    def wheel_states(self) -> Tuple[Tuple[float, float], Tuple[float, float]]:
        """((left, right) joint angles in rad, (left, right) joint velocities in rad/s)."""
        (pl, vl, _, _), (pr, vr, _, _) = pybullet.getJointStates(
            self.robot, self.wheels, physicsClientId=self.client)
        return (pl, pr), (vl, vr)

    def frame_in_footprint(self, frame: str) -> np.ndarray:
        """4x4 pose of a URDF frame (base_scan, imu_link, camera...) in base_footprint."""
        if frame not in self._frames:
            root = self.description.root_link
            self._frames[frame] = self.description.transform(root, frame)
        return self._frames[frame]

    def frame_pose(self, frame: str) -> Tuple[np.ndarray, np.ndarray]:
        """World (position, 3x3 rotation) of a URDF frame rigidly attached to the chassis."""
        pos, orn = self.footprint_pose()
        rot = np.array(pybullet.getMatrixFromQuaternion(orn)).reshape(3, 3)
        local = self.frame_in_footprint(frame)
        return np.array(pos) + rot @ local[:3, 3], rot @ local[:3, :3]

    def ray_distances(self, origin: np.ndarray, directions: np.ndarray,
                      max_range: float) -> np.ndarray:
        """Distance (m) from ``origin`` along each world-frame unit direction to the first world
        surface; inf where nothing is hit within ``max_range``. The robot never hits itself."""
        ends = origin + directions * max_range
        starts = np.broadcast_to(origin, ends.shape)
        hits = pybullet.rayTestBatch(starts.tolist(), ends.tolist(),
                                     collisionFilterMask=WORLD_COLLISION_GROUP,
                                     physicsClientId=self.client)
        return np.array([h[2] * max_range if h[0] >= 0 else np.inf for h in hits])

    def close(self) -> None:
        """Disconnect the pybullet client."""
        if self.client is not None:
            with quiet_output():  # the window's threads say goodbye on fd 1 and 2
                disable_egl(self.client)  # client ids are reused after a disconnect
                pybullet.disconnect(physicsClientId=self.client)
            self.client = None
