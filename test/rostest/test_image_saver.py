#!/usr/bin/env python3
"""rostest node: a real ROS consumer of the camera, image_view's image_saver (started by the
.test on /camera/rgb/image_raw), writes frames to PNG files; the test opens one and checks its
size and that it shows the arena's green head hexagon (upper left of the Waffle Pi's view)."""
import glob
import os
import unittest

import numpy as np
import rospy
import rostest
from PIL import Image as PilImage

from sim_test_support import wait_for


class ImageSaverTest(unittest.TestCase):
    def test_image_saver_writes_the_view(self):
        rospy.init_node("test_image_saver")
        pattern = rospy.get_param("~glob")
        self.assertTrue(wait_for(lambda: len(glob.glob(pattern)) >= 2, 60.0),
                        "image_saver wrote no file matching %s" % pattern)
        first = sorted(glob.glob(pattern))[0]
        with PilImage.open(first) as png:
            self.assertEqual(png.size, (640, 480))
            rgb = np.asarray(png.convert("RGB")).astype(int)
        green = (rgb[..., 1] > 120) & (rgb[..., 0] < 80) & (rgb[..., 2] < 80)
        self.assertGreater(green[:240, :320].mean(), 0.02, "no green head in %s" % first)
        for path in glob.glob(pattern):
            os.remove(path)


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "image_saver", ImageSaverTest)
