"""sim/world/spawn_check.py: a robot spawned on a raised floor stands on it, as Gazebo's physics would
put it; a shape higher than a step stays an obstacle that refuses the spawn."""
import pytest

from tutorial_turtlebot.errors import WorldError
from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
from tutorial_turtlebot.sim.world.spawn_check import MAX_STEP, check_spawn, resting_height
from tutorial_turtlebot.sim.files.world_sdf import load_world


def floor_world(tmp_path, top, tilt=0.0):
    """An empty world whose floor is a static 4 x 4 m box with its top at ``top`` m."""
    path = tmp_path / "raised.world"
    path.write_text(
        '<sdf version="1.6"><world name="raised"><include><uri>model://ground_plane</uri>'
        '</include><model name="floor"><static>true</static><pose>0 0 %g %g 0 0</pose>'
        '<link name="link"><collision name="c"><geometry><box><size>4 4 0.2</size></box>'
        '</geometry></collision></link></model></world></sdf>' % (top - 0.1, tilt))
    return str(path)


def test_a_spawn_on_a_raised_floor_is_lifted_onto_it(tmp_path):
    world = load_world(floor_world(tmp_path, 0.013))
    assert resting_height(world, 0.0, 0.0, 0.1) == pytest.approx(0.013)
    check_spawn(world, 0.0, 0.0, 0.1, z=0.013)                 # clear once on it
    assert resting_height(world, 0.0, 0.0, 0.1, z=0.5) == 0.5  # above it: as given


def test_the_robot_starts_standing_on_the_raised_floor(tmp_path):
    sim = Simulation(SimConfig(model="burger", world=floor_world(tmp_path, 0.013), x=0.0, y=0.0))
    try:
        assert sim.spawn[2] == pytest.approx(0.013)
        for _ in range(400):
            sim.step()
        assert sim.robot.ground_truth()[0][2] == pytest.approx(0.013, abs=0.005)
    finally:
        sim.close()


def test_a_shape_higher_than_a_step_stays_an_obstacle(tmp_path):
    world = load_world(floor_world(tmp_path, MAX_STEP + 0.02))
    assert resting_height(world, 0.0, 0.0, 0.1) == 0.0
    with pytest.raises(WorldError, match="is inside floor::link::c"):
        check_spawn(world, 0.0, 0.0, 0.1)


def test_a_tilted_shape_is_no_floor(tmp_path):
    world = load_world(floor_world(tmp_path, 0.013, tilt=0.3))
    assert resting_height(world, 0.0, 0.0, 0.1) == 0.0
