#!/usr/bin/env python3
"""rostest node: a robot's range sensor and bumper through the real /gazebo (robot_sensors.test).
The URDF test/fixtures/robot_sensors/probe.urdf is spawned with the real command line
(``rosrun tutorial_turtlebot spawn_model -urdf -file ... -model probe -robot_namespace probe``)
at the origin of test/fixtures/robot_sensors/robot_sensors.world: its range sensor, 0.2 m behind
the robot's origin, reads through it the wall whose face is 0.5 m ahead on /probe/front/range
(sensor_msgs/Range) in frame probe/sonar_link; its bumper on /probe/bumper
(gazebo_msgs/ContactsState) reports its chassis on the floor.

Every wait is on wall time with a limit."""
import os

import rostest
from gazebo_msgs.msg import ContactsState
from sensor_msgs.msg import Range

from sim_test_support import SimTestCase, one_message, spawn_model

URDF = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "fixtures",
                    "robot_sensors", "probe.urdf")


class RobotSensorsTest(SimTestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.spawned = spawn_model("-urdf", "-file", URDF, "-model", "probe",
                                  "-robot_namespace", "probe", "-z", "0.035")

    def test_1_spawned_by_the_command_line(self):
        status, out = self.spawned
        self.assertEqual(status, 0, out)
        self.assertIn("Successfully spawned entity", out)
        self.assertTrue(self.gz.wait_names(lambda n: "probe" in n), self.gz.names())

    def test_2_the_range_reads_the_wall_ahead(self):
        msg = one_message("/probe/front/range", Range)
        self.assertIsNotNone(msg, "no /probe/front/range")
        self.assertEqual(msg.header.frame_id, "probe/sonar_link")
        self.assertEqual(msg.radiation_type, Range.ULTRASOUND)
        self.assertAlmostEqual(msg.min_range, 0.02, places=6)      # float32
        self.assertAlmostEqual(msg.max_range, 3.0, places=6)
        self.assertAlmostEqual(msg.range, 0.7, delta=0.02)

    def test_3_the_bumper_reports_the_chassis_on_the_floor(self):
        msg = one_message("/probe/bumper", ContactsState)
        self.assertIsNotNone(msg, "no /probe/bumper")
        self.assertEqual(msg.header.frame_id, "probe/chassis")
        self.assertEqual([(s.collision1_name, s.collision2_name) for s in msg.states],
                         [("probe::chassis::chassis_collision", "ground::link::collision")])
        self.assertGreater(msg.states[0].total_wrench.force.z, 1.0)


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "robot_sensors", RobotSensorsTest)
