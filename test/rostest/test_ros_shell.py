#!/usr/bin/env python3
"""rostest node: the lab's shell commands, and the docs' blocks marked ``<!-- sim example -->``,
against the running sim (ros_shell.test)."""
import glob
import math
import os
import re
import shlex
import subprocess
import unittest

import rospy
import rostest
from gazebo_msgs.srv import GetModelState

from sim_test_support import WAIT

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), os.pardir, os.pardir))
PAGES = ["README.md"] + sorted(os.path.relpath(p, ROOT)
                               for p in glob.glob(os.path.join(ROOT, "doc", "*.md")))
SIM_EXAMPLE = re.compile(r"<!-- sim example -->\s*\n```bash\n(.*?)\n```", re.S)
LOG_STAMP = re.compile(r"^\[(\w+)\] \[[\d.]+, [\d.]+\]: ", re.M)
SIM_TIME = re.compile(r"^sim_time: [\d.]+$", re.M)


def sim_examples():
    """(page:line, [(command, expected output or None)]) of each sim example block, in order.
    A block of ``$ COMMAND`` lines shows each command's output; other blocks are commands only."""
    for page in PAGES:
        with open(os.path.join(ROOT, page), encoding="utf-8") as handle:
            text = handle.read()
        for match in SIM_EXAMPLE.finditer(text):
            where = "%s:%d" % (page, text.count("\n", 0, match.start(1)) + 1)
            lines = match.group(1).splitlines()
            if not any(line.startswith("$ ") for line in lines):
                yield where, [(line, None) for line in lines if line.strip()]
                continue
            steps = []
            for line in lines:
                if line.startswith("$ "):
                    steps.append((line[2:], []))
                elif steps:
                    steps[-1][1].append(line)
            yield where, [(command, "\n".join(output)) for command, output in steps]


def option(argv, name, default=None):
    return argv[argv.index(name) + 1] if name in argv[:-1] else default


def normalise(text):
    """Output without what changes from run to run: log stamps and the sim time."""
    text = SIM_TIME.sub("sim_time: T", LOG_STAMP.sub(r"[\1] [T]: ", text))
    return "\n".join(line.rstrip() for line in text.strip("\n").splitlines())


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

    def test_doc_sim_examples(self):
        """Each sim example of the docs, in page order, exits 0, has no ``success: False``, and
        prints what the page shows (log stamps and sim time aside)."""
        examples = list(sim_examples())
        self.assertGreaterEqual(len(examples), 6, "too few <!-- sim example --> blocks found")
        for service in ("get_world_properties", "set_model_state", "spawn_sdf_model",
                        "spawn_urdf_model", "delete_model", "set_parameters"):
            rospy.wait_for_service("/gazebo/" + service, timeout=WAIT)
        for where, steps in examples:
            for command, expected in steps:
                done = subprocess.run(["bash", "-o", "pipefail", "-c", command], cwd=ROOT,
                                      stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                                      stderr=subprocess.STDOUT, text=True, timeout=WAIT)
                self.assertEqual(done.returncode, 0, "%s: %s exited %d:\n%s"
                                 % (where, command, done.returncode, done.stdout))
                self.assertNotIn("success: False", done.stdout,
                                 "%s: %s:\n%s" % (where, command, done.stdout))
                if expected is not None:
                    self.assertEqual(normalise(done.stdout), normalise(expected),
                                     "%s: %s prints other than the page shows" % (where, command))
        # the models spawn_model put down are still where the pages put them: none was pushed
        rospy.sleep(2.0)
        spots = {}
        for _, steps in examples:
            for command, _ in steps:
                argv = shlex.split(command)
                if "spawn_model" in argv and "-model" in argv:
                    spots[option(argv, "-model")] = (float(option(argv, "-x", "0")),
                                                     float(option(argv, "-y", "0")))
        self.assertGreaterEqual(len(spots), 3, spots)
        get_state = rospy.ServiceProxy("/gazebo/get_model_state", GetModelState)
        for name, (x, y) in spots.items():
            pose = get_state(model_name=name).pose.position
            self.assertLess(math.hypot(pose.x - x, pose.y - y), 0.05,
                            "%s spawned at (%g, %g) is at (%.2f, %.2f)" % (name, x, y, pose.x,
                                                                           pose.y))

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
