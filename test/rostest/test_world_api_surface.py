#!/usr/bin/env python3
"""rostest node: /gazebo's surface in the empty world without a robot of its own (real time):
exactly gazebo_ros' topics and services (the list of gazebo_ros' own ros_network_default
test, with Gazebo 11's ~performance_metrics), no /tf until a robot that drives is spawned,
delete_light, and set_joint_properties on a spawned URDF's revolute joint (damping reported
and felt, its hiStop holding it against apply_joint_effort).

Every wait is on wall time with a limit. Each test deletes what it spawned."""
import math
import os

import rosgraph
import rospkg
import rospy
import rostest
from gazebo_msgs.msg import ODEJointProperties
from gazebo_msgs.srv import (ApplyJointEffort, DeleteLight, GetJointProperties,
                             GetLightProperties, JointRequest, SetJointProperties)

from sim_test_support import SHORT_WAIT as WAIT
from sim_test_support import SimTestCase, pose, publishers, wait_for

PACKAGE = rospkg.RosPack().get_path("tutorial_turtlebot")
with open(os.path.join(PACKAGE, "urdf", "turtlebot3_burger.urdf")) as _f:
    BURGER = _f.read()
with open(os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "fixtures",
                       "hinge.urdf")) as _f:
    HINGE = _f.read()   # a flap on a vertical revolute joint (stops +-1.5 rad) over a heavy base
SERVICES = {"delete_light": DeleteLight, "get_light_properties": GetLightProperties,
            "set_joint_properties": SetJointProperties,
            "get_joint_properties": GetJointProperties, "apply_joint_effort": ApplyJointEffort,
            "clear_joint_forces": JointRequest}
# what gazebo_ros' api plugin offers (Gazebo 11.2 and later: ~performance_metrics too)
TOPICS = {"/clock", "/rosout", "/gazebo/link_states", "/gazebo/model_states",
          "/gazebo/parameter_descriptions", "/gazebo/parameter_updates",
          "/gazebo/performance_metrics"}
SUBSCRIPTIONS = {"/gazebo/set_model_state", "/gazebo/set_link_state"}
GAZEBO_SERVICES = {"/gazebo/" + name for name in (
    "apply_body_wrench", "apply_joint_effort", "clear_body_wrenches", "clear_joint_forces",
    "delete_light", "delete_model", "get_joint_properties", "get_light_properties",
    "get_link_properties", "get_link_state", "get_loggers", "get_model_properties",
    "get_model_state", "get_physics_properties", "get_world_properties", "pause_physics",
    "reset_simulation", "reset_world", "set_joint_properties", "set_light_properties",
    "set_link_properties", "set_link_state", "set_logger_level", "set_model_configuration",
    "set_model_state", "set_parameters", "set_physics_properties", "spawn_sdf_model",
    "spawn_urdf_model", "unpause_physics")}
MODELS = ("hinged", "tb3")


def offered_by(node="/gazebo"):
    """(topics published, topics subscribed, services) of ``node``, as the master lists them."""
    state = rosgraph.Master("/test").getSystemState()
    return tuple({name for name, nodes in kind if node in nodes} for kind in state)


class WorldApiSurfaceTest(SimTestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        for name, srv in SERVICES.items():
            rospy.wait_for_service("/gazebo/" + name, timeout=WAIT)
            setattr(cls, name, rospy.ServiceProxy("/gazebo/" + name, srv))

    def tearDown(self):
        for name in MODELS:
            self.gz.delete_model(model_name=name)

    def spawn(self, name, xml, where, namespace=""):
        resp = self.gz.spawn_urdf_model(model_name=name, model_xml=xml,
                                        robot_namespace=namespace, initial_pose=where,
                                        reference_frame="")
        self.assertTrue(resp.success, resp.status_message)

    def sim_seconds(self, seconds):
        """Wait until ``seconds`` of sim time passed (at most WAIT wall s)."""
        end = rospy.get_time() + seconds
        self.assertTrue(wait_for(lambda: rospy.get_time() >= end, WAIT), "the clock stalled")

    def joint(self, name):
        props = self.get_joint_properties(joint_name=name)
        self.assertTrue(props.success, props.status_message)
        return props.damping[0], props.position[0], props.rate[0]

    def test_gazebos_topics_and_services_and_no_tf_without_a_robot(self):
        topics, subscriptions, services = offered_by()
        self.assertEqual(topics, TOPICS)
        self.assertEqual(subscriptions, SUBSCRIPTIONS)
        self.assertEqual(services, GAZEBO_SERVICES)
        self.assertEqual(publishers("/tf"), [])

    def test_tf_comes_with_a_spawned_robot_and_goes_with_it(self):
        self.spawn("tb3", BURGER, pose(0.0, 0.0), namespace="tb3")
        self.assertTrue(wait_for(lambda: "/gazebo" in publishers("/tf"), WAIT),
                        publishers("/tf"))
        self.assertIn("/tb3/odom", offered_by()[0])
        resp = self.gz.delete_model(model_name="tb3")
        self.assertTrue(resp.success, resp.status_message)
        self.assertTrue(wait_for(lambda: "/gazebo" not in publishers("/tf"), WAIT),
                        publishers("/tf"))

    def test_delete_light_removes_the_sun(self):
        self.assertTrue(self.get_light_properties(light_name="sun").success)
        resp = self.delete_light(light_name="sun")
        self.assertEqual((resp.success, resp.status_message),
                         (True, "DeleteLight: sun successfully deleted"))
        resp = self.get_light_properties(light_name="sun")
        self.assertEqual((resp.success, resp.status_message),
                         (False, "getLightProperties: Requested light sun not found!"))
        resp = self.delete_light(light_name="sun")
        self.assertEqual((resp.success, resp.status_message),
                         (False, "DeleteLight: Requested light sun not found!"))

    def test_set_joint_properties_damps_a_revolute_joint_and_its_hi_stop_holds_it(self):
        self.spawn("hinged", HINGE, pose(1.0, 0.0, 0.06))
        self.assertEqual(self.joint("hinge")[0], 0.0)
        resp = self.set_joint_properties(
            joint_name="hinge", ode_joint_config=ODEJointProperties(damping=[0.5], hiStop=[0.3]))
        self.assertEqual((resp.success, resp.status_message),
                         (True, "SetJointProperties: properties set"))
        self.assertEqual(self.joint("hinged::hinge")[0], 0.5)
        # 0.05 N m against 0.5 N m s/rad: 0.1 rad/s (undamped the flap would gain ~3 rad/s^2)
        resp = self.apply_joint_effort(joint_name="hinge", effort=0.05,
                                       start_time=rospy.Time(0), duration=rospy.Duration(-1))
        self.assertTrue(resp.success, resp.status_message)
        self.sim_seconds(1.5)
        _, position, rate = self.joint("hinge")
        self.assertAlmostEqual(rate, 0.1, delta=0.02)
        self.assertLess(position, 0.25)
        # 2 N m pushes on to the stop at 0.3 rad (the URDF's is 1.5) and no further
        self.apply_joint_effort(joint_name="hinge", effort=1.95, start_time=rospy.Time(0),
                                duration=rospy.Duration(-1))
        self.sim_seconds(2.0)
        _, position, rate = self.joint("hinge")
        self.assertAlmostEqual(position, 0.3, delta=0.01)
        self.assertLess(abs(rate), 0.05)
        resp = self.set_joint_properties(
            joint_name="hinge", ode_joint_config=ODEJointProperties(damping=[math.nan]))
        self.assertEqual((resp.success, resp.status_message), (
            False, "SetJointProperties: ode_joint_config.damping[0]: NaN or infinite value"))
        self.assertEqual(self.joint("hinge")[0], 0.5)
        resp = self.set_joint_properties(joint_name="elbow")
        self.assertEqual((resp.success, resp.status_message),
                         (False, "SetJointProperties: joint not found"))


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "world_api_surface", WorldApiSurfaceTest)
