#!/usr/bin/env python3
"""rostest node: ``graph`` (rqt_graph's picture without rqt) on the live sim + teleop.

It runs the package's ``graph`` executable as ``rosrun`` does, against the real master and
nodes: ``--output g.dot`` holds the edge /turtlebot3_teleop_keyboard -> /gazebo labelled
/cmd_vel and nothing of /rosout; ``--output g.png`` and ``g.svg`` are a PNG and an SVG;
without DISPLAY it prints the text picture; a node stopped with SIGSTOP (it never answers)
costs rosgraph's 1 s timeout and is hidden, or drawn red; with no master it says so in one
line and exits non-zero.
"""
import os
import shutil
import signal
import subprocess
import tempfile
import time
import unittest

import rosgraph
import rospy
import rostest

from sim_test_support import WAIT, NodeProcess, PtyProcess, free_port, stop_process, wait_for

TELEOP = "/turtlebot3_teleop_keyboard"
STUCK = "/graph_test_stuck"
RUN = 30.0    # wall s a single run of graph may take (each node gets 1 s to answer)
DOT_EDGE = ('n___turtlebot3_teleop_keyboard -> n___gazebo [label="/cmd_vel", '
            'URL="topic:/cmd_vel", penwidth=1];')


class GraphTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_graph")
        cls.folder = tempfile.mkdtemp(prefix="test_graph_")
        cls.term = PtyProcess("teleop_key", "__name:=turtlebot3_teleop_keyboard")
        cls.master = rosgraph.Master("/test_graph")

    @classmethod
    def tearDownClass(cls):
        cls.term.quit()
        shutil.rmtree(cls.folder, ignore_errors=True)

    def graph(self, *args, env=None):
        """Run ``graph ARGS``: (exit status, stdout, stderr, wall seconds)."""
        start = time.monotonic()
        proc = NodeProcess("graph", *args, env=env)
        status = proc.wait(RUN)
        if status is None:
            proc.kill()
            self.fail("graph %s still running after %g s" % (" ".join(args), RUN))
        return status, proc.stdout, proc.stderr, time.monotonic() - start

    def path(self, name):
        return os.path.join(self.folder, name)

    def dot_when(self, predicate, *args):
        """The .dot graph writes, once ``predicate(text)`` holds (or the last one)."""
        out = self.path("g.dot")
        text = [""]

        def look():
            status, _, err, _ = self.graph("--output", out, *args)
            self.assertEqual(status, 0, err)
            with open(out) as dot:
                text[0] = dot.read()
            return predicate(text[0])
        wait_for(look, WAIT, 0.5)
        return text[0]

    def test_1_dot_has_teleop_to_gazebo_over_cmd_vel_and_no_rosout(self):
        dot = self.dot_when(lambda text: DOT_EDGE in text)
        self.assertIn(DOT_EDGE, dot, "the teleop terminal shows:\n" + self.term.output)
        self.assertTrue(dot.startswith("digraph graphname {"), dot)
        self.assertIn('n___gazebo [label="/gazebo", shape="ellipse"', dot)
        self.assertIn('n___gazebo -> n___robot_state_publisher [label="/joint_states"', dot)
        self.assertNotIn("rosout", dot)
        self.assertNotIn("/clock", dot)
        # the master does know /rosout: it is hidden, as rqt_graph hides it
        self.assertIn("/rosout", [t for t, _ in self.master.getSystemState()[0]])

        topics = self.dot_when(lambda text: "t___cmd_vel -> n___gazebo" in text,
                               "--mode", "active")
        self.assertIn("\tn___turtlebot3_teleop_keyboard -> t___cmd_vel [penwidth=1];", topics)
        self.assertIn("\tt___cmd_vel -> n___gazebo [penwidth=1];", topics)
        self.assertIn('t___cmd_vel [label="/cmd_vel", shape="box"', topics)
        self.assertNotIn("t___scan", topics)   # a leaf topic: hidden by default

    def test_2_png_and_svg(self):
        self.dot_when(lambda text: DOT_EDGE in text)
        for name, magic in (("g.png", b"\x89PNG\r\n\x1a\n"), ("g.svg", b"<svg")):
            status, out, err, _ = self.graph("--output", self.path(name))
            self.assertEqual(status, 0, err)
            self.assertIn("wrote %s" % self.path(name), out)
            with open(self.path(name), "rb") as image:
                data = image.read()
            if name.endswith(".png"):
                self.assertEqual(data[:8], magic)
                self.assertGreater(len(data), 1000)
            else:
                self.assertIn(magic, data)
                self.assertIn(b"/turtlebot3_teleop_keyboard", data)

    def test_3_text_picture_without_display(self):
        self.dot_when(lambda text: DOT_EDGE in text)
        env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY")}
        status, out, err, _ = self.graph(env=env)
        self.assertEqual(status, 0, err)
        self.assertTrue(out.startswith("Nodes only: "), out)
        self.assertIn("  %s --/cmd_vel--> /gazebo\n" % TELEOP, out)
        self.assertIn("  /gazebo --/joint_states--> /robot_state_publisher\n", out)
        self.assertNotIn("rosout", out)
        status, out, err, _ = self.graph("--text", "--mode", "all")
        self.assertEqual(status, 0, err)
        self.assertIn("  %s --> [/cmd_vel] --> /gazebo\n" % TELEOP, out)

    def test_4_a_node_that_does_not_answer(self):
        env = dict(os.environ)
        stuck = subprocess.Popen(["rostopic", "hz", "/scan", "__name:=" + STUCK[1:]],
                                 stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                                 stderr=subprocess.DEVNULL, env=env)
        try:
            self.dot_when(lambda text: "n___graph_test_stuck [" in text and
                          'n___gazebo -> n___graph_test_stuck [label="/scan"' in text)
            stuck.send_signal(signal.SIGSTOP)   # registered, but its XML-RPC never answers
            status, out, err, seconds = self.graph("--text")
            self.assertEqual(status, 0, err)
            self.assertLess(seconds, 20.0)
            self.assertNotIn(STUCK, out)         # unreachable: hidden by default
            self.assertIn("%s --/cmd_vel--> /gazebo" % TELEOP, out)
            self.assertEqual(err, "")             # no traceback from rosgraph
            status, out, err, _ = self.graph("--text", "--hide", "debug")
            self.assertEqual(status, 0, err)
            self.assertIn("%s (DEAD)" % STUCK, out)
            out_dot = self.path("stuck.dot")
            status, _, err, _ = self.graph("--output", out_dot, "--hide", "debug")
            with open(out_dot) as dot:
                self.assertIn('URL="%s (DEAD)", tooltip="%s (DEAD)", color="red"'
                              % (STUCK, STUCK), dot.read())
        finally:
            stop_process(stuck, 10.0)

    def test_5_no_master(self):
        env = dict(os.environ, ROS_MASTER_URI="http://localhost:%d" % free_port())
        for args in ((), ("--output", self.path("none.dot")), ("--text",)):
            status, out, err, _ = self.graph(*args, env=env)
            self.assertNotEqual(status, 0)
            self.assertEqual(out, "")
            self.assertEqual(len(err.splitlines()), 1, err)
            self.assertTrue(err.startswith("graph: error: cannot reach the ROS master at "
                                           "http://localhost:"), err)
        self.assertFalse(os.path.exists(self.path("none.dot")))

    def test_6_bad_mode_and_suffix(self):
        status, out, err, _ = self.graph("--mode", "topics")
        self.assertEqual(status, 2)
        self.assertEqual(err, "graph: error: unknown mode 'topics': the modes are nodes, "
                              "active, all (nodes: Nodes only; active: Nodes/Topics (active); "
                              "all: Nodes/Topics (all))\n")
        status, out, err, _ = self.graph("--output", self.path("g.jpg"))
        self.assertEqual(status, 2)
        self.assertEqual(len(err.splitlines()), 1, err)
        self.assertIn("must end in .png, .svg or .dot", err)
        self.assertFalse(os.path.exists(self.path("g.jpg")))


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "test_graph", GraphTest)
