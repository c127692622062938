"""``libgazebo_ros_p3d.so``, a model plugin: nav_msgs/Odometry of link <bodyName>'s pose and
twist, in the world or in another link of the model (<frameName>), as gazebo_ros_p3d fills
it: frame_id <frameName> (default "world"), child_frame_id <bodyName> as written, the pose
shifted by <xyzOffset> and turned by <rpyOffset>, gaussian noise (<gaussianNoise>, a standard
deviation) on the twist alone, and its square on the diagonals of both covariances.
<topicName> and <bodyName> are required (Gazebo's plugin stops loading without them);
<updateRate> 0 is every physics step. Units: m, rad, Hz.
"""
from dataclasses import dataclass
from typing import Optional, Tuple

from .. import limits
from .model_plugin_values import NOT_RUN, body_link, vector
from .sensor_reader import NOISE, strip_slash

P3D = "libgazebo_ros_p3d.so"
MODEL_FILES = (P3D,)
HOSTS = ("robot", "world")
DRIVE = False
PARAMS = frozenset({"robotNamespace", "bodyName", "topicName", "frameName", "xyzOffset",
                    "rpyOffset", "gaussianNoise", "updateRate", "alwaysOn"})
WORLD_FRAMES = ("world", "map")      # <frameName>s that mean the world frame (and "/..." ones)


@dataclass(frozen=True)
class P3dPlugin:
    """gazebo_ros_p3d of model ``model`` reading link ``body_name``."""

    name: str
    model: str
    body_name: str                           # the link read; also child_frame_id
    topic: str                               # <topicName>, in robot_namespace
    frame_name: str = "world"                # header.frame_id (a leading "/" dropped)
    reference_link: str = ""                 # the link <frameName> names; "" = the world
    xyz_offset: Tuple[float, float, float] = (0.0, 0.0, 0.0)     # m
    rpy_offset: Tuple[float, float, float] = (0.0, 0.0, 0.0)     # rad
    gaussian_noise: float = 0.0              # m/s, rad/s: on the twist
    update_rate: float = 0.0                 # Hz; 0 = every physics step
    robot_namespace: str = ""


def read(reader, plugin, model: str, links, joints) -> Optional[P3dPlugin]:
    """gazebo_ros_p3d's settings, or None (one warning) where Gazebo would not run it."""
    body = body_link(reader, plugin, links, None, "p3d needs the link it reads")
    if body is None:
        return None
    if plugin.find("topicName") is None:
        reader.warn("%s has no <topicName>: %s, as in Gazebo"
                    % (reader.describe(plugin), NOT_RUN), plugin)
        return None
    frame = strip_slash(reader.text(plugin, "frameName", "world"))
    reference = ""
    if frame not in WORLD_FRAMES:
        if frame not in links:
            reader.warn("%s: <frameName> %r is neither world, map nor a link of this model: "
                        "%s, as in Gazebo" % (reader.describe(plugin), frame, NOT_RUN), plugin)
            return None
        reference = frame
    return P3dPlugin(
        name=plugin.get("name", "").strip(), model=model, body_name=body,
        topic=reader.topic(plugin, "topicName", ""), frame_name=frame,
        reference_link=reference,
        xyz_offset=vector(reader, plugin, "xyzOffset", (0.0, 0.0, 0.0), limits.MAX_POSITION),
        rpy_offset=vector(reader, plugin, "rpyOffset", (0.0, 0.0, 0.0), limits.MAX_ANGLE),
        gaussian_noise=reader.bounded(plugin, "gaussianNoise", 0.0, plugin, NOISE),
        update_rate=reader.rate(plugin, "updateRate", 0.0, plugin),
        robot_namespace=reader.topic(plugin, "robotNamespace", ""))
