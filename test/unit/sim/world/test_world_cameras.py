"""World models' cameras running in the simulation (world/world_sensors' camera runners) on the
fixture world of test/fixtures/world_cameras, a red box under cameras 2 m above its top: a depth
camera's image and depth of one render, a multicamera's two views a baseline apart, a triggered
camera due once per trigger and never without one, a 16-bit grey image, a barrel-distorted
image. No ROS master. Units: m, s."""
from pathlib import Path

import numpy as np
import pytest

from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
from tutorial_turtlebot.sim.world.world_sensors import WORLD_SENSORS, TriggerSchedule

import unit_paths

FIXTURE = Path(unit_paths.ROOT) / "test" / "fixtures" / "world_cameras" / "world_cameras.world"
RED = [247, 0, 0]           # the box's red as the renderer lights it from above


@pytest.fixture(scope="module")
def sim():
    simulation = Simulation(SimConfig(world=str(FIXTURE), spawn_robot=False))
    yield simulation
    simulation.close()


def camera(sim, name):
    return next(s for s in sim.world_sensors.sensors if s.spec.name == name)


def due_names(sim, steps):
    names = []
    for _ in range(steps):
        for _, output in sim.step():
            if output == WORLD_SENSORS:
                names.extend(s.spec.name for s in sim.world_sensors.due_now)
    return names


def test_each_camera_has_its_plugins_runner(sim):
    kinds = {s.spec.name: s.kind for s in sim.world_sensors.sensors}
    assert kinds == {"depth_camera": "depth_camera", "stereo_camera": "multicamera",
                     "triggered_camera": "triggered_camera", "grey_camera": "camera",
                     "barrel_camera": "camera"}


def test_a_depth_cameras_image_and_depth_are_of_one_render(sim):
    depth_camera = camera(sim, "depth_camera")
    pixels, depth = depth_camera.frame(depth=True)
    assert pixels.shape == (48, 64, 3) and depth.shape == (48, 64)
    assert pixels[24, 32].tolist() == RED
    assert depth[24, 32] == pytest.approx(2.0, abs=0.01)     # the box's top
    assert depth[1, 1] > 2.4                                  # the ground around it
    assert depth_camera.frame()[1] is None


def test_a_multicameras_right_view_is_its_baseline_to_the_side(sim):
    stereo = camera(sim, "stereo_camera")
    left, right = stereo.images([True, True])
    red_cols = [np.flatnonzero(image[24, :, 1] < 50) for image in (left, right)]
    # 0.07 m to the right at 2 m: the box 55.4 px * 0.07 / 2 = 1.9 px to the left
    assert red_cols[0].mean() - red_cols[1].mean() == pytest.approx(1.9, abs=0.6)
    assert stereo.cameras[0].intrinsics.P()[3] == 0.0
    assert stereo.cameras[1].intrinsics.P()[3] == pytest.approx(-55.438 * 0.07, abs=1e-3)
    assert stereo.images([False, True])[0] is None


def test_image_formats_and_lens_distortion_on_the_rendered_image(sim):
    grey = camera(sim, "grey_camera")
    image = grey.image()
    assert image.dtype == np.dtype("<u2") and image.shape == (48, 64)
    assert image[24, 32] == round(0.299 * 247) * 257
    assert (grey.encoding, grey.pixel_bytes) == ("mono16", 2)
    triggered = camera(sim, "triggered_camera")
    assert triggered.image()[24, 32].tolist() == RED[::-1]       # B8G8R8: bgr8
    barrel = camera(sim, "barrel_camera")
    distorted = barrel.image()
    assert distorted[0, 0].tolist() == [0, 0, 0]                 # a barrel's black corner
    assert distorted[32, 32].tolist() == RED
    assert barrel.intrinsics.D() == [-0.2, 0.05, 0.002, -0.001, 0.01]


def test_a_triggered_camera_is_due_once_per_trigger_and_never_without_one(sim):
    triggered = camera(sim, "triggered_camera")
    assert "triggered_camera" not in due_names(sim, 200)
    triggered.trigger()
    names = due_names(sim, 200)
    assert names.count("triggered_camera") == 1
    triggered.trigger()
    triggered.trigger()
    assert due_names(sim, 2).count("triggered_camera") == 2      # one a step
    assert "triggered_camera" not in due_names(sim, 200)


def test_a_trigger_schedule_counts_its_triggers():
    schedule = TriggerSchedule(step_ns=1000)
    assert not schedule.due(0) and schedule.next_ns == 1000
    schedule.trigger()
    schedule.trigger()
    assert [schedule.due(t) for t in (1000, 2000, 3000)] == [True, True, False]
