"""The camera's ROS glue renders only for subscribers (no master: stand-in publishers)."""
import numpy as np
import pytest
import rospy

from tutorial_turtlebot.sim.devices.camera import CameraIntrinsics
from tutorial_turtlebot.gazebo.camera_publisher import CameraPublisher
from tutorial_turtlebot.sim.files.urdf.urdf_file import read_urdf, urdf_path


class FakePublisher:
    def __init__(self, topic, msg_type, queue_size):
        self.topic, self.connections, self.sent = topic, 0, []

    def get_num_connections(self):
        return self.connections

    def publish(self, msg):
        self.sent.append(msg)


class FakeSim:
    """Counts renders; returns a flat image and a 2 m depth."""

    def __init__(self, model):
        self.camera_sensor = read_urdf(urdf_path(model)).plugins.camera
        self.camera_spec = self.camera_sensor.spec
        self.camera_intrinsics = CameraIntrinsics.from_spec(self.camera_spec)
        self.renders = []

    def camera_image(self, depth=False):
        self.renders.append(depth)
        h, w = self.camera_spec.height, self.camera_spec.width
        return (np.full((h, w, 3), 100, np.uint8),
                np.full((h, w), 2.0, np.float32) if depth else None)


def make(model):
    sim = FakeSim(model)
    node = CameraPublisher(sim, make_publisher=FakePublisher)
    topics = {p.topic: p for p in node.image_pubs + node.info_pubs + node.jpeg_pubs
              + node.depth_pubs + node.points_pubs}
    return sim, node, topics


def test_nothing_rendered_without_subscribers():
    sim, node, topics = make("waffle")
    node.publish(rospy.Time(1))
    assert sim.renders == [] and all(not p.sent for p in topics.values())


def test_camera_info_alone_needs_no_render():
    sim, node, topics = make("waffle_pi")
    topics["camera/camera_info"].connections = 1
    node.publish(rospy.Time(1))
    assert sim.renders == [] and len(topics["camera/camera_info"].sent) == 1


@pytest.mark.parametrize("topic", ["camera/rgb/image_raw", "camera/image"])
def test_one_render_for_an_image_subscriber(topic):
    sim, node, topics = make("waffle_pi")
    topics[topic].connections = 1
    node.publish(rospy.Time(2))
    assert sim.renders == [False]
    msg = topics[topic].sent[0]
    assert (msg.encoding, msg.width, msg.height, msg.step) == ("rgb8", 640, 480, 1920)
    assert msg.header.stamp == rospy.Time(2) and len(msg.data) == 640 * 480 * 3


def test_depth_rendered_only_for_depth_subscribers():
    sim, node, topics = make("waffle")
    topics["camera/depth/image_raw"].connections = 1
    topics["camera/depth/points"].connections = 1
    node.publish(rospy.Time(3))
    assert sim.renders == [True]  # one render serves both
    depth = topics["camera/depth/image_raw"].sent[0]
    assert depth.encoding == "32FC1" and depth.step == 4 * 1920
    assert np.frombuffer(depth.data, np.float32)[0] == pytest.approx(2.0)
    cloud = topics["camera/depth/points"].sent[0]
    assert (cloud.width, cloud.height, cloud.point_step) == (1920, 1080, 32)


def test_waffle_pi_has_no_depth_topics():
    _, node, topics = make("waffle_pi")
    assert not node.depth_pubs and not node.points_pubs
    assert "camera/depth/camera_info" not in topics
