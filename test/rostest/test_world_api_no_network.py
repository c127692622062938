#!/usr/bin/env python3
"""rostest node: /gazebo with enable_ros_network false (the empty world, no robot): it runs
its clock and offers only /clock, rospy's /rosout publisher and its logger services, as
gazebo_ros' own ros_network_disabled test lists; no world API service comes.

Every wait is on wall time with a limit. Not a SimTestCase: there are no services to wait
for."""
import unittest

import rosgraph
import rospy
import rostest
from rosgraph_msgs.msg import Clock

from sim_test_support import WAIT, Recorder, wait_for


class WorldApiNoNetworkTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_world_api_no_network")

    def test_only_the_clock_and_rospys_own(self):
        clock = Recorder("/clock", Clock)
        self.assertTrue(wait_for(lambda: len(clock.msgs) > 10, WAIT), "no /clock")
        first = clock.msgs[0].clock
        self.assertTrue(wait_for(lambda: clock.msgs[-1].clock - first > rospy.Duration(1.0),
                                 WAIT), "the clock stalled")
        state = rosgraph.Master("/test").getSystemState()
        topics, subscriptions, services = (
            {name for name, nodes in kind if "/gazebo" in nodes} for kind in state)
        self.assertEqual(topics, {"/clock", "/rosout"})
        self.assertEqual(subscriptions, set())
        self.assertEqual(services, {"/gazebo/get_loggers", "/gazebo/set_logger_level"})
        with self.assertRaises(rospy.ROSException):
            rospy.wait_for_service("/gazebo/get_world_properties", timeout=2.0)


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "world_api_no_network", WorldApiNoNetworkTest)
