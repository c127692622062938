"""ROS-free helpers of ``image_view``: sensor_msgs/Image fields (or a CompressedImage's bytes)
to an RGB NumPy array, the scale that fits an image in a window, and the received frame rate.

No cv_bridge: the encodings a TurtleBot3 and the usual ROS cameras publish are decoded with
NumPy. Depth images are scaled for display as image_view does (cv_bridge's
``cvtColorForDisplay``): ``32FC1`` metres over 0..10 m and ``16UC1`` millimetres over
0..10000 mm by default, near dark and far bright; NaN, inf and values outside the range are
black or white at the ends (NaN black).
"""
import collections
import io
import math
from typing import Optional, Sequence, Tuple

import numpy as np


class ImageDecodeError(ValueError):
    """The image cannot be decoded; ``str(err)`` is one readable line."""


class UnsupportedEncoding(ImageDecodeError):
    """An encoding this viewer does not know."""


# encoding -> (NumPy dtype of one channel, channels)
_LAYOUTS = {
    "rgb8": ("u1", 3), "bgr8": ("u1", 3), "rgba8": ("u1", 4), "bgra8": ("u1", 4),
    "mono8": ("u1", 1), "8UC1": ("u1", 1), "8UC3": ("u1", 3), "8UC4": ("u1", 4),
    "mono16": ("u2", 1), "16UC1": ("u2", 1), "32FC1": ("f4", 1),
}
ENCODINGS = tuple(_LAYOUTS)

# Display range of depth encodings when none is given (cv_bridge's defaults for depth).
DEFAULT_RANGES = {"32FC1": (0.0, 10.0), "16UC1": (0.0, 10000.0)}


def decode_image(encoding: str, width: int, height: int, step: int, data,
                 is_bigendian: bool = False,
                 value_range: Optional[Tuple[float, float]] = None,
                 dynamic: bool = False) -> np.ndarray:
    """The image in ``data`` (bytes of a sensor_msgs/Image with these fields) as a C-contiguous
    ``(height, width, 3)`` uint8 RGB array.

    Rows are ``step`` bytes apart (padding after each row is skipped); bytes after the last row
    are ignored. ``8UC3``/``8UC4`` are taken as BGR/BGRA (OpenCV's order, as image_view does);
    alpha is dropped. Single-channel images become grey: ``mono8``/``8UC1`` as they are,
    ``mono16`` over 0..65535, ``16UC1`` and ``32FC1`` (depth) over ``value_range`` (low, high),
    by default 0..10000 (mm) and 0..10 (m), or over the finite values' own minimum and maximum
    when ``dynamic`` is true. Raises UnsupportedEncoding for another encoding and
    ImageDecodeError when the sizes do not add up.
    """
    layout = _LAYOUTS.get(encoding)
    if layout is None:
        raise UnsupportedEncoding("unsupported encoding %r (supported: %s)"
                                  % (encoding, ", ".join(ENCODINGS)))
    kind, channels = layout
    dtype = np.dtype(kind).newbyteorder(">" if is_bigendian else "<")
    for name, value in (("width", width), ("height", height), ("step", step)):
        if not isinstance(value, (int, np.integer)) or isinstance(value, bool) or value <= 0:
            raise ImageDecodeError("bad %s %r in a %s image: must be a positive whole number"
                                   % (name, value, encoding))
    row_bytes = width * channels * dtype.itemsize
    if step < row_bytes:
        raise ImageDecodeError("step %d is less than width %d x %d bytes a pixel = %d in a %s "
                               "image" % (step, width, channels * dtype.itemsize, row_bytes,
                                          encoding))
    if step % dtype.itemsize:
        raise ImageDecodeError("step %d is not a whole number of %d-byte values in a %s image"
                               % (step, dtype.itemsize, encoding))
    size = len(data)
    if size < step * height:
        raise ImageDecodeError("%d bytes of data in a %dx%d %s image with step %d: "
                               "%d expected (height x step)"
                               % (size, width, height, encoding, step, step * height))
    buffer = np.frombuffer(data, dtype=np.uint8, count=step * height)
    rows = buffer.reshape(height, step)[:, :row_bytes]
    pixels = rows.copy().view(dtype).reshape(height, width, channels)
    if kind == "u1":
        if channels == 1:
            return _grey(pixels[..., 0])
        if encoding in ("rgb8", "rgba8"):
            return np.ascontiguousarray(pixels[..., :3])
        return np.ascontiguousarray(pixels[..., 2::-1])  # BGR(A) -> RGB
    values = pixels[..., 0].astype(np.float64)
    if dynamic:
        finite = values[np.isfinite(values)]
        low, high = (float(finite.min()), float(finite.max())) if finite.size else (0.0, 1.0)
    elif value_range is not None:
        low, high = float(value_range[0]), float(value_range[1])
    else:
        low, high = DEFAULT_RANGES.get(encoding, (0.0, 65535.0))
    return _grey(scale_to_bytes(values, low, high))


def scale_to_bytes(values: np.ndarray, low: float, high: float) -> np.ndarray:
    """``values`` mapped linearly from [low, high] to 0..255 (uint8), clipped; NaN to 0 and
    +inf to 255, -inf to 0. ``high <= low`` maps everything finite to 0."""
    span = high - low
    with np.errstate(invalid="ignore", over="ignore"):
        if span > 0 and math.isfinite(span):
            scaled = (values - low) * (255.0 / span)
        else:
            scaled = np.zeros_like(values)
            scaled[values == np.inf] = 255.0
        scaled = np.nan_to_num(scaled, nan=0.0, posinf=255.0, neginf=0.0)
    return np.clip(np.rint(scaled), 0, 255).astype(np.uint8)


def _grey(plane: np.ndarray) -> np.ndarray:
    return np.ascontiguousarray(np.repeat(plane[..., np.newaxis], 3, axis=2))


def decode_compressed(data) -> np.ndarray:
    """A sensor_msgs/CompressedImage's bytes (JPEG or PNG) as a ``(height, width, 3)`` uint8
    RGB array. Raises ImageDecodeError when Pillow cannot read them."""
    from PIL import Image, UnidentifiedImageError
    try:
        with Image.open(io.BytesIO(bytes(data))) as picture:
            return np.asarray(picture.convert("RGB"))
    except (UnidentifiedImageError, OSError, ValueError) as err:
        raise ImageDecodeError("cannot decode the compressed image (%d bytes): %s"
                               % (len(data), err))


def fit_scale(width: int, height: int, max_width: int, max_height: int,
              upscale: bool = False) -> float:
    """The factor that makes a ``width`` x ``height`` image fit in ``max_width`` x
    ``max_height``, keeping its aspect ratio: at most 1 (shrink only) unless ``upscale``."""
    if width <= 0 or height <= 0:
        return 1.0
    scale = min(max(max_width, 1) / float(width), max(max_height, 1) / float(height))
    return scale if upscale else min(1.0, scale)


def scaled_size(width: int, height: int, scale: float) -> Tuple[int, int]:
    """``width`` x ``height`` times ``scale``, rounded, at least 1 x 1."""
    return max(1, int(round(width * scale))), max(1, int(round(height * scale)))


class FrameRate:
    """Frames per second over the last ``window`` seconds of the caller's clock (wall time in
    image_view): ``tick(t)`` for every frame received, ``rate(now)`` to read."""

    def __init__(self, window: float = 2.0):
        self.window = float(window)
        self._times = collections.deque()

    def tick(self, t: float) -> None:
        """One frame arrived at time ``t`` (s)."""
        self._times.append(t)
        self._forget(t)

    def rate(self, now: float) -> float:
        """Frames per second over the last window up to ``now``; 0 with fewer than two frames
        in it. The frames' own span is used while they keep coming (so a steady stream reads
        exactly its rate); a pause longer than the mean interval lowers the rate."""
        self._forget(now)
        times: Sequence[float] = self._times
        if len(times) < 2:
            return 0.0
        span = times[-1] - times[0]
        if span <= 0:
            return 0.0
        intervals = len(times) - 1
        span += max(0.0, (now - times[-1]) - span / intervals)
        return intervals / span

    def _forget(self, now: float) -> None:
        while self._times and self._times[0] < now - self.window:
            self._times.popleft()
