#!/usr/bin/env python3
"""rostest node: the sim's ROS graph in turtlebot3_world with a Burger at the spawn pose.

Topics, types and publisher, message fields and frames, /clock, the spawn pose in /odom, the
scan against the arena's geometry (doc/turtlebot3.md 4.2), the IMU at rest and the whole TF tree.
"""
import math
import time
import unittest

import numpy as np
import rosgraph
import rospy
import rostest
import tf2_ros
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import Imu, JointState, LaserScan

from sim_test_support import Recorder, arena_wall_distance, wait_for, yaw_of

EXPECTED_TOPICS = {
    "/clock": "rosgraph_msgs/Clock",
    "/odom": "nav_msgs/Odometry",
    "/tf": "tf2_msgs/TFMessage",
    "/joint_states": "sensor_msgs/JointState",
    "/scan": "sensor_msgs/LaserScan",
    "/imu": "sensor_msgs/Imu",
}
SPAWN = (-2.0, -0.5)
SCAN_ORIGIN_X = SPAWN[0] - 0.032  # burger base_scan is 0.032 m behind base_footprint


def wall_distance(bearing_deg: float) -> float:
    """Distance from the scan origin at the spawn to the arena's wall along a bearing."""
    return arena_wall_distance((SCAN_ORIGIN_X, SPAWN[1]), bearing_deg)


class SimGraphTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_sim_graph")
        cls.scan = Recorder("scan", LaserScan)
        cls.odom = Recorder("odom", Odometry)
        cls.imu = Recorder("imu", Imu)
        cls.joints = Recorder("joint_states", JointState)
        cls.clock = Recorder("/clock", Clock)
        cls.tf_buffer = tf2_ros.Buffer()
        cls.tf_listener = tf2_ros.TransformListener(cls.tf_buffer)
        for rec in (cls.scan, cls.odom, cls.imu, cls.joints, cls.clock):
            assert rec.latest(30.0) is not None, "no message on %s" % rec.sub.name

    def test_topics_types_and_publisher(self):
        master = rosgraph.Master("/test_sim_graph")
        types = dict(master.getTopicTypes())
        publishers = {topic: nodes for topic, nodes in master.getSystemState()[0]}
        subscribers = {topic: nodes for topic, nodes in master.getSystemState()[1]}
        for topic, msg_type in EXPECTED_TOPICS.items():
            self.assertEqual(types.get(topic), msg_type, topic)
            self.assertIn("/gazebo", publishers.get(topic, []), topic)
        self.assertIn("/gazebo", subscribers.get("/cmd_vel", []))
        self.assertIn("/robot_state_publisher", publishers.get("/tf_static", []))

    def test_odom_fields_and_spawn_pose(self):
        msg = self.odom.latest()
        self.assertEqual(msg.header.frame_id, "odom")
        self.assertEqual(msg.child_frame_id, "base_footprint")
        p = msg.pose.pose.position
        self.assertAlmostEqual(p.x, SPAWN[0], delta=0.02)
        self.assertAlmostEqual(p.y, SPAWN[1], delta=0.02)
        self.assertAlmostEqual(yaw_of(msg.pose.pose.orientation), 0.0, delta=0.02)
        cov = msg.pose.covariance
        self.assertEqual([cov[i * 7] for i in range(6)], [1e-5, 1e-5, 1e12, 1e12, 1e12, 1e-3])
        self.assertGreater(msg.header.stamp.to_sec(), 0.0)

    def test_clock_advances(self):
        first = self.clock.latest().clock
        self.assertTrue(wait_for(lambda: self.clock.latest().clock.to_sec()
                                 > first.to_sec() + 0.5, 10.0), "/clock does not advance")

    def test_odom_arrives_when_due_not_in_bursts(self):
        """At real time each /odom leaves when its stamp is due on the wall clock: the gap
        between two arrivals matches the gap between their stamps (median within 4 ms). Sent
        in 20 ms bursts they would be off by 7 to 13 ms."""
        arrivals = []
        sub = rospy.Subscriber("odom", Odometry, lambda m: arrivals.append(
            (time.monotonic(), m.header.stamp.to_sec())), queue_size=100)
        try:
            self.assertTrue(wait_for(lambda: len(arrivals) > 90, 30.0), "too few /odom")
        finally:
            sub.unregister()
        errors = sorted(abs((a1 - a0) - (s1 - s0)) for (a0, s0), (a1, s1)
                        in zip(arrivals[1:], arrivals[2:]))  # the first may have queued
        median = errors[len(errors) // 2]
        rospy.loginfo("/odom arrival-interval error: median %.1f ms, max %.1f ms",
                      1000 * median, 1000 * errors[-1])
        self.assertLess(median, 0.004)

    def test_scan_fields(self):
        msg = self.scan.latest()
        self.assertEqual(msg.header.frame_id, "base_scan")
        self.assertEqual(len(msg.ranges), 360)
        self.assertEqual(list(msg.intensities), [0.0] * 360)
        self.assertAlmostEqual(msg.angle_min, 0.0)
        self.assertAlmostEqual(msg.angle_max, 6.28319, places=5)
        self.assertAlmostEqual(msg.angle_increment, 6.28319 / 359, places=6)
        self.assertAlmostEqual(msg.range_min, 0.12, places=5)
        self.assertAlmostEqual(msg.range_max, 3.5, places=5)
        for r in msg.ranges:  # Gazebo's convention: +-inf outside the range, else inside it
            self.assertTrue(math.isinf(r) or 0.12 <= r <= 3.5, r)

    def test_scan_matches_the_arena(self):
        ranges = np.array(self.scan.latest().ranges)
        increment = math.degrees(6.28319 / 359)
        # Straight ahead along y = -0.5 nothing stands within 3.5 m.
        self.assertTrue(np.isposinf(ranges[0]), ranges[0])
        for index in (180, 270, 135, 225):  # behind, right, back-left, back-right: the wall
            expected = wall_distance(index * increment)
            self.assertAlmostEqual(ranges[index], expected, delta=0.06, msg="ray %d" % index)
        # The pillar at (-1.1, 0), r 0.15: its nearest face, seen at about 28 degrees.
        dx, dy = -1.1 - SCAN_ORIGIN_X, 0.0 - SPAWN[1]
        bearing = math.degrees(math.atan2(dy, dx))
        index = int(round(bearing / increment))
        self.assertAlmostEqual(ranges[index], math.hypot(dx, dy) - 0.15, delta=0.06)

    def test_imu_at_rest(self):
        msg = self.imu.latest()
        self.assertEqual(msg.header.frame_id, "imu_link")
        # gravity, as the real IMU
        self.assertAlmostEqual(msg.linear_acceleration.z, 9.8, delta=0.3)
        self.assertAlmostEqual(yaw_of(msg.orientation), 0.0, delta=0.02)
        self.assertAlmostEqual(msg.angular_velocity.z, 0.0, delta=0.05)

    def test_joint_states(self):
        msg = self.joints.latest()
        self.assertEqual(list(msg.name), ["wheel_left_joint", "wheel_right_joint"])
        self.assertEqual(len(msg.position), 2)
        self.assertEqual(len(msg.velocity), 2)

    def test_tf_tree(self):
        for child in ("base_link", "base_scan", "imu_link", "wheel_left_link", "caster_back_link"):
            self.assertTrue(self.tf_buffer.can_transform("odom", child, rospy.Time(0),
                                                         rospy.Duration(10.0)), child)
        t = self.tf_buffer.lookup_transform("base_footprint", "base_scan", rospy.Time(0))
        self.assertAlmostEqual(t.transform.translation.z, 0.182, delta=1e-3)
        self.assertAlmostEqual(t.transform.translation.x, -0.032, delta=1e-3)


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "sim_graph", SimGraphTest)
