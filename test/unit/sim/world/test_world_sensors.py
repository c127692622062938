"""World models' sensors running in the simulation (world/world_sensors): the fixture world of
test/fixtures/world_sensors stepped without a robot. A range sensor 0.5 m before a box and one
facing nothing, a block laser's clipping, an overhead camera's image of a red box, a laser on a
movable model, each at its rate; spawned and deleted models' sensors; a reset. No ROS master.
Units: m, s, rad."""
import math
from pathlib import Path

import numpy as np
import pytest

from tutorial_turtlebot.sim.world import reference_frames as rf
from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
from tutorial_turtlebot.sim.world.world_control import WorldControl
from tutorial_turtlebot.sim.world.world_sensors import WORLD_SENSORS

import unit_paths

FIXTURE = Path(unit_paths.ROOT) / "test" / "fixtures" / "world_sensors" / "world_sensors.world"
SONAR_SDF = '''<sdf version="1.6"><model name="x"><static>true</static><link name="l">
<sensor name="spawned_sonar" type="ray"><update_rate>50</update_rate><ray><scan><horizontal>
<samples>1</samples></horizontal></scan><range><min>0.05</min><max>3</max></range></ray>
<plugin name="p" filename="libgazebo_ros_range.so"><topicName>spawned</topicName></plugin>
</sensor></link></model></sdf>'''


@pytest.fixture(scope="module")
def sim():
    simulation = Simulation(SimConfig(world=str(FIXTURE), spawn_robot=False))
    yield simulation
    simulation.close()


def sensor(sim, name):
    return next(s for s in sim.world_sensors.sensors if s.spec.name == name)


def ticks(sim, steps):
    """{sensor name: ticks} over ``steps`` physics steps."""
    counts = {}
    for _ in range(steps):
        for robot, output in sim.step():
            if output == WORLD_SENSORS:
                for due in sim.world_sensors.due_now:
                    counts[due.spec.name] = counts.get(due.spec.name, 0) + 1
    return counts


def test_each_sensor_ticks_at_its_rate_of_sim_time(sim):
    steps = int(round(2.0 / sim.config.time_step)) - 1   # 2 s of sim time: ticks at 0, ...
    counts = ticks(sim, steps)
    # the camera's updateRate 5 (its sensor's 10), the sonar's 10 (its sensor's 20)
    assert counts == {"overhead_camera": 10, "sonar": 20, "sonar_free": 20, "profiler": 10,
                      "lidar": 10}


def test_a_range_sensor_half_a_metre_before_a_box_reads_half_a_metre(sim):
    sonar = sensor(sim, "sonar")
    readings = np.array([sonar.reading() for _ in range(50)])
    assert np.all(np.abs(readings - 0.5) < 4 * 0.005), readings       # gaussianNoise 0.005
    assert abs(readings.mean() - 0.5) < 0.003 and readings.std() > 0.002
    np.testing.assert_allclose(sonar.ranges().min(), 0.5, atol=1e-6)   # without the noise


def test_a_range_sensor_facing_nothing_reads_its_max_range_exactly(sim):
    """gazebo_ros_range: nothing hit is range_max itself, with no noise."""
    assert sensor(sim, "sonar_free").reading() == 2.0
    assert sensor(sim, "sonar_free").radiation_type == 0 and sensor(sim, "sonar").radiation_type


def test_the_block_lasers_points_lie_within_min_and_max_range(sim):
    points, channel = sensor(sim, "profiler").cloud()
    assert points.shape == (200, 3) and channel.shape == (200,)
    norms = np.linalg.norm(points, axis=1)
    assert np.all((norms > 0.4 - 1e-5) & (norms < 1.0 + 1e-5)), norms
    # the step's top 0.7 m below the sensor (its x looks down); the floor, 1.2 m away, is
    # beyond range_max: those rays read range_max
    on_step = norms < 0.8
    assert 10 < on_step.sum() < 190
    # x looks straight down: the step's points 0.7 m along it (at the plugin's angles, half a
    # ray step on from the rays that hit), its rays 0.7 m / cos(their angle) long
    assert np.all((points[on_step, 0] > 0.69) & (norms[on_step] < 0.76))
    np.testing.assert_allclose(norms[~on_step], 1.0, atol=1e-6)


def test_an_overhead_camera_sees_the_red_box_in_the_middle_and_the_ground_around(sim):
    camera = sensor(sim, "overhead_camera")
    image = camera.image()
    assert image.shape == (120, 160, 3) and image.dtype == np.uint8
    red = (image[:, :, 0] > 150) & (image[:, :, 1] < 60) & (image[:, :, 2] < 60)
    # the box's top, 0.5 m wide, 2 m away: about 0.5 / (2 tan(hfov / 2)) of the width
    assert red[50:70, 70:90].all()
    width = red[60].sum()
    assert abs(width - 160 * 0.5 / (2 * 2.0 * math.tan(1.047 / 2))) < 4, width
    corners = image[[2, 2, -3, -3], [2, -3, 2, -3]]
    assert not red[[2, 2, -3, -3], [2, -3, 2, -3]].any()
    assert np.all(np.abs(corners.astype(int) - corners[0].astype(int)) < 10)   # the ground
    assert camera.intrinsics.width == 160 and camera.intrinsics.cx == 80.5


def test_a_laser_on_a_movable_model_follows_its_link(sim):
    lidar = sensor(sim, "lidar")
    scan = lidar.scan()
    # from (0, 3, 0.25) along -y: the red box's face at y 0.25
    assert scan[3] == pytest.approx(2.75, abs=0.01)
    assert np.isinf(scan[:3]).all()
    rover = sim.models.get("rover")
    rover.set_state(((3.0, 2.0, 0.1), (0.0, 0.0, 0.0, 1.0)), rf.ZERO_TWIST)
    # now along -y from (3, 2): the target box (x 3.5..3.7) is not there; the sonar post has
    # no collision; the red box is behind: nothing
    assert sensor(sim, "lidar").scan()[3] == math.inf
    rover.set_state(((2.0, 0.0, 0.1), (0.0, 0.0, 0.0, 1.0)), rf.ZERO_TWIST)
    assert sensor(sim, "lidar").scan()[0] == pytest.approx(1.5, abs=0.01)   # the target's face


def test_a_spawned_models_sensors_run_until_it_is_deleted():
    sim = Simulation(SimConfig(world=str(FIXTURE), spawn_robot=False))
    try:
        control = WorldControl(sim)
        before = len(sim.world_sensors.sensors)
        control.spawn("probe", SONAR_SDF, ((3.6, -1.0, 0.25), (0.0, 0.0, 0.7071068, 0.7071068)))
        counts = ticks(sim, int(round(0.2 / sim.config.time_step)))
        assert counts["spawned_sonar"] == 10          # 50 Hz
        spawned = sensor(sim, "spawned_sonar")
        assert spawned.spec.link == "probe::l"
        # facing +y from (3.6, -1): the target box (y -0.5..0.5) 0.5 m away
        assert spawned.reading() == pytest.approx(0.5, abs=1e-5)
        generation = sim.world_sensors.generation
        control.delete("probe")
        ticks(sim, 4)
        assert len(sim.world_sensors.sensors) == before
        assert sim.world_sensors.generation == generation + 1
    finally:
        sim.close()


def test_a_reset_starts_every_schedule_again(sim):
    ticks(sim, 7)
    sim.reset_simulation()
    assert sim.time_ns == 0
    assert sim.world_sensors.next_ns == 0
    due = [s.spec.name for r, o in sim.step() if o == WORLD_SENSORS
           for s in sim.world_sensors.due_now]
    assert sorted(due) == ["lidar", "overhead_camera", "profiler", "sonar", "sonar_free"]
