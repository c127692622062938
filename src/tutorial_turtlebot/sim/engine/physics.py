"""The physics of a world and the robots in it, simulated by pybullet. Knows nothing of ROS.

``WorldPhysics`` is one pybullet client (headless, or pybullet's window; its engine.client.Client
is ``client``): the world's bodies, gravity, the step, ray casts, the robots' collision bits.
A robot URDF loaded into it is a ``robot_body.RobotBody``. Frames: ``world`` is the SDF world
frame (z up). Units: m, s, rad, kg, N*m. Quaternions (x, y, z, w).
"""
from typing import Dict, FrozenSet, List, Optional, Tuple

import numpy as np

from . import bullet_shapes, collision_filters, gui_window
from .bullet import pybullet, quiet_output
from .client import Client
from .rendering import disable_egl, enable_egl
from .body_pool import BodyPool
from .world_bullet import WORLD_COLLISION_GROUP, build_world
from ..files import limits
from ..files.world_types import World
from ...errors import UserError


GRAVITY = 9.8                    # m/s^2, Gazebo's default
# Each robot has a collision group bit of its own: it collides with everything, and its laser's
# rays test the world and every other robot but never itself. Bullet's groups are 32-bit ints.
FIRST_ROBOT_BIT = 4
MAX_ROBOTS = 24
ROBOT_GROUPS = ((1 << MAX_ROBOTS) - 1) << FIRST_ROBOT_BIT
# surfaces_below: the hits of one ray it reads at most (Bullet's all-hits ray test, one pass
# per hit), and how near its start a hit is taken as the ray starting inside a convex solid (m)
MAX_RAY_HITS = 16
RAY_START_TOLERANCE = 1e-6
PROBE_RADIUS = 1e-4     # m: solids_at: the sphere that probes each point


class WorldPhysics:
    """One pybullet client: the world's bodies, gravity, the physics step, ray casts."""

    def __init__(self, world: World, time_step: float, solver_iterations: int = 20,
                 gui: bool = False, egl: bool = False):
        """``gui`` opens pybullet's own window (the caller checks that a display exists);
        ``egl`` loads the EGL renderer for cameras where it works here (see ``self.egl``)."""
        self.time_step = time_step
        client = gui_window.open_window() if gui else Client.connect(pybullet.DIRECT)
        if client is None:
            raise RuntimeError("pybullet could not open its window")
        self.client: Optional[Client] = client    # its pybullet client; None once closed
        bullet_shapes.track(client)
        collision_filters.track(client)
        self.gui = gui
        self.egl = False
        if egl and not gui:  # before any body: the plugin draws only bodies created after it
            with quiet_output():
                self.egl = enable_egl(client)
        client.setTimeStep(time_step)
        client.setGravity(0, 0, -GRAVITY)
        # enableFileCaching 0: pybullet would keep every mesh file it ever read, for good (the
        # files written here are new for each body: nothing would be read from that cache).
        # solverResidualThreshold 0: the solver runs all its iterations, as Gazebo's ODE does
        # at its default sor_pgs_rms_error_tol 0. Bullet's early stop is judged on a whole
        # island and depends on the run's history in a way restoreState does not put back: a
        # reset learning stage 4 stepped 1e-12 m off a new one after 400 steps, on the infinite
        # ground plane (its solved contact forces differed from identical contacts).
        client.setPhysicsEngineParameter(numSolverIterations=solver_iterations,
                                         enableFileCaching=0, deterministicOverlappingPairs=1,
                                         solverResidualThreshold=0.0)
        # one line each: what the world's building could not draw as its files say (textures
        # halved for the texture budget, unreadable now); the node logs them with the world's
        self.warnings: List[str] = []
        self.world_bodies = build_world(world, client, self.warnings)
        # deleted models' bodies kept for reuse (body_pool.BodyPool)
        self.body_pool = BodyPool(client)
        self._free_bits: List[int] = [1 << (FIRST_ROBOT_BIT + i) for i in range(MAX_ROBOTS)]
        # threads pybullet casts a batch of rays on: the hits are the same for any count; 2
        # take 60 % of the wall time on an idle second core, and a fifth more CPU in all
        self.ray_threads = 1

    def step(self) -> None:
        """Advance physics by one time step."""
        self.client.stepSimulation()

    def save_state(self) -> int:
        """Keep the state of every body (poses, velocities, joints: pybullet's saveState, in
        memory): the id to ``restore_state``, or to ``drop_state`` when no longer wanted."""
        return self.client.saveState()

    def restore_state(self, state: int) -> None:
        """Every body back to saved ``state`` (the bodies must be those it was saved with),
        and no contact left: the next steps are those of a world in that state built anew
        (collision_filters.renew_contacts)."""
        self.client.restoreState(stateId=state)
        self.renew_contacts()

    def body_ids(self) -> Tuple[int, ...]:
        """The id of every body in the client, in pybullet's order."""
        client = self.client
        return tuple(client.getBodyUniqueId(i) for i in range(client.getNumBodies()))

    def drop_state(self, state: int) -> None:
        """Free a saved state."""
        self.client.removeState(state)

    def renew_contacts(self) -> None:
        """Forget every contact, and find the pairs in a new world's order from the next step
        (after bodies were put back by hand, as restore_state does by itself)."""
        collision_filters.renew_contacts(self.client)

    def set_gravity(self, gravity) -> None:
        """Gravity (m/s^2, world frame)."""
        self.client.setGravity(*gravity)

    def set_parameters(self, time_step: float, gravity, solver: dict) -> None:
        """The step (s), gravity (m/s^2, world frame) and Bullet's solver parameters
        (physics_properties.bullet_parameters: pybullet's setPhysicsEngineParameter names)."""
        client = self.client
        client.setTimeStep(time_step)
        client.setGravity(*gravity)
        client.setPhysicsEngineParameter(**solver)
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
        hits = self.client.rayTestBatch(starts.tolist(), ends.tolist(), collisionFilterMask=mask,
                                        numThreads=self.ray_threads)
        return np.array([h[2] * max_range if h[0] >= 0 else np.inf for h in hits])

    def surfaces_below(self, points: np.ndarray, top: float, bottom: float,
                       static_only: bool = True, lowest: bool = False) -> np.ndarray:
        """The z (m) of the highest surface (with ``lowest``, the lowest) met by a ray cast
        straight down from z ``top`` to z ``bottom`` at each world (x, y) of the (N, 2)
        ``points``; nan where none is met. Only the world's bodies count (no robot), with
        ``static_only`` only static ones (mass 0: a movable model is passed through, it is no
        floor). Every hit of a ray counts (Bullet's all-hits ray test, a mesh's triangles met
        from either side), except one at its very start (a ray that starts inside a convex
        solid may report one there)."""
        client = self.client
        starts = [(float(x), float(y), top) for x, y in points]
        ends = [(float(x), float(y), bottom) for x, y in points]
        highest = np.full(len(starts), np.nan)
        static: Dict[Tuple[int, int], bool] = {}
        for number in range(MAX_RAY_HITS):
            hits = client.rayTestBatch(starts, ends, collisionFilterMask=WORLD_COLLISION_GROUP,
                                       reportHitNumber=number)
            if all(hit[0] < 0 for hit in hits):
                break
            for i, (uid, link, fraction, position, _) in enumerate(hits):
                if uid < 0 or fraction * (top - bottom) < RAY_START_TOLERANCE:
                    continue
                if static_only and (uid, link) not in static:
                    static[uid, link] = client.getDynamicsInfo(uid, link)[0] == 0.0
                if not static_only or static[uid, link]:
                    if np.isnan(highest[i]) or (position[2] < highest[i] if lowest
                                                else position[2] > highest[i]):
                        highest[i] = position[2]
        return highest

    def solids_at(self, points: np.ndarray) -> List[FrozenSet[Tuple[int, int]]]:
        """The static world colliders (body id, link index) whose solid holds each world
        (x, y, z) of the (N, 3) ``points`` (m), a point on a face (the seam of two tiles) in
        both: Bullet's closest points between a sphere of PROBE_RADIUS at the point and each
        static collider of the world's collision group whose bounding box holds it, at a
        negative distance (the point inside or within PROBE_RADIUS of the collider). A box,
        cylinder, sphere or a polyline's convex piece is solid, and so is the whole side of an
        infinite plane below its surface (a half-space, as Gazebo's); a static mesh is triangles
        only (a point inside a closed mesh is in none); movable models and robots never count."""
        client = self.client
        filters = client.filters or {}
        probe = None
        found = []
        for point in np.asarray(points, dtype=float).tolist():
            low = [v - PROBE_RADIUS for v in point]
            high = [v + PROBE_RADIUS for v in point]
            holders = set()
            for uid, link in client.getOverlappingObjects(low, high) or ():
                group = filters.get((uid, link), (0, 0))[0]
                if not group & WORLD_COLLISION_GROUP or client.getDynamicsInfo(uid, link)[0]:
                    continue
                if probe is None:   # built on first need: most landings never probe
                    probe = bullet_shapes.collision_shape(client, pybullet.GEOM_SPHERE,
                                                          radius=PROBE_RADIUS)
                contacts = client.getClosestPoints(-1, uid, 0.0, linkIndexB=link,
                                                   collisionShapeA=probe,
                                                   collisionShapePositionA=point)
                if any(contact[8] < 0.0 for contact in contacts or ()):
                    holders.add((uid, link))
            found.append(frozenset(holders))
        return found

    def overlaps(self, body: int, min_depth: float) -> List[Tuple[int, int, float, float]]:
        """(body id, link index, depth m, top z m) of each collider that ``body`` penetrates by
        more than ``min_depth``, deepest first: Bullet's closest points between ``body`` and
        every collider whose bounding box meets its own; top is the collider's bounding box's,
        an infinite plane's its highest point over ``body``'s box (``_plane_top``)."""
        client = self.client
        boxes = [client.getAABB(body, link) for link in range(-1, client.getNumJoints(body))]
        low = np.min([box[0] for box in boxes], axis=0).tolist()
        high = np.max([box[1] for box in boxes], axis=0).tolist()
        found = []
        for uid, link in client.getOverlappingObjects(low, high) or ():
            if uid == body:
                continue
            points = client.getClosestPoints(body, uid, 0.0, linkIndexB=link)
            depth = max((-point[8] for point in points), default=0.0)
            if depth > min_depth:
                top = client.getAABB(uid, link)[1][2]
                if top > limits.MAX_POSITION:    # unbounded: an infinite plane
                    top = self._plane_top(uid, link, low, high)
                found.append((uid, link, depth, top))
        return sorted(found, key=lambda overlap: -overlap[2])

    def _plane_top(self, uid: int, link: int, low, high) -> float:
        """The highest z (m) over the corners of the world box ``low``..``high`` (its x, y) of
        the infinite plane (``uid``, ``link``): world_bullet builds a plane as a body whose x-y
        plane is the surface; a vertical plane has no top there: the box's top."""
        client = self.client
        if link < 0:
            (px, py, pz), orientation = client.getBasePositionAndOrientation(uid)
        else:
            (px, py, pz), orientation = client.getLinkState(uid, link)[4:6]
        nx, ny, nz = pybullet.getMatrixFromQuaternion(orientation)[2::3]    # the body's z axis
        if abs(nz) < 1e-9:
            return float(high[2])
        return float(max(pz - (nx * (x - px) + ny * (y - py)) / nz
                         for x in (low[0], high[0]) for y in (low[1], high[1])))

    def close(self) -> None:
        """Disconnect the pybullet client."""
        if self.client is not None:
            with quiet_output():  # the window's threads say goodbye on fd 1 and 2
                disable_egl(self.client)  # the plugin and the renderer's state
                self.client.disconnect()
            bullet_shapes.forget_client(self.client)
            collision_filters.forget_client(self.client)
            self.client = None
