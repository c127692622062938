#!/usr/bin/env python3
"""rostest node: an SDF skid-steer robot through the real /gazebo (sdf_drives.test). The model
test/fixtures/sdf_drives/skid_steer.sdf is spawned with the real command line (``rosrun
tutorial_turtlebot spawn_model -sdf -file ... -model skidbot``); commanded 0.3 m/s on /cmd_vel,
its /odom (odom -> base_footprint) moves forward about 0.3 m in 1 s of sim time, the model's
pose with it; commanded 1 rad/s it turns left; /tf carries odom -> base_footprint (its
broadcastTF).

Every wait is on wall time with a limit."""
import math
import os

import rospy
import rostest
from geometry_msgs.msg import Twist, Vector3
from nav_msgs.msg import Odometry
from tf2_msgs.msg import TFMessage

from sim_test_support import WAIT, Recorder, SimTestCase, later, spawn_model, wait_for, yaw_of

MODEL = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "fixtures",
                     "sdf_drives", "skid_steer.sdf")


class SdfDrivesTest(SimTestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.spawned = spawn_model("-sdf", "-file", MODEL, "-model", "skidbot")
        cls.cmd = rospy.Publisher("/cmd_vel", Twist, queue_size=1)

    def drive(self, linear, angular=0.0):
        self.assertTrue(wait_for(lambda: self.cmd.get_num_connections() > 0, WAIT),
                        "/gazebo does not subscribe /cmd_vel")
        self.cmd.publish(Twist(linear=Vector3(linear, 0, 0), angular=Vector3(0, 0, angular)))

    def test_1_spawned_by_the_command_line(self):
        status, out = self.spawned
        self.assertEqual(status, 0, out)
        self.assertIn("Successfully spawned entity", out)
        self.assertTrue(self.gz.wait_names(lambda n: "skidbot" in n), self.gz.names())

    def test_2_it_drives_forward_then_turns_left_on_cmd_vel(self):
        odom = Recorder("/odom", Odometry)
        try:
            first = odom.latest(WAIT)
            self.assertIsNotNone(first, "no /odom")
            self.assertEqual((first.header.frame_id, first.child_frame_id),
                             ("odom", "base_footprint"))
            self.drive(0.3)
            start = later(odom, odom.latest(WAIT), 0.5)     # under way
            end = later(odom, start, 1.0)
            self.drive(0.0, 1.0)
            turning = later(odom, end, 0.5)
            turned = later(odom, turning, 1.0)
            self.drive(0.0)
        finally:
            odom.sub.unregister()
        p0, p1 = start.pose.pose.position, end.pose.pose.position
        self.assertAlmostEqual(p1.x - p0.x, 0.3, delta=0.06)    # it spawned facing x
        self.assertAlmostEqual(p1.y, p0.y, delta=0.02)
        self.assertAlmostEqual(end.twist.twist.linear.x, 0.3, delta=0.06)
        yaw = math.remainder(yaw_of(turned.pose.pose.orientation)
                             - yaw_of(turning.pose.pose.orientation), math.tau)
        self.assertGreater(yaw, 0.25, "it did not turn left")
        now = self.gz.position("skidbot")
        p = turned.pose.pose.position
        self.assertLess(math.dist((p.x, p.y), now[:2]), 0.05, "its odometry is its pose")

    def test_3_tf_carries_odom_to_base_footprint(self):
        found = []

        def keep(msg):
            found.extend(t for t in msg.transforms
                         if (t.header.frame_id, t.child_frame_id) == ("odom", "base_footprint"))
        sub = rospy.Subscriber("/tf", TFMessage, keep, queue_size=100)
        try:
            self.assertTrue(wait_for(lambda: bool(found), WAIT), "no odom -> base_footprint")
        finally:
            sub.unregister()


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "sdf_drives", SdfDrivesTest)
