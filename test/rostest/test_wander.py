#!/usr/bin/env python3
"""rostest node: wander, started by the .test file, drives a TurtleBot3 (~model) around
turtlebot3_world for ~duration (90 s) of sim time without touching anything and covers ground.

Every ground-truth /odom pose is checked against the world's collision shapes, read from the
same SDF file the sim loads (the nine pillars, the wall ring, the five green hexagons): the
robot's outline (the chassis box and the two wheels, doc/turtlebot3.md 1.1) must stay at least
CLEARANCE from each of them. All obstacles stand taller than the robot, so the check is 2D.
"""
import math
import unittest

import numpy as np
import rospy
import rostest
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from sensor_msgs.msg import LaserScan

from sim_test_support import Recorder, wait_for, yaw_of
from tutorial_turtlebot.sim.files.sdf.world_catalogue import resolve_world
from tutorial_turtlebot.sim.files.sdf.world_sdf import load_world

CLEARANCE = 0.01  # m
CELL = 0.5        # m, grid for "covers ground"
MIN_CELLS = 10    # distinct cells visited in 90 s


def rectangle(x0, x1, y0, y1):
    return ((x0, y0), (x1, y0), (x1, y1), (x0, y1))


# Each model's outline in base_footprint (x forward, y left), m: the chassis collision box and
# the two wheels (radius 0.033, width 0.018), doc/turtlebot3.md 1.1. Lidar and casters lie within.
ROBOT_PARTS = {
    "burger": (rectangle(-0.102, 0.038, -0.070, 0.070),
               rectangle(-0.033, 0.033, 0.071, 0.089), rectangle(-0.033, 0.033, -0.089, -0.071)),
    "waffle": (rectangle(-0.197, 0.069, -0.133, 0.133),
               rectangle(-0.033, 0.033, 0.135, 0.153), rectangle(-0.033, 0.033, -0.153, -0.135)),
}
ROBOT_PARTS["waffle_pi"] = ROBOT_PARTS["waffle"]


def transform(points, x, y, yaw):
    """Points (N x 2) from a frame at (x, y, yaw) into the world."""
    c, s = math.cos(yaw), math.sin(yaw)
    pts = np.asarray(points, dtype=float)
    return np.column_stack([x + c * pts[:, 0] - s * pts[:, 1], y + s * pts[:, 0] + c * pts[:, 1]])


def obstacles(world_name: str):
    """('circle', centre, radius) and ('polygon', corners N x 2) for every collision shape."""
    found = []
    for shape in load_world(resolve_world(world_name)[0]).collisions:
        x, y, _z, _roll, _pitch, yaw = shape.pose
        if shape.kind == "plane":
            continue  # the floor
        if shape.kind == "cylinder":
            found.append(("circle", np.array([x, y]), shape.size[0]))
        elif shape.kind == "box":
            hx, hy = shape.size[0] / 2.0, shape.size[1] / 2.0
            found.append(("polygon", transform([(-hx, -hy), (hx, -hy), (hx, hy), (-hx, hy)],
                                               x, y, yaw)))
        elif shape.kind == "polyline":
            found.append(("polygon", transform(shape.points, x, y, yaw)))
        else:
            raise AssertionError("no clearance check for %s (%s)" % (shape.name, shape.kind))
    return found


def point_segment_distance(p, a, b) -> float:
    ab, ap = b - a, p - a
    t = min(1.0, max(0.0, float(np.dot(ap, ab) / np.dot(ab, ab))))
    return float(np.hypot(*(ap - t * ab)))


def inside(p, poly) -> bool:
    """True when point p is inside the convex polygon ``poly`` (either winding)."""
    signs = []
    for a, b in zip(poly, np.roll(poly, -1, axis=0)):
        signs.append((b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]))
    return all(s > 0 for s in signs) or all(s < 0 for s in signs)


def polygon_distance(a, b) -> float:
    """Distance between convex polygons a and b; 0 where they overlap."""
    if any(inside(p, b) for p in a) or any(inside(p, a) for p in b):
        return 0.0
    best = math.inf
    for p in a:
        for q, r in zip(b, np.roll(b, -1, axis=0)):
            best = min(best, point_segment_distance(p, q, r))
    for p in b:
        for q, r in zip(a, np.roll(a, -1, axis=0)):
            best = min(best, point_segment_distance(p, q, r))
    return best  # convex polygons that do not overlap: the nearest pair involves a vertex


def clearance(part, obstacle) -> float:
    """Distance (m) from a robot part (polygon in the world) to an obstacle."""
    if obstacle[0] == "circle":
        centre, radius = obstacle[1], obstacle[2]
        if inside(centre, part):
            return 0.0
        edge = min(point_segment_distance(centre, q, r)
                   for q, r in zip(part, np.roll(part, -1, axis=0)))
        return max(0.0, edge - radius)
    return polygon_distance(part, obstacle[1])


def reach(obstacle) -> tuple:
    """(centre, radius) of a circle holding the obstacle, to skip far ones quickly."""
    if obstacle[0] == "circle":
        return obstacle[1], obstacle[2]
    centre = obstacle[1].mean(axis=0)
    return centre, float(np.max(np.hypot(*(obstacle[1] - centre).T)))


class WanderTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_wander")
        cls.duration = rospy.get_param("~duration", 90.0)
        cls.parts = ROBOT_PARTS[rospy.get_param("~model", "burger")]
        cls.obstacles = obstacles("turtlebot3_world")
        cls.odom = Recorder("odom", Odometry)
        cls.scan = Recorder("scan", LaserScan)
        cls.cmd = Recorder("cmd_vel", Twist)
        assert cls.odom.latest(30.0) is not None, "no odom"
        first = cls.odom.msgs[0]
        end = first.header.stamp + rospy.Duration(cls.duration)
        # Wall time: at real time 90 s; as fast as possible, less. The sim stalling fails it.
        wait_for(lambda: cls.odom.latest().header.stamp >= end, 2.0 * cls.duration + 30.0, 0.1)
        cls.msgs = cls.odom.between(first.header.stamp, end)

    def test_ran_the_whole_time(self):
        self.assertGreater(self.msgs[-1].header.stamp - self.msgs[0].header.stamp,
                           rospy.Duration(self.duration - 0.1), "odometry stopped early")
        self.assertGreater(len(self.msgs), 0.9 * 30 * self.duration, "odometry too sparse")

    def test_kept_up_with_the_scans(self):
        """wander answers (almost) every scan: it publishes once per scan it handles."""
        start, end = self.msgs[0].header.stamp, self.msgs[-1].header.stamp
        scans = len(self.scan.between(start, end))
        cmds, times = self.cmd.snapshot()
        answered = sum(1 for t in times if start <= t <= end)
        rospy.loginfo("%d scans, %d commands", scans, answered)
        self.assertGreater(scans, 0.9 * 5 * self.duration)
        self.assertGreater(answered, 0.9 * scans)

    def test_never_touches_anything(self):
        worst = (math.inf, None, None)
        for msg in self.msgs:
            p = msg.pose.pose.position
            yaw = yaw_of(msg.pose.pose.orientation)
            for obstacle in self.obstacles:
                centre, radius = reach(obstacle)
                if math.hypot(centre[0] - p.x, centre[1] - p.y) > radius + 0.3:
                    continue
                for part in self.parts:
                    gap = clearance(transform(part, p.x, p.y, yaw), obstacle)
                    if gap < worst[0]:
                        worst = (gap, msg, obstacle)
        gap, msg, _ = worst
        if msg is not None:
            p = msg.pose.pose.position
            rospy.loginfo("closest approach %.3f m at (%.2f, %.2f), t %.1f s", gap, p.x, p.y,
                          msg.header.stamp.to_sec())
            self.assertGreaterEqual(gap, CLEARANCE, "within %.3f m of an obstacle at (%.2f, "
                                    "%.2f), t %.1f s" % (gap, p.x, p.y, msg.header.stamp.to_sec()))

    def test_covers_ground(self):
        xy = np.array([(m.pose.pose.position.x, m.pose.pose.position.y) for m in self.msgs])
        cells = {(int(math.floor(x / CELL)), int(math.floor(y / CELL))) for x, y in xy}
        travelled = float(np.sum(np.hypot(*np.diff(xy, axis=0).T)))
        span = xy.max(axis=0) - xy.min(axis=0)
        rospy.loginfo("%d cells of %g m, %.1f m travelled, span %.2f x %.2f m", len(cells), CELL,
                      travelled, span[0], span[1])
        self.assertGreaterEqual(len(cells), MIN_CELLS)
        self.assertGreater(float(np.max(span)), 1.0)
        self.assertGreater(travelled, 5.0)


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "test_wander", WanderTest)
