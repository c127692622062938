#!/usr/bin/env python3
"""rostest node: the sim says once, in one line on /rosout, that it cannot reach a publisher of
a topic it subscribes to, and which address it tried (unreachable_publisher.test).

Fake publishers of /cmd_vel are registered with the master under fake node names: one at an
XML-RPC URI where nothing listens, one whose XML-RPC server (here, in the test) answers
requestTopic with a TCPROS address where nothing listens."""
import threading
import time
import unittest
import xmlrpc.server

import rosgraph
import rospy
import rostest
from rosgraph_msgs.msg import Log

from sim_test_support import WAIT, wait_for
from sim_test_support import free_port as closed_port

TOPIC = "/cmd_vel"
TYPE = "geometry_msgs/Twist"


class FakePublisher:
    """An XML-RPC node API that answers requestTopic with an unreachable TCPROS address."""

    def __init__(self, tcpros_port: int):
        self.server = xmlrpc.server.SimpleXMLRPCServer(("127.0.0.1", 0), logRequests=False,
                                                       allow_none=True)
        self.uri = "http://127.0.0.1:%d/" % self.server.server_address[1]
        self.requests = 0
        self.server.register_function(self.requestTopic, "requestTopic")
        self.server.register_function(
            lambda caller_id: [1, "", [[TOPIC, TYPE]]], "getPublications")
        threading.Thread(target=self.server.serve_forever, daemon=True).start()
        self.tcpros_port = tcpros_port

    def requestTopic(self, caller_id, topic, protocols):  # noqa: N802 - the XML-RPC name
        self.requests += 1
        return [1, "", ["TCPROS", "127.0.0.1", self.tcpros_port]]

    def close(self):
        self.server.shutdown()
        self.server.server_close()


class UnreachablePublisherTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_unreachable_publisher")
        cls.lines = []
        cls.lock = threading.Lock()
        cls.sub = rospy.Subscriber("/rosout", Log, cls.on_log, queue_size=1000)
        master = rosgraph.Master("/test_unreachable_publisher")

        def sim_subscribes():
            _, subs, _ = master.getSystemState()
            return "/gazebo" in dict(subs).get(TOPIC, ())
        assert wait_for(sim_subscribes, WAIT), "the sim never subscribed to %s" % TOPIC
        # the sim's /rosout publisher is connected to this node's subscriber
        assert wait_for(lambda: cls.sub.get_num_connections() > 0, WAIT)
        time.sleep(1.0)
        cls.registered = []

    @classmethod
    def tearDownClass(cls):
        for caller_id, uri in cls.registered:
            rosgraph.Master(caller_id).unregisterPublisher(TOPIC, uri)

    @classmethod
    def on_log(cls, msg):
        if msg.name == "/gazebo":
            with cls.lock:
                cls.lines.append(msg.msg)

    def register(self, caller_id, uri):
        rosgraph.Master(caller_id).registerPublisher(TOPIC, TYPE, uri)
        self.registered.append((caller_id, uri))

    def lines_with(self, text):
        with self.lock:
            return [line for line in self.lines if text in line]

    def test_1_an_unreachable_xmlrpc_uri_is_named_once(self):
        uri = "http://127.0.0.1:%d/" % closed_port()
        self.register("/fake_teleop", uri)
        self.assertTrue(wait_for(lambda: self.lines_with(uri), WAIT),
                        "no line about %s; the sim said: %s" % (uri, self.lines))
        line = self.lines_with(uri)[0]
        self.assertEqual(line, "cannot reach /fake_teleop's publisher of /cmd_vel at %s: "
                         "connection refused; is ROS_IP or ROS_HOSTNAME set on its machine?"
                         % uri)
        # The master tells the sim again (another publisher comes, the same one re-registers):
        # the sim tries the address again, and says nothing more about it.
        other = "http://127.0.0.1:%d/" % closed_port()
        self.register("/fake_teleop_2", other)
        self.assertTrue(wait_for(lambda: self.lines_with(other), WAIT), self.lines)
        self.register("/fake_teleop", uri)
        time.sleep(3.0)
        self.assertEqual(len(self.lines_with(uri)), 1, self.lines)
        self.assertEqual(len(self.lines_with(other)), 1, self.lines)

    def test_2_an_unreachable_tcpros_address_is_named_once(self):
        port = closed_port()
        fake = FakePublisher(port)
        try:
            self.register("/fake_remote", fake.uri)
            self.assertTrue(wait_for(lambda: self.lines_with(fake.uri), WAIT),
                            "no line about %s; the sim said: %s" % (fake.uri, self.lines))
            self.assertEqual(self.lines_with(fake.uri)[0],
                             "cannot reach /fake_remote's publisher of /cmd_vel at %s "
                             "(TCPROS 127.0.0.1:%d): connection refused; is ROS_IP or "
                             "ROS_HOSTNAME set on its machine?" % (fake.uri, port))
            requests = fake.requests
            self.register("/fake_remote", fake.uri)
            self.assertTrue(wait_for(lambda: fake.requests > requests, WAIT),
                            "the sim did not ask again")
            time.sleep(3.0)
            self.assertEqual(len(self.lines_with(fake.uri)), 1, self.lines)
        finally:
            fake.close()


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "unreachable_publisher", UnreachablePublisherTest)
