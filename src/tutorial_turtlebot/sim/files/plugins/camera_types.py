"""The data of a world model's camera plugins: gazebo_ros_camera (its ``<format>`` and lens
distortion), gazebo_ros_depth_camera, gazebo_ros_multicamera and gazebo_ros_triggered_camera.
Each is a ``WorldCamera``, a robot_plugin_types.CameraSensor with what a world camera adds.
Plain data: no ROS, no pybullet, no file reading (the plugin modules beside it read them).
Units: m, rad; lens coordinates are fractions of the image (0..1, x right, y down).
"""
from dataclasses import dataclass
from typing import Tuple

from ...kinematics import ZERO_XYZ_RPY, XyzRpy
from .robot_plugin_types import CameraSensor

DEPTH_CAMERA = "libgazebo_ros_depth_camera.so"
MULTICAMERA = "libgazebo_ros_multicamera.so"
TRIGGERED_CAMERA = "libgazebo_ros_triggered_camera.so"


@dataclass(frozen=True)
class LensDistortion:
    """A <camera>'s <distortion> (Brown's model, as Gazebo applies it to the image): radial
    ``k1 k2 k3``, tangential ``p1 p2``, ``center`` in fractions of the image; ``crop``: the
    image stretched so that a barrel distortion (k1 < 0) leaves no black border
    (gazebo_ros_camera's <borderCrop>)."""

    k1: float = 0.0
    k2: float = 0.0
    k3: float = 0.0
    p1: float = 0.0
    p2: float = 0.0
    center: Tuple[float, float] = (0.5, 0.5)
    crop: bool = False

    @property
    def is_identity(self) -> bool:
        return not any((self.k1, self.k2, self.k3, self.p1, self.p2))


@dataclass(frozen=True)
class WorldCamera(CameraSensor):
    """A world model's camera (the CameraSensor fields, with its <format>, lens and D, plus):
    ``trigger_topic`` the triggered camera's (relative to camera_name); ``depth_16bit`` a
    depth image in 16UC1 mm instead of 32FC1 m; ``lens_pose`` a multicamera's <camera> in
    its sensor; ``cameras`` a multicamera's cameras (left, right), each a WorldCamera of its
    own names."""

    trigger_topic: str = ""
    depth_16bit: bool = False
    lens_pose: XyzRpy = ZERO_XYZ_RPY
    cameras: Tuple["WorldCamera", ...] = ()


# Gazebo's image <format>s as gazebo_ros_camera_utils publishes them: (encoding, bytes a pixel)
IMAGE_FORMATS = {
    "L8": ("mono8", 1), "L_INT8": ("mono8", 1),
    "L16": ("mono16", 2), "L_INT16": ("mono16", 2),
    "R8G8B8": ("rgb8", 3), "RGB_INT8": ("rgb8", 3),
    "B8G8R8": ("bgr8", 3), "BGR_INT8": ("bgr8", 3),
    "R16G16B16": ("rgb16", 6), "RGB_INT16": ("rgb16", 6),
    "BAYER_RGGB8": ("bayer_rggb8", 1), "BAYER_BGGR8": ("bayer_bggr8", 1),
    "BAYER_GBRG8": ("bayer_gbrg8", 1), "BAYER_GRBG8": ("bayer_grbg8", 1),
}
UNKNOWN_FORMAT = ("bgr8", 3)      # camera_utils' label of a format it does not know
