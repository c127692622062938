"""``libgazebo_ros_openni_kinect.so`` on a ``<sensor type="depth">``: the camera's image and
CameraInfo (as gazebo_ros_camera, read by its ``read_camera``), plus a 32FC1 depth image, its
CameraInfo and a PointCloud2 of the points between pointCloudCutoff and pointCloudCutoffMax.
Read into robot_plugin_types.CameraSensor with ``spec.depth`` True. Runs on robots (a world
model's depth camera is for later). Units: m.
"""
from typing import Dict

from .gazebo_ros_camera import PARAMS as CAMERA_PARAMS, read_camera
from .robot_plugin_types import OPENNI_KINECT, CameraSensor
from .sensor_reader import DISTANCE

SENSORS = {OPENNI_KINECT: "depth"}
HOSTS = ("robot",)
PARAMS = CAMERA_PARAMS | {
    "depthImageTopicName", "depthImageCameraInfoTopicName", "pointCloudTopicName",
    "pointCloudCutoff", "pointCloudCutoffMax", "baseline"}


def read(reader, sensor, plugin, link: str) -> CameraSensor:
    """The depth camera of ``sensor`` on ``link`` with its ``plugin``."""
    return read_camera(reader, sensor, plugin, link, PARAMS, depth=True,
                       extra=_depth_fields)


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
