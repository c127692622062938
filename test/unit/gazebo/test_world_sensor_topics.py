"""The world models' sensors' ROS glue (gazebo/world_sensor_topics) on the fixture world of
test/fixtures/world_sensors, with stand-in publishers (no master): gazebo_ros' topic names and
frames, the messages' fields and stamps, nothing cast or rendered for a topic nobody subscribes
to, a spawned model's topics advertised and a deleted one's taken back."""
import math
from pathlib import Path

import numpy as np
import pytest
import rospy
from sensor_msgs.msg import CameraInfo, Image, LaserScan, PointCloud, Range

from tutorial_turtlebot.gazebo.world_sensor_topics import WorldSensorTopics
from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
from tutorial_turtlebot.sim.world.world_control import WorldControl
from tutorial_turtlebot.sim.world.world_sensors import WORLD_SENSORS

from unit_helpers import RecordingPublisher
import unit_paths

FIXTURE = Path(unit_paths.ROOT) / "test" / "fixtures" / "world_sensors" / "world_sensors.world"


class StampedPublisher(RecordingPublisher):
    """Records (header stamp, message) pairs."""

    def publish(self, msg):
        self.sent.append((msg.header.stamp, msg))


@pytest.fixture
def world():
    sim = Simulation(SimConfig(world=str(FIXTURE), spawn_robot=False))
    made = []

    def make(topic, msg_type, queue_size=1):
        made.append(StampedPublisher(topic, msg_type, queue_size))
        return made[-1]
    topics = WorldSensorTopics(sim, make)
    yield sim, topics, made
    sim.close()


def run(sim, topics, seconds):
    for _ in range(int(round(seconds / sim.config.time_step))):
        for robot, output in sim.step():
            if output == WORLD_SENSORS:
                topics.publish(rospy.Time(*divmod(sim.time_ns, 1_000_000_000)))


def by_topic(made):
    return {p.topic: p for p in made if not p.unregistered}


def test_each_plugin_advertises_its_gazebo_ros_topics(world):
    _, _, made = world
    assert {t: p.msg_type for t, p in by_topic(made).items()} == {
        "overhead/image_raw": Image, "overhead/camera_info": CameraInfo,   # cameraName/...
        "sonar": Range, "sonar_free": Range,
        "/profiler_cloud": PointCloud,                                     # robotNamespace /
        "rover/scan": LaserScan}


def test_nothing_is_cast_or_rendered_while_nobody_subscribes(world, monkeypatch):
    sim, topics, made = world
    looked = []
    for sensor in sim.world_sensors.sensors:
        monkeypatch.setattr(sensor, "pose", lambda s=sensor: looked.append(s) or (0, 0))
    run(sim, topics, 1.0)
    assert looked == [] and not any(p.sent for p in made)


def test_a_range_message_has_gazebo_ros_ranges_fields(world):
    sim, topics, made = world
    pubs = by_topic(made)
    pubs["sonar"].connections = pubs["sonar_free"].connections = 1
    run(sim, topics, 0.5)
    stamps = [stamp.to_sec() for stamp, _ in pubs["sonar"].sent]
    np.testing.assert_allclose(stamps, [0.0025, 0.1, 0.2, 0.3, 0.4, 0.5])   # 10 Hz of sim time
    msg = pubs["sonar"].sent[-1][1]
    assert (msg.header.frame_id, msg.radiation_type, msg.min_range, msg.max_range) == (
        "sonar_link", Range.INFRARED, 0.02, 2.0)
    assert msg.field_of_view == pytest.approx(0.2)
    assert abs(msg.range - 0.5) < 0.02
    free = pubs["sonar_free"].sent[-1][1]
    assert (free.header.frame_id, free.radiation_type, free.range, free.field_of_view) == (
        "world", Range.ULTRASOUND, free.max_range, 0.05)


def test_the_cloud_image_and_scan_messages(world):
    sim, topics, made = world
    pubs = by_topic(made)
    for topic in ("/profiler_cloud", "overhead/image_raw", "overhead/camera_info",
                  "rover/scan"):
        pubs[topic].connections = 1
    run(sim, topics, 0.3)
    cloud = pubs["/profiler_cloud"].sent[-1][1]
    assert cloud.header.frame_id == "profiler_frame" and len(cloud.points) == 200
    norms = [math.sqrt(p.x ** 2 + p.y ** 2 + p.z ** 2) for p in cloud.points]
    assert 0.4 < min(norms) and max(norms) <= 1.0 + 1e-5
    assert [c.name for c in cloud.channels] == [""] and len(cloud.channels[0].values) == 200
    image = pubs["overhead/image_raw"].sent[-1][1]
    assert (image.encoding, image.width, image.height, image.step, image.header.frame_id) == (
        "rgb8", 160, 120, 480, "overhead_optical_frame")
    pixels = np.frombuffer(image.data, np.uint8).reshape(120, 160, 3)
    assert pixels[60, 80, 0] > 150 and pixels[60, 80, 1] < 60
    info = pubs["overhead/camera_info"].sent[-1]
    assert info[0] == pubs["overhead/image_raw"].sent[-1][0]       # one stamp for both
    assert info[1].K[0] == pytest.approx(160 / (2 * math.tan(1.047 / 2)))
    scan = pubs["rover/scan"].sent[-1][1]
    assert (scan.header.frame_id, len(scan.ranges), scan.range_max) == ("rover_lidar", 4, 5.0)
    assert scan.ranges[3] == pytest.approx(2.75, abs=0.01)


def test_a_spawned_models_topics_come_and_go_with_it(world):
    sim, topics, made = world
    control = WorldControl(sim)
    control.spawn("probe", '<sdf version="1.6"><model name="x"><static>1</static><link '
                  'name="l"><sensor name="s" type="ray"><ray><scan><horizontal><samples>1'
                  '</samples></horizontal></scan><range><min>0.1</min><max>1</max></range>'
                  '</ray><plugin name="p" filename="libgazebo_ros_range.so"><robotNamespace>'
                  'probe</robotNamespace><topicName>range</topicName></plugin></sensor>'
                  '</link></model></sdf>', ((0.0, -5.0, 1.0), (0.0, 0.0, 0.0, 1.0)))
    run(sim, topics, 0.01)
    spawned = by_topic(made)["probe/range"]
    control.delete("probe")
    run(sim, topics, 0.01)
    assert spawned.unregistered and "probe/range" not in by_topic(made)
    assert "sonar" in by_topic(made)
