#!/usr/bin/env python3
"""rostest node: the graph of ``roslaunch tutorial_turtlebot sim_teleop.launch`` as rqt_graph
(nodes and topics) shows it: ``/turtlebot3_teleop_keyboard -> /cmd_vel -> /gazebo``, and
``/gazebo`` publishing /scan, /odom, /imu, /joint_states, /clock and /tf (doc/turtlebot3.md 3.1).

The .test file runs the simulation part; this node loads sim_teleop.launch with roslaunch's
loader, checks what it declares, and runs its teleop node on a pseudo-terminal (a keyboard node
needs one) under the declared name, with the declared remappings and parameters.
"""
import os
import unittest

import rosgraph
import roslaunch.config
import rospkg
import rospy
import rostest

from sim_test_support import PtyProcess, wait_for

TELEOP = "/turtlebot3_teleop_keyboard"
SENSORS = ("/scan", "/odom", "/imu", "/joint_states", "/clock", "/tf")


class SimTeleopGraphTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_sim_teleop_graph")
        cls.model = rospy.get_param("~model", "burger")
        launch = os.path.join(rospkg.RosPack().get_path("tutorial_turtlebot"), "launch",
                              "sim_teleop.launch")
        # Read as on a machine with no simulator yet: sim.launch's robot_description command
        # (--new-sim) would refuse to describe a second sim beside the one this test runs.
        master_uri = os.environ["ROS_MASTER_URI"]
        os.environ["ROS_MASTER_URI"] = "http://localhost:9"
        try:
            cls.config = roslaunch.config.load_config_default(
                [(launch, ["model:=%s" % cls.model])], None, verbose=False)
        finally:
            os.environ["ROS_MASTER_URI"] = master_uri
        cls.nodes = {rosgraph.names.ns_join(n.namespace, n.name): n for n in cls.config.nodes}
        teleop = cls.nodes.get(TELEOP)
        assert teleop is not None, "sim_teleop.launch declares no %s: %s" % (TELEOP,
                                                                             sorted(cls.nodes))
        for key, param in cls.config.params.items():  # what the launch sets besides sim.launch
            if not rospy.has_param(key):
                rospy.set_param(key, param.value)
        args = ["__name:=%s" % teleop.name] + ["%s:=%s" % pair for pair in teleop.remap_args]
        assert teleop.package == "tutorial_turtlebot", teleop.package
        cls.term = PtyProcess(teleop.type, *args)
        cls.master = rosgraph.Master("/test_sim_teleop_graph")

    @classmethod
    def tearDownClass(cls):
        cls.term.quit()

    def graph(self):
        """(publishers, subscribers): topic -> set of node names, from the master."""
        pubs, subs, _ = self.master.getSystemState()
        return ({t: set(n) for t, n in pubs}, {t: set(n) for t, n in subs})

    def edges(self):
        """rqt_graph's edges (publisher node, topic, subscriber node)."""
        pubs, subs = self.graph()
        return {(p, t, s) for t in pubs for p in pubs[t] for s in subs.get(t, ())}

    def test_launch_declares_sim_and_teleop(self):
        self.assertIn("/gazebo", self.nodes)
        self.assertEqual(self.nodes["/gazebo"].type, "sim")
        self.assertEqual(self.nodes[TELEOP].type, "teleop_key")
        self.assertEqual(self.config.params["/model"].value, self.model)

    def test_teleop_to_cmd_vel_to_gazebo(self):
        ok = wait_for(lambda: (TELEOP, "/cmd_vel", "/gazebo") in self.edges(), 30.0, 0.2)
        self.assertTrue(ok, "no edge %s -> /cmd_vel -> /gazebo; edges: %s; the teleop "
                        "terminal shows:\n%s" % (TELEOP, sorted(self.edges()), self.term.output))
        pubs, _ = self.graph()
        self.assertEqual(pubs["/cmd_vel"], {TELEOP}, "someone else publishes /cmd_vel")
        self.assertIsNone(self.term.proc.poll(), "the teleop node exited:\n" + self.term.output)

    def test_gazebo_publishes_the_sensors(self):
        ok = wait_for(lambda: all("/gazebo" in self.graph()[0].get(t, ()) for t in SENSORS),
                      30.0, 0.2)
        pubs, subs = self.graph()
        for topic in SENSORS:
            self.assertIn("/gazebo", pubs.get(topic, ()), topic)
        self.assertTrue(ok)
        self.assertIn("/gazebo", subs.get("/cmd_vel", ()))
        # robot_state_publisher turns /joint_states into the rest of /tf
        self.assertIn(("/gazebo", "/joint_states", "/robot_state_publisher"), self.edges())

    def test_teleop_node_info(self):
        """What ``rosnode info /turtlebot3_teleop_keyboard`` lists: it publishes /cmd_vel and
        subscribes /clock (sim time), and nothing under its private namespace."""
        wait_for(lambda: TELEOP in self.graph()[0].get("/cmd_vel", ()), 30.0, 0.2)
        pubs, subs = self.graph()
        published = {t for t, n in pubs.items() if TELEOP in n}
        subscribed = {t for t, n in subs.items() if TELEOP in n}
        self.assertIn("/cmd_vel", published)
        self.assertFalse([t for t in published if t.startswith(TELEOP + "/")], published)
        self.assertIn("/clock", subscribed)


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "test_sim_teleop_graph", SimTeleopGraphTest)
