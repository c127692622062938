"""The world models' cameras' ROS glue (gazebo/world_sensor_topics' camera topics) on the fixture
world of test/fixtures/world_cameras, with stand-in publishers and subscribers (no master):
gazebo_ros' topic names, the encodings of the <format>s, a depth camera's image, depth image and
point cloud of one stamp, a multicamera's two images of one stamp, a triggered camera's trigger
subscription and its one image per trigger, CameraInfo's D."""
import math
from pathlib import Path

import numpy as np
import pytest
import rospy
from sensor_msgs.msg import CameraInfo, Image, PointCloud2
from std_msgs.msg import Empty

from tutorial_turtlebot.gazebo.world_sensor_topics import WorldSensorTopics, depth_values
from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
from tutorial_turtlebot.sim.world.world_sensors import WORLD_SENSORS

from unit_helpers import RecordingPublisher
import unit_paths

FIXTURE = Path(unit_paths.ROOT) / "test" / "fixtures" / "world_cameras" / "world_cameras.world"


class StampedPublisher(RecordingPublisher):
    """Records (header stamp, message) pairs."""

    def publish(self, msg):
        self.sent.append((msg.header.stamp, msg))


class FakeSubscriber:
    def __init__(self, topic, msg_type, callback, queue_size):
        self.topic, self.msg_type, self.callback = topic, msg_type, callback
        self.unregistered = False

    def unregister(self):
        self.unregistered = True


@pytest.fixture(scope="module")
def world():
    sim = Simulation(SimConfig(world=str(FIXTURE), spawn_robot=False))
    made, subs = [], []

    def make(topic, msg_type, queue_size=1):
        made.append(StampedPublisher(topic, msg_type, queue_size))
        return made[-1]

    def subscribe(topic, msg_type, callback, queue_size=1):
        subs.append(FakeSubscriber(topic, msg_type, callback, queue_size))
        return subs[-1]
    topics = WorldSensorTopics(sim, make, subscribe)
    yield sim, topics, {p.topic: p for p in made}, subs
    topics.close()
    sim.close()


def run(sim, topics, seconds):
    for _ in range(int(round(seconds / sim.config.time_step))):
        for _, output in sim.step():
            if output == WORLD_SENSORS:
                topics.publish(rospy.Time(*divmod(sim.time_ns, 1_000_000_000)))


def test_the_camera_plugins_topics_and_types(world):
    _, _, pubs, subs = world
    types = {topic: pub.msg_type for topic, pub in pubs.items()}
    assert types == {
        "depth_cam/ir/image_raw": Image, "depth_cam/ir/camera_info": CameraInfo,
        "depth_cam/depth/image_raw": Image, "depth_cam/depth/camera_info": CameraInfo,
        "depth_cam/points": PointCloud2,
        "stereo/left/image_raw": Image, "stereo/left/camera_info": CameraInfo,
        "stereo/right/image_raw": Image, "stereo/right/camera_info": CameraInfo,
        "triggered/image_raw": Image, "triggered/camera_info": CameraInfo,
        "grey/image_raw": Image, "grey/camera_info": CameraInfo,
        "barrel/image_raw": Image, "barrel/camera_info": CameraInfo}
    assert [(s.topic, s.msg_type) for s in subs] == [("triggered/image_trigger", Empty)]


def test_a_depth_cameras_three_outputs_share_one_stamp(world):
    sim, topics, pubs, _ = world
    outputs = [pubs["depth_cam/" + t] for t in ("ir/image_raw", "depth/image_raw", "points",
                                                "depth/camera_info")]
    for pub in outputs:
        pub.connections = 1
    run(sim, topics, 0.3)
    stamps = [[stamp for stamp, _ in pub.sent] for pub in outputs]
    assert len(stamps[0]) >= 2 and all(s == stamps[0] for s in stamps)
    image, depth, points = (pub.sent[-1][1] for pub in outputs[:3])
    assert (image.encoding, image.step, image.header.frame_id) == (
        "rgb8", 3 * 64, "depth_optical_frame")
    metres = np.frombuffer(depth.data, dtype="<f4").reshape(48, 64)
    assert depth.encoding == "32FC1" and metres[24, 32] == pytest.approx(2.0, abs=0.01)
    assert (points.width, points.height, points.point_step) == (64, 48, 32)
    xyz = np.frombuffer(points.data, dtype="<f4").reshape(-1, 8)[:, :3]
    assert xyz[24 * 64 + 32, 2] == pytest.approx(2.0, abs=0.01)
    for pub in outputs:
        pub.connections = 0


def test_a_multicameras_two_images_have_one_stamp(world):
    sim, topics, pubs, _ = world
    left, right = pubs["stereo/left/image_raw"], pubs["stereo/right/image_raw"]
    info = pubs["stereo/right/camera_info"]
    for pub in (left, right, info):
        pub.connections = 1
    run(sim, topics, 0.5)
    assert len(left.sent) >= 2
    assert [s for s, _ in left.sent] == [s for s, _ in right.sent] == [s for s, _ in info.sent]
    assert left.sent[-1][1].data != right.sent[-1][1].data
    assert info.sent[-1][1].P[3] == pytest.approx(-55.438 * 0.07, abs=1e-3)
    for pub in (left, right, info):
        pub.connections = 0


def test_a_triggered_camera_publishes_one_image_per_trigger_and_none_before(world):
    sim, topics, pubs, subs = world
    image = pubs["triggered/image_raw"]
    image.connections = 1
    run(sim, topics, 0.5)
    assert image.sent == []
    subs[0].callback(Empty())
    run(sim, topics, 0.5)
    assert len(image.sent) == 1 and image.sent[0][1].encoding == "bgr8"
    subs[0].callback(Empty())
    subs[0].callback(Empty())
    run(sim, topics, 0.5)
    assert len(image.sent) == 3
    image.connections = 0


def test_format_encodings_and_distortion_in_camera_info(world):
    sim, topics, pubs, _ = world
    grey, barrel = pubs["grey/image_raw"], pubs["barrel/camera_info"]
    grey.connections = barrel.connections = 1
    run(sim, topics, 0.15)
    image = grey.sent[-1][1]
    assert (image.encoding, image.step, image.is_bigendian) == ("mono16", 128, 0)
    assert len(image.data) == 128 * 48
    assert list(barrel.sent[-1][1].D) == [-0.2, 0.05, 0.002, -0.001, 0.01]
    grey.connections = barrel.connections = 0


def test_depth_values_are_the_plugins_nan_or_millimetres():
    metres = np.array([[0.3, 2.0, math.inf]], dtype=np.float32)
    floats = depth_values(metres, 0.4, False)
    assert np.isnan(floats[0, 0]) and floats[0, 1] == 2.0 and floats[0, 2] == math.inf
    assert depth_values(metres, 0.4, True).tolist() == [[0, 2000, 0]]
    # openni_kinect's: NaN (0) at or beyond its pointCloudCutoffMax too
    kinect = depth_values(metres, 0.4, False, 5.0)
    assert np.isnan(kinect[0, 0]) and kinect[0, 1] == 2.0 and np.isnan(kinect[0, 2])
    assert depth_values(metres, 0.4, True, 1.5).tolist() == [[0, 0, 0]]
