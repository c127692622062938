#!/usr/bin/env python3
"""rostest node: a second simulator on the same master is refused, and the first one goes on
as if nothing happened (single_sim.test)."""
import os
import subprocess
import unittest
import xmlrpc.client

import rosgraph
import rospy
import rostest
from rosgraph_msgs.msg import Clock

from sim_test_support import WAIT, NodeProcess, wait_for


class SingleSimTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_single_sim")
        cls.master = rosgraph.Master("/test_single_sim")
        assert wait_for(lambda: cls.lookup("/gazebo") is not None, WAIT), "no /gazebo"
        assert wait_for(lambda: cls.lookup("/robot_state_publisher") is not None, WAIT)

    @classmethod
    def lookup(cls, node):
        try:
            return cls.master.lookupNode(node)
        except rosgraph.MasterException:
            return None

    def state(self):
        """What must not change: /gazebo's pid and URI, robot_state_publisher's URI, /model."""
        uri = self.lookup("/gazebo")
        pid = xmlrpc.client.ServerProxy(uri).getPid("/test_single_sim")[2]
        return pid, uri, self.lookup("/robot_state_publisher"), rospy.get_param("/model")

    def clock_runs(self):
        """True when /clock moves on."""
        first = rospy.wait_for_message("/clock", Clock, WAIT).clock
        return wait_for(lambda: rospy.wait_for_message("/clock", Clock, WAIT).clock > first,
                        WAIT)

    def assert_refused(self, status, output):
        self.assertIsNotNone(status, "the second simulator is still running:\n" + output)
        self.assertNotEqual(status, 0, output)
        self.assertIn("a simulator is already running on this ROS master (/gazebo at", output)
        self.assertNotIn("Traceback", output)

    def test_second_roslaunch_is_refused_and_changes_nothing(self):
        before = self.state()
        self.assertEqual(before[3], "waffle")
        run = subprocess.run(["roslaunch", "tutorial_turtlebot", "sim.launch", "model:=burger"],
                             stdin=subprocess.DEVNULL, capture_output=True, text=True,
                             timeout=WAIT, env=dict(os.environ))
        self.assert_refused(run.returncode, run.stdout + run.stderr)
        self.assertEqual(self.state(), before)
        self.assertTrue(self.clock_runs(), "the first simulator's clock stopped")

    def test_second_rosrun_sim_is_refused_and_changes_nothing(self):
        before = self.state()
        node = NodeProcess("sim")
        status = node.wait(WAIT)
        if status is None:
            node.kill()
        self.assert_refused(status, node.stdout + node.stderr)
        self.assertEqual(node.stderr.strip().count("\n"), 0, "more than one line:\n" + node.stderr)
        self.assertEqual(self.state(), before)
        self.assertTrue(self.clock_runs(), "the first simulator's clock stopped")


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "test_single_sim", SingleSimTest)
