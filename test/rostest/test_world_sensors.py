#!/usr/bin/env python3
"""rostest node: the sensors of a world file's models through the real /gazebo
(world_sensors.test; the world is test/fixtures/world_sensors/world_sensors.world, no robot).
An overhead camera 2 m above a red box sees red in the middle of its image; two range
sensors give gazebo_ros_range's fields (0.5 m before a box, max range facing nothing); a block
laser's points all lie within its min..max range; a spawned SDF model's range sensor publishes
on its topic until the model is deleted. Stamps are the sim time of the sensor's tick.

Every wait is on wall time with a limit."""
import math

import numpy as np
import rospy
import rostest
from sensor_msgs.msg import CameraInfo, Image, PointCloud, Range

from sim_test_support import WAIT, SimTestCase, pose, wait_for

NS_PER_S = 1_000_000_000
PROBE = '''<sdf version="1.6"><model name="probe"><static>true</static><link name="l">
  <sensor name="probe_sonar" type="ray"><update_rate>20</update_rate><ray><scan><horizontal>
  <samples>1</samples></horizontal></scan><range><min>0.05</min><max>3</max></range></ray>
  <plugin name="p" filename="libgazebo_ros_range.so"><topicName>probe_range</topicName>
  <frameName>probe_frame</frameName></plugin></sensor></link></model></sdf>'''


class WorldSensorsTest(SimTestCase):
    def latest(self, topic, msg_type):
        msg = rospy.wait_for_message(topic, msg_type, WAIT)
        self.assertIsNotNone(msg)
        return msg

    def assert_tick_stamp(self, stamp, rate):
        """A stamp of a tick at ``rate`` Hz of sim time: a multiple of the period (but the
        first, at the first step), not ahead of /clock by more than a clock period."""
        clock = self.gz.clock.latest(WAIT).clock
        self.assertLessEqual(stamp.to_sec(), clock.to_sec() + 0.011)
        period = round(NS_PER_S / rate)
        if stamp.to_nsec() > period:
            self.assertEqual(stamp.to_nsec() % period, 0, stamp.to_nsec())

    def test_1_the_overhead_camera_sees_the_red_box_in_the_middle(self):
        image = self.latest("/overhead/image_raw", Image)
        self.assertEqual((image.encoding, image.width, image.height, image.header.frame_id),
                         ("rgb8", 160, 120, "overhead_optical_frame"))
        pixels = np.frombuffer(image.data, np.uint8).reshape(120, 160, 3).astype(int)
        middle = pixels[55:65, 75:85]
        self.assertTrue(np.all((middle[:, :, 0] > 150) & (middle[:, :, 1] < 60)
                               & (middle[:, :, 2] < 60)), middle[0, 0])
        corner = pixels[3, 3]
        self.assertLess(abs(corner[0] - corner[1]), 20, "the ground around is grey, not red")
        self.assert_tick_stamp(image.header.stamp, 5.0)
        info = self.latest("/overhead/camera_info", CameraInfo)
        self.assertEqual((info.width, info.height, info.header.frame_id),
                         (160, 120, "overhead_optical_frame"))
        self.assertAlmostEqual(info.K[2], 80.5)

    def test_2_the_range_sensors_give_gazebo_ros_ranges_fields(self):
        sonar = self.latest("/sonar", Range)
        self.assertEqual((sonar.header.frame_id, sonar.radiation_type), ("sonar_link",
                                                                         Range.INFRARED))
        self.assertAlmostEqual(sonar.field_of_view, 0.2, places=6)
        self.assertAlmostEqual(sonar.min_range, 0.02, places=6)
        self.assertAlmostEqual(sonar.max_range, 2.0, places=6)
        self.assertLess(abs(sonar.range - 0.5), 0.02, sonar.range)
        self.assert_tick_stamp(sonar.header.stamp, 10.0)
        free = self.latest("/sonar_free", Range)
        self.assertEqual((free.header.frame_id, free.radiation_type, free.range),
                         ("world", Range.ULTRASOUND, free.max_range))
        self.assertAlmostEqual(free.field_of_view, 0.05, places=6)

    def test_3_the_block_lasers_points_are_within_its_range(self):
        cloud = self.latest("/profiler_cloud", PointCloud)
        self.assertEqual((cloud.header.frame_id, len(cloud.points)), ("profiler_frame", 200))
        norms = [math.sqrt(p.x ** 2 + p.y ** 2 + p.z ** 2) for p in cloud.points]
        self.assertGreater(min(norms), 0.4 - 1e-5)
        self.assertLess(max(norms), 1.0 + 1e-5)
        self.assertTrue(any(n < 0.8 for n in norms), "the step below is seen")
        self.assert_tick_stamp(cloud.header.stamp, 5.0)

    def test_4_a_spawned_models_sensor_publishes_until_it_is_deleted(self):
        resp = self.gz.spawn_sdf_model(model_name="probe", model_xml=PROBE,
                                       initial_pose=pose(3.6, -1.0, 0.25, math.pi / 2),
                                       reference_frame="world")
        self.assertTrue(resp.success, resp.status_message)
        msg = self.latest("/probe_range", Range)
        self.assertEqual(msg.header.frame_id, "probe_frame")
        self.assertAlmostEqual(msg.range, 0.5, places=4)   # the target box's side, no noise
        self.assertTrue(self.gz.delete_model(model_name="probe").success)
        self.assertTrue(wait_for(lambda: "/probe_range" not in dict(
            rospy.get_published_topics()), 20.0), "its topic is taken back")


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "test_world_sensors", WorldSensorsTest)
