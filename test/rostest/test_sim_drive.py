#!/usr/bin/env python3
"""rostest node: driving the sim through /cmd_vel and its /gazebo services (empty world).

Distances and angles are measured between odometry stamps, so the test holds at any
real-time factor; every wait is on wall time with a limit.
"""
import math
import time
import unittest

import rospy
import rostest
from rosgraph_msgs.msg import Clock

from sim_test_support import WAIT, Driver, Recorder, later, wait_for, yaw_of


class SimDriveTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_sim_drive")
        cls.model = rospy.get_param("~model", "waffle")
        cls.max_linear = {"burger": 0.22}.get(cls.model, 0.26)
        cls.drive = Driver()
        cls.clock = Recorder("/clock", Clock)
        assert cls.drive.odom.latest(30.0) is not None, "no odom"

    def setUp(self):
        self.drive.send(0.0, 0.0)
        self.drive.call("/gazebo/reset_world")
        self.drive.odom.clear()  # an earlier test may have set the clock back
        self.settle()

    def settle(self):
        """Wait until the robot is at rest, then return the latest odometry."""
        self.assertTrue(wait_for(lambda: abs(self.drive.odom.latest().twist.twist.linear.x) < 0.005
                                 and abs(self.drive.odom.latest().twist.twist.angular.z) < 0.01,
                                 WAIT), "robot does not come to rest")
        return self.drive.odom.latest()

    def steady(self, linear, angular):
        """Command a twist, wait until odometry shows it, return that odometry message."""
        self.drive.send(linear, angular)
        ok = wait_for(lambda: abs(self.drive.odom.latest().twist.twist.linear.x - linear) < 0.01
                      and abs(self.drive.odom.latest().twist.twist.angular.z - angular) < 0.05,
                      WAIT)
        self.assertTrue(ok, "odometry never reached (%.2f, %.2f)" % (linear, angular))
        return self.drive.odom.latest()

    def later(self, msg, seconds):
        return later(self.drive.odom, msg, seconds)

    def test_straight_0_2_for_5_s_moves_1_m(self):
        start = self.steady(0.2, 0.0)
        end = self.later(start, 5.0)
        p0, p1 = start.pose.pose.position, end.pose.pose.position
        self.assertAlmostEqual(math.hypot(p1.x - p0.x, p1.y - p0.y), 1.0, delta=0.05)
        self.assertLess(abs(p1.y - p0.y), 0.03)

    def test_turn_0_5_for_4_s_turns_2_rad_in_place(self):
        start = self.steady(0.0, 0.5)
        end = self.later(start, 4.0)
        turned = 0.0
        msgs = self.drive.odom.between(start.header.stamp, end.header.stamp)
        for a, b in zip(msgs, msgs[1:]):
            step = yaw_of(b.pose.pose.orientation) - yaw_of(a.pose.pose.orientation)
            turned += math.atan2(math.sin(step), math.cos(step))
        self.assertAlmostEqual(turned, 2.0, delta=0.08)
        p0, p1 = start.pose.pose.position, end.pose.pose.position
        self.assertLess(math.hypot(p1.x - p0.x, p1.y - p0.y), 0.03, "drifts while turning")

    def test_speed_is_clamped_to_the_model_limit(self):
        self.drive.send(5.0, 0.0)
        self.assertTrue(wait_for(lambda: self.drive.odom.latest().twist.twist.linear.x
                                 > self.max_linear - 0.01, WAIT))
        start = self.drive.odom.latest()
        end = self.later(start, 2.0)
        speed = (end.pose.pose.position.x - start.pose.pose.position.x) / 2.0
        self.assertAlmostEqual(speed, self.max_linear, delta=0.015)

    def test_nan_command_is_ignored(self):
        before = self.steady(0.1, 0.0)
        self.drive.send(float("nan"), 0.0)
        self.drive.send(0.1, float("inf"))
        end = self.later(before, 2.0)
        self.assertAlmostEqual(end.twist.twist.linear.x, 0.1, delta=0.01)
        self.assertTrue(math.isfinite(end.pose.pose.position.x))

    def test_reset_world_returns_to_spawn_and_time_runs_on(self):
        moved = self.later(self.steady(0.2, 0.3), 2.0)
        self.assertGreater(math.hypot(moved.pose.pose.position.x, moved.pose.pose.position.y), 0.3)
        self.drive.send(0.0, 0.0)
        self.drive.call("/gazebo/reset_world")  # returns once the reset is done
        self.drive.odom.clear()
        after = self.drive.odom.latest(WAIT)
        self.assertIsNotNone(after)
        p = after.pose.pose.position
        self.assertLess(math.hypot(p.x, p.y), 0.01)
        self.assertGreater(after.header.stamp, moved.header.stamp)

    def test_reset_simulation_sets_time_back(self):
        self.assertTrue(wait_for(lambda: self.clock.latest().clock.to_sec() > 3.0, WAIT))
        self.drive.call("/gazebo/reset_simulation")
        self.assertTrue(wait_for(lambda: self.clock.latest().clock.to_sec() < 2.0, 10.0),
                        "clock did not go back to 0")

    def test_pause_stops_the_clock(self):
        self.drive.call("/gazebo/pause_physics")
        try:
            time.sleep(0.3)
            paused_at = self.clock.latest().clock
            time.sleep(1.0)
            self.assertEqual(self.clock.latest().clock, paused_at)
        finally:
            self.drive.call("/gazebo/unpause_physics")
        self.assertTrue(wait_for(lambda: self.clock.latest().clock > paused_at, 10.0))


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "sim_drive", SimDriveTest)
