#!/usr/bin/env python3
"""rostest node: spawns and teleports at z 0 onto raised floors through the real /gazebo
(spawn_floors.test; the world is test/fixtures/worlds/floors/, make_floor_fixtures.py). The
robot stands on top of each floor, level, and its laser sees no floor; a robot spawned into a
wall is spawned, with one warning line naming the wall and a z_pos; a Waffle Pi spawned inside
the floor box stands on top of it.

Every wait is on wall time with a limit."""
import math
import os

import rospy
import rostest
from gazebo_msgs.msg import ModelState
from rosgraph_msgs.msg import Log
from sensor_msgs.msg import LaserScan

from sim_test_support import WAIT, NodeProcess, Recorder, SimTestCase, pose, wait_for

ROBOT = "turtlebot3_burger"
BURGER = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, os.pardir, "urdf",
                      "turtlebot3_burger.urdf")
WAFFLE_PI = os.path.join(os.path.dirname(BURGER), "turtlebot3_waffle_pi.urdf")
LEVEL = math.radians(0.5)
THIN_FLOOR, TRACK = ((12.0, 0.0, 0.0), 0.01), ((19.3, 0.0, math.pi / 2), 0.10)


def roll_pitch(q):
    roll = math.atan2(2 * (q.w * q.x + q.y * q.z), 1 - 2 * (q.x * q.x + q.y * q.y))
    pitch = math.asin(max(-1.0, min(1.0, 2 * (q.w * q.y - q.z * q.x))))
    return roll, pitch


class SpawnFloorsTest(SimTestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.log = []      # every node's log lines on /rosout (their stamps come unordered)
        rospy.Subscriber("/rosout", Log, cls.log.append, queue_size=100)
        assert cls.gz.wait_names(lambda n: ROBOT in n, WAIT), cls.gz.names()

    def assert_on(self, name, top, scan_topic):
        """After 1 s of sim time: ``name`` stands level on the floor whose top is ``top``, and
        a scan taken then sees nothing (each floor stands alone in 6 m of free space)."""
        start = self.gz.clock.latest(WAIT).clock
        scans = Recorder(scan_topic, LaserScan)
        try:
            scan = scans.after(start + rospy.Duration(1.0), WAIT)
        finally:
            scans.sub.unregister()
        self.assertIsNotNone(scan, "no scan on %s" % scan_topic)
        state = self.gz.get_model_state(model_name=name)
        self.assertTrue(state.success, state.status_message)
        self.assertAlmostEqual(state.pose.position.z, top, delta=0.003)
        roll, pitch = roll_pitch(state.pose.orientation)
        self.assertLess(abs(roll), LEVEL)
        self.assertLess(abs(pitch), LEVEL)
        seen = [r for r in scan.ranges if math.isfinite(r)]
        self.assertEqual(seen, [], "the laser sees %d rays, from %.2f m" % (
            len(seen), min(seen) if seen else 0.0))

    def test_1_the_robot_started_at_z_0_stands_on_the_floor_box(self):
        self.assert_on(ROBOT, 0.19, "/scan")

    def test_2_spawn_model_at_z_0_stands_on_the_slab_mesh(self):
        spawn = NodeProcess("spawn_model", "-urdf", "-file", BURGER, "-model", "tb3_1",
                            "-robot_namespace", "tb3_1", "-x", "6", "-y", "0", "-z", "0")
        try:
            self.assertEqual(spawn.wait(WAIT), 0, spawn.stdout + spawn.stderr)
            self.assert_on("tb3_1", 0.034, "/tb3_1/scan")
        finally:
            self.gz.delete_model(model_name="tb3_1")

    def test_3_set_model_state_at_z_0_lands_on_a_thin_box_and_a_track_mesh(self):
        for (x, y, yaw), top in (THIN_FLOOR, TRACK):
            resp = self.gz.set_model_state(ModelState(model_name=ROBOT, pose=pose(x, y, 0.0, yaw),
                                                      reference_frame="world"))
            self.assertTrue(resp.success, resp.status_message)
            self.assertAlmostEqual(self.gz.position(ROBOT)[2], top, delta=0.003)
            self.assert_on(ROBOT, top, "/scan")

    def test_4_a_robot_spawned_into_the_wall_is_spawned_with_one_warning(self):
        with open(BURGER) as f:
            urdf = f.read()
        resp = self.gz.spawn_urdf_model(model_name="tb3_2", model_xml=urdf,
                                        robot_namespace="tb3_2",
                                        initial_pose=pose(42.0, 0.08), reference_frame="world")
        try:
            self.assertTrue(resp.success, resp.status_message)
            self.assertTrue(self.gz.wait_names(lambda n: "tb3_2" in n, WAIT), self.gz.names())

            def warnings():
                return [m.msg for m in list(self.log)
                        if m.name == "/gazebo" and m.level == Log.WARN and "tb3_2" in m.msg
                        and "overlaps" in m.msg]
            self.assertTrue(wait_for(lambda: warnings(), WAIT), "no warning on /rosout")
            rospy.sleep(0.5)      # one line, not one and more
            (line,) = warnings()
            self.assertLessEqual(len(line), 200, line)
            self.assertIn("overlaps wall by", line)
            self.assertIn("z_pos 1.000", line)
        finally:
            self.gz.delete_model(model_name="tb3_2")

    def test_5_spawn_model_of_a_waffle_pi_inside_the_floor_box_stands_on_top(self):
        """The 0.19 m floor box holds a whole Waffle Pi (0.141 m) asked for z 0: on top, level,
        still after 1 s of sim time (doc/worlds.md, Floors: inside a solid floor)."""
        spawn = NodeProcess("spawn_model", "-urdf", "-file", WAFFLE_PI, "-model", "tb3_3",
                            "-robot_namespace", "tb3_3", "-x", "0", "-y", "0.45", "-z", "0")
        try:
            self.assertEqual(spawn.wait(WAIT), 0, spawn.stdout + spawn.stderr)
            start = self.gz.clock.latest(WAIT).clock
            placed = self.gz.position("tb3_3")
            self.assertAlmostEqual(placed[2], 0.19, delta=0.003)
            self.assertTrue(wait_for(lambda: self.gz.clock.latest(WAIT).clock
                                     >= start + rospy.Duration(1.0), WAIT))
            state = self.gz.get_model_state(model_name="tb3_3")
            self.assertTrue(state.success, state.status_message)
            here = state.pose.position
            self.assertLess(math.dist((here.x, here.y, here.z), placed), 0.01)
            roll, pitch = roll_pitch(state.pose.orientation)
            self.assertLess(abs(roll), math.radians(1.0))
            self.assertLess(abs(pitch), math.radians(1.0))
        finally:
            self.gz.delete_model(model_name="tb3_3")


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "spawn_floors", SpawnFloorsTest)
