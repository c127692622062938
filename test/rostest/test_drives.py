#!/usr/bin/env python3
"""rostest node: a skid-steer robot through the real /gazebo (drives.test). The URDF
test/fixtures/drives/skid_steer.urdf is spawned with the real command line (``rosrun
tutorial_turtlebot spawn_model -urdf -file ... -model skid -robot_namespace skid``); commanded
0.3 m/s on /skid/cmd_vel, its /skid/odom (frames skid/odom -> skid/base_footprint) moves
forward about 0.3 m in 1 s of sim time, and the model's pose with it.

Every wait is on wall time with a limit."""
import os

import rospy
import rostest
from geometry_msgs.msg import Twist, Vector3
from nav_msgs.msg import Odometry

from sim_test_support import WAIT, Recorder, SimTestCase, later, spawn_model, wait_for

URDF = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "fixtures",
                    "drives", "skid_steer.urdf")


class DrivesTest(SimTestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.spawned = spawn_model("-urdf", "-file", URDF, "-model", "skid",
                                  "-robot_namespace", "skid")

    def test_1_spawned_by_the_command_line(self):
        status, out = self.spawned
        self.assertEqual(status, 0, out)
        self.assertIn("Successfully spawned entity", out)
        self.assertTrue(self.gz.wait_names(lambda n: "skid" in n), self.gz.names())

    def test_2_it_drives_on_its_cmd_vel_and_its_odom_moves_forward(self):
        odom = Recorder("/skid/odom", Odometry)
        pub = rospy.Publisher("/skid/cmd_vel", Twist, queue_size=1)
        try:
            self.assertTrue(wait_for(lambda: pub.get_num_connections() > 0, WAIT),
                            "/gazebo does not subscribe /skid/cmd_vel")
            first = odom.latest(WAIT)
            self.assertIsNotNone(first, "no /skid/odom")
            self.assertEqual((first.header.frame_id, first.child_frame_id),
                             ("skid/odom", "skid/base_footprint"))
            pub.publish(Twist(linear=Vector3(0.3, 0, 0)))
            start = later(odom, odom.latest(WAIT), 0.5)     # under way
            end = later(odom, start, 1.0)
        finally:
            odom.sub.unregister()
            pub.unregister()
        moved = end.pose.pose.position.x - start.pose.pose.position.x
        self.assertAlmostEqual(moved, 0.3, delta=0.05)
        self.assertAlmostEqual(end.pose.pose.position.y, start.pose.pose.position.y, delta=0.02)
        self.assertAlmostEqual(end.twist.twist.linear.x, 0.3, delta=0.05)
        self.assertGreater(self.gz.position("skid")[0], 0.3)


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "drives", DrivesTest)
