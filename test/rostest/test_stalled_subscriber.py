#!/usr/bin/env python3
"""rostest node: a suspended subscriber does not stall the sim.

The Waffle Pi's camera sends about 28 MB per sim second, so a subscriber that stops reading
fills its socket buffers (tens of MB on loopback) within a few sim seconds. A sim that waited
on it would stop there; this one must keep its clock and its other topics going.
"""
import os
import signal
import subprocess
import time
import unittest

import rosgraph.masterapi
import rospy
import rostest
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock

from sim_test_support import Recorder, wait_for

IMAGE_TOPIC = "/camera/rgb/image_raw"
SIM_SECONDS = 20.0  # sim time that must pass while the subscriber is suspended


def subscribers_of(topic):
    """Node names subscribed to ``topic``, as the master knows them."""
    _, subscribers, _ = rosgraph.masterapi.Master(rospy.get_name()).getSystemState()
    return next((nodes for name, nodes in subscribers if name == topic), [])


class StalledSubscriberTest(unittest.TestCase):
    def setUp(self):
        rospy.init_node("test_stalled_subscriber")
        self.clock = Recorder("/clock", Clock)
        self.odom = Recorder("/odom", Odometry)
        self.assertIsNotNone(self.odom.latest(60.0), "no /odom from the sim")
        self.viewer = subprocess.Popen(["rostopic", "hz", IMAGE_TOPIC],
                                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)

    def tearDown(self):
        if self.viewer.poll() is None:
            os.kill(self.viewer.pid, signal.SIGCONT)
            self.viewer.terminate()
            self.viewer.wait(20)

    def test_sim_runs_on_past_a_suspended_subscriber(self):
        self.assertTrue(wait_for(lambda: any(n.startswith("/rostopic")
                                             for n in subscribers_of(IMAGE_TOPIC)), 60.0),
                        "rostopic hz never subscribed to %s" % IMAGE_TOPIC)
        time.sleep(3.0)  # connected, and images flow to it
        os.kill(self.viewer.pid, signal.SIGSTOP)
        start = self.clock.latest().clock
        end = start + rospy.Duration(SIM_SECONDS)
        self.assertTrue(wait_for(lambda: self.clock.latest().clock >= end, 150.0),
                        "the sim's clock stalled at %.1f s (suspended at %.1f s)"
                        % (self.clock.latest().clock.to_sec(), start.to_sec()))
        odom = self.odom.latest()
        self.assertGreaterEqual(odom.header.stamp, end - rospy.Duration(1.0),
                                "/odom stopped at %.1f s" % odom.header.stamp.to_sec())
        self.assertEqual(self.viewer.poll(), None, "rostopic hz ended by itself")


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "stalled_subscriber", StalledSubscriberTest)
