"""Camera images as Gazebo's camera plugins make them (drawn by engine.rendering). No ROS.

- ``CameraIntrinsics``: the CameraInfo gazebo_ros_camera_utils publishes (doc/turtlebot3.md 2.4).
- ``depth_image``, ``pointcloud_xyz``, ``pointcloud_bytes``, ``jpeg_bytes``: the payloads of the
  depth image, PointCloud2 and CompressedImage messages, without cv_bridge.

Images are row-major, row 0 at the top, column 0 at the left (sensor_msgs/Image order).
Units: metres, radians.
"""
import importlib.util
import io
import math
from dataclasses import dataclass
from typing import List, Optional, Sequence, Tuple

import numpy as np

from ..files.plugins.robot_plugin_types import CameraSpec

# The RealSense R200 plugin (gazebo_ros_openni_kinect) publishes depths and points only in
# (pointCloudCutoff, pointCloudCutoffMax); everything else is NaN.
DEPTH_CUTOFF = (0.4, 5.0)        # m

Vector = Sequence[float]


# --- CameraInfo ----------------------------------------------------------------------------------

@dataclass(frozen=True)
class CameraIntrinsics:
    """Pinhole model of an image ``width`` x ``height`` px, as gazebo_ros_camera_utils fills
    sensor_msgs/CameraInfo: square pixels, principal point ((w + 1) / 2, (h + 1) / 2), plumb_bob
    distortion ``distortion`` (k1, k2, t1, t2, k3: 5 zeros unless a world camera's plugin
    gives them), R identity, P[3] = -f * baseline."""

    width: int
    height: int
    f: float              # px: fx = fy
    cx: float             # px
    cy: float             # px
    baseline: float = 0.0  # m: gazebo_ros hackBaseline
    distortion: Tuple[float, ...] = (0.0,) * 5

    distortion_model = "plumb_bob"

    @classmethod
    def from_spec(cls, spec: CameraSpec) -> "CameraIntrinsics":
        f = spec.width / (2.0 * math.tan(spec.hfov / 2.0))
        return cls(spec.width, spec.height, f, (spec.width + 1) / 2.0, (spec.height + 1) / 2.0,
                   spec.baseline)

    @property
    def fx(self) -> float:
        return self.f

    @property
    def fy(self) -> float:
        return self.f

    def D(self) -> List[float]:
        """Distortion (k1, k2, t1, t2, k3)."""
        return list(self.distortion)

    def K(self) -> List[float]:
        """3x3 camera matrix, row-major (9 values)."""
        return [self.f, 0.0, self.cx,
                0.0, self.f, self.cy,
                0.0, 0.0, 1.0]

    def R(self) -> List[float]:
        """3x3 rectification rotation, row-major: identity."""
        return [1.0, 0.0, 0.0,
                0.0, 1.0, 0.0,
                0.0, 0.0, 1.0]

    def P(self) -> List[float]:
        """3x4 projection matrix, row-major (12 values); P[3] = -f * baseline."""
        return [self.f, 0.0, self.cx, -self.f * self.baseline,
                0.0, self.f, self.cy, 0.0,
                0.0, 0.0, 1.0, 0.0]


def depth_image(depth: np.ndarray, cutoff: Tuple[float, float] = DEPTH_CUTOFF) -> np.ndarray:
    """The 32FC1 depth image as the R200 plugin (gazebo_ros_openni_kinect) publishes it: metres
    strictly inside ``cutoff`` (0.4, 5.0), NaN everywhere else (too near, too far, no return)."""
    lo, hi = cutoff
    out = np.array(depth, dtype=np.float32, copy=True)
    with np.errstate(invalid="ignore"):
        out[~((out > lo) & (out < hi))] = np.nan
    return out


def pointcloud_xyz(depth: np.ndarray, intrinsics: CameraIntrinsics, stride: int = 1,
                   cutoff: Tuple[float, float] = DEPTH_CUTOFF, organized: bool = False,
                   rgb: Optional[np.ndarray] = None):
    """Points (N x 3 float32, metres in the optical frame) of every ``stride``-th pixel of
    ``depth`` whose depth lies strictly inside ``cutoff``.

    Each pixel's ray goes through its centre, as the renderer draws it and as Gazebo's point
    cloud computes it (column offset i - (width - 1) / 2 over f). ``organized``: keep one point
    per sampled pixel, row by row, NaN for those out of range (Gazebo's layout: height rows of
    width points, is_dense false); otherwise only the valid points (height 1).
    With ``rgb`` (the image of the same frame) returns (points, colours N x 3 uint8).
    """
    if not (isinstance(stride, int) and stride >= 1):
        raise ValueError("stride must be a positive integer, got %r" % (stride,))
    d = np.asarray(depth, dtype=np.float32)[::stride, ::stride]
    height, width = np.shape(depth)
    cols = (np.arange(0, width, stride, dtype=np.float32) - (width - 1) / 2.0) / intrinsics.f
    rows = (np.arange(0, height, stride, dtype=np.float32) - (height - 1) / 2.0) / intrinsics.f
    points = np.empty(d.shape + (3,), dtype=np.float32)
    points[:, :, 0] = d * cols[np.newaxis, :]
    points[:, :, 1] = d * rows[:, np.newaxis]
    points[:, :, 2] = d
    lo, hi = cutoff
    with np.errstate(invalid="ignore"):
        valid = (d > lo) & (d < hi)
    colours = None if rgb is None else np.asarray(rgb, dtype=np.uint8)[::stride, ::stride]
    if organized:
        points[~valid] = np.nan
        points = points.reshape(-1, 3)
        colours = None if colours is None else colours.reshape(-1, 3)
    else:
        points = points[valid]
        colours = None if colours is None else colours[valid]
    return points if rgb is None else (points, np.ascontiguousarray(colours))


# PointCloud2 layout of Gazebo's depth camera (PointCloud2Modifier "xyz", "rgb"): x, y, z float32
# at 0, 4, 8 and rgb at 16, 32 bytes a point; without colours 16 bytes a point. The rgb field
# is PCL's: one float32 whose bytes are the uint32 0x00RRGGBB, little-endian.
POINT_FIELDS_XYZ = (("x", 0), ("y", 4), ("z", 8))
POINT_FIELDS_XYZRGB = POINT_FIELDS_XYZ + (("rgb", 16),)


def pointcloud_bytes(points: np.ndarray, colours: Optional[np.ndarray] = None):
    """(data bytes, point_step, fields) of a little-endian sensor_msgs/PointCloud2 holding
    ``points`` (N x 3) and optionally ``colours`` (N x 3 uint8). ``fields`` is a tuple of
    (name, byte offset) pairs, each one FLOAT32 (PointField datatype 7) of count 1."""
    points = np.asarray(points, dtype=np.float32).reshape(-1, 3)
    if colours is None:
        step, fields = 16, POINT_FIELDS_XYZ
    else:
        step, fields = 32, POINT_FIELDS_XYZRGB
    out = np.zeros((len(points), step // 4), dtype="<f4")
    out[:, :3] = points
    if colours is not None:
        c = np.asarray(colours, dtype=np.uint32).reshape(-1, 3)
        out.view("<u4")[:, 4] = (c[:, 0] << 16) | (c[:, 1] << 8) | c[:, 2]
    return out.tobytes(), step, fields


def jpeg_available() -> bool:
    """Whether ``jpeg_bytes`` can encode here (needs PIL: python3-pil / Pillow), without
    importing it."""
    return importlib.util.find_spec("PIL") is not None


def jpeg_bytes(rgb: np.ndarray, quality: int = 80) -> bytes:
    """JPEG file bytes of an rgb8 image (height, width, 3), for sensor_msgs/CompressedImage
    (format "rgb8; jpeg compressed bgr8", as image_transport's compressed plugin names it)."""
    try:   # at the first image, not at start-up: PIL takes some 50 ms to import
        from PIL import Image
    except ImportError:  # pragma: no cover - depends on the machine
        raise RuntimeError("JPEG encoding needs PIL: install python3-pil (Debian, Ubuntu) "
                           "or Pillow (PyPI)") from None
    image = Image.fromarray(np.ascontiguousarray(rgb, dtype=np.uint8))
    buffer = io.BytesIO()
    image.save(buffer, format="JPEG", quality=int(quality))
    return buffer.getvalue()
