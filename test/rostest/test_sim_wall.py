#!/usr/bin/env python3
"""rostest node: full speed into the turtlebot3_world wall (spawned facing it) for 20 s of sim
time. The robot must end at the wall, in the corner it slides into, never through it, and
upright. /odom is ground truth here (odom_source world)."""
import math
import unittest

import rospy
import rostest

from sim_test_support import Driver, box_outside_arena, wait_for, yaw_of


class SimWallTest(unittest.TestCase):
    def test_full_speed_into_the_wall_stops_at_it(self):
        rospy.init_node("test_sim_wall")
        drive = Driver()
        start = drive.odom.latest(30.0)
        self.assertIsNotNone(start)
        self.assertAlmostEqual(abs(yaw_of(start.pose.pose.orientation)), math.pi, delta=0.05)
        drive.send(1.0, 0.0)  # clamped to the Burger's 0.22 m/s
        end = drive.odom.after(start.header.stamp + rospy.Duration(20.0), 120.0)
        drive.send(0.0, 0.0)
        self.assertIsNotNone(end, "no odometry 20 s of sim time later")
        pose = end.pose.pose
        x, y = pose.position.x, pose.position.y
        worst = box_outside_arena(x, y, yaw_of(pose.orientation))
        self.assertLess(worst, 0.01, "robot at (%.3f, %.3f) pokes %.3f m into the wall"
                        % (x, y, worst))
        self.assertGreater(worst, -0.03, "robot at (%.3f, %.3f) stopped short of the wall"
                           % (x, y))
        q = pose.orientation
        roll = math.atan2(2 * (q.w * q.x + q.y * q.z), 1 - 2 * (q.x * q.x + q.y * q.y))
        pitch = math.asin(max(-1.0, min(1.0, 2 * (q.w * q.y - q.z * q.x))))
        self.assertLess(max(abs(roll), abs(pitch)), 0.2, "robot tipped over")
        self.assertTrue(wait_for(lambda: abs(drive.odom.latest().twist.twist.linear.x) < 0.05,
                                 30.0))


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "sim_wall", SimWallTest)
