#!/usr/bin/env python3
"""rostest node: a robot with two lasers and two cameras through the real /gazebo
(two_lasers.test). The URDF test/fixtures/two_lasers/two_lasers.urdf is spawned with the real
command line (``rosrun tutorial_turtlebot spawn_model -urdf -file ... -model twin
-robot_namespace twin``) at the origin of test/fixtures/two_lasers/two_lasers.world: its front
laser reads the red box 1 m ahead on /twin/front/scan in frame twin/front_laser_link, its rear
laser the blue box 2 m behind on /twin/rear/scan in twin/rear_laser_link; the front camera's
image (red in the middle) and the rear depth camera's (blue, its depth image) arrive.

Every wait is on wall time with a limit."""
import os
import struct

import rostest
from sensor_msgs.msg import Image, LaserScan

from sim_test_support import SimTestCase, one_message, spawn_model

URDF = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "fixtures",
                    "two_lasers", "two_lasers.urdf")
AHEAD = 90          # the middle of each laser's 181 rays over -90..90 degrees: straight out


def middle_pixel(image: Image):
    """(r, g, b) of the middle pixel of an rgb8 image."""
    at = (image.height // 2) * image.step + (image.width // 2) * 3
    return tuple(bytearray(image.data[at:at + 3]))


class TwoLasersTest(SimTestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.spawned = spawn_model("-urdf", "-file", URDF, "-model", "twin",
                                  "-robot_namespace", "twin")

    def test_1_spawned_by_the_command_line(self):
        status, out = self.spawned
        self.assertEqual(status, 0, out)
        self.assertIn("Successfully spawned entity", out)
        self.assertTrue(self.gz.wait_names(lambda n: "twin" in n), self.gz.names())

    def test_2_each_laser_on_its_topic_in_its_frame_at_its_distance(self):
        for topic, frame, distance in (("/twin/front/scan", "twin/front_laser_link", 1.0),
                                       ("/twin/rear/scan", "twin/rear_laser_link", 2.0)):
            scan = one_message(topic, LaserScan)
            self.assertIsNotNone(scan, "no %s" % topic)
            self.assertEqual(scan.header.frame_id, frame)
            self.assertEqual(len(scan.ranges), 181)
            self.assertAlmostEqual(scan.ranges[AHEAD], distance, delta=0.03, msg=topic)

    def test_3_both_cameras_images_arrive(self):
        front = one_message("/twin/front_camera/image_raw", Image)
        self.assertIsNotNone(front, "no front camera image")
        self.assertEqual(front.header.frame_id, "twin/front_camera_link")
        r, g, b = middle_pixel(front)
        self.assertGreater(r, 2 * max(g, b), "the front camera does not see the red box")
        rear = one_message("/twin/rear_camera/rgb/image_raw", Image)
        self.assertIsNotNone(rear, "no rear camera image")
        self.assertEqual(rear.header.frame_id, "twin/rear_camera_link")
        r, g, b = middle_pixel(rear)
        self.assertGreater(b, 2 * max(r, g), "the rear camera does not see the blue box")
        depth = one_message("/twin/rear_camera/depth/image_raw", Image)
        self.assertIsNotNone(depth, "no rear depth image")
        at = (depth.height // 2) * depth.step + (depth.width // 2) * 4
        self.assertAlmostEqual(struct.unpack_from("<f", bytes(depth.data), at)[0], 2.03,
                               delta=0.03)


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "two_lasers", TwoLasersTest)
