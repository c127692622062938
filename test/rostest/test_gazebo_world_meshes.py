#!/usr/bin/env python3
"""rostest node: the sim in turtlebot3_world loaded from Gazebo's own files (model:// includes,
Collada meshes). Its models are the included ones; its scan matches, ray by ray, the scan of the
built-in primitive copy of the world from the same pose; driven backwards at full speed into
the mesh wall, the robot stops at the wall."""
import unittest

import numpy as np
import rospy
import rostest
from gazebo_msgs.msg import ModelState
from gazebo_msgs.srv import GetWorldProperties, SetModelState, SpawnModel
from geometry_msgs.msg import Pose
from sensor_msgs.msg import LaserScan

from sim_test_support import WAIT, Driver, arena_wall_distance, box_outside_arena, yaw_of
from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation


def reference_scan(x, y, yaw):
    """The built-in primitive turtlebot3_world's scan from the same pose."""
    sim = Simulation(SimConfig(world="turtlebot3_world", model="burger", x=x, y=y, yaw=yaw))
    try:
        for _ in range(200):
            sim.step()
        return np.array(sim.robot.scan(), dtype=float)
    finally:
        sim.close()


class GazeboWorldMeshesTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_gazebo_world_meshes")
        cls.drive = Driver()

    def test_1_the_models_are_the_included_ones(self):
        rospy.wait_for_service("/gazebo/get_world_properties", WAIT)
        names = rospy.ServiceProxy("/gazebo/get_world_properties", GetWorldProperties)().model_names
        self.assertEqual(names, ["ground_plane", "turtlebot3_world", "turtlebot3_burger"])

    def test_2_the_scan_sees_the_meshes_where_they_are(self):
        start = self.drive.odom.latest(WAIT)
        self.assertIsNotNone(start)
        scan = rospy.wait_for_message("/scan", LaserScan, WAIT)
        pose = start.pose.pose
        expected = reference_scan(pose.position.x, pose.position.y, yaw_of(pose.orientation))
        ranges = np.array(scan.ranges, dtype=float)
        both = np.isfinite(ranges) & np.isfinite(expected)
        self.assertGreater(both.sum(), 300, "most rays hit something in both worlds")
        error = np.abs(ranges[both] - expected[both])
        self.assertLess(np.median(error), 0.03, "median range error %.3f m" % np.median(error))
        self.assertLess(np.percentile(error, 95), 0.08)
        # straight behind: the arena wall, 0.64 m away at this pose
        behind = ranges[len(ranges) // 2]
        self.assertAlmostEqual(behind, arena_wall_distance((pose.position.x, pose.position.y),
                                                           180.0), delta=0.05)

    def test_3_backwards_into_the_mesh_wall_stops_at_it(self):
        """As sim_wall.test does in the built-in world: the robot reaches the wall and slides
        along it, never through it."""
        start = self.drive.odom.latest(WAIT)
        self.drive.send(-1.0, 0.0)  # clamped to the Burger's 0.22 m/s
        end = self.drive.odom.after(start.header.stamp + rospy.Duration(8.0), 120.0)
        self.drive.send(0.0, 0.0)
        self.assertIsNotNone(end)
        pose = end.pose.pose
        worst = box_outside_arena(pose.position.x, pose.position.y, yaw_of(pose.orientation))
        self.assertLess(worst, 0.01, "through the mesh wall by %.3f m" % worst)
        self.assertGreater(worst, -0.03, "stopped %.3f m short of the mesh wall" % -worst)
        self.assertLess(abs(pose.position.z), 0.05, "tipped or climbed the wall")

    def test_4_a_spawned_include_of_an_stl_model_is_seen_where_it_stands(self):
        """spawn_sdf_model of a model that includes model://mesh_pillar (an STL pillar, 0.2 m
        by 0.4 m: the include's pose replaces the model's own turn) 1 m ahead of the robot,
        put back at its spawn first: the scan straight ahead ends at the pillar's face."""
        state = ModelState(model_name="turtlebot3_burger")
        state.pose.position.x, state.pose.position.y = -2.0, -0.5
        state.pose.orientation.w = 1.0
        teleport = rospy.ServiceProxy("/gazebo/set_model_state", SetModelState)
        self.assertTrue(teleport(model_state=state).success)
        rospy.sleep(0.5)
        xml = ("<sdf version='1.6'><model name='pillars'><include><uri>model://mesh_pillar"
               "</uri><pose>0 0 0 0 0 0</pose></include></model></sdf>")
        pose = Pose()
        pose.position.x, pose.position.y = -1.0, -0.5
        spawn = rospy.ServiceProxy("/gazebo/spawn_sdf_model", SpawnModel)
        answer = spawn(model_name="pillars", model_xml=xml, initial_pose=pose)
        self.assertTrue(answer.success, answer.status_message)
        stamp = rospy.Time.now()
        ahead = None
        for _ in range(50):
            scan = rospy.wait_for_message("/scan", LaserScan, WAIT)
            if scan.header.stamp > stamp:
                ahead = float(np.median([scan.ranges[0], scan.ranges[1], scan.ranges[-1]]))
                break
        self.assertIsNotNone(ahead)
        # the pillar's near face 0.1 m before its centre at x -1.0; base_scan 0.032 m behind
        # base_footprint on the Burger
        self.assertAlmostEqual(ahead, 1.0 - 0.1 + 0.032, delta=0.04)


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "gazebo_world_meshes", GazeboWorldMeshesTest)
