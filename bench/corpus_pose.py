#!/usr/bin/env python3
"""make corpus: find a free pose for a robot in a world, through the simulator itself (no ROS).

bench/corpus.py runs this in a child process for each world of the corpus:
``python3 bench/corpus_pose.py WORLD_FILE [MODEL]`` (GAZEBO_MODEL_PATH and GAZEBO_RESOURCE_PATH
as the world needs them) prints one JSON line: ``{"x", "y", "z", "yaw", "open", "finite",
"candidates", "floors", "alternates"}`` or ``{"error": "one line"}``.

The world is loaded as Simulation loads it, with the robot parked far away (FAR). Candidate
points lie on a grid over the world's bounding box (every body's but infinite planes'). A point
is a free pose when:

- **a floor**: a ray down from PROBE_TOP meets a static surface between FLOOR_LOW and
  FLOOR_HIGH (m), flat within FLAT under the footprint (four more rays FOOT m around);
- **headroom**: nothing within HEADROOM above that floor;
- **clear in plan**: rings of RING_RAYS rays at the laser's and a low height see nothing nearer
  than CLEARANCE;
- **no overlap**: the robot's own body put there touches nothing (Bullet's closest points);
- **its laser agrees**: a scan of the robot's own laser from there has no return nearer than
  CLEARANCE - LASER_OFFSET.

Points are tried best first: the most ring rays that meet something within the laser's range
(inside a building before out in the open), then the nearest to the world's origin. ``z`` is
the floor's height there (m), ``yaw`` the most open direction of the laser ring (rad), ``open``
how far the ring sees along it (m, capped at the laser's range), ``finite`` the share of the
robot's scan with a return, ``floors`` how many grid points had a floor, ``candidates`` how
many of them were clear in plan, ``alternates`` up to ALTERNATES more free poses (the same
keys), each at least SPREAD from the others, next best first.
Units: metres, radians, world frame.
"""
import json
import math
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, os.pardir, "src"))

FAR = 5000.0          # m: where the robot is parked while candidates are probed
LIMIT = 150.0         # m: the search box is clipped to +-LIMIT around the origin
PAD = 2.0             # m: the search box reaches this far beyond the standing bodies
MAX_CANDIDATES = 4000  # grid points at most; the grid step grows with the box
MIN_STEP = 0.25       # m: the finest grid step
PROBE_TOP = 0.6       # m: rays down start here (below table tops and ceilings)
PROBE_BOTTOM = -0.5   # m: and end here
FLOOR_LOW = -0.05     # m: a floor's height must lie in FLOOR_LOW..FLOOR_HIGH
FLOOR_HIGH = 0.45
FLAT = 0.02           # m: the floor under the footprint within this of the centre's
FOOT = 0.17           # m: the footprint rays' distance from the centre
HEADROOM = 0.5        # m: nothing above the floor within this
CLEARANCE = 0.6       # m: nothing in plan within this of the centre
RING_RAYS = 36
RING_HEIGHTS = (0.05, 0.17)   # m above the floor: low obstacles and the laser's height
RING_RANGE = 3.5      # m: the LDS-01's range
LASER_OFFSET = 0.07   # m: how far the Waffle Pi's laser sits from base_footprint's centre
OVERLAP = 0.002       # m: a deeper penetration is an overlap
TRIES = 60            # candidates placed and scanned at most
ALTERNATES = 3        # free poses found besides the best, for a spawn the sim refuses
SPREAD = 2.0          # m between the free poses found
BATCH = 8000          # rays per pybullet call


def grid_points(low, high, max_count=MAX_CANDIDATES, min_step=MIN_STEP):
    """(N, 2) cell centres of a grid over the box ``low``..``high`` ((x, y) m each) with at
    most about ``max_count`` cells, none finer than ``min_step`` m."""
    width, depth = max(high[0] - low[0], min_step), max(high[1] - low[1], min_step)
    step = max(min_step, math.sqrt(width * depth / max_count))
    xs = np.arange(low[0] + step / 2, high[0], step)
    ys = np.arange(low[1] + step / 2, high[1], step)
    if not len(xs) or not len(ys):
        return np.array([[(low[0] + high[0]) / 2, (low[1] + high[1]) / 2]])
    gx, gy = np.meshgrid(xs, ys)
    return np.column_stack([gx.ravel(), gy.ravel()])


def ring_directions(count=RING_RAYS):
    """(count, 3) unit vectors in the x-y plane, the first along +x, counter-clockwise."""
    angles = np.arange(count) * (2 * math.pi / count)
    return np.column_stack([np.cos(angles), np.sin(angles), np.zeros(count)])


def rank(points, walls_seen, order_from=(0.0, 0.0)):
    """Indices of ``points`` best first: more ``walls_seen`` (ring rays with a hit), then
    nearer ``order_from``."""
    distance = np.hypot(points[:, 0] - order_from[0], points[:, 1] - order_from[1])
    return sorted(range(len(points)), key=lambda i: (-int(walls_seen[i]), float(distance[i])))


def most_open(distances):
    """(index, distance) of the ring ray that sees farthest (inf counts as RING_RANGE); of
    equals, the one whose neighbours see farthest."""
    capped = np.minimum(np.nan_to_num(distances, posinf=RING_RANGE), RING_RANGE)
    smooth = capped + 0.5 * (np.roll(capped, 1) + np.roll(capped, -1))
    best = int(np.argmax(smooth))
    return best, float(capped[best])


class PoseFinder:
    """Free poses in one loaded Simulation (its robot parked far away meanwhile)."""

    def __init__(self, sim):
        import pybullet
        self.p = pybullet
        self.sim = sim
        self.cid = sim.physics.client
        self.robot_id = sim.robot.body.robot
        self.world_ids = [b for b in sim.physics.body_ids() if b != self.robot_id]

    def rays(self, starts, ends):
        """(N,) hit fractions (1.0 where nothing is hit) and (N,) hit body ids (-1)."""
        fractions, bodies = [], []
        for i in range(0, len(starts), BATCH):
            hits = self.p.rayTestBatch(starts[i:i + BATCH].tolist(), ends[i:i + BATCH].tolist(),
                                       physicsClientId=self.cid)
            fractions += [h[2] if h[0] >= 0 else 1.0 for h in hits]
            bodies += [h[0] for h in hits]
        return np.array(fractions), np.array(bodies)

    def bounds(self):
        """((x, y) low, (x, y) high) of the world bodies' boxes that stand up from the floor
        (taller than FLOOR_HIGH: walls, furniture), PAD more around, clipped to LIMIT; of every
        body's but infinite planes' when none does (a floor alone)."""
        boxes = []
        for body in self.world_ids:
            for link in range(-1, self.p.getNumJoints(body, physicsClientId=self.cid)):
                box_low, box_high = self.p.getAABB(body, link, physicsClientId=self.cid)
                if max(box_high[0] - box_low[0], box_high[1] - box_low[1]) <= 4 * LIMIT:
                    boxes.append((np.array(box_low), np.array(box_high)))
        standing = [box for box in boxes if box[1][2] - box[0][2] > FLOOR_HIGH] or boxes
        if not standing:
            return np.array([-5.0, -5.0]), np.array([5.0, 5.0])
        low = np.min([box[0][:2] for box in standing], axis=0)
        high = np.max([box[1][:2] for box in standing], axis=0)
        return np.maximum(low - PAD, -LIMIT), np.minimum(high + PAD, LIMIT)

    def static(self, body):
        return self.p.getDynamicsInfo(int(body), -1, physicsClientId=self.cid)[0] == 0.0

    def floors(self, points):
        """(N,) floor height at each point, NaN where there is none or it is not flat."""
        count = len(points)
        offsets = [(0.0, 0.0), (FOOT, 0.0), (-FOOT, 0.0), (0.0, FOOT), (0.0, -FOOT)]
        xy = np.concatenate([points + o for o in offsets])
        starts = np.column_stack([xy, np.full(len(xy), PROBE_TOP)])
        ends = np.column_stack([xy, np.full(len(xy), PROBE_BOTTOM)])
        fractions, bodies = self.rays(starts, ends)
        heights = PROBE_TOP + fractions * (PROBE_BOTTOM - PROBE_TOP)
        heights[bodies < 0] = np.nan
        heights = heights.reshape(len(offsets), count)
        centre = heights[0].copy()
        statics = {b: self.static(b) for b in set(bodies[:count].tolist()) if b >= 0}
        for i in range(count):
            if (not math.isfinite(centre[i]) or not FLOOR_LOW <= centre[i] <= FLOOR_HIGH
                    or not statics.get(int(bodies[i]), False)
                    or not np.all(np.abs(heights[1:, i] - centre[i]) <= FLAT)):
                centre[i] = np.nan
        return centre

    def headroom(self, points, floors):
        """(N,) bools: nothing above the floor within HEADROOM."""
        starts = np.column_stack([points, floors + 0.02])
        ends = np.column_stack([points, floors + HEADROOM])
        fractions, _ = self.rays(starts, ends)
        return fractions >= 1.0

    def rings(self, points, floors):
        """(N, RING_RAYS) distances at the laser's height, and (N,) bools: clear of CLEARANCE
        at every ring height."""
        directions = ring_directions()
        clear = np.ones(len(points), bool)
        laser = None
        for height in RING_HEIGHTS:
            centres = np.column_stack([points, floors + height])
            starts = np.repeat(centres, RING_RAYS, axis=0)
            ends = starts + np.tile(directions * RING_RANGE, (len(points), 1))
            fractions, _ = self.rays(starts, ends)
            distances = np.where(fractions < 1.0, fractions * RING_RANGE, np.inf)
            distances = distances.reshape(len(points), RING_RAYS)
            clear &= np.min(distances, axis=1) >= CLEARANCE
            laser = distances
        return laser, clear

    def overlaps(self, x, y, z):
        """Whether the robot put at (x, y, z) penetrates any world body by more than OVERLAP."""
        body = self.robot_id
        low, high = self.p.getAABB(body, -1, physicsClientId=self.cid)
        for link in range(self.p.getNumJoints(body, physicsClientId=self.cid)):
            a, b = self.p.getAABB(body, link, physicsClientId=self.cid)
            low, high = np.minimum(low, a), np.maximum(high, b)
        for uid, _ in self.p.getOverlappingObjects(low.tolist(), high.tolist(),
                                                   physicsClientId=self.cid) or ():
            if uid == body:
                continue
            points = self.p.getClosestPoints(body, uid, 0.0, physicsClientId=self.cid)
            if any(-point[8] > OVERLAP for point in points):
                return True
        return False

    def find(self):
        """The free pose as a dict (see the module docstring), or {"error": ...}."""
        from tutorial_turtlebot.sim.kinematics import quat_from_yaw
        low, high = self.bounds()
        points = grid_points(low, high)
        floors = self.floors(points)
        keep = np.isfinite(floors)
        floor_count = int(keep.sum())
        points, floors = points[keep], floors[keep]
        if not len(points):
            return {"error": "no flat static floor between %g and %g m in %d grid points"
                    % (FLOOR_LOW, FLOOR_HIGH, len(keep))}
        keep = self.headroom(points, floors)
        points, floors = points[keep], floors[keep]
        laser, clear = self.rings(points, floors)
        points, floors, laser = points[clear], floors[clear], laser[clear]
        if not len(points):
            return {"error": "no floor point clear of %g m in plan (of %d with a floor)"
                    % (CLEARANCE, floor_count)}
        walls_seen = np.sum(np.isfinite(laser), axis=1)
        robot = self.sim.robot
        found = []
        for tried, i in enumerate(rank(points, walls_seen)):
            if tried >= TRIES or len(found) > ALTERNATES:
                break
            x, y, z = float(points[i, 0]), float(points[i, 1]), float(floors[i])
            if any(math.hypot(x - f["x"], y - f["y"]) < SPREAD for f in found):
                continue
            robot.body.place(((x, y, z + 0.005), quat_from_yaw(0.0)))
            if self.overlaps(x, y, z):
                continue
            ranges = np.asarray(robot.scan(), dtype=float)
            near = ranges[np.isfinite(ranges) | np.isneginf(ranges)]
            if len(near) and float(np.min(near)) < CLEARANCE - LASER_OFFSET:
                continue
            ray, open_distance = most_open(laser[i])
            found.append({"x": round(x, 3), "y": round(y, 3), "z": round(z, 3),
                          "yaw": round(ray * 2 * math.pi / RING_RAYS, 4),
                          "open": round(open_distance, 2),
                          "finite": round(float(np.mean(np.isfinite(ranges))), 3)})
        if not found:
            return {"error": "none of %d clear floor points passed the overlap and scan checks"
                    % min(len(points), TRIES)}
        return dict(found[0], alternates=found[1:], candidates=int(len(points)),
                    floors=floor_count)


def find_free_pose(world_path, model="waffle_pi"):
    """The free pose (dict) of ``world_path`` for ``model``, or {"error": one line}."""
    from tutorial_turtlebot.errors import UserError
    from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
    try:
        sim = Simulation(SimConfig(model=model, world=world_path, x=FAR, y=FAR, camera=False))
    except UserError as err:
        return {"error": str(err).splitlines()[0]}
    try:
        return PoseFinder(sim).find()
    finally:
        sim.close()


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    if not argv:
        sys.exit("usage: corpus_pose.py WORLD_FILE [MODEL]")
    print(json.dumps(find_free_pose(argv[0], *argv[1:2])), flush=True)


if __name__ == "__main__":
    main()
