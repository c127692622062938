"""image_view's ROS-free helpers: sensor_msgs/Image fields to RGB, compressed images, the fit
to the screen, the frame rate, the window title."""
import io
import math

import numpy as np
import pytest

from tutorial_turtlebot.lab.image_decoding import (
    ENCODINGS, FrameRate, ImageDecodeError, UnsupportedEncoding, decode_compressed,
    decode_image, fit_scale, scale_to_bytes, scaled_size)

# A 2x3 (height x width) test picture: distinct colours in every pixel.
RGB = np.array([[[255, 0, 0], [0, 255, 0], [0, 0, 255]],
                [[10, 20, 30], [200, 100, 50], [1, 2, 3]]], dtype=np.uint8)
H, W = RGB.shape[:2]


def padded(rows: np.ndarray, padding: int) -> bytes:
    """``rows`` (height, row bytes) as message data with ``padding`` junk bytes after each row."""
    rows = rows.reshape(rows.shape[0], -1).view(np.uint8)
    junk = np.full((rows.shape[0], padding), 0xAB, dtype=np.uint8)
    return np.hstack([rows, junk]).tobytes()


def decode(encoding, pixels, padding=0, **kwargs):
    data = padded(np.ascontiguousarray(pixels).reshape(pixels.shape[0], -1).view(np.uint8),
                  padding)
    step = len(data) // pixels.shape[0]
    return decode_image(encoding, pixels.shape[1], pixels.shape[0], step, data, **kwargs)


@pytest.mark.parametrize("padding", [0, 3])
def test_colour_encodings_give_the_same_rgb(padding):
    alpha = np.full((H, W, 1), 7, dtype=np.uint8)
    cases = {
        "rgb8": RGB, "bgr8": RGB[..., ::-1], "8UC3": RGB[..., ::-1],
        "rgba8": np.concatenate([RGB, alpha], axis=2),
        "bgra8": np.concatenate([RGB[..., ::-1], alpha], axis=2),
        "8UC4": np.concatenate([RGB[..., ::-1], alpha], axis=2),
    }
    for encoding, pixels in cases.items():
        out = decode(encoding, pixels, padding)
        assert out.dtype == np.uint8 and out.shape == (H, W, 3), encoding
        assert out.flags["C_CONTIGUOUS"], encoding
        np.testing.assert_array_equal(out, RGB, err_msg=encoding)


@pytest.mark.parametrize("encoding", ["mono8", "8UC1"])
def test_mono8_is_grey(encoding):
    grey = np.array([[0, 128, 255], [1, 2, 3]], dtype=np.uint8)
    out = decode(encoding, grey[..., np.newaxis], padding=1)
    assert out.shape == (H, W, 3)
    for channel in range(3):
        np.testing.assert_array_equal(out[..., channel], grey)


def test_mono16_uses_the_whole_range_and_both_byte_orders():
    values = np.array([[0, 65535, 32768], [257, 0, 65535]], dtype="<u2")
    expected = np.rint(values / 257.0).astype(np.uint8)
    out = decode("mono16", values[..., np.newaxis])
    np.testing.assert_array_equal(out[..., 0], expected)
    big = decode("mono16", values.astype(">u2")[..., np.newaxis], is_bigendian=True)
    np.testing.assert_array_equal(big, out)


def test_16uc1_depth_in_mm_over_ten_metres_by_default():
    mm = np.array([[0, 5000, 10000], [20000, 2500, 1]], dtype="<u2")
    out = decode("16UC1", mm[..., np.newaxis], padding=2)
    np.testing.assert_allclose(out[..., 0], [[0, 127.5, 255], [255, 63.75, 0]], atol=0.5)


def test_32fc1_depth_in_m_scaled_for_display():
    metres = np.array([[0.0, 5.0, 10.0], [np.nan, np.inf, 2.5]], dtype="<f4")
    out = decode("32FC1", metres[..., np.newaxis], padding=4)
    np.testing.assert_array_equal(out[..., 0], [[0, 128, 255], [0, 255, 64]])
    np.testing.assert_array_equal(out[..., 0], out[..., 2])
    # a range of its own, and big-endian floats
    ranged = decode("32FC1", metres.astype(">f4")[..., np.newaxis], is_bigendian=True,
                    value_range=(0.0, 5.0))
    np.testing.assert_array_equal(ranged[..., 0], [[0, 255, 255], [0, 255, 128]])


def test_32fc1_dynamic_scaling_uses_the_frame_own_range():
    metres = np.array([[0.5, 1.0, 1.5], [np.nan, 0.5, 1.5]], dtype="<f4")
    out = decode("32FC1", metres[..., np.newaxis], dynamic=True)
    np.testing.assert_array_equal(out[..., 0], [[0, 128, 255], [0, 0, 255]])
    # all NaN (nothing in range): black, no warning or error
    empty = decode("32FC1", np.full((H, W, 1), np.nan, dtype="<f4"), dynamic=True)
    assert not empty.any()


def test_scale_to_bytes_degenerate_range():
    values = np.array([1.0, np.inf, -np.inf, np.nan])
    np.testing.assert_array_equal(scale_to_bytes(values, 2.0, 2.0), [0, 255, 0, 0])


def test_trailing_bytes_after_the_last_row_are_ignored():
    data = RGB.tobytes() + b"\x00" * 5
    np.testing.assert_array_equal(decode_image("rgb8", W, H, 3 * W, data), RGB)


def test_a_camera_sized_frame():
    """A 640x480 rgb8 frame as the Waffle Pi publishes it, with bytes data as rospy gives."""
    frame = np.random.default_rng(1).integers(0, 256, (480, 640, 3), dtype=np.uint8)
    out = decode_image("rgb8", 640, 480, 1920, frame.tobytes())
    np.testing.assert_array_equal(out, frame)


def test_unknown_encoding_names_the_supported_ones():
    with pytest.raises(UnsupportedEncoding) as err:
        decode_image("yuv422", W, H, 2 * W, bytes(2 * W * H))
    message = str(err.value)
    assert "'yuv422'" in message and "rgb8" in message and "32FC1" in message
    assert "\n" not in message
    assert isinstance(err.value, ImageDecodeError)
    assert set(ENCODINGS) >= {"rgb8", "bgr8", "rgba8", "bgra8", "mono8", "16UC1", "32FC1"}


@pytest.mark.parametrize("args, words", [
    (("rgb8", W, H, 3 * W, bytes(3 * W * H - 1)), ["17 bytes", "18 expected"]),
    (("rgb8", W, H, 3 * W - 1, bytes(3 * W * H)), ["step 8", "9"]),
    (("32FC1", W, H, 4 * W + 2, bytes((4 * W + 2) * H)), ["step 14", "4-byte"]),
    (("rgb8", 0, H, 3 * W, bytes(18)), ["width 0"]),
    (("rgb8", W, -1, 3 * W, bytes(18)), ["height -1"]),
    (("mono8", W, H, 0, b""), ["step 0"]),
    (("mono8", 2.5, H, 3, bytes(6)), ["width 2.5"]),
])
def test_sizes_that_do_not_add_up_are_one_clear_line(args, words):
    with pytest.raises(ImageDecodeError) as err:
        decode_image(*args)
    message = str(err.value)
    assert "\n" not in message
    assert not isinstance(err.value, UnsupportedEncoding)
    for word in words:
        assert word in message, message


def test_compressed_jpeg_and_png():
    from PIL import Image
    picture = np.zeros((48, 64, 3), dtype=np.uint8)
    picture[:, :32] = (0, 200, 0)
    picture[:, 32:] = (200, 200, 200)
    for fmt in ("JPEG", "PNG"):
        buffer = io.BytesIO()
        Image.fromarray(picture).save(buffer, format=fmt)
        out = decode_compressed(buffer.getvalue())
        assert out.shape == (48, 64, 3) and out.dtype == np.uint8
        assert np.abs(out.astype(int) - picture).mean() < 3, fmt
    with pytest.raises(ImageDecodeError) as err:
        decode_compressed(b"not an image")
    assert "12 bytes" in str(err.value)


def test_fit_scale_shrinks_the_waffle_image_to_the_screen_only():
    scale = fit_scale(1920, 1080, 1240, 944)
    assert scale == pytest.approx(1240 / 1920)
    width, height = scaled_size(1920, 1080, scale)
    assert (width, height) == (1240, 698)
    assert fit_scale(640, 480, 1240, 944) == 1.0          # small images stay as they are
    assert fit_scale(640, 480, 1280, 960, upscale=True) == 2.0
    assert fit_scale(640, 480, 320, 100) == pytest.approx(100 / 480)  # height limits
    assert scaled_size(1000, 10, 0.01) == (10, 1)


def test_frame_rate_of_a_steady_stream_and_after_it_stops():
    meter = FrameRate(window=2.0)
    assert meter.rate(0.0) == 0.0
    t = 0.0
    for _ in range(150):           # 30 fps for 5 s
        t += 1 / 30.0
        meter.tick(t)
    assert meter.rate(t) == pytest.approx(30.0, rel=1e-6)
    assert meter.rate(t + 0.02) == pytest.approx(30.0, rel=1e-6)   # within one interval
    assert meter.rate(t + 1.0) < 20.0                              # stopped: falls
    assert meter.rate(t + 2.5) == 0.0                              # window empty
    meter.tick(10.0)
    assert meter.rate(10.0) == 0.0                                 # one frame is no rate
    meter.tick(10.1)
    assert meter.rate(10.1) == pytest.approx(10.0)
    assert math.isfinite(meter.rate(10.1))


def test_window_title():
    pytest.importorskip("rospy")  # the node module imports it
    from tutorial_turtlebot.lab.image_view_node import image_topic, window_title
    assert window_title("/camera/rgb/image_raw", (640, 480, "rgb8"), 29.96) == \
        "/camera/rgb/image_raw  640x480 rgb8  30.0 fps"
    assert window_title("/c", (1920, 1080, "rgb8"), 9.0, scale=0.6458) == \
        "/c  1920x1080 rgb8  9.0 fps  shown at 65%"
    assert window_title("/c", None, 0.0) == "/c  waiting for images"
    assert window_title("/c", None, 3.0, error="unsupported encoding 'yuv422'") == \
        "/c  waiting for images  3.0 fps  unsupported encoding 'yuv422'"
    assert image_topic("/camera/rgb/image_raw", "raw") == ("/camera/rgb/image_raw", False)
    assert image_topic("/camera/rgb/image_raw", "compressed") == \
        ("/camera/rgb/image_raw/compressed", True)
    assert image_topic("/camera/image/compressed", "raw") == ("/camera/image/compressed", True)
    assert image_topic("/camera/image/compressed", "compressed") == \
        ("/camera/image/compressed", True)
