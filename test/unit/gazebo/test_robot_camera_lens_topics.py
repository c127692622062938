"""The messages of a URDF robot's camera with a lens <distortion> and an image <format>
(test/fixtures/lens_robot, spawned in namespace lens): Image in its format's encoding (mono8
for L8), CameraInfo's D the plugin's [k1 k2 p1 p2 k3], as a world model's camera publishes
them; its jpeg grey; the plain camera beside it rgb8 with D zero (no master: stand-in
publishers; a real Simulation). A depth camera of another format keeps its depth."""
import io
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
import rospy

from tutorial_turtlebot.gazebo import robot_topics
from tutorial_turtlebot.gazebo.camera_publisher import CameraPublisher, jpeg_format, jpeg_source
from tutorial_turtlebot.gazebo.robot_topics import RobotTopics
from tutorial_turtlebot.sim.devices.camera import CameraIntrinsics, jpeg_available
from tutorial_turtlebot.sim.files.urdf.urdf_file import read_urdf, urdf_path
from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
from tutorial_turtlebot.sim.world.world_control import WorldControl

from unit_helpers import RecordingPublisher, at, run
import unit_paths

FIXTURE = Path(unit_paths.FIXTURES) / "lens_robot" / "lens_robot.urdf"
WORLD = Path(unit_paths.FIXTURES) / "two_lasers" / "two_lasers.world"


@pytest.fixture(scope="module")
def lens():
    patch = pytest.MonkeyPatch()
    patch.setattr(robot_topics.rospy, "Subscriber", RecordingPublisher)
    sim = Simulation(SimConfig(world=str(WORLD), spawn_robot=False))
    WorldControl(sim).spawn("lens", FIXTURE.read_text(), at(0.0, 0.0), kind="urdf",
                            robot_namespace="lens")
    run(sim, 0.3)
    topics = RobotTopics(sim.robots["lens"], RecordingPublisher, RecordingPublisher("/tf"))
    pubs = {pub.name: pub for pub in topics._advertised}
    for pub in pubs.values():
        pub.connections = 1
    topics.publishers["camera"](rospy.Time(1))
    topics.publishers["camera:1"](rospy.Time(1))
    yield sim.robots["lens"], pubs
    sim.close()
    patch.undo()


def test_the_distorted_camera_publishes_mono8_and_its_d(lens):
    robot, pubs = lens
    image, = pubs["/lens/lens_camera/image_raw"].sent
    info, = pubs["/lens/lens_camera/camera_info"].sent
    assert (image.encoding, image.width, image.height, image.step) == ("mono8", 64, 48, 64)
    assert image.data == robot.camera_image()[0].tobytes()
    assert list(info.D) == [-0.25, 0.0, 0.0, 0.0, 0.0] and info.distortion_model == "plumb_bob"
    assert info.header.frame_id == "lens/camera_link"


@pytest.mark.skipif(not jpeg_available(), reason="no PIL")
def test_its_jpeg_is_grey(lens):
    from PIL import Image as PilImage
    _, pubs = lens
    jpeg, = pubs["/lens/lens_camera/image_raw/compressed"].sent
    assert jpeg.format == "mono8; jpeg compressed mono8"
    decoded = PilImage.open(io.BytesIO(bytes(jpeg.data)))
    assert (decoded.mode, decoded.size) == ("L", (64, 48))


def test_the_plain_camera_beside_it_is_rgb8_with_d_zero(lens):
    robot, pubs = lens
    image, = pubs["/lens/plain_camera/image_raw"].sent
    info, = pubs["/lens/plain_camera/camera_info"].sent
    assert (image.encoding, image.step) == ("rgb8", 3 * 64)
    assert image.data == robot.camera_image(index=1)[0].tobytes()
    assert list(info.D) == [0.0] * 5
    assert np.frombuffer(image.data, np.uint8).size == 64 * 48 * 3


def test_jpeg_source_is_eight_bits_in_rgb_order():
    """What image_transport's compressed plugin encodes: 16-bit channels' high byte, bgr8
    turned back to rgb; a Bayer image has no jpeg topic (the plugin refuses it)."""
    grey16 = np.array([[0, 257 * 200]], dtype="<u2")
    assert jpeg_source(grey16, "mono16").tolist() == [[0, 200]]
    bgr = np.array([[[1, 2, 3]]], dtype=np.uint8)
    assert jpeg_source(bgr, "bgr8").tolist() == [[[3, 2, 1]]]
    assert jpeg_source(bgr.astype("<u2") * 257, "rgb16").tolist() == [[[1, 2, 3]]]
    assert (jpeg_format("mono16"), jpeg_format("rgb16")) == ("mono16; jpeg compressed mono8",
                                                             "rgb16; jpeg compressed bgr8")


class GreyDepthRobot:
    """A robot's depth camera (openni_kinect) of <format> L8: a grey image, a 2 m depth."""

    def __init__(self, image_format):
        sensor = read_urdf(urdf_path("waffle")).plugins.camera
        self.camera_sensor = replace(sensor, image_format=image_format,
                                     spec=replace(sensor.spec, width=8, height=6))
        self.camera_spec = self.camera_sensor.spec
        self.camera_intrinsics = CameraIntrinsics.from_spec(self.camera_spec)

    def camera_image(self, depth=False):
        grey = np.full((6, 8), 90, np.uint8)
        return grey, np.full((6, 8), 2.0, np.float32) if depth else None


@pytest.mark.parametrize("image_format, jpeg_topics", [("L8", 2), ("BAYER_RGGB8", 0)])
def test_a_depth_camera_of_another_format_keeps_its_depth_without_colours(image_format,
                                                                          jpeg_topics):
    node = CameraPublisher(GreyDepthRobot(image_format), make_publisher=RecordingPublisher)
    assert len(node.jpeg_pubs) == (jpeg_topics if jpeg_available() else 0)
    for pub in node.image_pubs + node.depth_pubs + node.points_pubs:
        pub.connections = 1
    node.publish(rospy.Time(1))
    image = node.image_pubs[0].sent[0]
    assert (image.encoding, image.step) == (node.encoding, 8)
    depth, cloud = node.depth_pubs[0].sent[0], node.points_pubs[0].sent[0]
    assert np.frombuffer(depth.data, np.float32)[0] == pytest.approx(2.0)
    assert [f.name for f in cloud.fields] == ["x", "y", "z"] and cloud.width == 8
