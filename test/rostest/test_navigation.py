#!/usr/bin/env python3
"""rostest node: the e-Manual's Navigation chapter on the sim. A map of the world is written
from the world's shapes as the sim reads them (nav_support.write_world_map, in the world frame);
``roslaunch tutorial_turtlebot turtlebot3_navigation.launch sim:=true rviz:=false
map_file:=...`` (map_server, amcl, move_base with ROBOTIS' parameters) runs in the navigation
extra's environment; the initial pose is set on /initialpose and the goals sent on
/move_base_simple/goal, as RViz's 2D Pose Estimate and 2D Nav Goal send them.

Checks: move_base reports each goal reached (/move_base/status), and the robot's true pose
(/gazebo/model_states) is then within ~xy_tolerance m and ~yaw_tolerance rad of it; every amcl
pose (/amcl_pose) lies within ~amcl_tolerance m of the true pose at its stamp; the robot's
footprint never enters a shape of the world (no collision).

Skipped, in one line, where the extra is not installed.
Params: ~model (burger), ~world (turtlebot3_world), ~spawn ("x y yaw", world frame, m and rad),
~goals ("x y yaw; x y yaw; ..."), ~map_box ("xmin ymin xmax ymax" of the map, m),
~real_time_factor (2.0), ~goal_timeout (sim s per goal, 120), ~xy_tolerance (0.2),
~yaw_tolerance (0.3), ~amcl_tolerance (0.1), ~initial_sigma and ~initial_sigma_yaw (the
initial pose's spread, m and rad: RViz's 0.5 and 0.26 by default).
"""
import bisect
import math
import os
import threading
import unittest

import numpy as np
import rospy
import rostest
from actionlib_msgs.msg import GoalStatus, GoalStatusArray
from geometry_msgs.msg import PoseStamped, PoseWithCovarianceStamped

from nav_support import (NOT_INSTALLED, Launch, TruePose, angle_diff, distance_field, log_dir,
                         nav_env, world_shapes, write_world_map)
from sim_test_support import pose, wait_for

WAIT = 120.0      # wall s: the sim, map_server, amcl and move_base up, on a busy machine
# The Burger's footprint (ROBOTIS' costmap_common_params_burger), in base_footprint (m): its
# corners and edge midpoints are checked against the world's shapes.
FOOTPRINT = ((-0.105, -0.105), (-0.105, 0.105), (0.041, 0.105), (0.041, -0.105))


def numbers(text: str):
    return [float(v) for v in text.split()]


def footprint_points():
    points = []
    for (ax, ay), (bx, by) in zip(FOOTPRINT, FOOTPRINT[1:] + FOOTPRINT[:1]):
        points += [(ax, ay), ((ax + bx) / 2, (ay + by) / 2)]
    return points


class TestNavigation(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_navigation")
        cls.env = nav_env()
        cls.launch = None
        if cls.env is None:
            return                # each test skips, saying how to install the extra
        p = rospy.get_param
        cls.world, model = p("~world", "turtlebot3_world"), p("~model", "burger")
        cls.spawn = numbers(p("~spawn", "-2.0 -0.5 0.0"))
        cls.goals = [numbers(g) for g in p("~goals", "").split(";") if g.strip()]
        stem = os.path.join(log_dir(), "test_navigation_map")
        map_file = write_world_map(cls.world, stem, numbers(p("~map_box", "-3.3 -3.3 3.3 3.3")))
        cls.launch = Launch(cls.env, "turtlebot3_navigation.launch", "sim:=true", "rviz:=false",
                            "model:=" + model, "world:=" + cls.world,
                            "map_file:=" + map_file, "x_pos:=%g" % cls.spawn[0],
                            "y_pos:=%g" % cls.spawn[1], "yaw:=%g" % cls.spawn[2],
                            "real_time_factor:=%g" % p("~real_time_factor", 2.0))
        cls.truth = TruePose(cls.world, model, cls._on_truth)
        cls.history = []          # (sim s, x, y, yaw): the true pose as it came
        cls.amcl = []             # (sim s, x, y) of /amcl_pose
        cls.status = None
        cls.lock = threading.Lock()
        rospy.Subscriber("/amcl_pose", PoseWithCovarianceStamped, cls._on_amcl)
        rospy.Subscriber("/move_base/status", GoalStatusArray, cls._on_status)
        cls.initial = rospy.Publisher("/initialpose", PoseWithCovarianceStamped, queue_size=1,
                                      latch=True)
        cls.goal = rospy.Publisher("/move_base_simple/goal", PoseStamped, queue_size=1)

    @classmethod
    def _on_truth(cls, xyyaw):
        with cls.lock:
            cls.history.append((rospy.Time.now().to_sec(),) + xyyaw)

    @classmethod
    def _on_amcl(cls, msg):
        p = msg.pose.pose.position
        with cls.lock:
            cls.amcl.append((msg.header.stamp.to_sec(), p.x, p.y))

    @classmethod
    def _on_status(cls, msg):
        cls.status = msg

    @classmethod
    def tearDownClass(cls):
        if cls.launch is not None:
            cls.launch.stop()

    def setUp(self):
        if self.env is None:
            self.skipTest(NOT_INSTALLED)

    def goal_state(self, goal_id):
        """The status of the goal whose id is not in ``goal_id`` (the ids before it), or None."""
        for s in (self.status.status_list if self.status else []):
            if s.goal_id.id not in goal_id:
                return s.status
        return None

    def test_goals_reached(self):
        up = wait_for(lambda: self.truth.pose is not None and self.status is not None
                      and self.goal.get_num_connections() > 0, WAIT)
        self.assertTrue(up, "sim or move_base not up within %g s; roslaunch said:\n%s"
                        % (WAIT, self.launch.tail()))
        shapes = world_shapes(self.world)
        for gx, gy, _ in self.goals:
            clear = distance_field(shapes, np.array([gx]), np.array([gy]))[0]
            self.assertGreater(clear, 0.3, "goal (%g, %g) is too near a shape" % (gx, gy))

        # As RViz's 2D Pose Estimate: the spawn, with ~initial_sigma (m) and
        # ~initial_sigma_yaw (rad) (RViz's own: 0.5 m, 0.26 rad).
        x, y, yaw = self.spawn
        initial = PoseWithCovarianceStamped()
        initial.header.frame_id = "map"
        initial.header.stamp = rospy.Time.now()
        initial.pose.pose = pose(x, y, 0.0, yaw)
        initial.pose.covariance[0] = initial.pose.covariance[7] = rospy.get_param(
            "~initial_sigma", 0.5) ** 2
        initial.pose.covariance[35] = rospy.get_param("~initial_sigma_yaw", 0.2618) ** 2
        self.initial.publish(initial)
        self.assertTrue(wait_for(lambda: self.amcl, 60.0), "amcl published no pose")
        with self.lock:
            del self.amcl[:]

        timeout = rospy.get_param("~goal_timeout", 120.0)
        for number, (gx, gy, gyaw) in enumerate(self.goals, 1):
            before = {s.goal_id.id for s in (self.status.status_list if self.status else [])}
            goal = PoseStamped()
            goal.header.frame_id = "map"
            goal.header.stamp = rospy.Time.now()
            goal.pose = pose(gx, gy, 0.0, gyaw)
            self.goal.publish(goal)
            deadline = rospy.Time.now() + rospy.Duration(timeout)
            while (not rospy.is_shutdown() and rospy.Time.now() < deadline
                   and self.goal_state(before) in (None, GoalStatus.PENDING, GoalStatus.ACTIVE)):
                rospy.sleep(0.2)
            state = self.goal_state(before)
            tx, ty, tyaw = self.truth.pose
            self.assertEqual(state, GoalStatus.SUCCEEDED,
                             "goal %d (%g, %g, %g): move_base status %s, the robot at "
                             "(%.2f, %.2f, %.2f); roslaunch said:\n%s"
                             % (number, gx, gy, gyaw, state, tx, ty, tyaw, self.launch.tail()))
            rospy.sleep(1.0)
            tx, ty, tyaw = self.truth.pose
            rospy.loginfo("test_navigation: goal %d reached: %.3f m, %.3f rad off", number,
                          math.hypot(tx - gx, ty - gy), abs(angle_diff(tyaw, gyaw)))
            self.assertLessEqual(math.hypot(tx - gx, ty - gy),
                                 rospy.get_param("~xy_tolerance", 0.2))
            self.assertLessEqual(abs(angle_diff(tyaw, gyaw)),
                                 rospy.get_param("~yaw_tolerance", 0.3))

        self.check_amcl()
        self.check_no_collision(shapes)

    def check_amcl(self):
        """Every amcl pose within ~amcl_tolerance of the true pose at its stamp."""
        with self.lock:
            history, amcl = list(self.history), list(self.amcl)
        times = [h[0] for h in history]
        errors = []
        for stamp, ax, ay in amcl:
            i = bisect.bisect_left(times, stamp)
            if 0 < i < len(times):
                _, tx, ty, _ = min(history[i - 1], history[i], key=lambda h: abs(h[0] - stamp))
                errors.append(math.hypot(ax - tx, ay - ty))
        self.assertGreater(len(errors), 5, "too few amcl poses while driving")
        rospy.loginfo("test_navigation: amcl off by %.3f m median, %.3f m at most (%d poses)",
                      float(np.median(errors)), max(errors), len(errors))
        self.assertLessEqual(max(errors), rospy.get_param("~amcl_tolerance", 0.1))

    def check_no_collision(self, shapes):
        """The footprint's corners and edge midpoints outside every shape, all along."""
        with self.lock:
            history = list(self.history[::10])
        points = footprint_points()
        xs, ys = [], []
        for _, x, y, yaw in history:
            c, s = math.cos(yaw), math.sin(yaw)
            xs += [x + c * px - s * py for px, py in points]
            ys += [y + s * px + c * py for px, py in points]
        closest = float(np.min(distance_field(shapes, np.array(xs), np.array(ys))))
        rospy.loginfo("test_navigation: footprint at least %.3f m from the world's shapes "
                      "(%d poses)", closest, len(history))
        self.assertGreater(closest, 0.0, "the robot's footprint entered a shape")


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "test_navigation", TestNavigation)
