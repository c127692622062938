#!/usr/bin/env python3
"""rostest node: an SDF robot through the real /gazebo (sdf_robot.test; the empty world, no
robot of its own). test/fixtures/sdf_robot/model.sdf, spawned with ``rosrun tutorial_turtlebot
spawn_model -sdf -file ... -model sdfbot``, drives forward on /cmd_vel (its diff drive in the
node's namespace): /odom moves forward, /scan comes from its laser, /tf carries odom ->
base_footprint; deleted, its topics go and a second spawn drives again.

Every wait is on wall time with a limit."""
import math
import os

import rospy
import rostest
from geometry_msgs.msg import Twist, Vector3
from nav_msgs.msg import Odometry
from sensor_msgs.msg import LaserScan
from tf2_msgs.msg import TFMessage

from sim_test_support import (WAIT, Recorder, SimTestCase, one_message, publishers, spawn_model,
                              wait_for)

MODEL = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "fixtures",
                     "sdf_robot", "model.sdf")


def spawn(name="sdfbot"):
    """rosrun tutorial_turtlebot spawn_model -sdf -file MODEL -model NAME: (exit status, its
    output)."""
    return spawn_model("-sdf", "-file", MODEL, "-model", name, "-x", "0.5", "-y", "-0.5")


class SdfRobotTest(SimTestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.spawned = spawn()
        cls.cmd = rospy.Publisher("/cmd_vel", Twist, queue_size=1)

    def drive(self, linear, angular=0.0):
        self.assertTrue(wait_for(lambda: self.cmd.get_num_connections() > 0, WAIT),
                        "nobody subscribes /cmd_vel")
        self.cmd.publish(Twist(linear=Vector3(linear, 0, 0), angular=Vector3(0, 0, angular)))

    def test_1_spawned_with_the_command_line(self):
        status, output = self.spawned
        self.assertEqual(status, 0, output)
        self.assertTrue(self.gz.wait_names(lambda n: "sdfbot" in n, WAIT), self.gz.names())

    def test_2_it_drives_forward_on_cmd_vel(self):
        odom = Recorder("/odom", Odometry)
        try:
            first = odom.latest(WAIT)
            self.assertIsNotNone(first, "no /odom")
            self.assertEqual((first.header.frame_id, first.child_frame_id),
                             ("odom", "base_footprint"))
            start = self.gz.position("sdfbot")
            self.drive(0.2)
            self.assertTrue(wait_for(lambda: math.dist(self.gz.position("sdfbot")[:2],
                                                       start[:2]) > 0.2, WAIT),
                            "it did not move 0.2 m")
            self.drive(0.0)
            last = odom.latest(WAIT)
        finally:
            odom.sub.unregister()
        moved = last.pose.pose.position.x - first.pose.pose.position.x
        self.assertGreater(moved, 0.15, "odom did not move forward (+x: it spawned facing x)")
        now = self.gz.position("sdfbot")
        p = last.pose.pose.position
        self.assertLess(math.dist((p.x, p.y), now[:2]), 0.05, "world odometry is its pose")

    def test_3_its_laser_publishes_scan(self):
        scan = one_message("/scan", LaserScan)
        self.assertIsNotNone(scan, "no /scan")
        self.assertEqual(scan.header.frame_id, "base_scan")
        self.assertEqual(len(scan.ranges), 360)

    def test_4_tf_carries_odom_to_base_footprint(self):
        found = []

        def keep(msg):
            found.extend(t for t in msg.transforms
                         if (t.header.frame_id, t.child_frame_id) == ("odom", "base_footprint"))
        sub = rospy.Subscriber("/tf", TFMessage, keep, queue_size=100)
        try:
            self.assertTrue(wait_for(lambda: bool(found), WAIT), "no odom -> base_footprint")
        finally:
            sub.unregister()

    def test_5_delete_takes_its_topics_and_a_respawn_drives(self):
        self.assertTrue(self.gz.delete_model(model_name="sdfbot").success)
        self.assertTrue(wait_for(lambda: not publishers("/odom"), WAIT), publishers("/odom"))
        status, output = spawn()
        self.assertEqual(status, 0, output)
        start = self.gz.position("sdfbot")
        self.drive(0.2)
        self.assertTrue(wait_for(lambda: math.dist(self.gz.position("sdfbot")[:2],
                                                   start[:2]) > 0.1, WAIT),
                        "the respawned robot did not drive")
        self.drive(0.0)

    def test_6_robot_namespace_puts_its_plugins_topics_there(self):
        """-robot_namespace gives every plugin of the SDF without a <robotNamespace> one, as
        gazebo_ros' spawn service does: the second robot's drive and laser are in /bot2."""
        status, output = spawn_model("-sdf", "-file", MODEL, "-model", "sdfbot2",
                                     "-robot_namespace", "bot2", "-x", "-1.5", "-y", "1.5")
        self.assertEqual(status, 0, output)
        self.assertTrue(wait_for(lambda: publishers("/bot2/odom") and publishers("/bot2/scan"),
                                 WAIT), "no /bot2/odom and /bot2/scan")
        cmd = rospy.Publisher("/bot2/cmd_vel", Twist, queue_size=1)
        try:
            self.assertTrue(wait_for(lambda: cmd.get_num_connections() > 0, WAIT))
            start, other = self.gz.position("sdfbot2"), self.gz.position("sdfbot")
            cmd.publish(Twist(linear=Vector3(0.2, 0, 0)))
            self.assertTrue(wait_for(lambda: math.dist(self.gz.position("sdfbot2")[:2],
                                                       start[:2]) > 0.1, WAIT),
                            "the namespaced robot did not drive on /bot2/cmd_vel")
            cmd.publish(Twist())
        finally:
            cmd.unregister()
        self.assertLess(math.dist(self.gz.position("sdfbot")[:2], other[:2]), 0.02,
                        "the first robot moved on the second's command")


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "test_sdf_robot", SdfRobotTest)
