"""Camera payloads (devices/camera.py): CameraInfo numbers, and the depth, point-cloud and JPEG
payloads. No ROS master. Rendering the images is engine/rendering.py's (test_rendering.py).

Numbers from doc/turtlebot3.md 2.4 (CameraInfo as gazebo_ros_camera_utils fills it) and 4.5 (the
AutoRace camera).
"""
import io
import math

import numpy as np
import pytest
from PIL import Image

from tutorial_turtlebot.sim.devices import camera
from tutorial_turtlebot.sim.devices.camera import (CameraIntrinsics, depth_image, jpeg_bytes,
                                                   pointcloud_bytes, pointcloud_xyz)
from tutorial_turtlebot.sim.files.plugins.robot_plugin_types import CameraSpec
from tutorial_turtlebot.sim.files.urdf.urdf_file import read_urdf, urdf_path


def urdf_camera(model, autorace=False):
    """The CameraSpec the model's URDF declares (the AutoRace burger's with ``autorace``)."""
    return read_urdf(urdf_path(model, autorace)).plugins.camera.spec


CAMERAS = {"waffle": urdf_camera("waffle"), "waffle_pi": urdf_camera("waffle_pi")}
AUTORACE_CAMERA = urdf_camera("burger", autorace=True)


# --- CameraInfo ----------------------------------------------------------------------------------

def test_waffle_pi_intrinsics():
    k = CameraIntrinsics.from_spec(CAMERAS["waffle_pi"])
    assert (k.width, k.height) == (640, 480)
    assert k.fx == k.fy == pytest.approx(530.47, abs=0.01)
    assert (k.cx, k.cy) == (320.5, 240.5)
    assert k.P()[3] == pytest.approx(-37.13, abs=0.01)          # -f * hackBaseline 0.07


def test_waffle_intrinsics():
    k = CameraIntrinsics.from_spec(CAMERAS["waffle"])
    assert (k.width, k.height) == (1920, 1080)
    assert k.f == pytest.approx(1206.89, abs=0.01)
    assert (k.cx, k.cy) == (960.5, 540.5)


def test_autorace_intrinsics():
    k = CameraIntrinsics.from_spec(AUTORACE_CAMERA)
    assert (k.width, k.height, k.cx, k.cy) == (320, 240, 160.5, 120.5)
    assert k.f == pytest.approx(320 / (2 * math.tan(1.085595 / 2)))
    assert k.P()[3] == pytest.approx(-k.f * 0.07)  # hackBaseline 0.07, as its gazebo.xacro


def test_camera_info_matrices():
    k = CameraIntrinsics.from_spec(CAMERAS["waffle_pi"])
    f = k.f
    assert k.K() == [f, 0, 320.5, 0, f, 240.5, 0, 0, 1]
    assert k.R() == [1, 0, 0, 0, 1, 0, 0, 0, 1]
    assert k.P() == [f, 0, 320.5, -f * 0.07, 0, f, 240.5, 0, 0, 0, 1, 0]
    assert k.D() == [0.0] * 5 and k.distortion_model == "plumb_bob"
    assert all(isinstance(v, float) for v in k.K() + k.R() + k.P())


# --- payloads ------------------------------------------------------------------------------------

def test_depth_image_is_nan_outside_the_r200_cutoff():
    depth = np.array([[0.2, 0.4, 0.41, 4.99], [5.0, 7.0, np.inf, 2.5]], dtype=np.float32)
    out = depth_image(depth)
    assert out.dtype == np.float32
    assert np.isnan(out[0, :2]).all() and np.isnan(out[1, :3]).all()
    assert out[0, 2:] == pytest.approx((0.41, 4.99)) and out[1, 3] == 2.5
    assert depth[0, 0] == np.float32(0.2)             # the input is untouched


def _plane(width=8, height=6, distance=2.0):
    spec = CameraSpec(width, height, 1.2, 30.0)
    return np.full((height, width), distance, dtype=np.float32), CameraIntrinsics.from_spec(spec)


def test_pointcloud_of_a_plane():
    depth, k = _plane()
    points = pointcloud_xyz(depth, k)
    assert points.shape == (48, 3) and points.dtype == np.float32
    assert np.all(points[:, 2] == 2.0)
    # Row-major order; column i sits at (i - (width - 1) / 2) / f, as Gazebo computes it.
    assert points[0, :2] == pytest.approx((2.0 * -3.5 / k.f, 2.0 * -2.5 / k.f))
    assert points[47, :2] == pytest.approx((2.0 * 3.5 / k.f, 2.0 * 2.5 / k.f))
    assert points[:8, 0] == pytest.approx(-points[7::-1, 0])


def test_pointcloud_cutoff_stride_and_layout():
    depth, k = _plane()
    depth[0, 0], depth[0, 2], depth[2, 4] = 0.3, np.inf, 6.0
    dense = pointcloud_xyz(depth, k)
    assert len(dense) == 45 and np.isfinite(dense).all()
    organized = pointcloud_xyz(depth, k, organized=True)
    assert organized.shape == (48, 3)
    assert np.isnan(organized[[0, 2, 20]]).all() and np.isfinite(organized[1]).all()
    strided = pointcloud_xyz(depth, k, stride=2, organized=True)
    assert strided.shape == (12, 3)                   # rows 0, 2, 4 x columns 0, 2, 4, 6
    assert np.isnan(strided[[0, 1, 6]]).all()
    assert strided[3] == pytest.approx((2.0 * 2.5 / k.f, 2.0 * -2.5 / k.f, 2.0))
    with pytest.raises(ValueError):
        pointcloud_xyz(depth, k, stride=0)


def test_pointcloud_with_colours_and_bytes():
    depth, k = _plane(4, 2)
    depth[0, 1] = np.nan
    rgb = np.arange(4 * 2 * 3, dtype=np.uint8).reshape(2, 4, 3)
    points, colours = pointcloud_xyz(depth, k, rgb=rgb)
    assert len(points) == len(colours) == 7
    assert colours[1].tolist() == rgb[0, 2].tolist()
    data, step, fields = pointcloud_bytes(points, colours)
    assert step == 32 and dict(fields) == {"x": 0, "y": 4, "z": 8, "rgb": 16}
    raw = np.frombuffer(data, dtype="<f4").reshape(7, 8)
    assert raw[:, :3] == pytest.approx(points)
    packed = np.frombuffer(data, dtype="<u4").reshape(7, 8)[:, 4]
    r, g, b = colours[1].astype(int)
    assert packed[1] == (r << 16) | (g << 8) | b
    data, step, fields = pointcloud_bytes(points)
    assert step == 16 and len(data) == 7 * 16 and [n for n, _ in fields] == ["x", "y", "z"]


def test_jpeg_decodes_to_the_image():
    assert camera.jpeg_available()
    rgb = np.zeros((480, 640, 3), dtype=np.uint8)
    rgb[:, :320] = (0, 200, 0)
    rgb[:, 320:] = (200, 200, 200)
    data = jpeg_bytes(rgb, quality=80)
    assert data[:2] == b"\xff\xd8"
    decoded = np.asarray(Image.open(io.BytesIO(data)).convert("RGB"))
    assert decoded.shape == (480, 640, 3)
    assert np.abs(decoded.astype(int) - rgb).mean() < 3
