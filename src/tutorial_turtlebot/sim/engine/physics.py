"""The physics of a world and the robots in it, simulated by pybullet. Knows nothing of ROS.

``WorldPhysics`` is one pybullet client (headless, or pybullet's window): the world's bodies,
gravity, the step, ray casts. ``RobotBody`` is one robot URDF loaded into it. Frames: ``world``
is the SDF world frame (z up); a robot's reference frame is its root link (``base_footprint``
on a TurtleBot3: on the floor between the wheels, x forward). pybullet places a body by its
centre of mass, so every pose here is converted to and from the root link.
Units: m, s, rad, kg, N*m. Quaternions (x, y, z, w).
"""
import hashlib
import os
from typing import Dict, List, Optional, Sequence, Tuple

import numpy as np

from . import bullet_shapes, collision_filters, gui_window
from .bullet import pybullet, quiet_output
from ..kinematics import Pose
from .rendering import disable_egl, enable_egl
from ..files.urdf_file import RobotDescription
from ..files.urdf_meshes import bullet_urdf_text
from .bodies import Body
from .urdf_loader import load_urdf
from .world_bullet import ALL_COLLISION_GROUPS, WORLD_COLLISION_GROUP, body_pool, build_world
from ..files.world_types import World
from ...errors import UserError



GRAVITY = 9.8                    # m/s^2, Gazebo's default
# Each robot has a collision group bit of its own: it collides with everything, and its laser's
# rays test the world and every other robot but never itself. Bullet's groups are 32-bit ints.
FIRST_ROBOT_BIT = 4
MAX_ROBOTS = 24
ROBOT_GROUPS = ((1 << MAX_ROBOTS) - 1) << FIRST_ROBOT_BIT
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
# surfaces_below: the hits of one ray it reads at most (Bullet's all-hits ray test, one pass
# per hit), and how near its start a hit is taken as the ray starting inside a convex solid (m)
MAX_RAY_HITS = 16
RAY_START_TOLERANCE = 1e-6


class WorldPhysics:
    """One pybullet client: the world's bodies, gravity, the physics step, ray casts."""

    def __init__(self, world: World, time_step: float, solver_iterations: int = 20,
                 gui: bool = False, egl: bool = False):
        """``gui`` opens pybullet's own window (the caller checks that a display exists);
        ``egl`` loads the EGL renderer for cameras where it works here (see ``self.egl``)."""
        self.time_step = time_step
        self.client = gui_window.open_window() if gui else pybullet.connect(pybullet.DIRECT)
        if self.client < 0:
            raise RuntimeError("pybullet could not open its window")
        cid = self.client
        bullet_shapes.track(cid)
        collision_filters.track(cid)
        self.gui = gui
        self.egl = False
        if egl and not gui:  # before any body: the plugin draws only bodies created after it
            with quiet_output():
                self.egl = enable_egl(cid)
        pybullet.setTimeStep(time_step, physicsClientId=cid)
        pybullet.setGravity(0, 0, -GRAVITY, physicsClientId=cid)
        # enableFileCaching 0: pybullet would keep every mesh file it ever read, for good (the
        # files written here are new for each body: nothing would be read from that cache)
        pybullet.setPhysicsEngineParameter(numSolverIterations=solver_iterations,
                                           enableFileCaching=0, deterministicOverlappingPairs=1,
                                           physicsClientId=cid)
        # one line each: what the world's building could not draw as its files say (textures
        # halved for the texture budget, unreadable now); the node logs them with the world's
        self.warnings: List[str] = []
        self.world_bodies = build_world(world, cid, self.warnings)
        self._free_bits: List[int] = [1 << (FIRST_ROBOT_BIT + i) for i in range(MAX_ROBOTS)]
        # threads pybullet casts a batch of rays on: the hits are the same for any count; 2
        # take 60 % of the wall time on an idle second core, and a fifth more CPU in all
        self.ray_threads = 1

    def step(self) -> None:
        """Advance physics by one time step."""
        pybullet.stepSimulation(physicsClientId=self.client)

    def save_state(self) -> int:
        """Keep the state of every body (poses, velocities, joints: pybullet's saveState, in
        memory): the id to ``restore_state``, or to ``drop_state`` when no longer wanted."""
        return pybullet.saveState(physicsClientId=self.client)

    def restore_state(self, state: int) -> None:
        """Every body back to saved ``state`` (the bodies must be those it was saved with),
        and no contact left: the next steps are those of a world in that state built anew
        (collision_filters.renew_contacts)."""
        pybullet.restoreState(stateId=state, physicsClientId=self.client)
        self.renew_contacts()

    def body_ids(self) -> Tuple[int, ...]:
        """The id of every body in the client, in pybullet's order."""
        cid = self.client
        return tuple(pybullet.getBodyUniqueId(i, physicsClientId=cid)
                     for i in range(pybullet.getNumBodies(physicsClientId=cid)))

    def drop_state(self, state: int) -> None:
        """Free a saved state."""
        pybullet.removeState(state, physicsClientId=self.client)

    def renew_contacts(self) -> None:
        """Forget every contact, and find the pairs in a new world's order from the next step
        (after bodies were put back by hand, as restore_state does by itself)."""
        collision_filters.renew_contacts(self.client)

    def set_parameters(self, time_step: float, gravity, solver: dict) -> None:
        """The step (s), gravity (m/s^2, world frame) and Bullet's solver parameters
        (physics_properties.bullet_parameters: pybullet's setPhysicsEngineParameter names)."""
        cid = self.client
        pybullet.setTimeStep(time_step, physicsClientId=cid)
        pybullet.setGravity(*gravity, physicsClientId=cid)
        pybullet.setPhysicsEngineParameter(physicsClientId=cid, **solver)
        self.time_step = time_step

    def take_robot_bit(self) -> int:
        """A collision group bit for a new robot; UserError when MAX_ROBOTS run already."""
        if not self._free_bits:
            raise UserError("at most %d robots can run in one simulation" % MAX_ROBOTS)
        return self._free_bits.pop(0)

    def give_back_robot_bit(self, bit: int) -> None:
        self._free_bits.append(bit)
        self._free_bits.sort()

    def ray_distances(self, origin: np.ndarray, directions: np.ndarray, max_range: float,
                      mask: int = WORLD_COLLISION_GROUP) -> np.ndarray:
        """Distance (m) from ``origin`` along each world-frame unit direction to the first
        surface of a body in a collision group of ``mask``; inf where none is hit within
        ``max_range``."""
        ends = origin + directions * max_range
        starts = np.broadcast_to(origin, ends.shape)
        hits = pybullet.rayTestBatch(starts.tolist(), ends.tolist(), collisionFilterMask=mask,
                                     numThreads=self.ray_threads, physicsClientId=self.client)
        return np.array([h[2] * max_range if h[0] >= 0 else np.inf for h in hits])

    def surfaces_below(self, points: np.ndarray, top: float, bottom: float,
                       static_only: bool = True) -> np.ndarray:
        """The z (m) of the highest surface met by a ray cast straight down from z ``top`` to
        z ``bottom`` at each world (x, y) of the (N, 2) ``points``; nan where none is met.
        Only the world's bodies count (no robot), with ``static_only`` only static ones (mass
        0: a movable model is passed through, it is no floor). Every hit of a ray counts
        (Bullet's all-hits ray test), except one at its very start (a ray that starts inside
        a convex solid may report one there)."""
        cid = self.client
        starts = [(float(x), float(y), top) for x, y in points]
        ends = [(float(x), float(y), bottom) for x, y in points]
        highest = np.full(len(starts), np.nan)
        static: Dict[Tuple[int, int], bool] = {}
        for number in range(MAX_RAY_HITS):
            hits = pybullet.rayTestBatch(starts, ends, collisionFilterMask=WORLD_COLLISION_GROUP,
                                         reportHitNumber=number, physicsClientId=cid)
            if all(hit[0] < 0 for hit in hits):
                break
            for i, (uid, link, fraction, position, _) in enumerate(hits):
                if uid < 0 or fraction * (top - bottom) < RAY_START_TOLERANCE:
                    continue
                if static_only and (uid, link) not in static:
                    static[uid, link] = pybullet.getDynamicsInfo(
                        uid, link, physicsClientId=cid)[0] == 0.0
                if (not static_only or static[uid, link]) and not position[2] <= highest[i]:
                    highest[i] = position[2]
        return highest

    def overlaps(self, body: int, min_depth: float) -> List[Tuple[int, int, float, float]]:
        """(body id, link index, depth m, top z m) of each collider that ``body`` penetrates by
        more than ``min_depth``, deepest first: Bullet's closest points between ``body`` and
        every collider whose bounding box meets its own; top is the collider's bounding box's."""
        cid = self.client
        boxes = [pybullet.getAABB(body, link, physicsClientId=cid)
                 for link in range(-1, pybullet.getNumJoints(body, physicsClientId=cid))]
        low = np.min([box[0] for box in boxes], axis=0).tolist()
        high = np.max([box[1] for box in boxes], axis=0).tolist()
        found = []
        for uid, link in pybullet.getOverlappingObjects(low, high, physicsClientId=cid) or ():
            if uid == body:
                continue
            points = pybullet.getClosestPoints(body, uid, 0.0, linkIndexB=link,
                                               physicsClientId=cid)
            depth = max((-point[8] for point in points), default=0.0)
            if depth > min_depth:
                top = pybullet.getAABB(uid, link, physicsClientId=cid)[1][2]
                found.append((uid, link, depth, top))
        return sorted(found, key=lambda overlap: -overlap[2])

    def close(self) -> None:
        """Disconnect the pybullet client."""
        if self.client is not None:
            with quiet_output():  # the window's threads say goodbye on fd 1 and 2
                disable_egl(self.client)  # client ids are reused after a disconnect
                pybullet.disconnect(physicsClientId=self.client)
            bullet_shapes.forget_client(self.client)
            collision_filters.forget_client(self.client)
            self.client = None


class RobotBody:
    """One robot URDF in a WorldPhysics: its pose, velocity, wheels and frames."""

    def __init__(self, physics: WorldPhysics, description: RobotDescription, spawn_pose: Pose,
                 wheel_joints: Sequence[str] = (), wheel_torque: float = 0.0):
        """``spawn_pose``: the root link's world pose; ``wheel_joints``: (left, right) joint
        names driven by velocity with at most ``wheel_torque`` N*m, or () for none."""
        self.physics = physics
        self.client = physics.client
        self.description = description
        self.wheel_torque = wheel_torque
        self.collision_bit = physics.take_robot_bit()
        # rays of this robot's sensors: the world and every other robot
        self.ray_mask = (WORLD_COLLISION_GROUP | ROBOT_GROUPS) & ~self.collision_bit
        try:
            self.robot = self._load(description)
        except Exception:
            physics.give_back_robot_bit(self.collision_bit)
            raise
        cid = self.client
        self._com_in_footprint = pybullet.getDynamicsInfo(self.robot, -1, physicsClientId=cid)[3:5]
        self._footprint_in_com = pybullet.invertTransform(*self._com_in_footprint)
        self.wheels = self._wheel_indices(wheel_joints)
        self._held: Optional[Tuple[float, float]] = None  # wheel angles the brake holds
        self._anchored = False
        self._frames: Dict[str, np.ndarray] = {}
        (x, y, z), orn = spawn_pose
        self.spawn_pose: Pose = ((x, y, z + SPAWN_CLEARANCE), tuple(orn))
        self.reset_robot()

    def _load(self, description: Optional[RobotDescription] = None) -> int:
        """Load the description's URDF (kept as text for rebuild), or again that text."""
        cid = self.client
        if description is not None:
            self._bullet_urdf = bullet_urdf_text(
                description.root, os.path.dirname(os.path.abspath(description.path)))
        pool = body_pool(self.physics)   # a deleted robot of the same URDF is reused
        parked = pool.take(self._pool_key())
        if parked:
            robot = parked[0]
        else:
            robot = load_urdf(cid, self._bullet_urdf)
            pool.remember([robot])
        for link in range(-1, pybullet.getNumJoints(robot, physicsClientId=cid)):
            collision_filters.set_filter(cid, robot, link, self.collision_bit,
                                         ALL_COLLISION_GROUPS)
            pybullet.changeDynamics(robot, link, lateralFriction=BODY_FRICTION,
                                    spinningFriction=0.0, rollingFriction=0.0, restitution=0.0,
                                    linearDamping=0.0, angularDamping=0.0,
                                    activationState=pybullet.ACTIVATION_STATE_DISABLE_SLEEPING,
                                    physicsClientId=cid)
        return robot

    @property
    def body(self) -> Body:
        """The robot's pybullet body (a new one after ``rebuild``)."""
        return Body(self.client, self.robot)

    def _pool_key(self) -> tuple:
        """The BodyPool key of this robot's body: the digest of the URDF pybullet loaded."""
        return ("robot", hashlib.sha256(self._bullet_urdf.encode("utf-8")).hexdigest())

    def _wheel_indices(self, names: Sequence[str]) -> Tuple[int, ...]:
        cid = self.client
        by_name = {pybullet.getJointInfo(self.robot, j, physicsClientId=cid)[1].decode(): j
                   for j in range(pybullet.getNumJoints(self.robot, physicsClientId=cid))}
        wheels = tuple(by_name[name] for name in names)
        for j in wheels:
            pybullet.changeDynamics(self.robot, j, lateralFriction=WHEEL_FRICTION,
                                    physicsClientId=cid)
        return wheels

    # --- commands ------------------------------------------------------------------------------

    def set_wheel_velocities(self, left: float, right: float) -> None:
        """Joint velocity targets in rad/s, reached with at most the wheel torque; releases
        the brake."""
        if self.wheels:
            self._held = None
            self._anchor_wheels(False)
            pybullet.setJointMotorControlArray(
                self.robot, self.wheels, pybullet.VELOCITY_CONTROL,
                targetVelocities=(left, right), forces=(self.wheel_torque,) * 2,
                physicsClientId=self.client)

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
            pybullet.setJointMotorControlArray(
                self.robot, self.wheels, pybullet.POSITION_CONTROL, targetPositions=angles,
                targetVelocities=(0.0, 0.0), forces=(self.wheel_torque,) * 2,
                positionGains=(BRAKE_POSITION_GAIN,) * 2, velocityGains=(1.0, 1.0),
                physicsClientId=self.client)
        self._anchor_wheels(True)

    def _anchor_wheels(self, anchored: bool) -> None:
        """Anchor the tyres' contacts, or not. A contact made unanchored keeps its points
        unanchored while it holds (a robot stopped after driving kept creeping), so anchoring
        renews the tyres' contacts, and with them those a teleport or reset left behind:
        setting a link's collision filter (to what it is) drops its contacts in pybullet,
        and the next step makes them afresh."""
        if anchored != self._anchored:
            cid = self.client
            for j in self.wheels:
                pybullet.changeDynamics(self.robot, j, frictionAnchor=int(anchored),
                                        physicsClientId=cid)
                if anchored:
                    collision_filters.set_filter(cid, self.robot, j, self.collision_bit,
                                                 ALL_COLLISION_GROUPS)
            self._anchored = anchored

    def reset_robot(self) -> None:
        """Put the robot back at its spawn pose, at rest, every joint at angle 0."""
        self.place(self.spawn_pose)
        cid = self.client
        for j in range(pybullet.getNumJoints(self.robot, physicsClientId=cid)):
            pybullet.resetJointState(self.robot, j, 0.0, 0.0, physicsClientId=cid)
        # Velocity 0 with the wheel torque (brake released: its held angles are gone) until
        # the drive's next control tick brakes.
        self.restart_wheels()

    def restart_wheels(self) -> None:
        """The wheels' motors as ``reset_robot`` leaves them, for a body whose state was
        restored (WorldPhysics.restore_state): velocity 0 with the wheel torque, brake off."""
        self.set_wheel_velocities(0.0, 0.0)

    def place(self, pose: Pose) -> None:
        """Put the root link at world ``pose``, at rest."""
        cid = self.client
        pos, orn = pybullet.multiplyTransforms(*pose, *self._com_in_footprint)
        pybullet.resetBasePositionAndOrientation(self.robot, pos, orn, physicsClientId=cid)
        pybullet.resetBaseVelocity(self.robot, (0, 0, 0), (0, 0, 0), physicsClientId=cid)

    def rebuild(self) -> None:
        """Replace the robot's body by a new one loaded from the same URDF, at its spawn pose
        (a body whose state went NaN cannot be repaired in place: world_models.sound)."""
        old, cid = self.robot, self.client
        self.robot = self._load()
        pybullet.removeBody(old, physicsClientId=cid)
        collision_filters.forget_body(cid, old)
        for j in self.wheels:
            pybullet.changeDynamics(self.robot, j, lateralFriction=WHEEL_FRICTION,
                                    physicsClientId=cid)
        self._held, self._anchored = None, False
        self.reset_robot()

    def remove(self) -> None:
        """Take the robot out of the world (parked for reuse: world_bullet.BodyPool)."""
        pool = body_pool(self.physics)
        if not pool.park(self._pool_key(), [self.robot]):
            pybullet.removeBody(self.robot, physicsClientId=self.client)
            collision_filters.forget_body(self.client, self.robot)
            pool.forget([self.robot])
        self.physics.give_back_robot_bit(self.collision_bit)

    # --- state -----------------------------------------------------------------------------------

    def footprint_pose(self) -> Pose:
        """World pose of the root link (base_footprint): ((x, y, z), (qx, qy, qz, qw))."""
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
