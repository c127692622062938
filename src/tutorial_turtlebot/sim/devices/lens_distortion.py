"""A camera's lens distortion as Gazebo applies it to the rendered image (rendering/Distortion,
its legacy mode): Brown's model in fractions of the image about the lens ``center``,

    x = u - cx, y = v - cy, r2 = x^2 + y^2
    x' = x (1 + k1 r2 + k2 r2^2 + k3 r2^3) + p2 (r2 + 2 x^2) + 2 p1 x y
    y' = y (1 + k1 r2 + k2 r2^2 + k3 r2^3) + p1 (r2 + 2 y^2) + 2 p2 x y

an undistorted point (u, v) lands at (cx + x', cy + y') of the distorted image. That is
OpenCV's plumb_bob with D = (k1, k2, p1, p2, k3) when the focal length equals the image width
(a horizontal field of view of 2 atan(1/2)); gazebo_ros publishes D so. ``crop``: a barrel
distortion (k1 < 0) is stretched so that the distorted corners of the image reach the corners
(no black border; D no longer fits it). A distorted pixel whose undistorted point lies outside
the image is black.

``DistortionMap`` is the remap of one camera, computed once: for each distorted pixel the
undistorted point (the model inverted by fixed-point iteration) and its bilinear weights.
Pure numpy, no ROS. Images are row-major, row 0 at the top.
"""
from typing import Tuple

import numpy as np

from ..files.plugins.camera_types import LensDistortion

ITERATIONS = 20     # fixed-point steps of the inversion: far below a pixel for |k| < 1


def distort(u: np.ndarray, v: np.ndarray, lens: LensDistortion) -> Tuple[np.ndarray, np.ndarray]:
    """Where the undistorted image points (u, v) (fractions of the image) land."""
    cx, cy = lens.center
    x, y = u - cx, v - cy
    r2 = x * x + y * y
    radial = 1.0 + r2 * (lens.k1 + r2 * (lens.k2 + r2 * lens.k3))
    xd = x * radial + lens.p2 * (r2 + 2.0 * x * x) + 2.0 * lens.p1 * x * y
    yd = y * radial + lens.p1 * (r2 + 2.0 * y * y) + 2.0 * lens.p2 * x * y
    return cx + xd, cy + yd


def undistort(ud: np.ndarray, vd: np.ndarray,
              lens: LensDistortion) -> Tuple[np.ndarray, np.ndarray]:
    """The undistorted points whose distortion is (ud, vd): ``distort`` inverted."""
    cx, cy = lens.center
    x0, y0 = ud - cx, vd - cy
    x, y = x0.copy(), y0.copy()
    for _ in range(ITERATIONS):
        r2 = x * x + y * y
        radial = 1.0 + r2 * (lens.k1 + r2 * (lens.k2 + r2 * lens.k3))
        dx = lens.p2 * (r2 + 2.0 * x * x) + 2.0 * lens.p1 * x * y
        dy = lens.p1 * (r2 + 2.0 * y * y) + 2.0 * lens.p2 * x * y
        x, y = (x0 - dx) / radial, (y0 - dy) / radial
    return cx + x, cy + y


class DistortionMap:
    """The remap of a ``width`` x ``height`` px camera with ``lens``."""

    def __init__(self, lens: LensDistortion, width: int, height: int):
        self.width, self.height = width, height
        ud = (np.arange(width) + 0.5) / width
        vd = (np.arange(height) + 0.5) / height
        ud, vd = np.meshgrid(ud, vd)
        if lens.crop and lens.k1 < 0:
            (ax, ay), (bx, by) = (distort(np.float64(c), np.float64(c), lens) for c in (0, 1))
            ud, vd = ax + ud * (bx - ax), ay + vd * (by - ay)
        u, v = undistort(ud, vd, lens)
        col, row = u * width - 0.5, v * height - 0.5        # source pixel, centre-based
        inside = (col > -0.5) & (col < width - 0.5) & (row > -0.5) & (row < height - 0.5)
        col = np.clip(col, 0.0, width - 1.0)
        row = np.clip(row, 0.0, height - 1.0)
        c0 = np.minimum(np.floor(col).astype(np.intp), width - 2 if width > 1 else 0)
        r0 = np.minimum(np.floor(row).astype(np.intp), height - 2 if height > 1 else 0)
        fc, fr = col - c0, row - r0
        c1 = np.minimum(c0 + 1, width - 1)
        r1 = np.minimum(r0 + 1, height - 1)
        self.source = (u, v)                  # each distorted pixel's undistorted point
        self.inside = inside
        corners = ((r0, c0), (r0, c1), (r1, c0), (r1, c1))
        self._index = [(r * width + c).ravel() for r, c in corners]
        weights = [(1 - fr) * (1 - fc), (1 - fr) * fc, fr * (1 - fc), fr * fc]
        self._weights = [(w * inside).ravel()[:, np.newaxis].astype(np.float32)
                         for w in weights]

    def apply(self, image: np.ndarray) -> np.ndarray:
        """The distorted image of ``image`` (height x width x channels, uint8), uint8."""
        flat = image.reshape(self.width * self.height, -1)
        out = np.zeros(flat.shape, dtype=np.float32)
        for index, weight in zip(self._index, self._weights):
            out += flat[index] * weight
        return np.rint(out).astype(np.uint8).reshape(image.shape)
