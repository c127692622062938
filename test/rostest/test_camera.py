#!/usr/bin/env python3
"""rostest node: the simulated camera of the model under test (param ~model) at the
turtlebot3_world spawn: message fields, CameraInfo, what the image shows, depth; and that the
burger has no camera unless asked (param ~expect_camera false)."""
import io
import math
import unittest

import numpy as np
import rosgraph
import rospy
import rostest
from sensor_msgs.msg import CameraInfo, CompressedImage, Image, PointCloud2

from sim_test_support import WAIT, wait_for
from sim_test_support import one_message as wait_message

# (width, height, hfov) per model, doc/turtlebot3.md 2.4 and 4.5.
CAMERAS = {"waffle_pi": (640, 480, 1.085595), "waffle": (1920, 1080, 1.3439),
           "burger": (320, 240, 1.085595)}


def as_rgb(msg):
    return np.frombuffer(msg.data, dtype=np.uint8).reshape(msg.height, msg.width, 3)


class CameraTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_camera")
        cls.model = rospy.get_param("~model")
        cls.expect_camera = rospy.get_param("~expect_camera", True)

    def test_camera_topics_exist_only_with_a_camera(self):
        master = rosgraph.Master("/test_camera")
        # The sim advertises its world API's topics after every sensor's (gazebo/sim_node.py).
        last = "/gazebo/model_states"
        self.assertTrue(wait_for(lambda: last in dict(master.getTopicTypes()), WAIT))
        types = dict(master.getTopicTypes())
        for topic in ("/camera/rgb/image_raw", "/camera/image", "/camera/rgb/camera_info",
                      "/camera/camera_info", "/camera/rgb/image_raw/compressed"):
            self.assertEqual(topic in types, self.expect_camera, topic)
        self.assertEqual("/camera/depth/image_raw" in types,
                         self.expect_camera and self.model == "waffle")

    def test_image_fields_and_camera_info(self):
        if not self.expect_camera:
            self.skipTest("no camera on this robot (checked by the test above)")
        width, height, hfov = CAMERAS[self.model]
        for image_topic, info_topic in (("/camera/rgb/image_raw", "/camera/rgb/camera_info"),
                                        ("/camera/image", "/camera/camera_info")):
            img = wait_message(image_topic, Image)
            self.assertEqual((img.width, img.height, img.encoding, img.step),
                             (width, height, "rgb8", 3 * width))
            self.assertEqual(len(img.data), 3 * width * height)
            self.assertEqual(img.header.frame_id, "camera_rgb_optical_frame")
            self.assertGreater(img.header.stamp.to_sec(), 0.0)
            info = wait_message(info_topic, CameraInfo)
            f = width / (2.0 * math.tan(hfov / 2.0))
            self.assertEqual((info.width, info.height), (width, height))
            self.assertEqual(info.distortion_model, "plumb_bob")
            self.assertEqual(list(info.D), [0.0] * 5)
            np.testing.assert_allclose(info.K, [f, 0, (width + 1) / 2.0, 0, f,
                                                (height + 1) / 2.0, 0, 0, 1], rtol=1e-6)
            self.assertEqual(info.header.frame_id, "camera_rgb_optical_frame")

    def test_compressed_is_a_jpeg_of_the_image(self):
        if not self.expect_camera:
            self.skipTest("no camera on this robot")
        from PIL import Image as PilImage
        msg = wait_message("/camera/rgb/image_raw/compressed", CompressedImage)
        self.assertIn("jpeg", msg.format)
        decoded = PilImage.open(io.BytesIO(bytes(msg.data)))
        self.assertEqual(decoded.size, CAMERAS[self.model][:2])

    def test_sees_the_green_head_hexagon(self):
        """At the spawn (-2, -0.5) facing +x, the green head (x >= 2.33, |y| <= 1) is ahead
        and to the left: in the image's upper half, left of the centre, some pixels are
        green, and the bottom rows are the floor (not green, not black)."""
        if not self.expect_camera or self.model == "burger":
            self.skipTest("the head is seen by the waffles' level cameras")
        rgb = as_rgb(wait_message("/camera/rgb/image_raw", Image)).astype(int)
        h, w, _ = rgb.shape
        green = (rgb[..., 1] > 120) & (rgb[..., 0] < 80) & (rgb[..., 2] < 80)
        self.assertGreater(green[: h // 2, : w // 2].mean(), 0.02, "no green upper left")
        self.assertLess(green[-h // 8:].mean(), 0.01, "floor is green")
        bottom = rgb[-h // 8:].reshape(-1, 3)
        self.assertGreater(bottom.mean(), 60, "floor is black: image upside down?")

    def test_depth_reads_the_wall_distance(self):
        if not self.expect_camera or self.model != "waffle":
            self.skipTest("depth is the waffle's RealSense")
        depth = wait_message("/camera/depth/image_raw", Image)
        self.assertEqual((depth.encoding, depth.step), ("32FC1", 4 * depth.width))
        d = np.frombuffer(depth.data, dtype=np.float32).reshape(depth.height, depth.width)
        # The waffle's optical frame is 0.117 m above the floor (doc/turtlebot3.md 1.3): the pixel
        # row that looks down at atan(0.117 / 1.2) sees the floor 1.2 m ahead (within the
        # R200's 0.4..5 m; nearer than the first obstacle along that line of sight).
        f = depth.width / (2.0 * math.tan(1.3439 / 2.0))
        expected = 1.2
        row = int(round((depth.height + 1) / 2.0 - 0.5 + f * 0.117 / expected))
        self.assertAlmostEqual(float(d[row, depth.width // 2]), expected, delta=0.05)
        self.assertTrue(np.isnan(d[-1, depth.width // 2]), "under 0.4 m must be NaN")
        points = wait_message("/camera/depth/points", PointCloud2)
        self.assertEqual((points.width, points.height), (depth.width, depth.height))
        self.assertEqual(points.header.frame_id, "camera_rgb_optical_frame")


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "camera", CameraTest)
