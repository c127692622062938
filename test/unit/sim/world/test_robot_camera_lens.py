"""A URDF robot's camera with a lens <distortion> and an image <format> (test/fixtures/lens_robot:
lens_camera, barrel k1 -0.25, L8; plain_camera beside it, R8G8B8): read into its CameraSensor
as a world model's camera is, and its image made by the same device code
(image_formats.CameraOutput): the same pixels as a world model's camera (world_sensors'
CameraRunner) at its pose. The TurtleBot3 cameras publish their images as drawn. Units: m."""
from dataclasses import fields
from pathlib import Path

import numpy as np
import pytest

from tutorial_turtlebot.sim.devices.image_formats import CameraOutput, converted
from tutorial_turtlebot.sim.devices.lens_distortion import distort
from tutorial_turtlebot.sim.files.plugins.camera_types import LensDistortion, WorldCamera
from tutorial_turtlebot.sim.files.urdf.urdf_file import read_urdf, urdf_path
from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
from tutorial_turtlebot.sim.world.world_control import WorldControl
from tutorial_turtlebot.sim.world.world_sensors import CameraRunner

from unit_helpers import at, run
import unit_paths

FIXTURE = Path(unit_paths.FIXTURES) / "lens_robot" / "lens_robot.urdf"
WORLD = Path(unit_paths.FIXTURES) / "two_lasers" / "two_lasers.world"    # a red box 1 m ahead
BARREL = LensDistortion(k1=-0.25, crop=False)


@pytest.fixture(scope="module")
def lens_robot():
    sim = Simulation(SimConfig(world=str(WORLD), spawn_robot=False))
    WorldControl(sim).spawn("lens", FIXTURE.read_text(), at(0.0, 0.0), kind="urdf",
                            robot_namespace="lens")
    robot = sim.robots["lens"]
    run(sim, 0.3)
    yield sim, robot
    sim.close()


def test_the_lens_and_format_are_read_as_a_world_cameras_without_a_warning(lens_robot):
    _, robot = lens_robot
    assert robot.warnings == []
    lens, plain = (camera.sensor for camera in robot.cameras)
    assert (lens.name, lens.image_format, lens.lens) == ("lens_camera", "L8", BARREL)
    assert lens.info_distortion == (-0.25, 0.0, 0.0, 0.0, 0.0)      # k1 k2 t1 t2 k3
    assert robot.camera_intrinsics.D() == [-0.25, 0.0, 0.0, 0.0, 0.0]
    assert (plain.image_format, plain.lens, plain.info_distortion) == ("R8G8B8", None,
                                                                       (0.0,) * 5)
    assert robot.cameras[1].image is None and robot.cameras[1].intrinsics.D() == [0.0] * 5


def test_the_robots_distorted_grey_image_is_a_world_cameras_at_its_pose(lens_robot):
    """A world model's camera of the same <camera> and plugin, at the robot camera's pose."""
    sim, robot = lens_robot
    image, depth = robot.camera_image()
    assert image.dtype == np.uint8 and image.shape == (48, 64) and depth is None
    sensor = robot.camera_sensor
    spec = WorldCamera(**{f.name: getattr(sensor, f.name) for f in fields(sensor)})
    world = CameraRunner(spec, robot, sim.physics, np.random.default_rng(0))
    world.pose = lambda: robot.body.pose_in_world(robot.cameras[0].pose)
    assert world.encoding == "mono8"
    assert np.array_equal(world.image(), image)
    undistorted = converted(robot.camera_image(index=1)[0], "L8")
    assert not np.array_equal(image, undistorted)
    assert image[0, 0] == 0 and undistorted[0, 0] > 0     # a barrel's black corner
    assert image[24, 32] == undistorted[24, 32]             # the centre stays


def test_the_box_top_edge_bends_as_brown_model_says(lens_robot):
    """The red box's top edge, a straight line in the undistorted view, bows toward the image
    centre at its ends where the model puts it: the undistorted edge's row moved by
    k1 r^2."""
    _, robot = lens_robot
    undistorted = robot.camera_image(index=1)[0]
    red = undistorted[:, :, 0].astype(int) > 2 * undistorted[:, :, 1].astype(int) + 30
    top = int(np.argmax(red[:, 32]))                  # the edge's first red row, straight
    assert all(int(np.argmax(red[:, col])) == top for col in (8, 56))
    grey = robot.camera_image()[0]
    box = converted(undistorted, "L8")[top + 2, 32]   # the box's grey, below its edge
    seen = np.abs(grey.astype(int) - int(box)) <= 3
    for col in (8, 56):
        u, v = (col + 0.5) / 64, (top + 0.5) / 48
        ud, vd = distort(np.float64(u), np.float64(v), BARREL)
        row, at_col = int(vd * 48), int(ud * 64)
        assert row > top                                    # pulled toward the centre
        assert int(np.argmax(seen[:, at_col])) == pytest.approx(row, abs=1)


@pytest.mark.parametrize("model", ["waffle", "waffle_pi"])
def test_turtlebot3_cameras_publish_their_images_as_drawn(model):
    """R8G8B8 without <distortion>: nothing is made of the drawn image, D stays zero."""
    camera = read_urdf(urdf_path(model)).plugins.camera
    assert (camera.image_format, camera.lens, camera.info_distortion) == ("R8G8B8", None,
                                                                          (0.0,) * 5)
    assert CameraOutput(camera.image_format, camera.lens, 64, 48).plain
