#!/usr/bin/env python3
"""rostest node: three TurtleBot3 Burgers from multi_turtlebot3.launch in one sim.

Every wait is on wall time with a limit."""
import math
import os
import time

import rospy
import rostest
import tf2_ros
from geometry_msgs.msg import Twist, Vector3
from gazebo_msgs.msg import ModelState
from nav_msgs.msg import Odometry
from sensor_msgs.msg import Imu, JointState, LaserScan

from sim_test_support import NodeProcess, Recorder, SimTestCase, pose, publishers, wait_for, yaw_of
from sim_test_support import SHORT_WAIT as WAIT

ROBOTS = ("tb3_0", "tb3_1", "tb3_2")
SPAWN = {"tb3_0": (-7.0, -1.0, 1.57), "tb3_1": (7.0, -1.0, 1.57), "tb3_2": (0.5, 3.0, 0.0)}
# Three places within 0.9 m of (-3.5, -3.0), where the house is clear for 1.3 m around.
TRIANGLE = {"tb3_0": (-3.5, -3.6), "tb3_1": (-3.5, -2.4), "tb3_2": (-2.9, -3.0)}
BURGER_RADIUS = 0.04   # m: the LDS housing, what a Burger's laser meets of another Burger
URDF_DIR = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, os.pardir, "urdf")
BURGER = os.path.join(URDF_DIR, "turtlebot3_burger.urdf")


class MultiTurtleBot3(SimTestCase):

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.odom = {r: Recorder("/%s/odom" % r, Odometry) for r in ROBOTS}
        cls.scan = {r: Recorder("/%s/scan" % r, LaserScan) for r in ROBOTS}
        cls.imu = {r: Recorder("/%s/imu" % r, Imu) for r in ROBOTS}
        cls.joints = {r: Recorder("/%s/joint_states" % r, JointState) for r in ROBOTS}
        cls.cmd = {r: rospy.Publisher("/%s/cmd_vel" % r, Twist, queue_size=1) for r in ROBOTS}
        cls.tf = tf2_ros.Buffer()
        cls.tf_listener = tf2_ros.TransformListener(cls.tf)
        assert cls.gz.wait_names(lambda names: all(r in names for r in ROBOTS), WAIT)

    def setUp(self):
        for r in ROBOTS:   # each test starts with the three at their launch poses, at rest
            self.place(r, *SPAWN[r])
        for r in ROBOTS:   # ... and their odometry (and TF) says so
            x, y, _ = SPAWN[r]
            self.assertTrue(wait_for(lambda: self._odom_near(r, x, y), WAIT))

    def _odom_near(self, robot, x, y):
        odom = self.odom[robot].latest(1.0)
        return odom is not None and math.dist(
            (odom.pose.pose.position.x, odom.pose.pose.position.y), (x, y)) < 0.02

    def place(self, robot, x, y, yaw=0.0):
        resp = self.gz.set_model_state(ModelState(model_name=robot, pose=pose(x, y, yaw=yaw)))
        self.assertTrue(resp.success, resp.status_message)

    def position(self, robot):
        return self.gz.position(robot)[:2]

    def test_1_each_robot_has_its_topics_and_frames(self):
        """model_states lists tb3_0..2; each robot publishes odom, scan, imu and joint_states
        in its namespace with frames prefixed by it; odom starts at its spawn pose."""
        names = self.gz.names()
        self.assertTrue(set(ROBOTS) <= set(names), names)
        for r in ROBOTS:
            odom = self.odom[r].latest(WAIT)
            self.assertIsNotNone(odom, "no /%s/odom" % r)
            self.assertEqual((odom.header.frame_id, odom.child_frame_id),
                             ("%s/odom" % r, "%s/base_footprint" % r))
            x, y, yaw = SPAWN[r]
            self.assertAlmostEqual(odom.pose.pose.position.x, x, delta=0.05)
            self.assertAlmostEqual(odom.pose.pose.position.y, y, delta=0.05)
            self.assertAlmostEqual(yaw_of(odom.pose.pose.orientation), yaw, delta=0.05)
            scan = self.scan[r].latest(WAIT)
            self.assertEqual((scan.header.frame_id, len(scan.ranges)), ("%s/base_scan" % r, 360))
            self.assertEqual(self.imu[r].latest(WAIT).header.frame_id, "%s/imu_link" % r)
            joints = self.joints[r].latest(WAIT)
            self.assertEqual(list(joints.name), ["wheel_left_joint", "wheel_right_joint"])
            self.assertEqual(publishers("/%s/scan" % r), ["/gazebo"])
        self.assertEqual(publishers("/scan"), [])   # no robot in the root namespace

    def test_2_each_robot_drives_by_its_own_cmd_vel(self):
        """0.2 m/s on /tb3_1/cmd_vel moves tb3_1 along its heading (+y); the others stay."""
        start = {r: self.position(r) for r in ROBOTS}
        deadline = time.monotonic() + 4.0
        while time.monotonic() < deadline:
            self.cmd["tb3_1"].publish(Twist())
            self.cmd["tb3_1"].publish(Twist(linear=Vector3(0.2, 0.0, 0.0)))
            time.sleep(0.1)
        self.cmd["tb3_1"].publish(Twist())
        moved = {r: math.dist(start[r], self.position(r)) for r in ROBOTS}
        self.assertGreater(moved["tb3_1"], 0.3, moved)
        self.assertGreater(self.position("tb3_1")[1] - start["tb3_1"][1], 0.3)
        self.assertLess(moved["tb3_0"], 0.01, moved)
        self.assertLess(moved["tb3_2"], 0.01, moved)
        odom = self.odom["tb3_1"].latest(WAIT).pose.pose.position
        self.assertAlmostEqual(odom.y, self.position("tb3_1")[1], delta=0.05)

    def test_3_each_tf_tree_is_whole(self):
        """tf2 finds, for every robot, its laser, IMU and wheel in its own odom frame: the
        sim's tb3_i/odom -> tb3_i/base_footprint joined to robot_state_publisher's
        tb3_i/base_footprint -> ... (tf_prefix)."""
        for r in ROBOTS:
            for child in ("base_scan", "imu_link", "wheel_left_link", "base_link"):
                ok = wait_for(lambda: self.tf.can_transform(
                    "%s/odom" % r, "%s/%s" % (r, child), rospy.Time(0)), WAIT)
                self.assertTrue(ok, "no transform %s/odom -> %s/%s" % (r, r, child))
            stamp = self.odom[r].latest(WAIT).header.stamp   # a TF after the setUp's teleport
            self.assertTrue(wait_for(lambda: self.tf.can_transform(
                "%s/odom" % r, "%s/base_scan" % r, stamp), WAIT))
            t = self.tf.lookup_transform("%s/odom" % r, "%s/base_scan" % r, stamp)
            x, y, _ = SPAWN[r]
            self.assertAlmostEqual(t.transform.translation.x, x, delta=0.1)
            self.assertAlmostEqual(t.transform.translation.y, y, delta=0.1)
        self.assertFalse(self.tf.can_transform("odom", "tb3_0/base_footprint", rospy.Time(0)))

    def test_4_scans_see_the_other_robots(self):
        """Three robots 0.85-1.2 m apart in an open part of the house: in each one's scan the
        ray toward each other robot ends at that robot (its centre distance minus its
        radius), not at a wall beyond; the robot never sees itself."""
        for r in ROBOTS:
            self.place(r, *TRIANGLE[r])
        time.sleep(1.0)
        for r in ROBOTS:
            stamp = self.scan[r].latest(WAIT).header.stamp
            scan = self.scan[r].after(stamp, WAIT)
            self.assertIsNotNone(scan)
            x, y = self.position(r)
            for other in ROBOTS:
                if other == r:
                    continue
                ox, oy = self.position(other)
                bearing = math.atan2(oy - y, ox - x) % (2 * math.pi)   # yaw 0: scan frame = world
                index = round(bearing / scan.angle_increment) % len(scan.ranges)
                near = [scan.ranges[(index + k) % len(scan.ranges)] for k in (-1, 0, 1)]
                expected = math.dist((x, y), (ox, oy)) - BURGER_RADIUS
                self.assertLess(min(abs(v - expected) for v in near), 0.1,
                                "%s toward %s: %s, expected %.2f" % (r, other, near, expected))
            self.assertGreater(min(scan.ranges), 0.3)   # its own body is not in its scan

    def test_5_a_fourth_is_spawned_and_deleted(self):
        """spawn_model -urdf -file turtlebot3_burger.urdf -model tb3_3 -robot_namespace tb3_3:
        (after tb3_0 is there, -wait): exit 0, tb3_3 in model_states, /tb3_3/scan from /gazebo;
        delete_model: gone, and its
        topics with it."""
        spawn = NodeProcess("spawn_model", "-urdf", "-file", BURGER, "-model", "tb3_3",
                            "-robot_namespace", "tb3_3", "-x", "-3.5", "-y", "-3.0",
                            "-wait", "tb3_0")
        self.assertEqual(spawn.wait(WAIT), 0, spawn.stdout + spawn.stderr)
        self.assertIn("tb3_3", self.gz.names())
        scan = Recorder("/tb3_3/scan", LaserScan)
        msg = scan.latest(WAIT)
        self.assertIsNotNone(msg)
        self.assertEqual(msg.header.frame_id, "tb3_3/base_scan")
        self.assertEqual(publishers("/tb3_3/scan"), ["/gazebo"])
        resp = self.gz.delete_model(model_name="tb3_3")
        self.assertTrue(resp.success, resp.status_message)
        self.assertTrue(self.gz.wait_names(lambda names: "tb3_3" not in names, WAIT))
        self.assertTrue(wait_for(lambda: publishers("/tb3_3/scan") == [], WAIT))
        self.assertTrue(wait_for(lambda: publishers("/tb3_3/odom") == [], WAIT))
        scan.sub.unregister()

    def test_6_bad_spawns_are_refused_and_the_others_run_on(self):
        """An occupied namespace, an illegal one, and a URDF with a bad plugin block are each
        refused with exit 1 and one status line; the three robots still publish and drive."""
        with open(BURGER) as f:
            text = f.read()
        bad = text.replace("<samples>360</samples>", "<samples>-5</samples>")
        self.assertNotEqual(bad, text)
        bad_path = "/tmp/test_multi_bad_burger_%d.urdf" % os.getpid()
        with open(bad_path, "w") as f:
            f.write(bad)
        cases = [(["-model", "tb3_x", "-robot_namespace", "tb3_0"], "already uses namespace"),
                 (["-model", "tb3_y", "-robot_namespace", "tb 3"], "not a legal ROS namespace"),
                 (["-model", "tb3_z", "-robot_namespace", "tb3_9", "-file", bad_path],
                  "<samples>")]
        try:
            for args, words in cases:
                if "-file" not in args:
                    args = args + ["-file", BURGER]
                proc = NodeProcess("spawn_model", "-urdf", *args)
                self.assertEqual(proc.wait(WAIT), 1, proc.stdout + proc.stderr)
                self.assertIn(words, proc.stdout + proc.stderr)
        finally:
            os.unlink(bad_path)
        names = self.gz.names()
        self.assertFalse({"tb3_x", "tb3_y", "tb3_z"} & set(names), names)
        self.assertEqual(publishers("/tb3_9/scan"), [])
        for r in ROBOTS:
            stamp = self.odom[r].latest(WAIT).header.stamp
            self.assertIsNotNone(self.odom[r].after(stamp, 5.0), "%s stopped" % r)


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "multi_turtlebot3", MultiTurtleBot3)
