#!/usr/bin/env python3
"""rostest node: a plain URDF spawned with the real command line (``rosrun tutorial_turtlebot
spawn_model -urdf -file .../pendulum.urdf -model pendulum``; urdf_pendulum.test) is the SDF
model Gazebo makes of it: its links and joints as Gazebo lists them (the root link "world" no
link, the weight lumped into the bob under Gazebo's name), its revolute joint "swing" turns
under gravity (get_joint_properties' position sweeps from 0 towards its limit) while the model
stays joined to the world, and /gazebo/link_states names its links by their URDF names. A
second spawn after a delete (the parked bodies) swings again.

Every wait is on wall time with a limit."""
import os

import rospy
import rostest
from gazebo_msgs.msg import LinkStates
from gazebo_msgs.srv import GetJointProperties

from sim_test_support import WAIT, SimTestCase, one_message, spawn_model, wait_for

URDF = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "fixtures",
                    "urdf_pendulum", "pendulum.urdf")
STILL = 1e-4      # m: what "did not move" allows


def spawn(name, x):
    return spawn_model("-urdf", "-file", URDF, "-model", name, "-x", str(x), "-y", "1.0")


class UrdfPendulumTest(SimTestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        rospy.wait_for_service("/gazebo/get_joint_properties", timeout=WAIT)
        cls.joint = rospy.ServiceProxy("/gazebo/get_joint_properties", GetJointProperties)

    def swing(self, name):
        return self.joint(joint_name="%s::swing" % name)

    def swept(self, name, seconds=1.0):
        """The joint positions (rad) of ``name``'s swing read over ``seconds`` of sim time."""
        positions = []
        start = self.gz.clock.latest(WAIT).clock

        def read():
            answer = self.swing(name)
            self.assertTrue(answer.success, answer.status_message)
            positions.append(answer.position[0])
            return self.gz.clock.latest(WAIT).clock >= start + rospy.Duration(seconds)
        self.assertTrue(wait_for(read, WAIT), "no %g s of sim time" % seconds)
        return positions

    def test_1_spawned_listed_and_swinging(self):
        status, out = spawn("pendulum", 1.0)
        self.assertEqual(status, 0, out)
        self.assertIn("Successfully spawned entity", out)
        self.assertTrue(self.gz.wait_names(lambda n: "pendulum" in n), self.gz.names())
        props = self.gz.get_model_properties(model_name="pendulum")
        self.assertFalse(props.is_static)
        self.assertEqual(list(props.body_names), ["post", "bob"])
        self.assertEqual(list(props.joint_names), ["world_joint", "swing"])
        self.assertIn("bob_fixed_joint_lump__weight_collision_1", list(props.geom_names))
        positions = self.swept("pendulum")      # level at 0, down at pi/2, stopped near 3
        self.assertGreater(max(positions) - min(positions), 1.0, positions)
        self.assertTrue(all(-0.2 < p < 3.4 for p in positions), positions)
        model = self.gz.get_model_state(model_name="pendulum")
        self.assertAlmostEqual(model.pose.position.x, 1.0, delta=STILL)   # held by the world
        self.assertAlmostEqual(model.pose.position.z, 0.0, delta=STILL)
        bob = self.gz.get_link_state(link_name="pendulum::bob", reference_frame="")
        self.assertTrue(bob.success, bob.status_message)
        self.assertAlmostEqual(bob.link_state.pose.position.z, 1.0, delta=STILL)   # the pivot
        states = one_message("/gazebo/link_states", LinkStates)
        self.assertIn("pendulum::bob", states.name)
        self.assertIn("pendulum::post", states.name)

    def test_2_deleted_and_spawned_again_it_swings_again(self):
        self.assertTrue(self.gz.delete_model(model_name="pendulum").success)
        self.assertTrue(self.gz.wait_names(lambda n: "pendulum" not in n), self.gz.names())
        status, out = spawn("again", -1.0)
        self.assertEqual(status, 0, out)
        self.assertTrue(self.gz.wait_names(lambda n: "again" in n), self.gz.names())
        positions = self.swept("again")
        self.assertGreater(max(positions) - min(positions), 1.0, positions)


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "urdf_pendulum", UrdfPendulumTest)
