"""StageEnv's render modes (learning/stage_render.py, learning/stage_env.py): the top-down
picture's mapping and what it shows where (the robot, its heading, the goal, the laser's rays,
the moving obstacles), Gymnasium's checks, the human window under Xvfb, the camera option.
No ROS. Units: m, rad; pixels as (col, row), row 0 at the top."""
import importlib
import json
import math
import os
import shutil
import subprocess
import sys
import warnings

import numpy as np
import pytest

gymnasium = pytest.importorskip("gymnasium")   # tools/setup.sh installs it

importlib.import_module("tutorial_turtlebot.learning")   # registers the ids
from tutorial_turtlebot.learning import robotis_stages as rs  # noqa: E402
from tutorial_turtlebot.learning import stage_render as sr  # noqa: E402
from tutorial_turtlebot.learning.stage_env import StageEnv  # noqa: E402
from tutorial_turtlebot.sim.kinematics import yaw_from_quat  # noqa: E402


def pixels_of(image, *colours):
    """(cols, rows) of the pixels of any of ``colours``."""
    mask = np.zeros(image.shape[:2], bool)
    for colour in colours:
        mask |= np.all(image == np.array(colour, np.uint8), axis=2)
    rows, cols = np.nonzero(mask)
    return cols, rows


def centroid(image, *colours):
    cols, rows = pixels_of(image, *colours)
    assert len(cols) > 0, "no pixel of %s" % (colours,)
    return np.array([cols.mean(), rows.mean()])


def is_colour(image, col, row, colour, around=0):
    """Whether a pixel within ``around`` px of (col, row) (rounded) has ``colour``."""
    c, r = int(round(col)), int(round(row))
    patch = image[max(r - around, 0):r + around + 1, max(c - around, 0):c + around + 1]
    return bool(np.any(np.all(patch == np.array(colour, np.uint8), axis=2)))


def robot_plan(env):
    """(x, y, yaw) of base_footprint from the env's odometry (world frame)."""
    odom = env.robot.odom()
    return odom.position[0], odom.position[1], yaw_from_quat(odom.orientation)


@pytest.fixture
def stage_1():
    env = StageEnv(1, render_mode="rgb_array")
    yield env
    env.close()


def test_make_with_rgb_array_gives_the_declared_image_without_a_warning():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        env = gymnasium.make("TurtleBot3Stage1-v0", render_mode="rgb_array")
        try:
            env.reset(seed=0)
            image = env.render()
            env.step(2)
            assert env.render().shape == image.shape
            from gymnasium.utils.passive_env_checker import env_render_passive_checker
            env_render_passive_checker(env.unwrapped)
        finally:
            env.close()
    assert env.unwrapped.render_mode == "rgb_array"
    assert env.metadata["render_modes"] == ["rgb_array", "human"]
    assert env.metadata["render_fps"] == 5 == round(1 / rs.STEP_TIME)
    assert image.shape == (sr.SIZE, sr.SIZE, 3) and image.dtype == np.uint8


def test_the_mapping_puts_x_right_y_up_and_the_arena_where_its_walls_are(stage_1):
    stage_1.reset(seed=0)
    image = stage_1.render()
    view = stage_1._render.view
    c0, r0 = view.world_to_pixel(0.0, 0.0)
    c1, r1 = view.world_to_pixel(1.0, 0.0)
    c2, r2 = view.world_to_pixel(0.0, 1.0)
    assert (c1 - c0, r1 - r0) == pytest.approx((view.scale, 0.0))
    assert (c2 - c0, r2 - r0) == pytest.approx((0.0, -view.scale))
    # stage 1's walls: 0.15 m thick, centred 2 m from the origin on each side
    for x, y in ((0.0, 2.0), (2.0, 0.5), (0.3, -2.0), (-2.0, -1.0)):
        assert is_colour(image, *view.world_to_pixel(x, y), sr.STATIC), (x, y)
    for x, y in ((0.0, 1.85), (1.85, 0.5), (0.0, 2.2), (-2.2, 0.0)):
        assert not is_colour(image, *view.world_to_pixel(x, y), sr.STATIC), (x, y)
    # the arena fills the picture but for the margin
    assert view.scale == pytest.approx(sr.SIZE / (4.15 + 2 * sr.MARGIN), rel=1e-4)


def test_the_robot_is_drawn_at_its_pose_and_moves_with_it(stage_1):
    stage_1.reset(seed=0)
    view_of = None
    seen = []
    for steps in (0, 8, 8):
        for _ in range(steps):
            stage_1.step(1)                      # forward, turning left at 0.75 rad/s
        image = stage_1.render()
        view_of = stage_1._render.view
        x, y, yaw = robot_plan(stage_1)
        centre = centroid(image, sr.ROBOT, sr.HEADING)
        assert centre == pytest.approx(view_of.world_to_pixel(x, y), abs=0.5)
        # the disc has the footprint's radius: its area in pixels
        area = len(pixels_of(image, sr.ROBOT, sr.HEADING)[0])
        radius = 0.1237 * view_of.scale
        assert area == pytest.approx(math.pi * radius ** 2, rel=0.08)
        # the heading bar runs from the centre along the robot's yaw (y up: rows go down)
        bar = centroid(image, sr.HEADING) - centre
        assert math.atan2(-bar[1], bar[0]) == pytest.approx(yaw, abs=0.12)
        assert np.hypot(*bar) == pytest.approx(radius / 2, abs=1.0)
        cols, rows = pixels_of(image, sr.HEADING)      # every pixel of it on that half line
        along = (cols - centre[0]) * math.cos(yaw) - (rows - centre[1]) * math.sin(yaw)
        across = (cols - centre[0]) * math.sin(yaw) + (rows - centre[1]) * math.cos(yaw)
        assert np.all(np.abs(across) <= 2.3) and np.all(along >= -2.3)
        seen.append((centre, x, y, yaw))
    (c0, x0, y0, yaw0), (c1, x1, y1, yaw1), (c2, x2, y2, _) = seen
    assert yaw1 - yaw0 > 1.0 and y2 > y1 > y0 + 0.05      # it turned left and went up
    for (ca, xa, ya, _), (cb, xb, yb, _) in ((seen[0], seen[1]), (seen[1], seen[2])):
        moved = np.array([xb - xa, -(yb - ya)]) * view_of.scale
        assert cb - ca == pytest.approx(moved, abs=0.7)
        assert np.hypot(*moved) > 10


def test_the_goal_is_drawn_at_the_goal(stage_1):
    _, info = stage_1.reset(seed=0)
    view = None
    for goal in (info["goal"], (-1.1, 0.9), (0.4, -1.2)):
        stage_1.goal = goal
        image = stage_1.render()
        view = stage_1._render.view
        where = np.array(view.world_to_pixel(*goal))
        assert centroid(image, sr.GOAL) == pytest.approx(where, abs=0.3)
        # the ring at the distance that counts as reached
        cols, rows = pixels_of(image, sr.GOAL_ZONE)
        distances = np.hypot(cols - where[0], rows - where[1])
        assert np.median(distances) == pytest.approx(rs.GOAL_RANGE * view.scale, abs=1.0)
    assert info["goal"] == rs.FIRST_GOAL


def laser_rays(env):
    """(origin (x, y), directions (N x 2)) of the laser's rays in the world plan, from its
    frame's pose and the scan's angles."""
    origin, rotation = env.robot.body.frame_pose(env.robot.laser_sensor.link)
    laser = env.robot.laser
    angles = laser.angle_min + laser.angle_increment * np.arange(laser.samples)
    yaw = math.atan2(rotation[1, 0], rotation[0, 0])
    return origin[:2], np.stack([np.cos(yaw + angles), np.sin(yaw + angles)], 1)


def test_rays_end_where_the_ranges_say():
    env = StageEnv(2, render_mode="rgb_array")          # the pillars: ranges of all lengths
    try:
        env.reset(seed=0)
        checked = 0
        for _ in range(2):
            for _ in range(6):
                env.step(3)
            image = env.render()
            view = env._render.view
            origin, directions = laser_rays(env)
            ranges = np.asarray(env.last_ranges, float)
            assert len(ranges) == rs.SCAN_SAMPLES and np.all(np.isfinite(ranges))
            for r, d in zip(ranges, directions):
                end = origin + r * d
                if np.hypot(*(end - env.goal)) < rs.GOAL_RANGE + 0.1:
                    continue                             # (the goal's marker drawn over it)
                assert is_colour(image, *view.world_to_pixel(*end), sr.RAY_HIT, around=1), r
                short = origin + (r - 3 / view.scale) * d
                assert is_colour(image, *view.world_to_pixel(*short), sr.RAY_HIT, around=1)
                beyond = origin + (r + 4 / view.scale) * d
                assert not is_colour(image, *view.world_to_pixel(*beyond), sr.RAY_HIT, around=1)
                checked += 1
        assert checked >= 44
    finally:
        env.close()


def test_no_return_rays_reach_range_max_fainter_and_none_for_too_close():
    env = StageEnv(1)
    try:
        view = sr.StageView(env.sim.world, 0.1)
    finally:
        env.close()
    directions = np.array([[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [0.0, -1.0]])
    ranges = [math.inf, 1.2, -math.inf, math.nan]
    image = view.draw((-1.5, -1.5, 0.0), (1.5, 1.5), (0.0, 0.0), directions, ranges, 1.7)
    to = view.world_to_pixel
    assert is_colour(image, *to(1.7, 0.0), sr.RAY_NONE, around=1)
    assert not is_colour(image, *to(1.75, 0.0), sr.RAY_NONE, around=1)
    assert not is_colour(image, *to(1.0, 0.0), sr.RAY_HIT)
    assert is_colour(image, *to(0.0, 1.2), sr.RAY_HIT, around=1)
    assert not is_colour(image, *to(0.0, 1.26), sr.RAY_HIT, around=1)
    for x, y in ((-0.5, 0.0), (0.0, -0.5)):                # -inf and NaN: no ray at all
        assert not is_colour(image, *to(x, y), sr.RAY_HIT, around=1)
        assert not is_colour(image, *to(x, y), sr.RAY_NONE, around=1)


def test_the_moving_obstacles_are_drawn_where_they_are_now():
    env = StageEnv(3, render_mode="rgb_array")          # four pillars spinning about the origin
    try:
        env.reset(seed=0)
        image = env.render()
        view = env._render.view
        spawn = [(x, y) for x in (-0.6, 0.6) for y in (-0.6, 0.6)]
        for x, y in spawn:
            assert is_colour(image, *view.world_to_pixel(x, y), sr.MOVING)
        for _ in range(20):
            env.step(2)
        image = env.render()
        (mx, my, _), quat = env.sim.models.get("obstacle").pose()
        yaw = yaw_from_quat(quat)
        assert abs(yaw) > 0.4
        c, s = math.cos(yaw), math.sin(yaw)
        for x, y in spawn:
            now = (mx + c * x - s * y, my + s * x + c * y)
            assert is_colour(image, *view.world_to_pixel(*now), sr.MOVING)
            assert not is_colour(image, *view.world_to_pixel(x, y), sr.MOVING)
    finally:
        env.close()


def test_without_a_display_human_says_so_in_one_line_and_runs_on(monkeypatch, capfd):
    """Gymnasium's env checker makes every declared mode, on a machine without a display
    too: the env says what is missing once, and steps."""
    monkeypatch.delenv("DISPLAY", raising=False)
    for make in (lambda: StageEnv(1, render_mode="human"),
                 lambda: gymnasium.make("TurtleBot3Stage1-v0", render_mode="human")):
        env = make()
        try:
            message = capfd.readouterr().err
            assert message.count("\n") == 1 and "$DISPLAY" in message and "rgb_array" in message
            env.reset(seed=0)
            env.step(2)
            assert env.render() is None
            assert capfd.readouterr().err == ""
        finally:
            env.close()


def test_an_unreachable_display_is_said_in_one_line(monkeypatch, capfd):
    monkeypatch.setenv("DISPLAY", ":8917")
    env = StageEnv(1, render_mode="human")
    try:
        env.reset(seed=0)
        message = capfd.readouterr().err
        assert message.count("\n") == 1 and ":8917" in message
        env.step(2)
        assert capfd.readouterr().err == ""
    finally:
        env.close()


def test_bad_render_options_are_refused_and_none_draws_nothing():
    with pytest.raises(ValueError, match="the modes are None, 'rgb_array', 'human'"):
        StageEnv(1, render_mode="ansi")
    with pytest.raises(ValueError, match="render_camera=True needs a model with a camera"):
        StageEnv(1, render_camera=True)
    env = StageEnv(1)
    try:
        env.reset(seed=0)
        with pytest.warns(UserWarning, match="render_mode None"):
            assert env.render() is None
    finally:
        env.close()


def test_render_camera_gives_the_waffle_pis_camera_image():
    env = StageEnv(1, model="waffle_pi", render_mode="rgb_array", render_camera=True)
    try:
        env.reset(seed=0)
        env.step(2)
        image = env.render()
        spec = env.robot.camera_spec
        assert image.shape == (spec.height, spec.width, 3) and image.dtype == np.uint8
        assert np.array_equal(image, env.robot.camera_image()[0])
    finally:
        env.close()


HUMAN_SCRIPT = r"""
import json, math, time, warnings
import gymnasium, tutorial_turtlebot.learning
from tutorial_turtlebot.sim.kinematics import yaw_from_quat
from gymnasium.utils.env_checker import check_env
from tutorial_turtlebot.learning import stage_render as sr
env = gymnasium.make("TurtleBot3Stage1-v0", render_mode="human")
start = time.monotonic()
env.reset(seed=0)
for _ in range(3):
    env.step(1)
wall = time.monotonic() - start
window = env.unwrapped._render.window
root = window._root
odom = env.unwrapped.robot.odom()
yaw = yaw_from_quat(odom.orientation)
behind = (odom.position[0] - 0.06 * math.cos(yaw), odom.position[1] - 0.06 * math.sin(yaw))
col, row = env.unwrapped._render.view.world_to_pixel(*behind)   # on the disc, off its bar
shown = root.tk.call(window._label.cget("image"), "get", int(round(col)), int(round(row)))
out = {"open": window.is_open, "title": root.title(), "wall": wall,
       "render": repr(env.render()), "shown": list(shown),
       "size": [int(root.tk.call("image", side, window._label.cget("image")))
                for side in ("width", "height")]}
with warnings.catch_warnings(record=True) as caught:
    warnings.simplefilter("always")
    check_env(env.unwrapped)
out["warnings"] = [str(w.message) for w in caught]
env.close()
out["closed"] = not window.is_open
print(json.dumps(out))
"""


@pytest.mark.skipif(shutil.which("xvfb-run") is None, reason="xvfb-run is not installed")
def test_human_mode_shows_the_picture_in_a_window_under_xvfb():
    done = subprocess.run(["xvfb-run", "-a", sys.executable, "-c", HUMAN_SCRIPT],
                          capture_output=True, text=True, timeout=240,
                          env=dict(os.environ, PYTHONWARNINGS="default"))
    assert done.returncode == 0, done.stderr[-2000:]
    out = json.loads(done.stdout.strip().splitlines()[-1])
    assert out["open"] and out["title"] == "TurtleBot3 stage 1" and out["closed"]
    assert out["size"] == [sr.SIZE, sr.SIZE]
    assert tuple(out["shown"]) == sr.ROBOT                # the robot, where its pose says
    assert out["render"] == "None"
    assert out["wall"] >= 3 * 0.2 - 0.02                  # 4 frames at render_fps 5
    assert out["warnings"] == []                          # check_env: every render mode
