"""The ROS glue of a robot's sensors that world_sensors runs (gazebo/world_sensor_topics on the
robot of test/fixtures/robot_sensors/probe.urdf, spawned into namespace probe), with stand-in
publishers (no master): gazebo_ros_range's and gazebo_ros_bumper's topics in the spawn's
namespace, their frames the robot's links prefixed as robot_topics prefixes them, nothing read
for a topic nobody subscribes to. Units: m."""
from pathlib import Path

import pytest
import rospy
from gazebo_msgs.msg import ContactsState
from sensor_msgs.msg import Range

from tutorial_turtlebot.gazebo.world_sensor_topics import WorldSensorTopics
from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
from tutorial_turtlebot.sim.world.world_control import WorldControl
from tutorial_turtlebot.sim.world.world_sensors import WORLD_SENSORS

from unit_helpers import RecordingPublisher, at
import unit_paths

FIXTURE = Path(unit_paths.FIXTURES) / "robot_sensors"


@pytest.fixture(scope="module")
def probe():
    sim = Simulation(SimConfig(world=str(FIXTURE / "robot_sensors.world"), spawn_robot=False))
    made = {}

    def make(topic, msg_type, queue_size=1):
        made[topic] = RecordingPublisher(topic, msg_type, queue_size)
        return made[topic]
    topics = WorldSensorTopics(sim, make)
    WorldControl(sim).spawn("probe", (FIXTURE / "probe.urdf").read_text(),
                            at(0.0, 0.0, 0.035), kind="urdf", robot_namespace="probe")
    yield sim, topics, made
    sim.close()


def run(sim, topics, seconds):
    for _ in range(int(round(seconds / sim.config.time_step))):
        for _, output in sim.step():
            if output == WORLD_SENSORS:
                topics.publish(rospy.Time(*divmod(sim.time_ns, 1_000_000_000)))


def test_1_the_topics_in_the_robots_namespace_and_nothing_read_unasked(probe, monkeypatch):
    sim, topics, made = probe
    read = []
    run(sim, topics, 0.05)       # the spawned robot's sensors are advertised
    for sensor in sim.world_sensors.sensors:
        for name in ("contacts", "reading"):
            if hasattr(sensor, name):
                monkeypatch.setattr(sensor, name, lambda *a: read.append(a))
    run(sim, topics, 0.5)
    assert {t: p.msg_type for t, p in made.items()} == {
        "/probe/front/range": Range, "/probe/bumper": ContactsState}
    assert read == [] and not any(p.sent for p in made.values())


def test_2_the_range_reads_the_wall_in_its_links_frame(probe):
    sim, topics, made = probe
    made["/probe/front/range"].connections = 1
    run(sim, topics, 0.1)
    msg = made["/probe/front/range"].sent[-1]
    assert msg.header.frame_id == "probe/sonar_link"
    assert (msg.radiation_type, msg.min_range, msg.max_range) == (Range.ULTRASOUND, 0.02, 3.0)
    assert msg.field_of_view == pytest.approx(0.1)
    assert msg.range == pytest.approx(0.7, abs=0.02)
    assert len(made["/probe/front/range"].sent) == 2       # 20 Hz


def test_3_the_bumper_reports_the_chassis_on_the_floor(probe):
    sim, topics, made = probe
    made["/probe/bumper"].connections = 1
    run(sim, topics, 0.1)
    msg = made["/probe/bumper"].sent[-1]
    assert msg.header.frame_id == "probe/chassis"
    [state] = msg.states
    assert (state.collision1_name, state.collision2_name) == (
        "probe::chassis::chassis_collision", "ground::link::collision")
    assert state.total_wrench.force.z > 1.0
