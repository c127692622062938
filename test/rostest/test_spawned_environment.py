#!/usr/bin/env python3
"""rostest node: a vendor-style environment launch (spawned_environment.test) runs with the
package's own means: the sim starts paused from empty_world.launch (gazebo_ros's arguments), the
xacro of test/fixtures/environment/ is spawned from its parameter by spawn_model -urdf -param,
as Gazebo 11 makes it (static, its wall links lumped into the floor under Gazebo's names), and
after /gazebo/unpause_physics the clock runs and the pen stays where it was spawned.

Every wait is on wall time with a limit."""
import rospy
import rostest
from std_srvs.srv import Empty

from sim_test_support import WAIT, SimTestCase, wait_for

STILL = 1e-6      # m


class SpawnedEnvironmentTest(SimTestCase):
    def test_1_spawned_paused_static_with_gazebos_names(self):
        # paused, /gazebo/model_states waits for the physics (as Gazebo's): ask the world
        self.assertTrue(wait_for(
            lambda: "pen" in self.gz.get_world_properties().model_names, WAIT),
            self.gz.get_world_properties().model_names)
        self.assertTrue(self.gz.get_physics_properties().pause)      # paused:=true
        props = self.gz.get_model_properties(model_name="pen")
        self.assertTrue(props.success, props.status_message)
        self.assertTrue(props.is_static)
        self.assertEqual(list(props.body_names), ["floor"])          # fixed joints lumped
        # Gazebo 11's names: the lumped links in joint-name order, numbered in the floor
        self.assertEqual(sorted(props.geom_names), [
            "floor_collision", "floor_fixed_joint_lump__wall_east_collision_1",
            "floor_fixed_joint_lump__wall_north_collision_2",
            "floor_fixed_joint_lump__wall_south_collision_3",
            "floor_fixed_joint_lump__wall_west_collision_4"])
        position = self.gz.position("pen")
        self.assertAlmostEqual(position[0], 1.0, places=6)           # -x 1.0

    def test_2_unpaused_the_clock_runs_and_the_pen_stays(self):
        before = self.gz.position("pen")
        rospy.wait_for_service("/gazebo/unpause_physics", timeout=WAIT)
        rospy.ServiceProxy("/gazebo/unpause_physics", Empty)()
        first = self.gz.clock.latest(WAIT).clock
        self.assertTrue(wait_for(lambda: self.gz.clock.latest(WAIT).clock
                                 >= first + rospy.Duration(2.0), WAIT), "no 2 s of sim time")
        after = self.gz.position("pen")
        self.assertLess(max(abs(a - b) for a, b in zip(after, before)), STILL)


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "spawned_environment", SpawnedEnvironmentTest)
