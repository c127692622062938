"""``libgazebo_ros_imu.so``, a model plugin of a URDF robot's ``<gazebo>`` block: the robot's
IMU (``RobotPlugins.imu``, one a robot: a second is one warning), sensor_msgs/Imu of link
<bodyName> (required), frame_id <frameName> (default: that link), on <topicName> (default
"/default_imu", as gazebo_ros_imu's) at <updateRate> (0: every physics step), <gaussianNoise>
a standard deviation. It does not run on world models here (one warning). Read into
robot_plugin_types' ``ImuPlugin``. No ROS, no pybullet. Units: Hz, rad/s, m/s^2.
"""
from .robot_plugin_types import IMU, ImuPlugin
from .sensor_reader import NOISE

MODEL_FILES = (IMU,)
HOSTS = ("robot",)
DRIVE = False
PARAMS = frozenset({"robotNamespace", "bodyName", "frameName", "topicName", "serviceName",
                    "updateRate", "gaussianNoise", "xyzOffset", "rpyOffset", "alwaysOn", "imu"})


def read(reader, plugin, model: str, links, joints) -> ImuPlugin:
    """The IMU of the <plugin> ``plugin`` (a robot's, its parameters checked already); a
    missing <bodyName> or a link the robot does not have is refused (robot_plugins' reader)."""
    if plugin.find("bodyName") is None:
        reader.fail(plugin, "missing <bodyName> (the link the IMU reads)")
    body = reader.link(plugin, "bodyName", "", plugin)
    # topicName and serviceName default to /default_imu in gazebo_ros_imu.
    return ImuPlugin(
        name=plugin.get("name", "").strip(), body_name=body,
        frame_name=reader.link(plugin, "frameName", "", plugin),
        topic=reader.topic(plugin, "topicName", "/default_imu"),
        service_name=reader.topic(plugin, "serviceName", "/default_imu"),
        update_rate=reader.rate(plugin, "updateRate", 0.0, plugin),
        gaussian_noise=reader.bounded(plugin, "gaussianNoise", 0.0, plugin, NOISE),
        robot_namespace=reader.topic(plugin, "robotNamespace", ""))
