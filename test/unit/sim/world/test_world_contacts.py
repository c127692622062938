"""World models' contact and IMU sensors running in the simulation (world/world_sensors'
BumperRunner and ImuSensorRunner, world/contact_names, engine/contacts, devices/imu): the
fixture world of test/fixtures/world_contacts stepped without a robot. A 2 kg box resting on a
static force plate: the plate's bumper feels its weight, the box's bumper the plate's reaction,
nothing once the box is lifted away; the box's IMU reads gravity's reaction and no rates; a
collision its link does not have is one warning. No ROS master. Units: m, s, N, m/s^2."""
from pathlib import Path

import numpy as np
import pytest

from tutorial_turtlebot.sim.world import reference_frames as rf
from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
from tutorial_turtlebot.sim.world.world_control import WorldControl

import unit_paths

FIXTURE = (Path(unit_paths.ROOT) / "test" / "fixtures" / "world_contacts"
           / "world_contacts.world")
WEIGHT = 2.0 * 9.8     # N, the crate's


@pytest.fixture(scope="module")
def sim():
    simulation = Simulation(SimConfig(world=str(FIXTURE), spawn_robot=False))
    for _ in range(int(round(1.0 / simulation.config.time_step))):   # 1 s: the crate settles
        simulation.step()
    yield simulation
    simulation.close()


def sensor(sim, name):
    return next(s for s in sim.world_sensors.sensors if s.spec.name == name)


def total_force(state):
    return np.sum([force for force, _ in state.wrenches], axis=0)


def test_the_force_plate_feels_the_resting_boxs_weight(sim):
    [state] = sensor(sim, "plate_contact").contacts()
    assert (state.collision1, state.collision2) == ("force_plate::plate::top",
                                                    "crate::body::shell")
    force = total_force(state)
    assert force[2] == pytest.approx(-WEIGHT, rel=0.02)      # pushed down, plate's frame
    assert np.hypot(force[0], force[1]) < 0.01 * WEIGHT
    assert len(state.positions) == len(state.normals) == len(state.depths) >= 3
    for normal, position in zip(state.normals, state.positions):
        np.testing.assert_allclose(normal, (0.0, 0.0, -1.0), atol=1e-3)   # box into plate
        assert abs(position[2] - 0.05) < 0.002 and max(map(abs, position[:2])) < 0.101


def test_the_boxs_own_bumper_feels_the_plates_reaction(sim):
    [state] = sensor(sim, "crate_contact").contacts()
    assert (state.collision1, state.collision2) == ("crate::body::shell",
                                                    "force_plate::plate::top")
    assert total_force(state)[2] == pytest.approx(WEIGHT, rel=0.02)
    np.testing.assert_allclose(state.normals[0], (0.0, 0.0, 1.0), atol=1e-3)
    # the torque about the box's origin (its centre): the points' levers cancel out
    torque = np.sum([t for _, t in state.wrenches], axis=0)
    assert np.all(np.abs(torque) < 0.01 * WEIGHT * 0.1)


def test_the_imu_on_the_resting_box_reads_gravitys_reaction_and_no_rates(sim):
    imu = sensor(sim, "crate_imu")
    assert (imu.spec.frame, imu.spec.topic, imu.spec.robot_namespace, imu.spec.rate) == (
        "crate_imu_link", "imu", "/crate", 50.0)
    imu.reading(sim.time_ns)
    sim.step()
    reading = imu.reading(sim.time_ns)
    np.testing.assert_allclose(reading.linear_acceleration, (0.0, 0.0, 9.8), atol=0.02)
    np.testing.assert_allclose(reading.angular_velocity, (0.0, 0.0, 0.0), atol=1e-3)
    np.testing.assert_allclose(np.abs(reading.orientation), (0.0, 0.0, 0.0, 1.0), atol=1e-3)


def test_a_collision_the_link_does_not_have_is_one_warning_and_no_contacts(sim):
    [warning] = sim.world_sensors.warnings
    assert "'post::link::no_such_collision'" in warning and "\n" not in warning
    assert sensor(sim, "misnamed").contacts() == []


def test_nothing_once_the_box_is_lifted_away(sim):
    control = WorldControl(sim)
    control.set_model_state("crate", ((0.0, 0.0, 3.0), (0.0, 0.0, 0.0, 1.0)), rf.ZERO_TWIST)
    for _ in range(5):
        sim.step()
    assert sensor(sim, "plate_contact").contacts() == []
    assert sensor(sim, "crate_contact").contacts() == []
    imu = sensor(sim, "crate_imu")
    imu.reading(sim.time_ns)
    sim.step()
    falling = imu.reading(sim.time_ns)      # free fall: the accelerometer feels nothing
    np.testing.assert_allclose(falling.linear_acceleration, (0.0, 0.0, 0.0), atol=0.05)
