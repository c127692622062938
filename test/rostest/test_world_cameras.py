#!/usr/bin/env python3
"""rostest node: the cameras of a world file's model through the real /gazebo
(world_cameras.test; the world is test/fixtures/world_cameras/world_cameras.world, no robot),
as gazebo_ros_pkgs' camera tests check theirs: a depth camera's image, depth image and point
cloud arrive with one stamp, not older than a second of sim time; a multicamera's left and right
images carry one stamp; a triggered camera publishes nothing until a std_msgs/Empty on its
trigger topic, then one image for each trigger; a 16-bit camera's encoding is mono16; a barrel
camera's camera_info carries D = (k1, k2, p1, p2, k3). Nothing but the triggered camera
subscribes to an image_trigger topic.

Every wait is on wall time with a limit."""
import time

import numpy as np
import rosgraph
import rospy
import rostest
from sensor_msgs.msg import CameraInfo, Image, PointCloud2
from std_msgs.msg import Empty

from sim_test_support import WAIT, Recorder, SimTestCase, wait_for


def stamps(recorder):
    return [m.header.stamp for m in recorder.snapshot()[0]]


class WorldCamerasTest(SimTestCase):
    def test_1_a_depth_cameras_image_depth_and_points_share_one_stamp(self):
        recorders = [Recorder("/depth_cam/ir/image_raw", Image),
                     Recorder("/depth_cam/depth/image_raw", Image),
                     Recorder("/depth_cam/points", PointCloud2)]
        try:
            self.assertTrue(wait_for(lambda: all(len(r.msgs) >= 3 for r in recorders), WAIT))
            common = set(stamps(recorders[0])) & set(stamps(recorders[1])) & set(
                stamps(recorders[2]))
            self.assertTrue(common, "one tick's three messages carry one stamp")
            image, depth, points = (r.latest() for r in recorders)
            self.assertLess((rospy.Time.now() - image.header.stamp).to_sec(), 1.0)
            self.assertEqual((image.encoding, depth.encoding), ("rgb8", "32FC1"))
            self.assertEqual((points.width, points.height), (64, 48))
            metres = np.frombuffer(depth.data, dtype="<f4").reshape(48, 64)
            self.assertAlmostEqual(float(metres[24, 32]), 2.0, delta=0.02)
            pixels = np.frombuffer(image.data, np.uint8).reshape(48, 64, 3)
            self.assertGreater(int(pixels[24, 32, 0]), 150)      # the red box in the middle
        finally:
            for recorder in recorders:
                recorder.sub.unregister()

    def test_2_a_multicameras_left_and_right_images_share_one_stamp(self):
        left = Recorder("/stereo/left/image_raw", Image)
        right = Recorder("/stereo/right/image_raw", Image)
        info = Recorder("/stereo/right/camera_info", CameraInfo)
        try:
            self.assertTrue(wait_for(lambda: set(stamps(left)) & set(stamps(right)), WAIT))
            self.assertLess((rospy.Time.now() - left.latest().header.stamp).to_sec(), 1.0)
            right_info = info.latest()
            self.assertIsNotNone(right_info)
            self.assertAlmostEqual(right_info.P[3], -right_info.P[0] * 0.07, places=6)
            self.assertEqual(left.latest().header.frame_id, "stereo_optical_frame")
        finally:
            for recorder in (left, right, info):
                recorder.sub.unregister()

    def test_3_a_triggered_camera_gives_one_image_per_trigger(self):
        images = Recorder("/triggered/image_raw", Image)
        trigger = rospy.Publisher("/triggered/image_trigger", Empty, queue_size=1, latch=True)
        try:
            self.assertTrue(wait_for(lambda: images.sub.get_num_connections() > 0, WAIT))
            time.sleep(2.0)
            self.assertEqual(len(images.msgs), 0, "no image before a trigger")
            self.assertEqual(self.trigger_topics(), ["/triggered/image_trigger"])
            self.assertTrue(wait_for(lambda: trigger.get_num_connections() > 0, WAIT))
            trigger.publish(Empty())
            self.assertTrue(wait_for(lambda: len(images.msgs) >= 1, WAIT))
            time.sleep(2.0)
            self.assertEqual(len(images.msgs), 1, "exactly one image for one trigger")
            self.assertEqual(images.latest().encoding, "bgr8")
            trigger.publish(Empty())
            time.sleep(0.05)
            trigger.publish(Empty())
            self.assertTrue(wait_for(lambda: len(images.msgs) >= 3, WAIT))
            time.sleep(2.0)
            self.assertEqual(len(images.msgs), 3)
        finally:
            images.sub.unregister()
            trigger.unregister()

    def test_4_formats_and_distortion(self):
        grey = Recorder("/grey/image_raw", Image)
        barrel = Recorder("/barrel/camera_info", CameraInfo)
        try:
            image, info = grey.latest(WAIT), barrel.latest(WAIT)
            self.assertIsNotNone(image)
            self.assertEqual((image.encoding, image.step, len(image.data)),
                             ("mono16", 128, 128 * 48))
            self.assertIsNotNone(info)
            self.assertEqual(info.distortion_model, "plumb_bob")
            self.assertEqual(list(info.D), [-0.2, 0.05, 0.002, -0.001, 0.01])
        finally:
            grey.sub.unregister()
            barrel.sub.unregister()

    @staticmethod
    def trigger_topics():
        state = rosgraph.Master("/test").getSystemState()
        return sorted(name for name, _ in state[1] if "image_trigger" in name)


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "test_world_cameras", WorldCamerasTest)
