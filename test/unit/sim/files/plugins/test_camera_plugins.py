"""A world model's camera plugins read (gazebo_ros_camera's world reading, and the modules
gazebo_ros_depth_camera, gazebo_ros_multicamera, gazebo_ros_triggered_camera): the fixture
world of test/fixtures/world_cameras, each plugin's defaults and topic names as gazebo_plugins
writes them, the <format> and <distortion> of a camera, CameraInfo's D (the plugin's
distortionK1.. in D's order, or the lens' with autoDistortion), and what warns. No ROS, no
pybullet. Units: m, rad, Hz."""
from pathlib import Path

import pytest

from tutorial_turtlebot.errors import WorldError
from tutorial_turtlebot.sim.files.plugins.camera_types import (
    DEPTH_CAMERA, MULTICAMERA, TRIGGERED_CAMERA, LensDistortion, WorldCamera)
from tutorial_turtlebot.sim.files.plugins.robot_plugin_types import CAMERA, OPENNI_KINECT
from tutorial_turtlebot.sim.files.sdf.world_sdf import load_world

from unit_helpers import world_file
import unit_paths

FIXTURE = Path(unit_paths.ROOT) / "test" / "fixtures" / "world_cameras" / "world_cameras.world"
CAMERA_BODY = ('<camera name="c"><image><width>8</width><height>6</height>%s</image>%s'
               '</camera>')


def camera_model(plugin_file, kind="camera", image="", lens="", params="", cameras=None):
    body = cameras if cameras is not None else CAMERA_BODY % (image, lens)
    return ('<model name="m"><static>true</static><link name="l"><sensor name="s" type="%s">%s'
            '<plugin name="p" filename="%s">%s</plugin></sensor></link></model>'
            % (kind, body, plugin_file, params))


def read(tmp_path, text):
    world = load_world(world_file(tmp_path, text))
    return world.sensors, list(world.warnings)


def test_the_fixture_worlds_cameras_are_read_with_their_plugins():
    by_name = {s.name: s for s in load_world(str(FIXTURE)).sensors}
    assert list(by_name) == ["depth_camera", "stereo_camera", "triggered_camera", "grey_camera",
                             "barrel_camera"]
    assert all(isinstance(s, WorldCamera) for s in by_name.values())
    depth = by_name["depth_camera"]
    assert (depth.plugin_file, depth.spec.depth, depth.point_cloud_cutoff) == (
        DEPTH_CAMERA, True, 0.5)
    triggered = by_name["triggered_camera"]
    assert (triggered.plugin_file, triggered.trigger_topic, triggered.image_format) == (
        TRIGGERED_CAMERA, "image_trigger", "B8G8R8")
    assert by_name["grey_camera"].image_format == "L16"
    barrel = by_name["barrel_camera"]
    assert barrel.lens == LensDistortion(k1=-0.2, k2=0.05, k3=0.01, p1=0.002, p2=-0.001,
                                         crop=False)
    assert barrel.info_distortion == (-0.2, 0.05, 0.002, -0.001, 0.01)   # k1 k2 p1 p2 k3


def test_a_multicamera_is_its_left_and_right_cameras_each_with_its_pose_and_baseline():
    stereo = {s.name: s for s in load_world(str(FIXTURE)).sensors}["stereo_camera"]
    assert stereo.plugin_file == MULTICAMERA
    left, right = stereo.cameras
    assert (left.camera_name, right.camera_name) == ("stereo/left", "stereo/right")
    assert (left.spec.baseline, right.spec.baseline) == (0.0, 0.07)
    assert left.lens_pose == (0.0,) * 6 and right.lens_pose == (0, -0.07, 0, 0, 0, 0)
    assert left.frame == right.frame == "stereo_optical_frame"
    assert left.pose == right.pose == (0.0, 0.0, 0.0, 0.0, 1.5707963, 0.0)


def test_depth_camera_defaults_are_gazebo_ros_depth_cameras(tmp_path):
    [depth], warnings = read(tmp_path, camera_model(DEPTH_CAMERA, "depth"))
    assert warnings == []
    assert (depth.image_topic, depth.info_topic, depth.depth_image_topic,
            depth.depth_info_topic, depth.point_cloud_topic) == (
        "ir/image_raw", "ir/camera_info", "depth/image_raw", "depth/camera_info", "points")
    assert (depth.point_cloud_cutoff, depth.depth_16bit) == (0.4, False)
    [sixteen], _ = read(tmp_path, camera_model(DEPTH_CAMERA, "depth", params=(
        "<useDepth16UC1Format>true</useDepth16UC1Format><imageTopicName>rgb</imageTopicName>")))
    assert (sixteen.depth_16bit, sixteen.image_topic) == (True, "rgb")


def test_an_openni_kinect_on_a_world_model_is_a_depth_camera_with_its_far_cutoff(tmp_path):
    """gazebo_ros_openni_kinect advertises gazebo_ros_depth_camera's topics with the same
    defaults; it adds pointCloudCutoffMax (5 m)."""
    [kinect], warnings = read(tmp_path, camera_model(OPENNI_KINECT, "depth"))
    assert warnings == []
    assert isinstance(kinect, WorldCamera) and kinect.spec.depth
    assert (kinect.plugin_file, kinect.image_topic, kinect.info_topic, kinect.depth_image_topic,
            kinect.depth_info_topic, kinect.point_cloud_topic) == (
        OPENNI_KINECT, "ir/image_raw", "ir/camera_info", "depth/image_raw",
        "depth/camera_info", "points")
    assert (kinect.point_cloud_cutoff, kinect.point_cloud_cutoff_max,
            kinect.depth_16bit) == (0.4, 5.0, False)
    [far], _ = read(tmp_path, camera_model(OPENNI_KINECT, "depth", params=(
        "<pointCloudCutoffMax>2.5</pointCloudCutoffMax>"
        "<useDepth16UC1Format>1</useDepth16UC1Format>")))
    assert (far.point_cloud_cutoff_max, far.depth_16bit) == (2.5, True)


def test_a_triggered_cameras_trigger_topic_is_its_own(tmp_path):
    [camera], _ = read(tmp_path, camera_model(TRIGGERED_CAMERA, params=(
        "<cameraName>cam</cameraName><triggerTopicName>shoot</triggerTopicName>")))
    assert (camera.camera_name, camera.trigger_topic) == ("cam", "shoot")


def test_camera_info_d_is_the_plugins_in_d_order_unless_auto_distortion(tmp_path):
    lens = ('<distortion><k1>-0.1</k1><k2>-0.2</k2><k3>-0.3</k3><p1>0.01</p1><p2>0.02</p2>'
            '<center>0.4 0.6</center></distortion>')
    params = ('<distortionK1>1</distortionK1><distortionK2>2</distortionK2><distortionK3>3'
              '</distortionK3><distortionT1>4</distortionT1><distortionT2>5</distortionT2>')
    [camera], warnings = read(tmp_path, camera_model(CAMERA, lens=lens, params=params))
    assert warnings == []
    assert camera.info_distortion == (1.0, 2.0, 4.0, 5.0, 3.0)
    assert camera.lens == LensDistortion(-0.1, -0.2, -0.3, 0.01, 0.02, (0.4, 0.6), crop=True)
    [auto], _ = read(tmp_path, camera_model(CAMERA, lens=lens, params=params + (
        "<autoDistortion>1</autoDistortion>")))
    assert auto.info_distortion == (-0.1, -0.2, 0.01, 0.02, -0.3)
    [plain], _ = read(tmp_path, camera_model(CAMERA))
    assert plain.lens is None and plain.info_distortion == (0.0,) * 5


@pytest.mark.parametrize("image_format", ["L8", "L16", "R8G8B8", "B8G8R8", "R16G16B16",
                                          "BAYER_RGGB8", "RGB_INT8"])
def test_the_formats_camera_utils_publishes_are_kept_without_a_warning(tmp_path, image_format):
    [camera], warnings = read(tmp_path, camera_model(
        CAMERA, image="<format>%s</format>" % image_format))
    assert (camera.image_format, warnings) == (image_format, [])


def test_an_unknown_format_is_one_located_warning(tmp_path):
    [camera], [warning] = read(tmp_path, camera_model(CAMERA, image="<format>FLOAT32</format>"))
    assert camera.image_format == "FLOAT32"
    assert ":4: " in warning and "'FLOAT32'" in warning and "bgr8" in warning


def test_a_multicamera_camera_neither_left_nor_right_is_one_warning(tmp_path):
    cameras = ('<camera name="left"><image><width>8</width><height>6</height></image></camera>'
               '<camera name="middle"/>')
    [stereo], [warning] = read(tmp_path, camera_model(MULTICAMERA, "multicamera",
                                                      cameras=cameras))
    assert [c.camera_name for c in stereo.cameras] == ["/left"]
    assert "'middle'" in warning and "neither left nor right" in warning
    with pytest.raises(WorldError, match="left or right"):
        read(tmp_path, camera_model(MULTICAMERA, "multicamera", cameras='<camera name="x"/>'))


def test_a_wrong_lens_term_is_refused_in_one_line(tmp_path):
    with pytest.raises(WorldError) as err:
        read(tmp_path, camera_model(CAMERA, lens="<distortion><k1>x</k1></distortion>"))
    assert "<k1>" in str(err.value) and "\n" not in str(err.value)
