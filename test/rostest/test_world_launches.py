#!/usr/bin/env python3
"""rostest node: turtlebot3_house.launch with a Burger: /odom starts at the spawn (-3, 1) facing
+x, and the scan there meets the house's walls where doc/turtlebot3.md 4.3 puts them.

From the Burger's scan origin (0.032 m behind base_footprint, 0.182 m up) at (-3.032, 1.0):
ahead (+x) Wall_101's west face at x -0.125; behind (-x) Wall_99 / Wall_88's east face at
x -5.075; right (-y) the 1.0 m Wall_108's north face at y -0.0999; left (+y) nothing within the
3.5 m range (the big central room is 4.2 m deep there).
"""
import math
import unittest

import numpy as np
import rospy
import rostest
from nav_msgs.msg import Odometry
from sensor_msgs.msg import LaserScan

from sim_test_support import Recorder, wait_for, yaw_of

SPAWN = (-3.0, 1.0)
SCAN_ORIGIN = (SPAWN[0] - 0.032, SPAWN[1])
EXPECTED = {                      # bearing (deg) -> distance (m) from the scan origin
    0: -0.125 - SCAN_ORIGIN[0],          # 2.907 to Wall_101
    180: SCAN_ORIGIN[0] - -5.075,        # 2.043 to Wall_99
    270: SCAN_ORIGIN[1] - -0.0999,       # 1.100 to Wall_108
}
TOLERANCE = 0.05                  # m: noise sigma 0.01, a 1 degree step off the exact bearing


def reading(scan, bearing_deg):
    """Median of the three readings nearest ``bearing_deg`` (from angle_min, angle_increment)."""
    index = int(round((math.radians(bearing_deg) - scan.angle_min) / scan.angle_increment))
    n = len(scan.ranges)
    return float(np.median([scan.ranges[(index + k) % n] for k in (-1, 0, 1)]))


class WorldLaunchesTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_world_launches")
        cls.odom = Recorder("odom", Odometry)
        cls.scan = Recorder("scan", LaserScan)
        for rec in (cls.odom, cls.scan):
            assert rec.latest(40.0) is not None, "no message on %s" % rec.sub.name

    def test_world_parameter(self):
        self.assertEqual(rospy.get_param("/gazebo/world"), "turtlebot3_house")

    def test_odom_starts_at_the_house_spawn(self):
        first = self.odom.msgs[0]
        p = first.pose.pose.position
        self.assertAlmostEqual(p.x, SPAWN[0], delta=0.02)
        self.assertAlmostEqual(p.y, SPAWN[1], delta=0.02)
        self.assertAlmostEqual(yaw_of(first.pose.pose.orientation), 0.0, delta=0.02)

    def test_scan_meets_the_house_walls(self):
        self.assertTrue(wait_for(lambda: len(self.scan.msgs) >= 3, 20.0), "fewer than 3 scans")
        scans = self.scan.msgs[-3:]
        for bearing, distance in EXPECTED.items():
            measured = np.median([reading(s, bearing) for s in scans])
            self.assertAlmostEqual(measured, distance, delta=TOLERANCE,
                                   msg="bearing %d deg: %.3f m, expected %.3f m"
                                   % (bearing, measured, distance))
        left = [reading(s, 90) for s in scans]
        self.assertTrue(all(math.isinf(r) and r > 0 for r in left), left)


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "world_launches", WorldLaunchesTest)
