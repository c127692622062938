#!/usr/bin/env python3
"""rostest node: a world with actors (test/fixtures/worlds/actors.world, our own) runs through
roslaunch: /gazebo/model_states lists the actors after the world's models and before the robot,
as Gazebo 11 lists them (World::LoadEntities); the walker moves along its script in sim time;
the laser does not see it (Gazebo's CPU ray sensor never sees an actor)."""
import math

import rospy
import rostest
from sensor_msgs.msg import LaserScan

from sim_test_support import WAIT, Recorder, SimTestCase, wait_for

MODELS = ["ground_plane", "curtain_rail", "wall", "walker", "pacer", "turtlebot3_burger"]


class WorldActorsTest(SimTestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.scans = Recorder("scan", LaserScan)
        assert cls.scans.latest(WAIT) is not None, "no scan"

    def walker_at(self, after: rospy.Time):
        """(sim time, x, y) of the walker in the first model_states at or after ``after``."""
        def found():
            msgs, _ = self.gz.states.snapshot()
            return msgs and rospy.Time.now() >= after
        self.assertTrue(wait_for(found, WAIT), "no model_states")
        msg = self.gz.latest_states()
        p = msg.pose[list(msg.name).index("walker")].position
        return rospy.Time.now().to_sec(), p.x, p.y

    def test_actors_are_listed_move_and_are_not_seen_by_the_laser(self):
        self.assertTrue(self.gz.wait_names(lambda names: names == MODELS), self.gz.names())
        start = self.walker_at(rospy.Time.now())
        later = self.walker_at(rospy.Time.now() + rospy.Duration(3.0))
        moved = math.hypot(later[1] - start[1], later[2] - start[2])
        rospy.loginfo("the walker moved %.2f m in %.2f s of sim time", moved,
                      later[0] - start[0])
        self.assertGreater(moved, 0.3)      # 2 m a side in 4 s, 1 s turning at each corner
        self.assertLess(moved, 0.8 * (later[0] - start[0]) + 0.3)

        # while the walker is 2.3 to 3.7 m straight ahead of the laser, it returns nothing
        def ahead_of_the_laser():
            x, y, _ = self.gz.position("walker")
            return abs(y + 2.0) < 0.05 and 0.3 < x < 1.7
        self.assertTrue(wait_for(ahead_of_the_laser, WAIT), "the walker never came by")
        scan = self.scans.latest()
        ahead = sorted(scan.ranges[i] for i in (-2, -1, 0, 1, 2))[2]
        self.assertTrue(math.isinf(ahead) or ahead > scan.range_max, ahead)


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "test_world_actors", WorldActorsTest)
