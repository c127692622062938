#!/usr/bin/env python3
"""rostest node: model plugins through the real /gazebo (model_plugins.test; the world is
test/fixtures/model_plugins/model_plugins.world, no robot of its own). The box's p3d, read at
the sim time get_model_state answers at with physics paused, is within 1 mm of the model's
pose while the box slides; the pendulum's joint states name its hinge and give
get_joint_properties' position; hector's IMU reads +9.8 m/s^2 up on the resting box and its
GPS fix lies north of the reference; the robot that spawn_model put in namespace tb_p3d
publishes its p3d and joint states there.

Every wait is on wall time with a limit."""
import math
import time

import rospy
import rostest
from gazebo_msgs.msg import ModelState
from gazebo_msgs.srv import GetJointProperties
from nav_msgs.msg import Odometry
from sensor_msgs.msg import Imu, JointState, NavSatFix

from sim_test_support import WAIT, Recorder, SimTestCase, one_message, wait_for


class ModelPluginsTest(SimTestCase):
    def tearDown(self):
        self.gz.unpause_physics()

    def test_1_p3d_is_the_models_pose_at_one_sim_time(self):
        odom = Recorder("/box_odom", Odometry)
        try:
            self.assertIsNotNone(odom.latest(WAIT))
            state = ModelState(model_name="box")
            state.pose.position.x, state.pose.position.z = 3.0, 0.1
            state.pose.orientation.w = 1.0
            state.twist.linear.x = 2.0                      # it slides: 2 mm a step
            self.assertTrue(self.gz.set_model_state(state).success)
            time.sleep(0.05)
            self.gz.pause_physics()
            answer = self.gz.get_model_state(model_name="box", relative_entity_name="world")
            self.assertTrue(answer.success, answer.status_message)
            stamp = answer.header.stamp
            self.assertTrue(wait_for(lambda: odom.between(stamp, stamp), WAIT),
                            "no p3d message of the paused sim time")
            msg = odom.between(stamp, stamp)[-1]
        finally:
            odom.sub.unregister()
        self.assertEqual((msg.header.frame_id, msg.child_frame_id), ("world", "body"))
        p, q = msg.pose.pose.position, answer.pose.position
        self.assertLess(math.dist((p.x, p.y, p.z), (q.x, q.y, q.z)), 0.001, (p, q))
        self.assertGreater(msg.twist.twist.linear.x, 0.1, "the box was sliding")

    def test_2_joint_states_name_the_hinge_with_its_position(self):
        states = Recorder("/pendulum/joint_states", JointState)
        try:
            self.assertIsNotNone(states.latest(WAIT))
            self.gz.pause_physics()
            now = self.gz.get_model_state(model_name="pendulum").header.stamp
            props = rospy.ServiceProxy("/gazebo/get_joint_properties", GetJointProperties)(
                joint_name="hinge")
            self.assertTrue(wait_for(lambda: states.between(now - rospy.Duration(0.05), now),
                                     WAIT))
            msg = states.between(now - rospy.Duration(0.05), now)[-1]
        finally:
            states.sub.unregister()
        self.assertEqual(list(msg.name), ["hinge"])
        self.assertEqual(len(msg.velocity), 1)
        # the message is of the last 50 Hz tick before the pause: moved on at its rate since
        ahead = (now - msg.header.stamp).to_sec()
        self.assertLess(ahead, 0.021)
        self.assertAlmostEqual(msg.position[0] + msg.velocity[0] * ahead, props.position[0],
                               delta=0.01)
        if ahead == 0.0:
            self.assertAlmostEqual(msg.position[0], props.position[0], places=6)

    def test_3_hector_imu_reads_gravity_up_and_the_gps_a_fix(self):
        imu = one_message("/box/imu", Imu)
        self.assertIsNotNone(imu)
        self.assertEqual(imu.header.frame_id, "body")
        self.assertAlmostEqual(imu.linear_acceleration.z, 9.8, delta=0.2)
        fix = one_message("/box/fix", NavSatFix)
        self.assertIsNotNone(fix)
        self.assertEqual((fix.header.frame_id, fix.status.status, fix.status.service),
                         ("body", 0, 1))
        self.assertGreater(fix.latitude, 49.9)          # x is north: the box is at x > 0
        self.assertAlmostEqual(fix.longitude, 8.9, places=6)

    def test_4_the_spawned_robots_p3d_is_in_its_namespace(self):
        self.assertTrue(wait_for(lambda: "rover" in self.gz.names(), 60.0), "rover spawned")
        odom = one_message("/tb_p3d/ground_truth", Odometry)
        self.assertIsNotNone(odom)
        self.assertEqual((odom.header.frame_id, odom.child_frame_id), ("world", "base_link"))
        self.assertAlmostEqual(odom.pose.pose.position.x, 1.0, delta=0.02)
        self.assertAlmostEqual(odom.pose.pose.position.y, -2.0, delta=0.02)
        joints = one_message("/tb_p3d/joint_states", JointState)
        self.assertIsNotNone(joints)
        self.assertEqual(list(joints.name), ["left_joint", "right_joint"])


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "test_model_plugins", ModelPluginsTest)
