#!/usr/bin/env python3
"""rostest node: a world written for Gazebo by others (house_like, autorace_like,
autorace_2020_like in test/fixtures/worlds: the structures of turtlebot3_gazebo's
turtlebot3_house, turtlebot3_autorace and turtlebot3_autorace_2020 worlds, our own files) runs:
its models are in get_world_properties (what Gazebo would skip is left out), the scan sees the
obstacle straight ahead where the world puts it, and the robot drives toward it: odometry and
the scan agree on how far.

Private parameters: ``~models`` (names that must be in the world), ``~ahead`` (m, from the laser
to the obstacle straight ahead at the spawn).
"""
import unittest

import rospy
import rostest
from gazebo_msgs.srv import GetWorldProperties
from sensor_msgs.msg import LaserScan

from sim_test_support import WAIT, Driver, Recorder, later, wait_for

SPEED = 0.15        # m/s
DRIVE = 2.0         # s of sim time
TOLERANCE = 0.05    # m: the laser's noise (sigma 0.01 m) and the start and stop


def ahead(scan) -> float:
    """The median of the 5 rays around straight ahead (m): the noise averaged out a little."""
    rays = sorted(scan.ranges[i] for i in (-2, -1, 0, 1, 2))
    return rays[2]


class WildWorldTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_wild_worlds")
        rospy.wait_for_service("/gazebo/get_world_properties", timeout=WAIT)
        cls.world = rospy.ServiceProxy("/gazebo/get_world_properties", GetWorldProperties)
        cls.scans = Recorder("scan", LaserScan)
        cls.drive = Driver()
        assert cls.drive.odom.latest(WAIT) is not None, "no odom"
        assert cls.scans.latest(WAIT) is not None, "no scan"

    def test_models_scan_and_drive(self):
        names = self.world().model_names
        for name in rospy.get_param("~models"):
            self.assertIn(name, names)
        expected = float(rospy.get_param("~ahead"))
        start_scan = self.scans.latest()
        self.assertAlmostEqual(ahead(start_scan), expected, delta=TOLERANCE)
        start = self.drive.odom.latest()
        self.drive.send(SPEED, 0.0)
        moving = later(self.drive.odom, start, DRIVE)
        self.drive.send(0.0, 0.0)
        self.assertTrue(wait_for(lambda: abs(self.drive.odom.latest().twist.twist.linear.x)
                                 < 0.002, WAIT), "the robot did not stop")
        rest = self.drive.odom.latest()
        travelled = rest.pose.pose.position.x - start.pose.pose.position.x
        rospy.loginfo("%.3f m ahead, drove %.3f m (%.3f m after %g s)", ahead(start_scan),
                      travelled, moving.pose.pose.position.x - start.pose.pose.position.x, DRIVE)
        self.assertGreater(travelled, 0.8 * SPEED * DRIVE)
        end_scan = self.scans.after(rest.header.stamp + rospy.Duration(0.5), WAIT)
        self.assertIsNotNone(end_scan, "no scan after the drive")
        self.assertAlmostEqual(ahead(end_scan), expected - travelled, delta=TOLERANCE)


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "test_wild_worlds", WildWorldTest)
