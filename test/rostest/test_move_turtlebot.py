#!/usr/bin/env python3
"""rostest node: ``move_turtlebot 0.2 0.5`` drives the sim in a circle of radius 0.4 m and
stops the robot when interrupted; bad arguments get a usage line and status 2.

The test starts ``move_turtlebot`` as a user does (the package's executable, arguments on the
command line) and interrupts it with SIGINT, what Ctrl-C sends. Path and rates are measured
between odometry stamps (sim time); the launch file runs the sim at real time.
"""
import math
import os
import unittest

import numpy as np
import rospy
import rostest
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry

from sim_test_support import WAIT, NodeProcess, Recorder, later, wait_for, yaw_of

LINEAR, ANGULAR = 0.2, 0.5
RADIUS = LINEAR / ANGULAR  # 0.4 m


def fit_circle(xy):
    """(centre x, centre y, radius) of the least-squares circle through points (N x 2)."""
    x, y = xy[:, 0], xy[:, 1]
    a = np.column_stack([x, y, np.ones_like(x)])
    b = x * x + y * y
    (c0, c1, c2), *_ = np.linalg.lstsq(a, b, rcond=None)
    cx, cy = c0 / 2.0, c1 / 2.0
    return cx, cy, math.sqrt(c2 + cx * cx + cy * cy)


class MoveTurtlebotTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_move_turtlebot")
        cls.odom = Recorder("odom", Odometry)
        cls.cmd = Recorder("cmd_vel", Twist)
        assert cls.odom.latest(30.0) is not None, "no odom"
        cls.node = None

    @classmethod
    def tearDownClass(cls):
        if cls.node is not None:
            cls.node.kill()

    def later(self, msg, seconds):
        return later(self.odom, msg, seconds)

    def test_1_circle_then_stop_on_sigint(self):
        start_pose = self.odom.latest()
        type(self).node = node = NodeProcess("move_turtlebot", "%g" % LINEAR, "%g" % ANGULAR)

        # It reaches the commanded twist (the sim ramps the wheels at 1 m/s^2).
        steady = wait_for(lambda: abs(self.odom.latest().twist.twist.linear.x - LINEAR) < 0.01
                          and abs(self.odom.latest().twist.twist.angular.z - ANGULAR) < 0.03,
                          WAIT)
        self.assertTrue(steady, "odometry never showed (%g, %g); move_turtlebot said:\n%s%s"
                        % (LINEAR, ANGULAR, node.stdout, node.stderr))
        first = self.odom.latest()

        # One full turn (2 pi / 0.5 = 12.6 s of sim time): a circle of radius 0.4 m.
        period = 2.0 * math.pi / ANGULAR
        last = self.later(first, period)
        msgs = self.odom.between(first.header.stamp, last.header.stamp)
        self.assertGreater(len(msgs), 0.8 * 30 * period, "odometry too sparse")
        xy = np.array([(m.pose.pose.position.x, m.pose.pose.position.y) for m in msgs])
        cx, cy, radius = fit_circle(xy)
        rospy.loginfo("circle: centre (%.3f, %.3f), radius %.3f m", cx, cy, radius)
        self.assertAlmostEqual(radius, RADIUS, delta=0.1 * RADIUS)
        spread = np.hypot(xy[:, 0] - cx, xy[:, 1] - cy)
        self.assertLess(float(np.max(np.abs(spread - radius))), 0.03, "not a circle")
        # Counter-clockwise (angular.z > 0): the centre is on the robot's left.
        heading = yaw_of(first.pose.pose.orientation)
        p = first.pose.pose.position
        left = -math.sin(heading) * (cx - p.x) + math.cos(heading) * (cy - p.y)
        self.assertAlmostEqual(left, RADIUS, delta=0.1 * RADIUS)
        # After one period it is back where it was.
        q = last.pose.pose.position
        self.assertLess(math.hypot(q.x - p.x, q.y - p.y), 0.08)
        # It is the circle that starts where the robot stood: 0.4 m to the left of it.
        s, h = start_pose.pose.pose.position, yaw_of(start_pose.pose.pose.orientation)
        self.assertLess(math.hypot(cx - (s.x - RADIUS * math.sin(h)),
                                   cy - (s.y + RADIUS * math.cos(h))), 0.05)

        # The commands: (0.2, 0.5) on /cmd_vel at about 10 Hz of ROS time.
        cmds, times = self.cmd.snapshot()
        window = [c for c, t in zip(cmds, times)
                  if first.header.stamp <= t <= last.header.stamp]
        self.assertTrue(all(c.linear.x == LINEAR and c.angular.z == ANGULAR for c in window))
        rate = len(window) / period
        rospy.loginfo("cmd_vel: %d messages in %.1f s of sim time", len(window), period)
        self.assertAlmostEqual(rate, 10.0, delta=2.5, msg="publishing rate %.1f Hz" % rate)

        # Ctrl-C: the node exits cleanly, a zero Twist was its last word, the robot stops.
        status = node.interrupt(20.0)
        self.assertIsNotNone(status, "move_turtlebot still running 20 s after SIGINT")
        self.assertEqual(status, 0, node.stderr)
        self.assertNotIn("Traceback", node.stderr + node.stdout)
        self.assertTrue(wait_for(lambda: self.cmd.snapshot()[0][-1] == Twist(), 5.0),
                        "last cmd_vel is %s" % self.cmd.snapshot()[0][-1])
        stopped_at = self.odom.latest()
        rest = self.later(stopped_at, 1.0)
        self.assertLess(abs(rest.twist.twist.linear.x), 0.005)
        self.assertLess(abs(rest.twist.twist.angular.z), 0.01)
        end = self.later(rest, 2.0)
        a, b = rest.pose.pose.position, end.pose.pose.position
        self.assertLess(math.hypot(b.x - a.x, b.y - a.y), 0.005, "still moving after the stop")
        self.assertLess(abs(yaw_of(end.pose.pose.orientation) - yaw_of(rest.pose.pose.orientation)),
                        0.01)

    def test_3_command_line_settings_last_one_run(self):
        """``_duration:=2 _rate:=5`` hold for that run: it stops by itself after 2 s of sim time,
        and nothing is left on the parameter server, so a plain run after it goes on."""
        node = NodeProcess("move_turtlebot", "0.1", "0", "_duration:=2", "_rate:=5")
        status = node.wait(WAIT)
        self.assertEqual(status, 0, "move_turtlebot _duration:=2 did not end by itself: %s%s"
                         % (node.stdout, node.stderr))
        self.assertIn("2 s done", node.stdout + node.stderr)
        for name in ("/move_turtlebot/duration", "/move_turtlebot/rate"):
            self.assertFalse(rospy.has_param(name), "%s outlived the run" % name)
        plain = NodeProcess("move_turtlebot", "0", "0")
        try:
            self.assertIsNone(plain.wait(8.0), "the next plain run stopped on its own: %s%s"
                              % (plain.stdout, plain.stderr))
        finally:
            plain.interrupt(20.0)

    def test_2_bad_arguments_usage_and_status_2(self):
        env = dict(os.environ, ROS_MASTER_URI="http://localhost:9")  # no master there
        for args in ((), ("0.2",), ("0.2", "0.5", "7"), ("fast", "0.5"), ("0.2", "nan")):
            node = NodeProcess("move_turtlebot", *args, env=env)
            status = node.wait(20.0)
            if status is None:
                node.kill()
            self.assertEqual(status, 2, "move_turtlebot %s" % " ".join(args))
            self.assertIn("usage: move_turtlebot LINEAR ANGULAR", node.stderr)
            self.assertNotIn("Traceback", node.stderr)


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "test_move_turtlebot", MoveTurtlebotTest)
