"""A camera's <format> as gazebo_ros_camera_utils publishes it (devices/image_formats): the
encoding and bytes a pixel of each format, 16-bit values (8-bit times 257, little-endian),
grey, bgr and Bayer pixels, and an unknown format labelled bgr8 with R8G8B8 bytes."""
import numpy as np
import pytest

from tutorial_turtlebot.sim.devices.image_formats import converted, encoding

RGB = np.array([[[255, 0, 0], [0, 255, 0]], [[0, 0, 255], [10, 20, 30]]], dtype=np.uint8)


@pytest.mark.parametrize("image_format, expected", [
    ("L8", ("mono8", 1)), ("L_INT8", ("mono8", 1)), ("L16", ("mono16", 2)),
    ("R8G8B8", ("rgb8", 3)), ("RGB_INT8", ("rgb8", 3)), ("B8G8R8", ("bgr8", 3)),
    ("R16G16B16", ("rgb16", 6)), ("RGB_INT16", ("rgb16", 6)),
    ("BAYER_RGGB8", ("bayer_rggb8", 1)), ("BAYER_GRBG8", ("bayer_grbg8", 1)),
    ("FLOAT32", ("bgr8", 3))])
def test_each_format_has_camera_utils_encoding_and_pixel_size(image_format, expected):
    assert encoding(image_format) == expected


def test_sixteen_bit_colour_is_each_channel_times_257_little_endian():
    out = converted(RGB, "R16G16B16")
    assert out.dtype == np.dtype("<u2") and out.shape == (2, 2, 3)
    assert out[0, 0].tolist() == [65535, 0, 0]
    assert out[1, 1].tolist() == [2570, 5140, 7710]
    assert out.tobytes()[:2] == b"\xff\xff" and out[1, 1].tobytes()[:2] == bytes([10, 10])
    assert len(out.tobytes()) == 2 * 2 * 6


def test_grey_is_the_luma_and_sixteen_bit_grey_its_257_multiple():
    grey = converted(RGB, "L8")
    assert grey.dtype == np.uint8 and grey.shape == (2, 2)
    assert grey.tolist() == [[76, 150], [29, 18]]
    assert (converted(RGB, "L16") == grey.astype(np.uint16) * 257).all()


def test_bgr_swaps_the_channels_and_rgb_is_left_as_drawn():
    assert converted(RGB, "B8G8R8")[0, 0].tolist() == [0, 0, 255]
    assert converted(RGB, "R8G8B8") is RGB
    assert converted(RGB, "FLOAT32") is RGB      # labelled bgr8, bytes as drawn


def test_bayer_keeps_the_channel_of_each_pixels_place_in_the_pattern():
    assert converted(RGB, "BAYER_RGGB8").tolist() == [[255, 255], [0, 30]]
    assert converted(RGB, "BAYER_BGGR8").tolist() == [[0, 255], [0, 10]]
    assert converted(RGB, "BAYER_GBRG8").tolist() == [[0, 0], [0, 20]]
