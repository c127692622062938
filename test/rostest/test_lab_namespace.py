#!/usr/bin/env python3
"""rostest node: the lab's nodes find their robot by their namespace (lab_namespace.test).

The sim runs in /tb3_2 (/tb3_2/odom, /tb3_2/scan, /tb3_2/cmd_vel), with /tb3_2/model waffle and
/model burger on the parameter server. wander.launch ns:=tb3_2 must drive that robot and leave
/cmd_vel alone; teleop_key run as ``ROS_NAMESPACE=tb3_1 rosrun tutorial_turtlebot teleop_key``
in a pseudo-terminal must publish on /tb3_1/cmd_vel, name it in its banner and take /model
(burger: no /tb3_1/model); in /tb3_2 it must take /tb3_2/model (waffle's limits). Both with
TURTLEBOT3_MODEL=waffle_pi, which comes after any model parameter.
The tests run in the order of their names: the teleop in /tb3_2 comes after wander's drive.
"""
import contextlib
import math
import os
import time
import unittest

import rosgraph
import rospy
import rostest
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry

from sim_test_support import PtyProcess, Recorder, wait_for
from sim_test_support import SHORT_WAIT as WAIT

KEY_GAP = 0.05  # wall s between typed keys


@contextlib.contextmanager
def environment(**values):
    """These environment variables for the processes started inside (as in
    ``ROS_NAMESPACE=tb3_1 rosrun ...``)."""
    before = {name: os.environ.get(name) for name in values}
    os.environ.update(values)
    try:
        yield
    finally:
        for name, value in before.items():
            if value is None:
                del os.environ[name]
            else:
                os.environ[name] = value


def graph():
    """(publishers, subscribers) as {topic: [node, ...]} from the master."""
    pubs, subs, _srvs = rosgraph.Master(rospy.get_name()).getSystemState()
    return dict(pubs), dict(subs)


def distance(a, b):
    pa, pb = a.pose.pose.position, b.pose.pose.position
    return math.hypot(pa.x - pb.x, pa.y - pb.y)


class LabNamespaceTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_lab_namespace")
        cls.odom = Recorder("/tb3_2/odom", Odometry)
        cls.plain_cmd = Recorder("/cmd_vel", Twist)
        assert cls.odom.latest(WAIT) is not None, "no /tb3_2/odom from the sim in /tb3_2"

    def assert_nothing_on_plain_cmd_vel(self):
        self.assertEqual(self.plain_cmd.msgs, [], "something published on /cmd_vel")
        self.assertNotIn("/cmd_vel", graph()[0], "a publisher of /cmd_vel")

    def run_teleop(self, namespace):
        """teleop_key in a terminal in ``namespace``, with TURTLEBOT3_MODEL=waffle_pi: the
        last resort, which a model parameter found anywhere must beat."""
        with environment(ROS_NAMESPACE=namespace, TURTLEBOT3_MODEL="waffle_pi"):
            term = PtyProcess("teleop_key")
        self.addCleanup(term.close)
        self.assertTrue(wait_for(lambda: "currently:\tspeed" in term.output, WAIT),
                        "no status line; the terminal shows:\n%s" % term.output)
        return term

    def quit_teleop(self, term):
        term.send("\x03")
        self.assertEqual(term.wait(20.0), 0, term.output)
        self.assertNotIn("Traceback", term.output)

    def test_1_wander_in_tb3_2_drives_the_robot_there(self):
        pubs, subs = graph()
        self.assertIn("/tb3_2/wander", subs.get("/tb3_2/scan", []))
        self.assertTrue(wait_for(lambda: "/tb3_2/wander" in graph()[0].get("/tb3_2/cmd_vel", []),
                                 WAIT), "wander does not publish /tb3_2/cmd_vel")
        start = self.odom.latest()
        self.assertTrue(wait_for(lambda: distance(self.odom.latest(), start) > 0.3, WAIT),
                        "the robot in /tb3_2 did not move: %.3f m"
                        % distance(self.odom.latest(), start))
        self.assertNotIn("/odom", pubs, "the sim is not in its namespace")
        self.assert_nothing_on_plain_cmd_vel()

    def test_2_teleop_with_ros_namespace_tb3_1_drives_tb3_1_cmd_vel(self):
        cmd = Recorder("/tb3_1/cmd_vel", Twist)
        term = self.run_teleop("tb3_1")
        lines = [line for line in term.output.splitlines() if line.strip()]
        self.assertEqual(lines[0], "Control Your TurtleBot3! (driving /tb3_1/cmd_vel)", term.output)
        # No /tb3_1/model: the search from /tb3_1 upward finds /model, burger (before
        # $TURTLEBOT3_MODEL, waffle_pi).
        self.assertIn("burger: speed up to 0.22 m/s, turn up to 2.84 rad/s", term.output)
        self.assertTrue(wait_for(lambda: cmd.msgs, WAIT), "nothing on /tb3_1/cmd_vel")
        for _ in range(5):
            term.send("i")
            time.sleep(KEY_GAP)
        self.assertTrue(wait_for(lambda: any(c.linear.x > 0.05 for c in cmd.msgs), 5.0),
                        "i did not drive /tb3_1/cmd_vel forward")
        self.quit_teleop(term)
        self.assertTrue(wait_for(lambda: cmd.msgs[-1] == Twist(), 5.0))
        self.assert_nothing_on_plain_cmd_vel()

    def test_3_model_in_the_robots_namespace_beats_the_global_one(self):
        term = self.run_teleop("tb3_2")
        self.assertIn("Control Your TurtleBot3! (driving /tb3_2/cmd_vel)", term.output)
        self.assertIn("waffle: speed up to 0.26 m/s, turn up to 1.82 rad/s", term.output)
        self.quit_teleop(term)
        self.assert_nothing_on_plain_cmd_vel()


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "test_lab_namespace", LabNamespaceTest)
