"""Camera images (engine/rendering.py): which cameras can be made, the view matrix, the EGL
plugin, and images rendered with TinyRenderer and EGL. No ROS master. The CameraInfo numbers and
the payloads are devices/camera.py's (test_camera.py).

Scene facts are measured on the world's own geometry: a ray cast from the camera through a pixel
must meet what the image shows there.
"""
import dataclasses
import math

import numpy as np
import pybullet
import pytest

from tutorial_turtlebot.sim.engine import rendering
from tutorial_turtlebot.sim.engine import physics as physics_module
from tutorial_turtlebot.sim.engine.client import Client
from tutorial_turtlebot.sim.devices.camera import CameraIntrinsics
from tutorial_turtlebot.sim.engine.rendering import (BACKGROUND_RGB, CameraRenderer, validate_spec,
                                                     view_matrix)
from tutorial_turtlebot.errors import UserError
from tutorial_turtlebot.sim.files.plugins.robot_plugin_types import CameraSpec
from tutorial_turtlebot.sim.files.urdf.urdf_file import read_urdf, urdf_path
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
        CameraRenderer(Client(0), spec, use_egl=False)


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
    client = Client.connect()
    try:
        assert rendering.enable_egl(client) is True
        assert rendering.enable_egl(client) is True       # again: harmless
        assert rendering.egl_enabled(client)
    finally:
        rendering.disable_egl(client)
        client.disconnect()
    assert not rendering.egl_enabled(client)


SILENT_START = r"""
import os, sys
os.environ["GAZEBO_MODEL_PATH"] = sys.argv[2]
from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
sim = Simulation(SimConfig(model="waffle_pi", world=sys.argv[1], x=0.0, y=0.0, yaw=0.0))
assert sim.physics.egl and sim.robot.camera is not None
for _ in range(3):
    sim.robot.camera_image()
sim.close()
sys.stderr.write("done\n")
"""


def test_a_textured_world_with_a_camera_prints_nothing_on_stdout(tmp_path):
    """pybullet's EGL plugin prints its GL vendor and version when it loads and
    "ven = Mesa/X.org" at its first two images, straight to file descriptor 1: none of it may
    reach a node's stdout (rospy's log lines go there). A fresh process, its fd 1 captured."""
    if not rendering.egl_available():
        pytest.skip("EGL does not render on this machine")
    import os
    import subprocess
    import sys
    import unit_paths
    world = os.path.join(unit_paths.FIXTURES, "worlds", "textured", "max_style_crates.world")
    models = os.path.join(unit_paths.FIXTURES, "gazebo_models")
    done = subprocess.run([sys.executable, "-c", SILENT_START, world, models],
                          stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=120,
                          env=dict(os.environ, ROS_HOME=str(tmp_path)))
    assert done.returncode == 0 and done.stderr.endswith(b"done\n"), done.stderr[-2000:]
    assert done.stdout == b""


def test_enable_egl_says_false_without_the_plugin(monkeypatch):
    monkeypatch.setattr(rendering, "_egl_works", None)
    monkeypatch.setattr(rendering, "egl_plugin_path", lambda: None)
    assert rendering.enable_egl(Client(0)) is False
    monkeypatch.setattr(rendering, "_egl_works", None)
    monkeypatch.setattr(rendering, "egl_plugin_path", lambda: "/nonexistent/eglRenderer.so")
    assert rendering.egl_available() is False            # the child process fails, not this one
    rendering.disable_egl(Client(12345))                  # nothing loaded: no error


# --- rendering the turtlebot3_world --------------------------------------------------------------

def _simulation(monkeypatch, model, renderer):
    """A Simulation at the turtlebot3_world spawn whose client has the EGL plugin (loaded right
    after connect, before any body) when ``renderer`` is "egl"."""
    if renderer == "egl" and not rendering.egl_available():
        pytest.skip("EGL does not render on this machine (see test_egl_loads_on_this_machine)")
    connect = Client.connect

    def connect_with_egl(*args, **kwargs):
        client = connect(*args, **kwargs)
        if renderer == "egl":
            assert rendering.enable_egl(client)
        return client
    monkeypatch.setattr(physics_module.Client, "connect", connect_with_egl)
    sim = Simulation(SimConfig(model=model, camera=True))
    monkeypatch.setattr(physics_module.Client, "connect", connect)
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


# --- z-buffer, tiles, texture budget -------------------------------------------------------------

def test_zbuffer_to_depth_inverts_opengls_depth():
    near, far = 0.03, 100.0
    depths = np.array([near, 0.1, 1.0, 2.6145, 10.0, 50.0])
    zbuffer = (far - far * near / depths) / (far - near)           # what OpenGL stores
    out = rendering.zbuffer_to_depth(zbuffer, near, far)
    assert out.dtype == np.float32
    assert out == pytest.approx(depths, rel=1e-3)
    assert out[:4] == pytest.approx(depths[:4], rel=1e-5)          # near ones to a few um
    nothing = rendering.zbuffer_to_depth(np.array([1.0, 1.0 - 6e-8]), near, far)
    assert np.all(np.isinf(nothing))                               # nothing drawn: +inf


def test_large_images_are_cut_in_equal_tiles():
    spec = CAMERAS["waffle"]                                       # 1920 x 1080
    tiles = rendering._tiles(spec, 1024, 768)
    assert [t[0] for t in tiles] == [(0, 540, 0, 960), (0, 540, 960, 1920),
                                     (540, 1080, 0, 960), (540, 1080, 960, 1920)]
    assert len(rendering._tiles(CAMERAS["waffle_pi"], 1024, 768)) == 1


def test_one_tile_has_the_cameras_frustum():
    """An image in one tile is projected as pybullet's own symmetric frustum of the same field of
    view; TinyRenderer's half-pixel shift moves its centre by half a pixel right and up."""
    spec = CAMERAS["waffle_pi"]
    (rows_cols, projection), = rendering._tiles(spec, spec.width, spec.height)
    assert rows_cols == (0, spec.height, 0, spec.width)
    vfov = 2 * math.atan(math.tan(spec.hfov / 2) * spec.height / spec.width)
    expected = pybullet.computeProjectionMatrixFOV(math.degrees(vfov), spec.width / spec.height,
                                                   spec.near, spec.far)
    assert projection == pytest.approx(expected, abs=1e-5)
    (_, shifted), = rendering._tiles(spec, spec.width, spec.height, (0.5, 0.5))
    # Column-major: entries 8 and 9 are OpenGL's (r + l) / (r - l) and (t + b) / (t - b).
    assert shifted[8] == pytest.approx(1.0 / spec.width, rel=1e-5)
    assert shifted[9] == pytest.approx(1.0 / spec.height, rel=1e-5)
