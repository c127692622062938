#!/usr/bin/env python3
"""rostest node: jointed SDF models through the real /gazebo (joints.test; the world is
test/fixtures/joints/joints.world, no robot): the cart stands level on its hinged wheels, a
jointed link's state is its own frame, get_joint_properties, apply_joint_effort and
get_model_properties reach the SDF joints over ROS, and the damped pendulum swings down and is
put back by reset_world. Every wait is on wall time with a limit."""
import math

import rospy
import rostest
from gazebo_msgs.msg import LinkStates
from gazebo_msgs.srv import ApplyJointEffort, GetJointProperties

from sim_test_support import WAIT, SimTestCase, wait_for


def rpy(q):
    """(roll, pitch) of a geometry_msgs/Quaternion, rad."""
    roll = math.atan2(2 * (q.w * q.x + q.y * q.z), 1 - 2 * (q.x * q.x + q.y * q.y))
    pitch = math.asin(max(-1.0, min(1.0, 2 * (q.w * q.y - q.z * q.x))))
    return roll, pitch


class JointsTest(SimTestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        for name in ("get_joint_properties", "apply_joint_effort"):
            rospy.wait_for_service("/gazebo/" + name, timeout=30.0)
        cls.joint = rospy.ServiceProxy("/gazebo/get_joint_properties", GetJointProperties)
        cls.effort = rospy.ServiceProxy("/gazebo/apply_joint_effort", ApplyJointEffort)

    def sim_time(self):
        return self.gz.clock.latest(WAIT).clock.to_sec()

    def wait_sim(self, seconds):
        end = self.sim_time() + seconds
        self.assertTrue(wait_for(lambda: self.sim_time() >= end, WAIT + seconds * 3))

    def link(self, name):
        msg = rospy.wait_for_message("/gazebo/link_states", LinkStates, WAIT)
        return msg.pose[list(msg.name).index(name)]

    def test_1_the_cart_stands_level_on_its_wheels(self):
        self.wait_sim(2.0)
        chassis = self.link("cart::chassis")
        self.assertLess(max(abs(a) for a in rpy(chassis.orientation)), 0.01)
        self.assertAlmostEqual(chassis.position.z, 0.15, delta=0.01)
        wheel = self.link("cart::left_wheel")       # its own frame: on its axle, turned -90
        self.assertAlmostEqual(wheel.position.y - chassis.position.y, 0.18, delta=0.002)
        self.assertAlmostEqual(wheel.position.z, 0.1, delta=0.005)

    def test_2_the_sdf_joints_answer_over_ros(self):
        props = self.gz.get_model_properties(model_name="cart")
        self.assertEqual(list(props.joint_names), ["left_hinge", "right_hinge"])
        rail = self.joint(joint_name="slider::rail")
        self.assertTrue(rail.success)
        self.assertEqual(rail.type, GetJointProperties._response_class.PRISMATIC)
        self.assertAlmostEqual(rail.position[0], -0.2, delta=0.01)   # on its lower stop
        answer = self.effort(joint_name="slider::rail", effort=20.0,   # lifts the 1 kg block
                             start_time=rospy.Time(0), duration=rospy.Duration(0.5))
        self.assertTrue(answer.success, answer.status_message)
        self.wait_sim(0.4)        # up at its upper stop by 0.3 s, held there until 0.5 s
        self.assertGreater(self.joint(joint_name="slider::rail").position[0], 0.19)

    def test_3_the_damped_pendulum_dies_down_and_reset_world_puts_it_back(self):
        """It starts swung out 0.1 rad (0.1 m from under its hinge at x 6) and comes to hang
        straight down (its joint at -0.1 rad: 0 is where the file puts it)."""
        self.assertTrue(wait_for(lambda: self.sim_time() >= 8.0, WAIT + 30))
        self.assertAlmostEqual(self.link("damped::bob").position.x, 6.0, delta=0.03)
        self.assertAlmostEqual(self.joint(joint_name="damped::hinge").position[0], -0.1,
                               delta=0.03)
        self.gz.reset_world()
        self.assertAlmostEqual(self.joint(joint_name="damped::hinge").position[0], 0.0,
                               delta=0.02)
        bob = self.link("damped::bob")
        self.assertAlmostEqual(bob.position.x, 5.9, delta=0.01)   # swung out 0.1 rad again


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "joints", JointsTest)
