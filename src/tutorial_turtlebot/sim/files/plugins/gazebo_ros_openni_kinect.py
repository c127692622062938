"""``libgazebo_ros_openni_kinect.so`` on a ``<sensor type="depth">``: the camera's image and
CameraInfo, plus a depth image, its CameraInfo and a PointCloud2 (x y z rgb) of the points
between pointCloudCutoff (0.4 m) and pointCloudCutoffMax (5 m), NaN (a 16UC1 depth image's 0)
outside them. On a robot it is read by gazebo_ros_camera's ``read_camera`` into a
robot_plugin_types.CameraSensor with ``spec.depth`` True (SimRobot renders it: 32FC1); on a
world model by ``read_world_camera`` into a camera_types.WorldCamera, run as
gazebo_ros_depth_camera is (world_sensors.DepthCameraRunner): the two plugins advertise the
same topics with the same defaults (ir/image_raw, ir/camera_info, depth/image_raw,
depth/camera_info, points, useDepth16UC1Format), the kinect adding the far cut-off. Units: m.
"""
from typing import Dict

from .gazebo_ros_camera import PARAMS as CAMERA_PARAMS, WORLD_PARAMS, read_camera
from .gazebo_ros_camera import read_world_camera
from .robot_plugin_types import OPENNI_KINECT, CameraSensor
from .sensor_reader import DISTANCE

SENSORS = {OPENNI_KINECT: "depth"}
HOSTS = ("robot", "world")
PARAMS = CAMERA_PARAMS | {
    "depthImageTopicName", "depthImageCameraInfoTopicName", "pointCloudTopicName",
    "pointCloudCutoff", "pointCloudCutoffMax", "baseline"}
WORLD_KINECT_PARAMS = WORLD_PARAMS | PARAMS | {"useDepth16UC1Format"}


def read(reader, sensor, plugin, link: str) -> CameraSensor:
    """The depth camera of ``sensor`` on ``link`` with its ``plugin``."""
    if reader.host == "world":
        return read_world_camera(reader, sensor, plugin, link, WORLD_KINECT_PARAMS, depth=True,
                                 extra=_world_fields)
    return read_camera(reader, sensor, plugin, link, PARAMS, depth=True,
                       extra=_robot_fields)


def _depth_fields(reader, plugin) -> Dict[str, object]:
    cutoff = reader.bounded(plugin, "pointCloudCutoff", 0.4, plugin, DISTANCE)
    cutoff_max = reader.bounded(plugin, "pointCloudCutoffMax", 5.0, plugin, DISTANCE)
    if cutoff_max <= cutoff:
        reader.fail(reader.found(plugin, "pointCloudCutoffMax", plugin),
                    "pointCloudCutoffMax %g must be greater than pointCloudCutoff %g"
                    % (cutoff_max, cutoff), plugin)
    return dict(
        depth_image_topic=reader.topic(plugin, "depthImageTopicName", "depth/image_raw"),
        depth_info_topic=reader.topic(plugin, "depthImageCameraInfoTopicName",
                                      "depth/camera_info"),
        point_cloud_topic=reader.topic(plugin, "pointCloudTopicName", "points"),
        point_cloud_cutoff=cutoff, point_cloud_cutoff_max=cutoff_max)


def _robot_fields(reader, plugin) -> Dict[str, object]:
    """A robot's kinect: the plugin's own defaults of the image topics (ir/...), not
    gazebo_ros_camera's."""
    return dict(_depth_fields(reader, plugin),
                image_topic=reader.topic(plugin, "imageTopicName", "ir/image_raw"),
                info_topic=reader.topic(plugin, "cameraInfoTopicName", "ir/camera_info"))


def _world_fields(reader, plugin) -> Dict[str, object]:
    """A world model's kinect: the robot's fields and the 16-bit depth option."""
    return dict(_robot_fields(reader, plugin),
                depth_16bit=reader.flag(plugin, "useDepth16UC1Format", False, plugin))
