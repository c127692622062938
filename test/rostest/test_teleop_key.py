#!/usr/bin/env python3
"""rostest node: the keyboard teleop in a pseudo-terminal, as a student runs it.

The test opens a pty, starts ``teleop_key`` on it (stdin, stdout, stderr and controlling
terminal: ``setsid -c``), types keys on the master side and watches /cmd_vel and /odom:
``i`` ramps forward up to "speed 0.2" by 0.02 m/s per key, no key for half a second stops
smoothly, ``k`` stops at once, ``j`` turns left, Ctrl-C (``\\x03``, SIGINT through the terminal)
quits with a zero Twist last and the terminal's modes as they were before.
"""
import termios
import time
import unittest

import rospy
import rostest
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry

from sim_test_support import NodeProcess, PtyProcess, Recorder, wait_for, yaw_of
from sim_test_support import SHORT_WAIT as WAIT

KEY_GAP = 0.05     # wall s between typed keys: faster than the node's 0.1 s read timeout
STEP = 0.02 + 1e-6  # m/s, the largest change of linear.x per loop


class TeleopKeyTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_teleop_key")
        cls.cmd = Recorder("cmd_vel", Twist)
        cls.odom = Recorder("odom", Odometry)
        assert cls.odom.latest(30.0) is not None, "no odom"

    def type_keys(self, key, count):
        for _ in range(count):
            self.term.send(key)
            time.sleep(KEY_GAP)

    def commands_since(self, mark):
        return self.cmd.snapshot()[0][mark:]

    def test_keys_drive_and_ctrl_c_restores_the_terminal(self):
        self.term = term = PtyProcess("teleop_key")
        try:
            self.drive_through_the_terminal(term)
        finally:
            term.close()

    def drive_through_the_terminal(self, term):
        # Started: the handout's banner and status line; the terminal in cbreak mode (no line
        # buffering, no echo), so the check of the restored modes below means something.
        self.assertTrue(wait_for(lambda: "currently:\tspeed 0.2\tturn 1" in term.output, WAIT),
                        "no status line; the terminal shows:\n%s" % term.output)
        for line in ("u    i    o", "j    k    l", "m    ,    .", "space key, k : force stop",
                     "anything else : stop smoothly", "CTRL-C to quit"):
            self.assertIn(line, term.output)
        self.assertTrue(wait_for(lambda: len(self.cmd.msgs) >= 3, WAIT), "nothing on /cmd_vel")
        lflag = term.modes()[3]
        self.assertFalse(lflag & termios.ICANON, "terminal still line-buffered")
        self.assertFalse(lflag & termios.ECHO, "terminal still echoes")
        self.assertTrue(all(c == Twist() for c in self.cmd.msgs), "moves before any key")

        # i, twelve times: linear.x ramps up by at most 0.02 per key to 0.2; the robot moves.
        start = self.odom.latest()
        mark = len(self.cmd.msgs)
        self.type_keys("i", 12)
        self.assertTrue(wait_for(lambda: any(abs(c.linear.x - 0.2) < 1e-6
                                             for c in self.commands_since(mark)), 5.0),
                        "linear.x never reached 0.2")
        ramp = [c.linear.x for c in self.commands_since(mark)]
        ramp = ramp[:ramp.index(max(ramp)) + 1]
        self.assertAlmostEqual(max(ramp), 0.2, places=6)
        self.assertGreaterEqual(len([v for v in ramp if 0.0 < v < 0.2]), 8, ramp)
        for a, b in zip(ramp, ramp[1:]):
            self.assertTrue(0.0 <= b - a <= STEP, "not a ramp: %s" % ramp)
        self.assertTrue(all(c.angular.z == 0.0 for c in self.commands_since(mark)))

        # No key: after about half a second it stops smoothly, 0.02 per loop down to 0.
        mark = len(self.cmd.msgs)
        self.assertTrue(wait_for(lambda: any(c.linear.x == 0.0 for c in self.commands_since(mark)),
                                 5.0), "did not stop without keys")
        down = [c.linear.x for c in self.commands_since(mark)]
        down = down[:down.index(0.0) + 1]
        self.assertGreaterEqual(len([v for v in down if 0.0 < v < 0.2]), 8, down)
        for a, b in zip(down, down[1:]):
            self.assertTrue(0.0 <= a - b <= STEP, "not a smooth stop: %s" % down)
        moved = self.odom.latest()
        self.assertGreater(moved.pose.pose.position.x - start.pose.pose.position.x, 0.1,
                           "the robot did not drive forward")

        # i again up to speed, then k: straight from 0.2 to 0, no ramp.
        self.type_keys("i", 12)
        self.assertTrue(wait_for(lambda: abs(self.cmd.msgs[-1].linear.x - 0.2) < 1e-6, 5.0))
        mark = len(self.cmd.msgs)
        self.term.send("k")
        self.assertTrue(wait_for(lambda: any(c.linear.x < 0.2 - 1e-6
                                             for c in self.commands_since(mark)), 5.0))
        after = [c.linear.x for c in self.commands_since(mark)]
        first_lower = next(v for v in after if v < 0.2 - 1e-6)
        self.assertEqual(first_lower, 0.0, "k did not stop at once: %s" % after)

        # j: turning left (angular.z > 0, ramping by 0.1 per key), not driving.
        wait_for(lambda: abs(self.odom.latest().twist.twist.linear.x) < 0.005, 5.0)
        before = self.odom.latest()
        mark = len(self.cmd.msgs)
        self.type_keys("j", 8)
        self.assertTrue(wait_for(lambda: any(c.angular.z >= 0.5
                                             for c in self.commands_since(mark)), 5.0))
        turning = self.commands_since(mark)
        self.assertTrue(all(c.angular.z >= 0.0 and c.linear.x == 0.0 for c in turning))
        self.assertTrue(wait_for(lambda: yaw_of(self.odom.latest().pose.pose.orientation)
                                 - yaw_of(before.pose.pose.orientation) > 0.1, 5.0),
                        "the robot did not turn left")

        # Ctrl-C: it quits, a zero Twist last, the terminal as it was.
        self.term.send("\x03")
        status = term.wait(20.0)
        self.assertIsNotNone(status, "teleop_key still running 20 s after Ctrl-C")
        self.assertEqual(status, 0, term.output)
        self.assertNotIn("Traceback", term.output)
        self.assertTrue(wait_for(lambda: self.cmd.msgs[-1] == Twist(), 5.0),
                        "last cmd_vel: %s" % self.cmd.msgs[-1])
        self.assertEqual(term.modes(), term.modes_before, "terminal modes not restored")

    def test_without_a_terminal_it_says_so(self):
        node = NodeProcess("teleop_key")  # stdin is /dev/null
        status = node.wait(20.0)
        if status is None:
            node.kill()
        self.assertIsNotNone(status, "teleop_key without a terminal did not exit")
        self.assertNotEqual(status, 0)
        self.assertIn("no terminal", node.stderr)
        self.assertNotIn("Traceback", node.stderr)


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "test_teleop_key", TeleopKeyTest)
