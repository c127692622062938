"""``libgazebo_ros_depth_camera.so`` on a ``<sensor type="depth">`` of a world model: the
camera's image and CameraInfo (default topics ir/image_raw and ir/camera_info), a depth image
(32FC1 m, or 16UC1 mm with useDepth16UC1Format; NaN or 0 at or inside pointCloudCutoff, 0.4 m
by default) with its CameraInfo (depth/image_raw, depth/camera_info) and an organized
PointCloud2 (points), all of one render and one stamp. Read by gazebo_ros_camera's
``read_world_camera`` into a camera_types.WorldCamera with ``spec.depth`` True. Runs on world
models and on robots (world.robot_sensors). Units: m.
"""
from typing import Dict

from .camera_types import DEPTH_CAMERA, WorldCamera
from .gazebo_ros_camera import WORLD_PARAMS, read_world_camera
from .sensor_reader import DISTANCE

SENSORS = {DEPTH_CAMERA: "depth"}
HOSTS = ("robot", "world")
PARAMS = WORLD_PARAMS | {
    "depthImageTopicName", "depthImageCameraInfoTopicName", "pointCloudTopicName",
    "pointCloudCutoff", "useDepth16UC1Format", "reflectanceTopicName", "normalsTopicName",
    "reduceNormals"}


def read(reader, sensor, plugin, link: str) -> WorldCamera:
    """The depth camera of ``sensor`` on ``link`` with its ``plugin``."""
    return read_world_camera(reader, sensor, plugin, link, PARAMS, depth=True,
                             extra=_depth_fields)


def _depth_fields(reader, plugin) -> Dict[str, object]:
    cutoff = reader.bounded(plugin, "pointCloudCutoff", 0.4, plugin, DISTANCE)
    return dict(
        image_topic=reader.topic(plugin, "imageTopicName", "ir/image_raw"),
        info_topic=reader.topic(plugin, "cameraInfoTopicName", "ir/camera_info"),
        depth_image_topic=reader.topic(plugin, "depthImageTopicName", "depth/image_raw"),
        depth_info_topic=reader.topic(plugin, "depthImageCameraInfoTopicName",
                                      "depth/camera_info"),
        point_cloud_topic=reader.topic(plugin, "pointCloudTopicName", "points"),
        point_cloud_cutoff=cutoff, point_cloud_cutoff_max=float("inf"),
        depth_16bit=reader.flag(plugin, "useDepth16UC1Format", False, plugin))
