#!/usr/bin/env python3
"""rostest node: the e-Manual's SLAM chapter on the sim. ``roslaunch tutorial_turtlebot
turtlebot3_slam.launch sim:=true rviz:=false`` (gmapping with ROBOTIS' parameters) runs in the
navigation extra's environment while the robot drives a fixed loop around the arena, between the
pillars and the walls; then ``rosrun map_server map_saver`` saves the map.

Checks, with the world's shapes as the sim reads them (nav_support.world_shapes): at least
~min_near of the map's occupied cells lie within ~near m of a shape; every wall's inner face is
seen along ~face_seen of its length; every pillar has at least MIN_PILLAR_CELLS occupied cells
within ~near m of it. The map frame is placed in the world by the robot's true pose
(/gazebo/model_states) and map -> base_footprint (tf) at the end.

Skipped, in one line, where the extra is not installed.
Params: ~model (burger), ~world (turtlebot3_world), ~real_time_factor (2.0), ~near (0.10 m),
~min_near (0.95), ~face_seen (0.9), ~map (the map's path stem; default in the ROS log folder).
"""
import math
import os
import time
import unittest

import numpy as np
import rospy
import rostest
import tf2_ros
from geometry_msgs.msg import Twist, Vector3

from nav_support import (NOT_INSTALLED, Launch, TruePose, angle_diff, distance_field, log_dir,
                         nav_env, read_map, run, world_shapes)
from sim_test_support import wait_for, yaw_of

WAIT = 120.0          # wall s: the sim and gmapping up, on a busy machine
RING = 2.05           # m from the arena's centre: the loop between the pillars and the walls
RING_POINTS = 16      # waypoints on it
SPEED = 0.18          # m/s ahead on the loop
TURN = 1.0            # rad/s at most
MIN_PILLAR_CELLS = 5
FACE_HALF = 1.2       # m either side of a wall face's middle that is checked (the face is 2.9)


class TestSlam(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_slam")
        cls.env = nav_env()
        cls.launch = None
        if cls.env is None:
            return                # each test skips, saying how to install the extra
        p = rospy.get_param
        cls.world, model = p("~world", "turtlebot3_world"), p("~model", "burger")
        cls.launch = Launch(cls.env, "turtlebot3_slam.launch", "sim:=true", "rviz:=false",
                            "model:=" + model, "world:=" + cls.world,
                            "real_time_factor:=%g" % p("~real_time_factor", 2.0))
        cls.truth = TruePose(cls.world, model)
        cls.cmd = rospy.Publisher("/cmd_vel", Twist, queue_size=1)
        cls.tf = tf2_ros.Buffer()
        cls.tf_listener = tf2_ros.TransformListener(cls.tf)

    @classmethod
    def tearDownClass(cls):
        if cls.launch is not None:
            cls.launch.stop()

    def setUp(self):
        if self.env is None:
            self.skipTest(NOT_INSTALLED)

    def drive_to(self, x: float, y: float, timeout: float) -> bool:
        """Drive to (x, y) (world frame, m) by the true pose: turn towards it, then go ahead
        while steering; False if not there within ``timeout`` sim s."""
        rate = rospy.Rate(20)
        deadline = rospy.Time.now() + rospy.Duration(timeout)
        while not rospy.is_shutdown() and rospy.Time.now() < deadline:
            px, py, yaw = self.truth.pose
            if math.hypot(x - px, y - py) < 0.15:
                return True
            error = angle_diff(math.atan2(y - py, x - px), yaw)
            ahead = SPEED if abs(error) < 0.5 else 0.0
            turn = max(-TURN, min(TURN, 2.0 * error))
            self.cmd.publish(Twist(linear=Vector3(ahead, 0, 0), angular=Vector3(0, 0, turn)))
            rate.sleep()
        return False

    def stop(self) -> None:
        self.cmd.publish(Twist())

    def world_from_map(self):
        """(x, y, yaw) of the map frame in the world (m, rad), from the true pose and tf's
        map -> base_footprint, both taken with the robot at rest."""
        t = self.tf.lookup_transform("map", "base_footprint", rospy.Time(0), rospy.Duration(10))
        mx, my = t.transform.translation.x, t.transform.translation.y
        myaw = yaw_of(t.transform.rotation)
        wx, wy, wyaw = self.truth.pose
        yaw = angle_diff(wyaw, myaw)
        c, s = math.cos(yaw), math.sin(yaw)
        return wx - (c * mx - s * my), wy - (s * mx + c * my), yaw

    def test_map_of_the_arena(self):
        launch = self.launch
        up = wait_for(lambda: self.truth.pose is not None
                      and self.cmd.get_num_connections() > 0
                      and self.tf.can_transform("map", "base_footprint", rospy.Time(0)), WAIT)
        self.assertTrue(up, "sim or gmapping not up within %g s; roslaunch said:\n%s"
                        % (WAIT, launch.tail()))
        started = time.monotonic()
        x0, y0, _ = self.truth.pose
        start = math.atan2(y0, x0)
        for k in range(1, RING_POINTS + 2):
            angle = start + 2.0 * math.pi * k / RING_POINTS
            reached = self.drive_to(RING * math.cos(angle), RING * math.sin(angle), 60.0)
            self.assertTrue(reached, "waypoint %d not reached; the robot is at %s" % (
                k, self.truth.pose))
        self.stop()
        rospy.sleep(3.0)          # gmapping's map_update_interval is 2 s
        rospy.loginfo("test_slam: loop driven in %.0f wall s", time.monotonic() - started)

        stem = rospy.get_param("~map", os.path.join(log_dir(), "test_slam_map"))
        status, said = run(self.env, "rosrun", "map_server", "map_saver", "-f", stem,
                           timeout=60.0)
        self.assertEqual(status, 0, said)
        cells, free = read_map(stem + ".yaml")
        self.assertGreater(free, 1000, "the map has almost no free space")

        ox, oy, oyaw = self.world_from_map()
        c, s = math.cos(oyaw), math.sin(oyaw)
        xs = ox + c * cells[:, 0] - s * cells[:, 1]
        ys = oy + s * cells[:, 0] + c * cells[:, 1]
        near = rospy.get_param("~near", 0.10)
        shapes = world_shapes(self.world)
        distance = distance_field(shapes, xs, ys)
        share = float(np.mean(distance <= near))
        rospy.loginfo("test_slam: %d occupied cells, %.1f %% within %g m of the world's shapes "
                      "(map frame at %.3f %.3f %.3f in the world)",
                      len(cells), 100 * share, near, ox, oy, oyaw)
        self.assertGreaterEqual(share, rospy.get_param("~min_near", 0.95))

        missing = []
        for shape in shapes:
            if shape.kind == "cylinder":
                gap = np.hypot(xs - shape.pose[0], ys - shape.pose[1]) - shape.size[0]
                if np.sum(np.abs(gap) <= near) < MIN_PILLAR_CELLS:
                    missing.append(shape.name)
            elif shape.kind == "box":
                others = [other for other in shapes if other is not shape]
                seen = self.face_seen(shape, others, xs, ys, near)
                if seen < rospy.get_param("~face_seen", 0.9):
                    missing.append("%s (%.0f %% of its face)" % (shape.name, 100 * seen))
        self.assertEqual(missing, [], "not in the map: %s" % ", ".join(missing))

    @staticmethod
    def face_seen(wall, others, xs, ys, near) -> float:
        """The share of points along ``wall``'s inner face (the one towards the arena's centre)
        that have an occupied cell within ``near`` m; points that another shape hides (one
        within ``near`` of them: the corners' hexagons stand in front of the walls' ends)
        are left out."""
        cx, cy, yaw = wall.pose[0], wall.pose[1], wall.pose[5]
        c, s = math.cos(yaw), math.sin(yaw)
        half = wall.size[1] / 2
        side = min((half, -half), key=lambda v: math.hypot(cx - s * v, cy + c * v))
        points = np.array([(cx + c * u - s * side, cy + s * u + c * side)
                           for u in np.linspace(-FACE_HALF, FACE_HALF, 25)])
        shown = distance_field(others, points[:, 0], points[:, 1]) > near
        seen = [np.min(np.hypot(xs - px, ys - py)) <= near for px, py in points[shown]]
        return float(np.mean(seen)) if seen else 0.0


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "test_slam", TestSlam)
