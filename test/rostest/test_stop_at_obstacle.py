#!/usr/bin/env python3
"""rostest node: stop_at_obstacle, started by the .test file with a Burger facing the pillar at
(-1.1, 0.0) (r 0.15, so its face toward the robot is at x = -1.25): the robot drives, comes to rest
with the pillar 0.4 to 0.5 m (plus the laser's noise) from its laser (ground truth from /odom:
base_scan is 0.032 m behind base_footprint) and stays at rest; put back at the spawn, it drives
on and stops again.

Distances and durations are measured between odometry stamps (sim time).
"""
import math
import unittest

import rospy
import rostest
from geometry_msgs.msg import Twist

from sim_test_support import WAIT, Driver, Recorder, later, wait_for, yaw_of

PILLAR = (-1.1, 0.0)  # centre, m
PILLAR_RADIUS = 0.15
SCAN_BEHIND = 0.032   # m, base_scan behind base_footprint (burger)
SPEED = 0.15          # stop_at_obstacle.launch's default ~speed
# The laser's gaussian noise (sigma 0.01 m, as Gazebo's Burger) makes the nearest of the ~30 rays
# ahead read about 2 sigma short: the node may stop on a reading of 0.50 m when the surface is
# 0.52 m away (seen once in CI: at rest 0.512 m). 3 sigma over the stop distance is still a stop.
NOISE_MARGIN = 0.03   # m


def pillar_distance(odom) -> float:
    """Distance (m) from the laser to the pillar's surface, from a ground-truth odometry pose."""
    p, q = odom.pose.pose.position, odom.pose.pose.orientation
    yaw = yaw_of(q)
    sx, sy = p.x - SCAN_BEHIND * math.cos(yaw), p.y - SCAN_BEHIND * math.sin(yaw)
    return math.hypot(PILLAR[0] - sx, PILLAR[1] - sy) - PILLAR_RADIUS


class StopAtObstacleTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_stop_at_obstacle")
        cls.cmd = Recorder("cmd_vel", Twist)
        cls.drive = Driver()  # the sim's services, and /odom
        cls.odom = cls.drive.odom
        assert cls.odom.latest(30.0) is not None, "no odom"

    def later(self, msg, seconds):
        return later(self.odom, msg, seconds)

    def drives_then_rests(self):
        """Wait until the robot drives at ~speed, then until it is at rest; check where it rests
        and that it stays there. Returns the distance to the pillar."""
        self.assertTrue(wait_for(lambda: self.odom.latest().twist.twist.linear.x > SPEED - 0.01,
                                 WAIT), "the robot never drove at %g m/s" % SPEED)
        moving = self.odom.latest()
        self.assertGreater(pillar_distance(moving), 0.5, "started inside the stop distance")
        self.assertTrue(wait_for(lambda: abs(self.odom.latest().twist.twist.linear.x) < 0.002,
                                 WAIT), "the robot never stopped")
        rest = self.odom.latest()
        distance = pillar_distance(rest)
        rospy.loginfo("at rest %.3f m from the pillar", distance)
        self.assertGreaterEqual(distance, 0.4)
        self.assertLessEqual(distance, 0.5 + NOISE_MARGIN)
        # It stays there: 3 s of sim time later it has not moved, and every command was zero.
        end = self.later(rest, 3.0)
        a, b = rest.pose.pose.position, end.pose.pose.position
        self.assertLess(math.hypot(b.x - a.x, b.y - a.y), 0.003, "crept after stopping")
        cmds, times = self.cmd.snapshot()
        held = [c for c, t in zip(cmds, times) if rest.header.stamp <= t <= end.header.stamp]
        self.assertGreaterEqual(len(held), 10, "stop_at_obstacle fell silent")  # 5 Hz scans
        self.assertTrue(all(c == Twist() for c in held), "non-zero command while at rest")
        return distance

    def test_stops_before_the_pillar_and_drives_on_when_clear(self):
        self.drives_then_rests()
        # The way clears (the robot is back at its spawn, 0.78 m from the pillar): on again.
        self.drive.call("/gazebo/reset_world")
        self.odom.clear()
        self.assertIsNotNone(self.odom.latest(WAIT))
        self.drives_then_rests()


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "test_stop_at_obstacle", StopAtObstacleTest)
