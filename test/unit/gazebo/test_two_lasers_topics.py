"""The ROS names of a robot with two lasers and two cameras (test/fixtures/two_lasers), spawned
in namespace twin: each sensor on its own topics, in its own frame, cast or rendered only for
a subscriber (no master: stand-in publishers; a real Simulation)."""
from pathlib import Path

import pytest
import rospy

from tutorial_turtlebot.gazebo import robot_topics
from tutorial_turtlebot.gazebo.robot_topics import RobotTopics
from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
from tutorial_turtlebot.sim.world.world_control import WorldControl

from unit_helpers import RecordingPublisher, at, run
import unit_paths

FIXTURE = Path(unit_paths.FIXTURES) / "two_lasers"


@pytest.fixture
def twin(monkeypatch):
    monkeypatch.setattr(robot_topics.rospy, "Subscriber", RecordingPublisher)
    sim = Simulation(SimConfig(world=str(FIXTURE / "two_lasers.world"), spawn_robot=False))
    WorldControl(sim).spawn("twin", (FIXTURE / "two_lasers.urdf").read_text(), at(0.0, 0.0),
                            kind="urdf", robot_namespace="twin")
    run(sim, 0.3)
    topics = RobotTopics(sim.robots["twin"], RecordingPublisher, RecordingPublisher("/tf"))
    yield topics, {pub.name: pub for pub in topics._advertised}
    sim.close()


def test_each_laser_on_its_topic_in_its_frame(twin):
    topics, pubs = twin
    assert topics.pubs["scan"].name == "/twin/front/scan"
    assert topics.pubs["scan:1"].name == "/twin/rear/scan"
    for pub in pubs.values():
        pub.connections = 1
    stamp = rospy.Time(1)
    topics.publishers["scan"](stamp)
    topics.publishers["scan:1"](stamp)
    front, = pubs["/twin/front/scan"].sent
    rear, = pubs["/twin/rear/scan"].sent
    assert (front.header.frame_id, rear.header.frame_id) == ("twin/front_laser_link",
                                                             "twin/rear_laser_link")
    assert front.ranges[90] == pytest.approx(1.0, abs=0.03)
    assert rear.ranges[90] == pytest.approx(2.0, abs=0.03)
    assert topics.sensor_updates["scan"] == topics.sensor_updates["scan:1"] == 1


def test_each_camera_on_its_topics_in_its_frame(twin):
    topics, pubs = twin
    front, rear = "/twin/front_camera/image_raw", "/twin/rear_camera/rgb/image_raw"
    depth = "/twin/rear_camera/depth/image_raw"
    for name in (front, rear, depth):
        pubs[name].connections = 1
    stamp = rospy.Time(1)
    topics.publishers["camera"](stamp)
    topics.publishers["camera:1"](stamp)
    (front_image,), (rear_image,), (depth_image,) = (pubs[n].sent for n in (front, rear, depth))
    assert front_image.header.frame_id == "twin/front_camera_link"
    assert rear_image.header.frame_id == depth_image.header.frame_id == "twin/rear_camera_link"
    assert (front_image.width, front_image.height, depth_image.encoding) == (80, 60, "32FC1")
    assert topics.sensor_updates["camera"] == topics.sensor_updates["camera:1"] == 1


def test_nothing_is_cast_or_rendered_without_a_subscriber(twin, monkeypatch):
    topics, pubs = twin
    robot = topics.robot

    def refused(*_args, **_kwargs):
        raise AssertionError("a sensor read for nobody")
    monkeypatch.setattr(robot, "scan", refused)
    monkeypatch.setattr(robot, "camera_image", refused)
    for name in ("scan", "scan:1", "camera", "camera:1"):
        topics.publishers[name](rospy.Time(1))
    assert not any(pub.sent for pub in pubs.values())
