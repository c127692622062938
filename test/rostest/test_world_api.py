#!/usr/bin/env python3
"""rostest node: Gazebo's world API on /gazebo (Burger in turtlebot3_world, real time).

Every wait is on wall time with a limit. The tests leave the world as they found it (robot
at its spawn, no spawned model, real time)."""
import math
import os
import time

import rospy
import rostest
from gazebo_msgs.msg import LinkStates, ModelState, ODEPhysics
from geometry_msgs.msg import Point, Pose, Quaternion, Twist, Vector3

from sim_test_support import ROBOT, Driver, SimTestCase, wait_for, yaw_of
from sim_test_support import SHORT_WAIT as WAIT

SPAWN = (-2.0, -0.5)
BOX = """<sdf version="1.6"><model name="box"><link name="link">
  <inertial><mass>0.1</mass><inertia><ixx>0.0004</ixx><iyy>0.0004</iyy><izz>0.0004</izz></inertia></inertial>
  <collision name="collision"><geometry><box><size>0.15 0.15 0.15</size></box></geometry>\
</collision>
  <visual name="visual"><geometry><box><size>0.15 0.15 0.15</size></box></geometry></visual>
</link></model></sdf>"""


def pose(x, y, z=0.0, yaw=0.0, zero_quaternion=False):
    q = (Quaternion(0, 0, 0, 0) if zero_quaternion
         else Quaternion(0, 0, math.sin(yaw / 2), math.cos(yaw / 2)))
    return Pose(position=Point(x, y, z), orientation=q)


def goal_xml():
    here = os.path.dirname(os.path.abspath(__file__))
    with open(os.path.join(here, os.pardir, os.pardir, "models", "goal_box", "model.sdf")) as f:
        return f.read()


class WorldApiTest(SimTestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.drive = Driver()
        assert cls.drive.odom.latest(WAIT) is not None, "no odom"

    def setUp(self):
        self.drive.send(0.0, 0.0)
        self.gz.unpause_physics()
        self.gz.reset_world()

    def tearDown(self):
        self.drive.send(0.0, 0.0)
        for name in ("box", "goal", "crate"):
            self.gz.delete_model(model_name=name)
        self.gz.unpause_physics()
        self.set_rate(400.0)

    def set_rate(self, max_update_rate):
        physics = self.gz.get_physics_properties()
        resp = self.gz.set_physics_properties(time_step=physics.time_step,
                                              max_update_rate=max_update_rate,
                                              gravity=physics.gravity,
                                              ode_config=physics.ode_config)
        self.assertTrue(resp.success, resp.status_message)

    # --- states --------------------------------------------------------------------------------

    def test_model_states_names_and_stream(self):
        self.assertTrue(self.gz.wait_names(lambda n: n == ["ground_plane", "ros_symbol", ROBOT]),
                        self.gz.names())
        msg = self.gz.latest_states()
        self.assertEqual(len(msg.pose), 3)
        self.assertEqual(len(msg.twist), 3)
        world = self.gz.get_world_properties()
        self.assertTrue(world.success)
        self.assertEqual(list(world.model_names), ["ground_plane", "ros_symbol", ROBOT])
        self.assertGreater(world.sim_time, 0.0)
        links = rospy.wait_for_message("/gazebo/link_states", LinkStates, WAIT)
        self.assertIn(ROBOT + "::base_footprint", links.name)
        self.assertIn(ROBOT + "::wheel_left_link", links.name)

    def test_get_model_state_equals_odom(self):
        time.sleep(1.0)    # at rest after the reset
        odom = self.drive.odom.latest()
        resp = self.gz.get_model_state(model_name=ROBOT, relative_entity_name="world")
        self.assertTrue(resp.success)
        self.assertEqual(resp.status_message, "GetModelState: got properties")
        self.assertAlmostEqual(resp.pose.position.x, odom.pose.pose.position.x, delta=2e-3)
        self.assertAlmostEqual(resp.pose.position.y, odom.pose.pose.position.y, delta=2e-3)
        self.assertAlmostEqual(resp.pose.position.x, SPAWN[0], delta=0.01)
        self.assertAlmostEqual(yaw_of(resp.pose.orientation),
                               yaw_of(odom.pose.pose.orientation), delta=2e-3)
        props = self.gz.get_model_properties(model_name=ROBOT)
        self.assertTrue(props.success)
        self.assertEqual(props.body_names[0], "base_footprint")
        self.assertFalse(props.is_static)
        relative = self.gz.get_model_state(model_name=ROBOT, relative_entity_name="ros_symbol")
        self.assertAlmostEqual(relative.pose.position.x, SPAWN[0], delta=0.01)

    def wait_at(self, x, y, timeout=WAIT):
        return wait_for(lambda: math.hypot(self.gz.position(ROBOT)[0] - x,
                                           self.gz.position(ROBOT)[1] - y) < 0.02, timeout)

    def test_teleport_by_service_running_and_paused(self):
        resp = self.gz.set_model_state(ModelState(ROBOT, pose(0.55, 0.55, 0.0, 1.0, False),
                                                  Twist(), ""))
        self.assertTrue(resp.success)
        self.assertEqual(resp.status_message, "SetModelState: set model state done")
        self.assertTrue(self.wait_at(0.55, 0.55))
        self.assertTrue(wait_for(lambda: abs(self.drive.odom.latest().pose.pose.position.x
                                             - 0.55) < 0.02, WAIT), "odom did not jump")
        # paused: the clock stands still and the teleport still happens
        self.gz.pause_physics()
        time.sleep(0.3)
        stamp = self.gz.clock.latest().clock
        quaternion = Quaternion(0, 0, 2.0, 2.0)       # not normalised: Gazebo normalises it
        resp = self.gz.set_model_state(ModelState(ROBOT, Pose(Point(-0.55, 0.55, 0), quaternion),
                                                  Twist(), "world"))
        self.assertTrue(resp.success)
        state = self.gz.get_model_state(model_name=ROBOT)
        self.assertAlmostEqual(state.pose.position.x, -0.55, delta=1e-3)
        self.assertAlmostEqual(yaw_of(state.pose.orientation), math.pi / 2, delta=1e-3)
        time.sleep(0.3)
        self.assertEqual(self.gz.clock.latest().clock, stamp)
        self.gz.unpause_physics()

    def test_teleport_by_topic_running_and_paused(self):
        pub = rospy.Publisher("/gazebo/set_model_state", ModelState, queue_size=1)
        wait_for(lambda: pub.get_num_connections() > 0, WAIT)
        pub.publish(ModelState(ROBOT, pose(0.55, -0.55), Twist(), ""))
        self.assertTrue(self.wait_at(0.55, -0.55))
        self.gz.pause_physics()
        pub.publish(ModelState(ROBOT, pose(-0.55, -0.55), Twist(), ""))
        self.assertTrue(self.wait_at(-0.55, -0.55))
        self.gz.unpause_physics()

    # --- spawn and delete ----------------------------------------------------------------------

    def test_spawn_a_box_ahead_push_it_and_delete_it(self):
        t0 = time.monotonic()
        resp = self.gz.spawn_sdf_model(model_name="box", model_xml=BOX,
                                       initial_pose=pose(SPAWN[0] + 0.4, SPAWN[1], 0.075),
                                       reference_frame="")
        spawn_ms = (time.monotonic() - t0) * 1000
        self.assertTrue(resp.success, resp.status_message)
        self.assertEqual(resp.status_message, "SpawnModel: Successfully spawned entity")
        self.assertTrue(self.gz.wait_names(lambda n: n[-1] == "box"))
        time.sleep(0.5)
        start = self.gz.position("box")
        self.drive.send(0.2, 0.0)
        self.assertTrue(wait_for(lambda: self.gz.position("box")[0] > start[0] + 0.2, WAIT),
                        "the robot did not push the box")
        self.drive.send(0.0, 0.0)
        self.assertGreater(self.gz.position("box")[0], self.gz.position(ROBOT)[0] + 0.1)
        t0 = time.monotonic()
        resp = self.gz.delete_model(model_name="box")
        delete_ms = (time.monotonic() - t0) * 1000
        self.assertTrue(resp.success)
        self.assertEqual(resp.status_message, "DeleteModel: successfully deleted model")
        self.assertTrue(self.gz.wait_names(lambda n: "box" not in n))
        rospy.loginfo("spawn %.1f ms, delete %.1f ms (wall, service round trip)",
                      spawn_ms, delete_ms)

    def test_spawned_models_go_back_after_both_resets(self):
        resp = self.gz.spawn_sdf_model(model_name="goal", model_xml=goal_xml(),
                                       robot_namespace="robotos_name_space",
                                       initial_pose=pose(0.6, 0.0, zero_quaternion=True),
                                       reference_frame="world")
        self.assertTrue(resp.success, resp.status_message)
        urdf = ('<robot name="r"><link name="base"><inertial><mass value="0.2"/>'
                '<inertia ixx="0.001" iyy="0.001" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial>'
                '<collision><geometry><cylinder radius="0.05" length="0.2"/></geometry></collision>'
                '</link></robot>')
        resp = self.gz.spawn_urdf_model(model_name="crate", model_xml=urdf,
                                        initial_pose=pose(-1.6, -1.6, 0.1), reference_frame="")
        self.assertTrue(resp.success, resp.status_message)
        for reset in (self.gz.reset_world, self.gz.reset_simulation):
            for name, x, y in (("goal", -0.5, 1.6), ("crate", -0.5, -1.8)):
                self.gz.set_model_state(ModelState(name, pose(x, y, 0.1), Twist(), ""))
                self.assertAlmostEqual(self.gz.position(name)[0], x, delta=1e-3)
            reset()
            self.assertEqual(self.gz.get_world_properties().model_names[-2:], ["goal", "crate"])
            self.assertAlmostEqual(self.gz.position("goal")[0], 0.6, delta=1e-3)
            self.assertAlmostEqual(self.gz.position("crate")[0], -1.6, delta=1e-3)
            goal = self.gz.get_model_state(model_name="goal")
            self.assertAlmostEqual(yaw_of(goal.pose.orientation), -1.5708, delta=1e-3)

    # --- failures ------------------------------------------------------------------------------

    def test_every_failure_answer(self):
        nan = float("nan")
        gz = self.gz
        self.gz.spawn_sdf_model(model_name="box", model_xml=BOX, initial_pose=pose(1.6, 1.6, 0.1))
        cases = [
            (gz.get_model_state(model_name="nope"), "GetModelState: model does not exist"),
            (gz.get_model_state(model_name=ROBOT, relative_entity_name="nope"), "scope"),
            (gz.set_model_state(ModelState("nope", pose(0, 0), Twist(), "")),
             "SetModelState: model does not exist"),
            (gz.set_model_state(ModelState(ROBOT, pose(0, 0), Twist(), "nope")),
             "reference frame"),
            (gz.set_model_state(ModelState(ROBOT, pose(nan, 0), Twist(), "")), "NaN"),
            (gz.get_link_state(link_name="nope::link"), "does not exist"),
            (gz.get_model_properties(model_name="nope"),
             "GetModelProperties: model does not exist"),
            (gz.spawn_sdf_model(model_name="box", model_xml=BOX), "entity already exists"),
            (gz.spawn_sdf_model(model_name="bad", model_xml="<sdf>\n<model name='m'>\n</sdf>"),
             "model_xml:3: malformed XML"),
            (gz.spawn_sdf_model(model_name="bad", model_xml=BOX, reference_frame="nope"),
             "reference_frame"),
            (gz.spawn_sdf_model(model_name="bad", model_xml="<sdf>" + "x" * 2000000 + "</sdf>"),
             "allowed"),
            (gz.spawn_urdf_model(model_name="bad", model_xml=BOX), "needs a <robot>"),
            (gz.spawn_sdf_model(model_name="bad", model_xml=BOX,
                                initial_pose=pose(nan, 0.0)), "NaN"),
            (gz.delete_model(model_name="nope"), "DeleteModel: model does not exist"),
            (gz.set_physics_properties(time_step=5.0, max_update_rate=1.0,
                                       gravity=Vector3(0, 0, -9.8),
                                       ode_config=ODEPhysics(sor_pgs_iters=20)), "time_step"),
        ]
        for resp, words in cases:
            self.assertFalse(resp.success, words)
            self.assertIn(words, resp.status_message)
            self.assertNotIn("\n", resp.status_message)
        # and nothing was lost: the world is as it was, the sim runs on
        self.assertEqual(list(gz.get_world_properties().model_names),
                         ["ground_plane", "ros_symbol", ROBOT, "box"])
        # a mesh file found nowhere is left out with a warning, as Gazebo leaves it out
        holey = BOX.replace("<box><size>0.15 0.15 0.15</size></box>",
                            "<mesh><uri>x.dae</uri></mesh>", 1)
        resp = gz.spawn_sdf_model(model_name="holey", model_xml=holey,
                                  initial_pose=pose(3.0, 3.0))
        self.assertTrue(resp.success, resp.status_message)
        self.assertIn("holey", gz.get_world_properties().model_names)
        self.assertTrue(gz.delete_model(model_name="holey").success)
        stamp = gz.clock.latest().clock
        self.assertTrue(wait_for(lambda: gz.clock.latest().clock > stamp, WAIT))

    # --- physics -------------------------------------------------------------------------------

    def test_max_update_rate_0_runs_faster_and_back(self):
        physics = self.gz.get_physics_properties()
        self.assertTrue(physics.success)
        self.assertAlmostEqual(physics.time_step * physics.max_update_rate, 1.0, places=6)
        self.set_rate(0.0)
        self.assertEqual(self.gz.get_physics_properties().max_update_rate, 0.0)
        fast = self.gz.factor()
        self.set_rate(400.0)
        normal = self.gz.factor()
        rospy.loginfo("factor: max_update_rate 0 -> %.2f, 400 -> %.2f", fast, normal)
        self.assertGreater(fast, 1.5)
        self.assertAlmostEqual(normal, 1.0, delta=0.2)

    def test_dynamic_reconfigure(self):
        from dynamic_reconfigure.client import Client
        client = Client("/gazebo", timeout=WAIT)
        config = client.get_configuration(timeout=WAIT)
        self.assertAlmostEqual(config["time_step"], 0.0025)
        self.assertAlmostEqual(config["max_update_rate"], 400.0)
        client.update_configuration({"max_update_rate": 0.0})
        self.assertEqual(self.gz.get_physics_properties().max_update_rate, 0.0)
        fast = self.gz.factor()
        client.update_configuration({"max_update_rate": 400.0})
        normal = self.gz.factor()
        rospy.loginfo("dynparam factor: max_update_rate 0 -> %.2f, 400 -> %.2f", fast, normal)
        self.assertGreater(fast, 1.5)
        self.assertAlmostEqual(normal, 1.0, delta=0.2)


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "world_api", WorldApiTest)
