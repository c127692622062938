#!/usr/bin/env python3
"""rostest node: the sim's lazy start (gazebo/node_start.py, lazy_start.test). A node that
subscribed to /scan before the sim started gets the first physics step's scan (sim time
0.0025 s), not the next one a laser period (0.2 s) later; the world API, made after the robot's
topics, is all there a moment later and answers."""
import time
import unittest

import rosgraph
import rospy
import rostest
from gazebo_msgs.srv import GetWorldProperties
from sensor_msgs.msg import LaserScan

from sim_test_support import SERVICES, WAIT, NodeProcess, wait_for

FIRST_STEP = 0.0025   # s of sim time: the first step (the default ~max_step_size)
# wall s from the first scan to the whole world API: a moment (about 0.1 s), with room for a
# loaded machine
API_MOMENT = 10.0
# what WorldApi makes last: the physics' dynamic_reconfigure; and its states topic
LAST_SERVICE = "/gazebo/set_parameters"
STATES_TOPIC = "/gazebo/model_states"


class LazyStartTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_lazy_start")
        cls.scans = []
        rospy.Subscriber("/scan", LaserScan,
                         lambda msg: cls.scans.append((time.monotonic(), msg)), queue_size=10)
        cls.sim = NodeProcess("sim", "_world:=empty", "_status_period:=0")

    @classmethod
    def tearDownClass(cls):
        if cls.sim.interrupt() is None:
            cls.sim.kill()

    def test_the_first_scan_is_the_first_steps_and_the_world_api_follows(self):
        self.assertTrue(wait_for(lambda: self.scans, WAIT), "no /scan:\n" + self.sim.stderr)
        arrived, first = self.scans[0]
        self.assertAlmostEqual(first.header.stamp.to_sec(), FIRST_STEP, places=6)
        master = rosgraph.Master("/test_lazy_start")
        wanted = ["/gazebo/" + name for name in SERVICES] + [LAST_SERVICE]

        def api_there():
            _, _, services = master.getSystemState()
            return (set(wanted) <= {name for name, _ in services}
                    and STATES_TOPIC in dict(master.getTopicTypes()))
        self.assertTrue(wait_for(api_there, API_MOMENT), "the world API did not come")
        self.assertLess(time.monotonic() - arrived, API_MOMENT)
        world = rospy.ServiceProxy("/gazebo/get_world_properties", GetWorldProperties)()
        self.assertTrue(world.success)
        self.assertIn("turtlebot3_burger", world.model_names)


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "test_lazy_start", LazyStartTest)
