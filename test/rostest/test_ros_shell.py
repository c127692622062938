#!/usr/bin/env python3
"""rostest node: the lab's shell commands against the running sim (ros_shell.test)."""
import subprocess
import unittest

import rospy
import rostest

from sim_test_support import WAIT


def run(*command):
    """(exit status, stdout + stderr) of a shell command as the student types it."""
    done = subprocess.run(list(command), stdin=subprocess.DEVNULL, capture_output=True,
                          text=True, timeout=WAIT)
    return done.returncode, done.stdout + done.stderr


class RosShellTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_ros_shell")

    def assert_shows(self, command, *lines):
        status, out = run(*command)
        self.assertEqual(status, 0, "%s failed:\n%s" % (" ".join(command), out))
        for line in lines:
            self.assertIn(line, out, "%s shows no %r:\n%s" % (" ".join(command), line, out))

    def test_rosmsg_show_odometry(self):
        """Lab step 5: the bare name finds nav_msgs/Odometry."""
        self.assert_shows(("rosmsg", "show", "Odometry"), "[nav_msgs/Odometry]:",
                          "geometry_msgs/PoseWithCovariance pose", "float64[36] covariance")

    def test_rosmsg_show_laserscan(self):
        """Lab step 7."""
        self.assert_shows(("rosmsg", "show", "LaserScan"), "[sensor_msgs/LaserScan]:",
                          "float32 angle_increment", "float32[] ranges")

    def test_rosmsg_show_twist(self):
        self.assert_shows(("rosmsg", "show", "geometry_msgs/Twist"),
                          "geometry_msgs/Vector3 linear", "geometry_msgs/Vector3 angular")

    def test_rossrv_show_empty_and_rostopic_type(self):
        self.assert_shows(("rossrv", "show", "std_srvs/Empty"), "---")
        self.assert_shows(("rostopic", "type", "/odom"), "nav_msgs/Odometry")


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "test_ros_shell", RosShellTest)
