#!/usr/bin/env python3
"""rostest node: plain URDF models held in place as Gazebo holds them (urdf_anchors.test; the
files are test/fixtures/urdf_anchors/), spawned with the real command line (``rosrun
tutorial_turtlebot spawn_model -urdf -file ... -model ...``) into the empty world, both above
the ground: the static environment (<gazebo><static>true</static>) and the camera post on a
root link "world" are where they were spawned after 10 s of sim time; the environment's
missing barn mesh is one warning line of /gazebo on /rosout, and the model is there all the
same.

Every wait is on wall time with a limit."""
import os

import rospy
import rostest
from rosgraph_msgs.msg import Log

from sim_test_support import ROBOT, WAIT, SimTestCase, spawn_model, wait_for

FIXTURES = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "fixtures",
                        "urdf_anchors")
SPAWNED = {"static_env": ("static_env.urdf", ("3.0", "0.0", "0.5")),
           "camera_post": ("world_anchored.urdf", ("-2.0", "1.0", "0.3"))}
STILL = 1e-6      # m: what "did not move" allows


def spawn(name):
    """rosrun tutorial_turtlebot spawn_model -urdf -file FILE -model NAME -x -y -z: (exit
    status, its output)."""
    path, (x, y, z) = SPAWNED[name]
    return spawn_model("-urdf", "-file", os.path.join(FIXTURES, path), "-model", name,
                       "-x", x, "-y", y, "-z", z)


class UrdfAnchorsTest(SimTestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.log = []      # /gazebo's lines on /rosout
        sub = rospy.Subscriber("/rosout", Log, cls.log.append, queue_size=100)
        assert cls.gz.wait_names(lambda n: ROBOT in n, WAIT), cls.gz.names()
        assert wait_for(lambda: sub.get_num_connections() > 0, WAIT)
        cls.spawned = {name: spawn(name) for name in SPAWNED}
        cls.start = {name: cls.gz.get_model_state(model_name=name) for name in SPAWNED}

    def test_1_both_spawned_by_the_command_line(self):
        for name, (status, out) in self.spawned.items():
            self.assertEqual(status, 0, out)
            self.assertIn("Spawn status: SpawnModel: Successfully spawned entity", out)
        self.assertTrue(self.gz.wait_names(lambda n: set(SPAWNED) <= set(n)), self.gz.names())
        env = self.gz.get_model_properties(model_name="static_env")
        self.assertTrue(env.is_static)
        post = self.gz.get_model_properties(model_name="camera_post")
        self.assertFalse(post.is_static)
        self.assertEqual(list(post.body_names), ["post", "head"])     # "world" is no link

    def test_2_both_stay_where_they_were_spawned_for_10_s(self):
        first = self.gz.clock.latest(WAIT).clock
        self.assertTrue(wait_for(lambda: self.gz.clock.latest(WAIT).clock
                                 >= first + rospy.Duration(10.0), WAIT), "no 10 s of sim time")
        for name, (_, xyz) in SPAWNED.items():
            start = self.start[name]
            self.assertTrue(start.success, start.status_message)
            now = self.gz.get_model_state(model_name=name)
            self.assertTrue(now.success, now.status_message)
            for axis, wanted in zip("xyz", xyz):
                self.assertAlmostEqual(getattr(start.pose.position, axis), float(wanted),
                                       delta=STILL)
                self.assertAlmostEqual(getattr(now.pose.position, axis), float(wanted),
                                       delta=STILL, msg="%s moved along %s" % (name, axis))
            for axis in "xyzw":
                self.assertAlmostEqual(getattr(now.pose.orientation, axis),
                                       getattr(start.pose.orientation, axis), delta=STILL)

    def test_3_the_missing_mesh_is_one_warning_and_the_model_is_there(self):
        def lines():
            return [m.msg for m in list(self.log) if m.name == "/gazebo" and m.level == Log.WARN
                    and m.msg.startswith("spawn static_env: ") and "barn.dae" in m.msg]
        self.assertTrue(wait_for(lambda: lines(), WAIT), [m.msg for m in self.log])
        (line,) = lines()
        self.assertIn("link 'barn' <collision> left out", line)
        self.assertNotIn("\n", line)
        self.assertIn("static_env", self.gz.names())
        self.assertFalse([m.msg for m in list(self.log) if m.name == "/gazebo"
                          and m.level == Log.WARN and "camera_post" in m.msg])


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "test_urdf_anchors", UrdfAnchorsTest)
