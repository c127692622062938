"""Cameras (camera.py): CameraInfo numbers, rendering with TinyRenderer and EGL, and the depth,
point-cloud and JPEG payloads. No ROS master.

Numbers from doc/turtlebot3.md 2.4 (CameraInfo as gazebo_ros_camera_utils fills it) and 4.5 (the
AutoRace camera). Scene facts are measured on the world's own geometry: a ray cast from the
camera through a pixel must meet what the image shows there.
"""
import dataclasses
import io
import math

import numpy as np
import pybullet
import pytest
from PIL import Image

from tutorial_turtlebot.sim.devices import camera
from tutorial_turtlebot.sim.engine import rendering
from tutorial_turtlebot.sim.engine import physics as physics_module
from tutorial_turtlebot.sim.devices.camera import (CameraIntrinsics, depth_image, jpeg_bytes,
                                                   pointcloud_bytes, pointcloud_xyz)
from tutorial_turtlebot.sim.engine.rendering import (BACKGROUND_RGB, CameraRenderer, validate_spec,
                                                     view_matrix)
from tutorial_turtlebot.errors import UserError
from tutorial_turtlebot.sim.files.robot_plugins import CameraSpec
from tutorial_turtlebot.sim.files.urdf_file import read_urdf, urdf_path
from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
from tutorial_turtlebot.sim.engine.world_bullet import WORLD_COLLISION_GROUP

OPTICAL_FRAME = "camera_rgb_optical_frame"


def urdf_camera(model, autorace=False):
    """The CameraSpec the model's URDF declares (the AutoRace burger's with ``autorace``)."""
    return read_urdf(urdf_path(model, autorace)).plugins.camera.spec


CAMERAS = {"waffle": urdf_camera("waffle"), "waffle_pi": urdf_camera("waffle_pi")}
AUTORACE_CAMERA = urdf_camera("burger", autorace=True)
RENDERERS = ("tiny", "egl")
GREEN_BODIES = ("head", "left_hand", "right_hand", "left_foot", "right_foot")


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


# --- validation ----------------------------------------------------------------------------------

@pytest.mark.parametrize("spec", list(CAMERAS.values())
                         + [AUTORACE_CAMERA, CameraSpec(1, 1, 0.01, 1.0),
                            CameraSpec(4096, 4096, 3.14, 30.0)])
def test_valid_cameras_pass(spec):
    validate_spec(spec)


@pytest.mark.parametrize("changes, words", [
    ({"width": 0}, "width 0"),
    ({"width": -640}, "width -640"),
    ({"height": 4097}, "height 4097"),
    ({"width": 640.0}, "width 640.0"),
    ({"height": True}, "height True"),
    ({"hfov": 0.0}, "horizontal_fov"),
    ({"hfov": math.pi}, "horizontal_fov"),
    ({"hfov": -1.0}, "horizontal_fov"),
    ({"hfov": float("nan")}, "horizontal_fov"),
    ({"near": 0.0}, "near"),
    ({"near": 5.0, "far": 1.0}, "near"),
    ({"rate": 0.0}, "rate"),
])
def test_impossible_cameras_are_refused_in_one_line(changes, words):
    spec = dataclasses.replace(CAMERAS["waffle_pi"], **changes)
    with pytest.raises(UserError) as err:
        validate_spec(spec)
    assert words in str(err.value) and "\n" not in str(err.value)
    with pytest.raises(UserError):
        CameraRenderer(0, spec, use_egl=False)


# --- view matrix ---------------------------------------------------------------------------------

def test_view_matrix_matches_pybullets_look_at():
    yaw = 0.7
    forward = np.array([math.cos(yaw), math.sin(yaw), 0.0])
    right = np.array([math.sin(yaw), -math.cos(yaw), 0.0])
    down = np.array([0.0, 0.0, -1.0])
    rotation = np.column_stack([right, down, forward])
    eye = np.array([1.0, -2.0, 0.3])
    expected = pybullet.computeViewMatrix(eye, eye + forward, -down)
    assert view_matrix(eye, rotation) == pytest.approx(expected, abs=1e-6)


# --- EGL -----------------------------------------------------------------------------------------

def test_egl_loads_on_this_machine():
    # ENVIRONMENT-DEPENDENT: true where Mesa's EGL is installed (Debian libegl1 and
    # libgl1-mesa-dri, as tools/setup.sh installs them) or a GPU driver provides EGL.
    assert rendering.egl_available(), ("pybullet's EGL plugin does not render here: install "
                                    "libegl1 and libgl1-mesa-dri")
    cid = pybullet.connect(pybullet.DIRECT)
    try:
        assert rendering.enable_egl(cid) is True
        assert rendering.enable_egl(cid) is True          # again: harmless
        assert rendering.egl_enabled(cid)
    finally:
        rendering.disable_egl(cid)
        pybullet.disconnect(cid)
    assert not rendering.egl_enabled(cid)


def test_enable_egl_says_false_without_the_plugin(monkeypatch):
    monkeypatch.setattr(rendering, "_egl_works", None)
    monkeypatch.setattr(rendering, "egl_plugin_path", lambda: None)
    assert rendering.enable_egl(0) is False
    monkeypatch.setattr(rendering, "_egl_works", None)
    monkeypatch.setattr(rendering, "egl_plugin_path", lambda: "/nonexistent/eglRenderer.so")
    assert rendering.egl_available() is False            # the child process fails, not this one
    rendering.disable_egl(12345)                          # nothing loaded: no error


# --- rendering the turtlebot3_world --------------------------------------------------------------

def _simulation(monkeypatch, model, renderer):
    """A Simulation at the turtlebot3_world spawn whose client has the EGL plugin (loaded right
    after connect, before any body) when ``renderer`` is "egl"."""
    if renderer == "egl" and not rendering.egl_available():
        pytest.skip("EGL does not render on this machine (see test_egl_loads_on_this_machine)")
    connect = pybullet.connect

    def connect_with_egl(*args, **kwargs):
        cid = connect(*args, **kwargs)
        if renderer == "egl":
            assert rendering.enable_egl(cid)
        return cid
    monkeypatch.setattr(physics_module.pybullet, "connect", connect_with_egl)
    sim = Simulation(SimConfig(model=model, camera=True))
    monkeypatch.setattr(physics_module.pybullet, "connect", connect)
    return sim


@pytest.fixture(params=RENDERERS)
def renderer(request):
    return request.param


@pytest.fixture
def waffle_pi(monkeypatch, renderer):
    sim = _simulation(monkeypatch, "waffle_pi", renderer)
    yield sim, renderer == "egl"
    rendering.disable_egl(sim.physics.client)
    sim.close()


def _pixel_rays(spec, position, rotation, pixels):
    """World ray ends (one per (col, row) pixel centre, 20 m long) and, per pixel, the factor from
    distance along the ray to depth along the optical axis."""
    f = CameraIntrinsics.from_spec(spec).f
    cols, rows = np.asarray(pixels, dtype=float).T
    local = np.column_stack([(cols + 0.5 - spec.width / 2) / f,
                             (rows + 0.5 - spec.height / 2) / f, np.ones(len(cols))])
    norms = np.linalg.norm(local, axis=1)
    ends = position + (local / norms[:, None]) @ np.asarray(rotation).T * 20.0
    return ends, 1.0 / norms


def _cast(sim, position, ends):
    """(body ids, distances m) of the world surfaces met from ``position`` to each end."""
    hits = pybullet.rayTestBatch([list(position)] * len(ends), ends.tolist(),
                                 collisionFilterMask=WORLD_COLLISION_GROUP,
                                 physicsClientId=sim.physics.client)
    return (np.array([h[0] for h in hits]),
            np.array([h[2] * 20.0 if h[0] >= 0 else np.inf for h in hits]))


def test_waffle_pi_sees_the_green_head_where_it_is(waffle_pi):
    sim, egl = waffle_pi
    spec = sim.robot.camera_spec
    position, rotation = sim.robot.body.frame_pose(OPTICAL_FRAME)
    assert position[:2] == pytest.approx((-1.924, -0.5), abs=0.002)   # spawn + camera offset
    rgb, depth = CameraRenderer(sim.physics.client, spec, use_egl=egl).render(
        position, rotation, depth=True)
    assert rgb.shape == (480, 640, 3) and rgb.dtype == np.uint8 and rgb.flags["C_CONTIGUOUS"]
    assert depth.shape == (480, 640) and depth.dtype == np.float32

    grid = [(c, r) for r in range(4, 480, 16) for c in range(4, 640, 16)]
    bodies, _ = _cast(sim, position, _pixel_rays(spec, position, rotation, grid)[0])
    green_ids = {sim.physics.world_bodies["ros_symbol::symbol::" + n] for n in GREEN_BODIES}
    head = sim.physics.world_bodies["ros_symbol::symbol::head"]
    r, g, b = (rgb[[p[1] for p in grid], [p[0] for p in grid]].astype(int).T)
    is_green = (g > 100) & (r < 60) & (b < 60)
    hits_green = np.isin(bodies, list(green_ids))
    hits_head = bodies == head
    assert hits_head.sum() > 40                       # the head fills a good part of the view
    assert np.mean(is_green[hits_green]) > 0.95       # green where the geometry puts green
    assert np.mean(is_green[~hits_green]) < 0.02      # and hardly anywhere else (edges)
    head_cols = np.array([p[0] for p in grid])[hits_head]
    assert head_cols.mean() < 320                     # left of the image centre, as seen
    # Straight ahead (y = -0.5) the ray meets the head's face at x = 2.6145.
    assert depth[240, 320] == pytest.approx(2.6145 - position[0], abs=0.01)


def test_image_is_right_side_up(waffle_pi):
    sim, egl = waffle_pi
    spec = sim.robot.camera_spec
    position, rotation = sim.robot.body.frame_pose(OPTICAL_FRAME)
    rgb, depth = CameraRenderer(sim.physics.client, spec, use_egl=egl).render(
        position, rotation, depth=True)
    # Above the arena walls, the background; below the horizon, the floor at the depth its
    # row gives for a camera at this height.
    assert np.all(rgb[0:20, 300:340] == BACKGROUND_RGB) and np.all(np.isinf(depth[0:20, 300:340]))
    for row in (300, 400, 470):
        expected = _floor_depth(spec, position, rotation, row)
        assert depth[row, 320] == pytest.approx(expected, rel=0.01)
        assert not np.array_equal(rgb[row, 320], BACKGROUND_RGB)


def _floor_depth(spec, position, rotation, row):
    """Depth along the optical axis of the floor (z = 0) seen at the centre of pixel ``row`` of
    the middle column."""
    f = CameraIntrinsics.from_spec(spec).f
    direction = np.asarray(rotation) @ (0.0, (row + 0.5 - spec.height / 2) / f, 1.0)
    return -position[2] / direction[2]


def _smooth(patch):
    """Whether a depth patch shows one surface (within 5 cm) or nothing at all."""
    return bool(np.all(np.isinf(patch)) or (np.all(np.isfinite(patch)) and np.ptp(patch) < 0.05))


def test_depth_matches_the_geometry(waffle_pi):
    """Over a grid of pixels, depth is the distance along the optical axis to what a ray through
    the pixel meets (away from edges, where a pixel may show either side)."""
    sim, egl = waffle_pi
    spec = sim.robot.camera_spec
    position, rotation = sim.robot.body.frame_pose(OPTICAL_FRAME)
    _, depth = CameraRenderer(sim.physics.client, spec, use_egl=egl).render(
        position, rotation, depth=True)
    grid = [(c, r) for r in range(6, 480, 12) for c in range(6, 640, 12)]
    ends, axial = _pixel_rays(spec, position, rotation, grid)
    _, distances = _cast(sim, position, ends)
    expected = distances * axial
    rendered = np.array([depth[r, c] for c, r in grid])
    smooth = np.array([_smooth(depth[r - 2:r + 3, c - 2:c + 3]) for c, r in grid])
    assert np.all(np.isinf(rendered[np.isinf(expected) & smooth]))
    both = np.isfinite(expected) & smooth
    assert both.sum() > 1000
    errors = np.abs(rendered[both] - expected[both])
    assert np.mean(errors < 0.02) > 0.97, np.percentile(errors, [50, 90, 99])
    assert np.median(errors) < 0.005


@pytest.mark.parametrize("model", ["waffle_pi", "waffle", "burger"])
def test_the_robot_stays_out_of_its_own_view(monkeypatch, renderer, model):
    sim = _simulation(monkeypatch, model, renderer)
    try:
        spec = sim.robot.camera_spec
        if renderer == "tiny" and spec.width > 640:      # TinyRenderer: a quarter of the pixels
            spec = dataclasses.replace(spec, width=spec.width // 2, height=spec.height // 2)
        view = CameraRenderer(sim.physics.client, spec, use_egl=renderer == "egl")
        position, rotation = sim.robot.body.frame_pose(OPTICAL_FRAME)
        with_robot, depth_with = view.render(position, rotation, depth=True)
        pybullet.removeBody(sim.robot.body.robot, physicsClientId=sim.physics.client)
        without_robot, depth_without = view.render(position, rotation, depth=True)
        assert np.array_equal(with_robot, without_robot)
        assert np.array_equal(depth_with, depth_without)
    finally:
        rendering.disable_egl(sim.physics.client)
        sim.close()


def test_autorace_camera_looks_down_10_degrees(monkeypatch):
    """The burger's AutoRace camera is pitched 0.174 rad down: its optical axis meets the floor
    height / sin(0.174) ahead."""
    sim = _simulation(monkeypatch, "burger", "tiny")
    try:
        spec = sim.robot.camera_spec
        position, rotation = sim.robot.body.frame_pose(OPTICAL_FRAME)
        assert rotation[:, 2] == pytest.approx((math.cos(0.174), 0.0, -math.sin(0.174)),
                                               abs=1e-3)
        rgb, depth = CameraRenderer(sim.physics.client, spec, use_egl=False).render(
            position, rotation, depth=True)
        assert rgb.shape == (240, 320, 3)
        for row in (110, 119, 120, 130):                 # rows near the centre: the floor
            assert depth[row, 160] == pytest.approx(_floor_depth(spec, position, rotation, row),
                                                    rel=0.005)
        # What the optical axis meets (the URDF's 1.57 for pi/2 tilts it by another 0.8 mrad).
        assert _floor_depth(spec, position, rotation, 119.5) == pytest.approx(
            position[2] / math.sin(0.174), rel=0.01)
    finally:
        sim.close()


def test_large_images_are_drawn_in_tiles_with_egl(monkeypatch):
    """EGL reads at most 1024 x 768 pixels per render: the waffle's 1920 x 1080 image is drawn as
    4 tiles, and every column of it is its own (no stretched 1024-pixel image)."""
    sim = _simulation(monkeypatch, "waffle", "egl")
    try:
        spec = sim.robot.camera_spec
        view = CameraRenderer(sim.physics.client, spec, use_egl=True)
        assert view.tile_count == 4
        position, rotation = sim.robot.body.frame_pose(OPTICAL_FRAME)
        _, depth = view.render(position, rotation, depth=True)
        floor = depth[600:, 960]                          # nearer with every row down
        assert np.all(np.diff(floor) < 0)                 # (a stretched image repeats rows)
        for row in (600, 800, 1079):
            for col in (959, 960):                        # both sides of the tile border
                assert depth[row, col] == pytest.approx(
                    _floor_depth(spec, position, rotation, row), rel=0.01)
    finally:
        rendering.disable_egl(sim.physics.client)
        sim.close()


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
