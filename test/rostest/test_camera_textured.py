#!/usr/bin/env python3
"""rostest node: the Waffle Pi's camera sees the texture of a Collada mesh. The cube's face
towards the robot shows red top left, green top right, blue bottom left and yellow bottom right
(test/fixtures/make_texture_fixtures.py); the image must show each colour in its quadrant of
the face, and the face in those colours, not in a plain grey."""
import unittest

import numpy as np
import rospy
import rostest
from sensor_msgs.msg import Image

from sim_test_support import one_message

MIN_PIXELS = 2000   # of each colour: each quadrant is about 110 x 110 px at 1.4 m


def colour_masks(rgb):
    """{name: bool mask} of the pixels that show each of the texture's colours (lit)."""
    r, g, b = (rgb[..., i].astype(int) for i in range(3))
    strong, weak = 100, 60
    return {"red": (r > strong) & (g < weak) & (b < weak),
            "green": (g > strong) & (r < weak) & (b < weak),
            "blue": (b > strong) & (r < weak) & (g < weak),
            "yellow": (r > strong) & (g > strong) & (b < weak)}


class TexturedCameraTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_camera_textured")

    def test_the_texture_is_in_the_image(self):
        msg = one_message("/camera/rgb/image_raw", Image)
        self.assertIsNotNone(msg, "no image on /camera/rgb/image_raw")
        self.assertEqual(msg.encoding, "rgb8")
        rgb = np.frombuffer(msg.data, dtype=np.uint8).reshape(msg.height, msg.width, 3)
        masks = colour_masks(rgb)
        centres = {}
        for name, mask in masks.items():
            self.assertGreater(mask.sum(), MIN_PIXELS, "too little %s in the image" % name)
            rows, cols = np.nonzero(mask)
            centres[name] = (cols.mean(), rows.mean())
        # left and right, top and bottom, as the texture has them (image row 0 at the top)
        self.assertLess(centres["red"][0], centres["green"][0])
        self.assertLess(centres["blue"][0], centres["yellow"][0])
        self.assertLess(centres["red"][1], centres["blue"][1])
        self.assertLess(centres["green"][1], centres["yellow"][1])
        # the face (between the four colours' centres) is all texture: no grey in it
        left = int(min(centres["red"][0], centres["blue"][0]))
        right = int(max(centres["green"][0], centres["yellow"][0]))
        top = int(min(centres["red"][1], centres["green"][1]))
        bottom = int(max(centres["blue"][1], centres["yellow"][1]))
        inside = np.zeros(rgb.shape[:2], dtype=bool)
        for mask in masks.values():
            inside |= mask
        self.assertGreater(inside[top:bottom, left:right].mean(), 0.9,
                           "the textured face is not drawn in its texture's colours")


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "camera_textured", TexturedCameraTest)
