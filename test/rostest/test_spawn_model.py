#!/usr/bin/env python3
"""rostest node: scripts/spawn_model run as a user runs it (a subprocess, as rosrun or
roslaunch would start it) against the real sim in the empty world.

Every wait is on wall time with a limit. Each test deletes what it spawned."""
import math
import os
import subprocess
import tempfile
import time

import rospy
import rostest

from sim_test_support import ROBOT, WAIT, NodeProcess, SimTestCase, executable, wait_for, yaw_of

BOX = """<sdf version="1.6"><model name="box"><link name="link">
  <inertial><mass>0.1</mass><inertia><ixx>0.0004</ixx><iyy>0.0004</iyy><izz>0.0004</izz></inertia></inertial>
  <collision name="collision"><geometry><box><size>0.15 0.15 0.15</size></box></geometry>\
</collision>
  <visual name="visual"><geometry><box><size>0.15 0.15 0.15</size></box></geometry></visual>
</link></model></sdf>"""
STATIC_BOX = BOX.replace("<link", "<static>true</static><link", 1)
CRATE = ('<robot name="r"><link name="base"><inertial><mass value="0.2"/><inertia ixx="0.001"'
         ' iyy="0.001" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial><collision><geometry>'
         '<cylinder radius="0.05" length="0.2"/></geometry></collision></link></robot>')
MODELS = ("box", "crate", "tilted", "anchor", "beside", "waiter", "later", "paused_box",
          "bonded")


def run(*args, stdin=None, env=None):
    """scripts/spawn_model ARGS to its end: (exit status, stdout, stderr)."""
    done = subprocess.run([executable("spawn_model")] + list(args), input=stdin,
                          capture_output=True, text=True, timeout=WAIT, env=env)
    return done.returncode, done.stdout, done.stderr


class SpawnModelTest(SimTestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        assert cls.gz.wait_names(lambda n: ROBOT in n, WAIT), cls.gz.names()
        cls.tmp = tempfile.mkdtemp(prefix="spawn_model_test_")
        cls.box_file = os.path.join(cls.tmp, "box.sdf")
        with open(cls.box_file, "w") as f:
            f.write(BOX)

    def tearDown(self):
        for name in MODELS:
            self.gz.delete_model(model_name=name)
        self.gz.unpause_physics()

    def assert_ran(self, result, *words):
        status, out, err = result
        self.assertEqual(status, 0, out + err)
        for w in words:
            self.assertIn(w, out)

    def test_sdf_box_from_file(self):
        # roslaunch adds __name:= and __log:=: they are not options
        result = run("-sdf", "-file", self.box_file, "-model", "box", "-x", "1.0", "-y", "-0.5",
                     "-z", "0.2", "-Y", "0.5", "__name:=box_spawner",
                     "__log:=" + os.path.join(self.tmp, "spawner.log"))
        self.assert_ran(result, "Loading model XML from file %s" % self.box_file,
                        "Calling service /gazebo/spawn_sdf_model",
                        "Spawn status: SpawnModel: Successfully spawned entity")
        self.assertTrue(self.gz.wait_names(lambda n: n[-1] == "box"), self.gz.names())
        state = self.gz.get_model_state(model_name="box")
        self.assertAlmostEqual(state.pose.position.x, 1.0, delta=0.02)
        self.assertAlmostEqual(state.pose.position.y, -0.5, delta=0.02)
        q = state.pose.orientation
        self.assertAlmostEqual(yaw_of(q), 0.5, delta=0.02)

    def test_urdf_from_a_relative_param_in_the_node_namespace(self):
        rospy.set_param("/lab/crate_description", CRATE)
        env = dict(os.environ, ROS_NAMESPACE="lab")
        status, out, err = run("-urdf", "-param", "crate_description", "-model", "crate",
                               "-x", "-1", "-z", "0.1", "-J", "base_joint", "0.3", env=env)
        self.assertEqual(status, 0, out + err)
        self.assertIn("Loading model XML from ros parameter crate_description", out)
        self.assertIn("Calling service /gazebo/spawn_urdf_model", out)
        self.assertIn("robot namespace /lab/", out)  # the default: the node's namespace
        # the crate has no joint base_joint: ignored, as Gazebo does, and the status says so
        self.assertIn("Set model configuration status: SetModelConfiguration: success "
                      "(ignored", out)
        self.assertIn("base_joint", out)
        self.assertTrue(self.gz.wait_names(lambda n: "crate" in n), self.gz.names())
        self.assertAlmostEqual(self.gz.position("crate")[0], -1.0, delta=0.02)
        # the same name at the root namespace is not there: one line, exit 1
        status, out, err = run("-urdf", "-param", "crate_description", "-model", "crate2")
        self.assertEqual(status, 1, out + err)
        self.assertIn("parameter crate_description (/crate_description) does not exist", err)

    def test_stdin_with_roll_pitch_yaw(self):
        status, out, err = run("-sdf", "-stdin", "-model", "tilted", "-x", "2", "-z", "1",
                               "-R", "0.2", "-P", "-0.3", "-Y", "1.0", stdin=STATIC_BOX)
        self.assertEqual(status, 0, out + err)
        self.assertIn("Loading model XML from stdin", out)
        q = self.gz.get_model_state(model_name="tilted").pose.orientation
        cr, sr = math.cos(0.1), math.sin(0.1)  # half angles
        cp, sp = math.cos(-0.15), math.sin(-0.15)
        cy, sy = math.cos(0.5), math.sin(0.5)
        expected = (sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy,
                    cr * cp * sy - sr * sp * cy, cr * cp * cy + sr * sp * sy)
        dot = abs(q.x * expected[0] + q.y * expected[1] + q.z * expected[2] + q.w * expected[3])
        self.assertAlmostEqual(dot, 1.0, delta=1e-4, msg=str(q))

    def test_reference_frame(self):
        self.assert_ran(run("-sdf", "-stdin", "-model", "anchor", "-x", "1", "-y", "-1",
                            "-z", "0.3", "-Y", str(math.pi / 2), stdin=STATIC_BOX))
        self.assert_ran(run("-sdf", "-stdin", "-model", "beside", "-x", "0.5",
                            "-reference_frame", "anchor", stdin=STATIC_BOX))
        world = self.gz.get_model_state(model_name="beside").pose.position
        self.assertAlmostEqual(world.x, 1.0, delta=1e-3)  # 0.5 along anchor's x = world +y
        self.assertAlmostEqual(world.y, -0.5, delta=1e-3)
        self.assertAlmostEqual(world.z, 0.3, delta=1e-3)
        rel = self.gz.get_model_state(model_name="beside", relative_entity_name="anchor")
        self.assertTrue(rel.success, rel.status_message)
        self.assertAlmostEqual(rel.pose.position.x, 0.5, delta=1e-3)
        self.assertAlmostEqual(rel.pose.position.y, 0.0, delta=1e-3)
        # an unknown frame: the service's answer, exit 1
        status, out, err = run("-sdf", "-stdin", "-model", "box", "-x", "1",
                               "-reference_frame", "nope", stdin=BOX)
        self.assertEqual(status, 1, out + err)
        self.assertIn("reference_frame", err)

    def test_wait_for_another_model(self):
        proc = NodeProcess("spawn_model", "-sdf", "-file", self.box_file, "-model", "waiter",
                           "-x", "-1", "-y", "1", "-z", "0.1", "-wait", "later")
        try:
            self.assertTrue(wait_for(lambda: "Waiting for model later before proceeding"
                                     in proc.stdout, WAIT), proc.stdout + proc.stderr)
            time.sleep(1.0)
            self.assertIsNone(proc.proc.poll(), proc.stdout + proc.stderr)
            self.assertNotIn("waiter", self.gz.names())
            self.assert_ran(run("-sdf", "-file", self.box_file, "-model", "later", "-x", "1",
                                "-y", "1", "-z", "0.1"))
            self.assertEqual(proc.wait(WAIT), 0, proc.stdout + proc.stderr)
            self.assertIn("Spawn status: SpawnModel: Successfully spawned entity", proc.stdout)
            self.assertTrue(self.gz.wait_names(lambda n: n[-2:] == ["later", "waiter"]),
                            self.gz.names())
        finally:
            proc.kill()

    def test_unpause(self):
        self.gz.pause_physics()
        time.sleep(0.3)
        stamp = self.gz.clock.latest().clock
        time.sleep(0.5)
        self.assertEqual(self.gz.clock.latest().clock, stamp, "the sim did not pause")
        self.assertTrue(self.gz.get_physics_properties().pause)
        self.assert_ran(run("-sdf", "-file", self.box_file, "-model", "paused_box",
                            "-x", "-1", "-y", "-1", "-z", "0.5",
                            "-unpause"), "Unpausing physics")
        self.assertFalse(self.gz.get_physics_properties().pause)
        self.assertTrue(wait_for(lambda: self.gz.clock.latest().clock > stamp, WAIT),
                        "the clock stands still after -unpause")
        # and the box, spawned while paused, falls once the physics runs
        self.assertTrue(wait_for(lambda: self.gz.position("paused_box")[2] < 0.1, WAIT))

    def test_duplicate_name(self):
        self.assert_ran(run("-sdf", "-file", self.box_file, "-model", "box", "-x", "1",
                            "-z", "0.1"))
        status, out, err = run("-sdf", "-file", self.box_file, "-model", "box", "-x", "-1")
        self.assertEqual(status, 1, out + err)
        errors = [line for line in err.splitlines() if "ERROR" in line]
        self.assertEqual(len(errors), 1, err)
        self.assertIn("Spawn failed: SpawnModel: Failure - entity already exists.", errors[0])
        self.assertEqual(self.gz.names().count("box"), 1)

    def test_missing_file(self):
        missing = os.path.join(self.tmp, "nope.sdf")
        names = self.gz.names()
        status, out, err = run("-sdf", "-file", missing, "-model", "box")
        self.assertEqual(status, 1, out + err)
        self.assertEqual(out, "")
        self.assertEqual(err, "spawn_model: error: specified file %s does not exist\n" % missing)
        self.assertEqual(self.gz.names(), names)

    def test_bond_deletes_the_model_at_ctrl_c(self):
        proc = NodeProcess("spawn_model", "-sdf", "-file", self.box_file, "-model", "bonded",
                           "-x", "1.5", "-z", "0.1", "-b")
        try:
            self.assertTrue(wait_for(lambda: "Waiting for shutdown to delete model bonded"
                                     in proc.stdout, WAIT), proc.stdout + proc.stderr)
            self.assertTrue(self.gz.wait_names(lambda n: "bonded" in n))
            time.sleep(1.0)
            self.assertIsNone(proc.proc.poll(), "-b did not stay")
            self.assertEqual(proc.interrupt(WAIT), 0, proc.stdout + proc.stderr)
            self.assertIn("Deleting model bonded", proc.stdout)
            self.assertTrue(self.gz.wait_names(lambda n: "bonded" not in n), self.gz.names())
        finally:
            proc.kill()


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "spawn_model", SpawnModelTest)
