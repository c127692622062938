"""A camera's image in the <format> Gazebo renders it to, as gazebo_ros_camera_utils publishes
it (camera_types.IMAGE_FORMATS: L8 mono8, L16 mono16, R8G8B8 rgb8, B8G8R8 bgr8, R16G16B16
rgb16, BAYER_* the bayer encodings): the pixels of sensor_msgs/Image, from the rgb8 image the
renderer draws. No ROS.

16-bit channels are the 8-bit value times 257 (0 -> 0, 255 -> 65535), little-endian
(is_bigendian 0); grey (L8, L16) is the BT.601 luma of the colour; a Bayer image keeps, for each
pixel, the one channel its place in the 2 x 2 pattern names (the first letters: row 0).
A format Gazebo does not render for gazebo_ros is drawn R8G8B8 and labelled bgr8, as
camera_utils labels it. ``CameraOutput``: a camera's rendered image made its published pixels
(the lens' distortion, then the format), for world models' cameras and robots' alike.
"""
from typing import Optional, Tuple

import numpy as np

from ..files.plugins.camera_types import IMAGE_FORMATS, UNKNOWN_FORMAT, LensDistortion
from .lens_distortion import DistortionMap

LUMA = np.array([0.299, 0.587, 0.114])
CHANNEL = {"R": 0, "G": 1, "B": 2}


def encoding(image_format: str) -> Tuple[str, int]:
    """(sensor_msgs encoding, bytes a pixel) of Gazebo's ``image_format``."""
    return IMAGE_FORMATS.get(image_format, UNKNOWN_FORMAT)


def converted(rgb: np.ndarray, image_format: str) -> np.ndarray:
    """The pixels (height, width[, channels]) of ``rgb`` (uint8, height x width x 3) in
    ``image_format``: uint8, or little-endian uint16 for the 16-bit formats; C-contiguous, so
    ``tobytes()`` is the message's data (step = width x bytes a pixel)."""
    name = encoding(image_format)[0]
    if name in ("rgb8", "bgr8") and image_format in IMAGE_FORMATS:
        return rgb if name == "rgb8" else np.ascontiguousarray(rgb[:, :, ::-1])
    if name == "bgr8":
        return rgb                       # unknown: the rendered R8G8B8 bytes, as they are
    if name.startswith("mono"):
        grey = np.rint(rgb @ LUMA).astype(np.uint8)
        return grey if name == "mono8" else _sixteen(grey)
    if name == "rgb16":
        return _sixteen(rgb)
    return _bayer(rgb, name[len("bayer_"):-1].upper())     # "bayer_rggb8": RGGB


def _sixteen(values: np.ndarray) -> np.ndarray:
    return values.astype("<u2") * np.uint16(257)


def _bayer(rgb: np.ndarray, pattern: str) -> np.ndarray:
    """One channel a pixel: ``pattern`` (RGGB, BGGR, GBRG, GRBG) row by row from the top left."""
    out = np.empty(rgb.shape[:2], dtype=np.uint8)
    for index, letter in enumerate(pattern):
        row, col = divmod(index, 2)
        out[row::2, col::2] = rgb[row::2, col::2, CHANNEL[letter]]
    return out


class CameraOutput:
    """What a ``width`` x ``height`` px camera publishes of the rgb8 image the renderer draws:
    distorted by ``lens`` (None or no terms: not; its DistortionMap made at the first image),
    then ``converted`` to ``image_format``. ``plain``: the image is published as drawn."""

    def __init__(self, image_format: str, lens: Optional[LensDistortion], width: int,
                 height: int):
        self.image_format = image_format
        self.encoding, self.pixel_bytes = encoding(image_format)
        self.lens = None if lens is None or lens.is_identity else lens
        self.size = (width, height)
        self.plain = self.lens is None and image_format == "R8G8B8"
        self._map: Optional[DistortionMap] = None

    def pixels(self, rgb: np.ndarray) -> np.ndarray:
        """The published pixels of the drawn ``rgb`` (uint8, height x width x 3)."""
        if self.lens is not None:
            if self._map is None:
                self._map = DistortionMap(self.lens, *self.size)
            rgb = self._map.apply(rgb)
        return converted(rgb, self.image_format)
