"""The ROS glue of world models' contact and IMU sensors (gazebo/world_sensor_topics'
_BumperTopic and _ImuSensorTopic) on the fixture world of test/fixtures/world_contacts, with
stand-in publishers (no master): gazebo_ros_bumper's and gazebo_ros_imu_sensor's topic names,
frames and fields, nothing read for a topic nobody subscribes to. Units: N, m/s^2, rad/s."""
from pathlib import Path

import pytest
import rospy
from gazebo_msgs.msg import ContactsState
from sensor_msgs.msg import Imu

from tutorial_turtlebot.gazebo.world_sensor_topics import WorldSensorTopics
from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
from tutorial_turtlebot.sim.world.world_sensors import WORLD_SENSORS

from unit_helpers import RecordingPublisher
import unit_paths

FIXTURE = (Path(unit_paths.ROOT) / "test" / "fixtures" / "world_contacts"
           / "world_contacts.world")


@pytest.fixture(scope="module")
def world():
    sim = Simulation(SimConfig(world=str(FIXTURE), spawn_robot=False))
    made = {}

    def make(topic, msg_type, queue_size=1):
        made[topic] = RecordingPublisher(topic, msg_type, queue_size)
        return made[topic]
    topics = WorldSensorTopics(sim, make)
    yield sim, topics, made
    sim.close()


def run(sim, topics, seconds):
    for _ in range(int(round(seconds / sim.config.time_step))):
        for _, output in sim.step():
            if output == WORLD_SENSORS:
                topics.publish(rospy.Time(*divmod(sim.time_ns, 1_000_000_000)))


def test_1_the_topics_and_nothing_read_while_nobody_subscribes(world, monkeypatch):
    sim, topics, made = world
    assert {t: p.msg_type for t, p in made.items()} == {
        "plate_contacts": ContactsState, "crate_contacts": ContactsState,
        "bumper_states": ContactsState, "/crate/imu": Imu}
    read = []
    for sensor in sim.world_sensors.sensors:
        for name in ("contacts", "reading"):
            if hasattr(sensor, name):
                monkeypatch.setattr(sensor, name, lambda *a: read.append(a))
    run(sim, topics, 1.0)        # the crate settles
    assert read == [] and not any(p.sent for p in made.values())


def test_2_the_plates_contacts_state(world):
    sim, topics, made = world
    made["plate_contacts"].connections = 1
    run(sim, topics, 0.1)
    msg = made["plate_contacts"].sent[-1]
    assert msg.header.frame_id == "world" and msg.header.stamp.to_nsec() == sim.time_ns
    [state] = msg.states
    assert (state.collision1_name, state.collision2_name) == ("force_plate::plate::top",
                                                              "crate::body::shell")
    assert state.total_wrench.force.z == pytest.approx(-19.6, rel=0.02)
    assert state.total_wrench.force.z == pytest.approx(sum(w.force.z for w in state.wrenches))
    assert len(state.wrenches) == len(state.contact_positions) == len(state.depths)
    assert state.contact_normals[0].z == pytest.approx(-1.0, abs=1e-3)
    assert "my geom:force_plate::plate::top" in state.info
    assert made["crate_contacts"].sent == []


def test_3_the_imu_message(world):
    sim, topics, made = world
    made["/crate/imu"].connections = 1
    run(sim, topics, 0.1)
    msg = made["/crate/imu"].sent[-1]
    assert msg.header.frame_id == "crate_imu_link"
    assert msg.linear_acceleration.z == pytest.approx(9.8, abs=0.02)
    assert abs(msg.angular_velocity.x) + abs(msg.angular_velocity.y) < 1e-3
    assert msg.orientation.w == pytest.approx(1.0, abs=1e-3)
    assert list(msg.orientation_covariance) == [0.0] * 9      # gaussianNoise 0
    assert len(made["/crate/imu"].sent) == 5                   # 50 Hz of sim time
