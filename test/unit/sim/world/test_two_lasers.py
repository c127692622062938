"""A robot with two lasers and two cameras (test/fixtures/two_lasers): every sensor runs, each
from its own link, at its own rate, with its own noise. Spawned as spawn_model spawns it in a
world with a red box whose face is 1 m ahead of the front laser and a blue one 2 m behind the
rear laser. Units: m, s."""
from pathlib import Path

import numpy as np
import pytest

from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
from tutorial_turtlebot.sim.world.world_control import WorldControl

from unit_helpers import at, run
import unit_paths

FIXTURE = Path(unit_paths.FIXTURES) / "two_lasers"
AHEAD = 90          # the middle of each laser's 181 rays over -90..90 degrees: straight out


@pytest.fixture(scope="module")
def twin():
    sim = Simulation(SimConfig(world=str(FIXTURE / "two_lasers.world"), spawn_robot=False))
    WorldControl(sim).spawn("twin", (FIXTURE / "two_lasers.urdf").read_text(), at(0.0, 0.0),
                            kind="urdf", robot_namespace="twin")
    robot = sim.robots["twin"]
    run(sim, 0.5)
    yield sim, robot
    sim.close()


def test_every_laser_and_camera_is_read_without_a_warning(twin):
    _, robot = twin
    assert robot.warnings == []
    assert [(laser.sensor.name, laser.sensor.topic, laser.sensor.frame, laser.output)
            for laser in robot.lasers] == [
        ("front_scan", "front/scan", "front_laser_link", "scan"),
        ("rear_scan", "rear/scan", "rear_laser_link", "scan:1")]
    assert [(c.sensor.name, c.sensor.camera_name, c.spec.depth, c.output)
            for c in robot.cameras] == [("front_camera", "front_camera", False, "camera"),
                                        ("rear_camera", "rear_camera", True, "camera:1")]
    # the single-sensor names are the first's
    assert robot.laser_sensor.name == "front_scan" and robot.camera_sensor.name == "front_camera"


def test_each_laser_looks_its_own_way(twin):
    """Front: the red box 1 m ahead; rear: the blue box 2 m behind; either scan through
    ``scan()`` and ``scan(index)``."""
    _, robot = twin
    front, rear = robot.scan(), robot.scan(1)
    assert len(front) == len(rear) == 181
    assert front[AHEAD] == pytest.approx(1.0, abs=0.03)
    assert rear[AHEAD] == pytest.approx(2.0, abs=0.03)
    assert robot.scan(0)[AHEAD] == pytest.approx(1.0, abs=0.03)


def test_each_sensor_runs_at_its_own_rate(twin):
    sim, _ = twin
    counts = run(sim, 1.0)
    assert counts[("twin", "scan")] == 10 and counts[("twin", "scan:1")] == 5
    assert counts[("twin", "camera")] == 10 and counts[("twin", "camera:1")] == 5


def test_each_camera_sees_its_own_box(twin):
    """The front camera's middle is the red box; the rear camera's the blue one, its depth
    that box's face 2.03 m behind the camera (x -0.12 m on the chassis)."""
    _, robot = twin
    front, _ = robot.camera_image()
    rear, depth = robot.camera_image(depth=True, index=1)
    assert front.shape == rear.shape == (60, 80, 3)
    red, blue = front[30, 40].astype(int), rear[30, 40].astype(int)
    assert red[0] > 2 * max(red[1], red[2]), red
    assert blue[2] > 2 * max(blue[0], blue[1]), blue
    assert depth[30, 40] == pytest.approx(2.03, abs=0.02)


def test_a_further_laser_has_its_own_seeded_noise(twin):
    """The rear laser's noise comes from its own generator: reseeded, the same draws; and
    drawing it leaves the first laser's (the robot's generator, shared with the IMU) as it
    was."""
    _, robot = twin
    robot.reseed(7)
    front, rear = robot.scan(), robot.scan(1)
    assert not np.array_equal(rear, robot.scan(1))          # noisy: each scan draws anew
    robot.reseed(7)
    assert np.array_equal(robot.scan(1), rear)              # the rear first this time ...
    assert np.array_equal(robot.scan(), front)              # ... the front's draws unchanged
