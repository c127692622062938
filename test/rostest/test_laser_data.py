#!/usr/bin/env python3
"""rostest node: what ``laser_data`` logs with a Burger at the turtlebot3_world spawn (-2.0, -0.5),
facing +x, checked against the arena (doc/turtlebot3.md 4.2): nothing within 3.5 m ahead along
y = -0.5; the hexagon's inner walls (flats 2.540 m from the centre, corners on +-x) behind, left
and right; the closest reading on the south-west wall's flat, 0.53 m away at 210 degrees.

The node runs from the .test file; its lines are read from /rosout.
"""
import math
import re
import unittest

import rospy
import rostest
from rosgraph_msgs.msg import Log

from sim_test_support import arena_wall_distance, wait_for

SPAWN = (-2.0, -0.5)
SCAN_ORIGIN = (SPAWN[0] - 0.032, SPAWN[1])  # burger base_scan is 0.032 m behind base_footprint
INCREMENT = math.degrees(6.28319 / 359)     # Gazebo's scan: 360 rays over 0..6.28319 rad
TOLERANCE = 0.06                            # m: noise sigma 0.01 plus the walls' geometry
LINES = 5

VALUE = r"(no reading|\d+\.\d\d m)"
LINE = re.compile(r"ahead: %s \| 0 deg: %s  90 deg: %s  180 deg: %s  270 deg: %s  359 deg: %s"
                  r" \| closest: (?:(\d+\.\d\d) m at (\d+) deg|no reading)$"
                  % ((VALUE,) * 6))


def wall_distance(bearing_deg: float) -> float:
    """Distance from the scan origin at the spawn to the arena's wall along a bearing."""
    return arena_wall_distance(SCAN_ORIGIN, bearing_deg)


def ray_bearing(degrees: float) -> float:
    """Bearing (degrees) of the Gazebo scan's ray nearest to ``degrees``: the ray laser_data
    reads for "90 deg" is ray 90 at 90.25 degrees, for "270 deg" ray 269 at 269.75."""
    return round(degrees / INCREMENT) % 360 * INCREMENT


def metres(text: str):
    return None if text == "no reading" else float(text.split()[0])


class LaserDataTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_laser_data")
        cls.lines = []
        cls.sub = rospy.Subscriber("/rosout", Log, cls.on_log, queue_size=100)
        wait_for(lambda: len(cls.lines) >= LINES, 60.0)

    @classmethod
    def on_log(cls, msg):
        if msg.name == "/laser_data" and msg.msg.startswith("ahead:"):
            cls.lines.append(msg.msg)

    def readings(self):
        self.assertGreaterEqual(len(self.lines), LINES, "laser_data logged %d scan lines: %s"
                                % (len(self.lines), self.lines))
        rows = []
        for line in self.lines[:LINES]:
            match = LINE.match(line)
            self.assertIsNotNone(match, "unexpected line: %r" % line)
            rows.append(match.groups())
        return rows

    def test_ahead_nothing_within_range(self):
        for ahead, deg0, _, _, _, deg359, _, _ in self.readings():
            self.assertEqual(ahead, "no reading")  # along y = -0.5: the head hexagon is 4.4 m off
            self.assertEqual(deg0, "no reading")
            self.assertEqual(deg359, "no reading")

    def test_behind_left_right_are_the_walls(self):
        expected = {name: wall_distance(ray_bearing(deg))
                    for name, deg in (("90", 90), ("180", 180), ("270", 270))}
        # 0.61 m behind, 2.05 m left, 1.05 m right (the slanted south-west and north-west flats)
        self.assertAlmostEqual(expected["180"], 0.612, delta=0.005)
        for _, _, left, behind, right, _, _, _ in self.readings():
            self.assertAlmostEqual(metres(behind), expected["180"], delta=TOLERANCE)
            self.assertAlmostEqual(metres(left), expected["90"], delta=TOLERANCE)
            self.assertAlmostEqual(metres(right), expected["270"], delta=TOLERANCE)

    def test_closest_is_the_south_west_wall(self):
        # The flat with its normal at 210 degrees is 0.530 m from the scan origin; the minimum of
        # a dozen noisy rays near it reads a little less.
        nearest = 2.540 - (math.cos(math.radians(210)) * SCAN_ORIGIN[0]
                           + math.sin(math.radians(210)) * SCAN_ORIGIN[1])
        self.assertAlmostEqual(nearest, 0.530, delta=0.001)
        for row in self.readings():
            distance, bearing = row[6], row[7]
            self.assertIsNotNone(distance, "no closest reading")
            self.assertGreater(float(distance), nearest - TOLERANCE)
            self.assertLessEqual(float(distance), nearest + 0.01)
            self.assertAlmostEqual(int(bearing), 210, delta=15)


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "test_laser_data", LaserDataTest)
