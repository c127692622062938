#!/usr/bin/env python3
"""rostest node: learning stage 3 as turtlebot3_dqn drives it (model_states names, 24 laser
samples, the obstacle spun through the set_model_state topic, the goal spawned and deleted while
model_states streams). Waits on wall time with limits."""
import math
import os
import time

import rospy
import rostest
from gazebo_msgs.msg import ModelState
from geometry_msgs.msg import Point, Pose, Quaternion, Twist, Vector3
from sensor_msgs.msg import LaserScan

from sim_test_support import SimTestCase, wait_for, yaw_of
from sim_test_support import SHORT_WAIT as WAIT


class StageTest(SimTestCase):
    def test_names_and_scan(self):
        self.assertTrue(self.gz.wait_names(
            lambda n: n == ["ground_plane", "turtlebot3_square", "obstacle", "turtlebot3_burger"]),
            self.gz.names())
        scan = rospy.wait_for_message("/scan", LaserScan, WAIT)
        self.assertEqual(len(scan.ranges), 24)
        self.assertAlmostEqual(scan.angle_increment, 6.28319 / 23, places=5)

    def test_obstacle_spins_through_the_topic(self):
        """moving_obstacle.py: read the obstacle's pose from model_states, publish the same pose
        with angular z 0.5, sleep 0.1 s (wall), again."""
        pub = rospy.Publisher("/gazebo/set_model_state", ModelState, queue_size=1)
        wait_for(lambda: pub.get_num_connections() > 0, WAIT)
        first = self.gz.get_model_state(model_name="obstacle").pose
        deadline = time.monotonic() + 3.0
        while time.monotonic() < deadline:
            states = self.gz.latest_states()
            i = states.name.index("obstacle")
            pub.publish(ModelState("obstacle", states.pose[i],
                                   Twist(angular=Vector3(0, 0, 0.5)), "world"))
            time.sleep(0.1)
        last = self.gz.get_model_state(model_name="obstacle").pose
        turned = yaw_of(last.orientation) - yaw_of(first.orientation)
        rospy.loginfo("obstacle turned %.3f rad in 3 s", turned)
        self.assertGreater(turned, 0.2)
        self.assertLess(math.hypot(last.position.x, last.position.y), 0.02)  # about its centre

    def test_goal_spawn_and_delete_seen_in_the_stream(self):
        here = os.path.dirname(os.path.abspath(__file__))
        with open(os.path.join(here, os.pardir, os.pardir, "models", "goal_box",
                               "model.sdf")) as f:
            xml = f.read()
        for x in (0.6, -0.3):
            self.gz.reset_simulation()
            resp = self.gz.spawn_sdf_model(model_name="goal", model_xml=xml,
                                           robot_namespace="robotos_name_space",
                                           initial_pose=Pose(Point(x, 0, 0),
                                                             Quaternion(0, 0, 0, 0)),
                                           reference_frame="world")
            self.assertTrue(resp.success, resp.status_message)
            self.assertTrue(self.gz.wait_names(lambda n: "goal" in n, WAIT))
            self.assertTrue(self.gz.delete_model(model_name="goal").success)
            self.assertTrue(self.gz.wait_names(lambda n: "goal" not in n, WAIT))


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "world_stages", StageTest)
