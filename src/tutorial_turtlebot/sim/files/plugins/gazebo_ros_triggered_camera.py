"""``libgazebo_ros_triggered_camera.so`` on a ``<sensor type="camera">`` of a world model: a
gazebo_ros_camera that draws nothing until a std_msgs/Empty arrives on its trigger topic
(``<cameraName>/<triggerTopicName>``, default image_trigger), then one image (and CameraInfo)
per trigger, at the next physics step. Read by gazebo_ros_camera's ``read_world_camera`` into
a camera_types.WorldCamera with ``trigger_topic`` set. Runs on world models and on robots
(world.robot_sensors).
"""
from .camera_types import TRIGGERED_CAMERA, WorldCamera
from .gazebo_ros_camera import WORLD_PARAMS, read_world_camera

SENSORS = {TRIGGERED_CAMERA: "camera"}
HOSTS = ("robot", "world")
PARAMS = WORLD_PARAMS


def read(reader, sensor, plugin, link: str) -> WorldCamera:
    """The triggered camera of ``sensor`` on ``link`` with its ``plugin``."""
    return read_world_camera(reader, sensor, plugin, link, PARAMS, extra=_trigger)


def _trigger(reader, plugin):
    return dict(trigger_topic=reader.topic(plugin, "triggerTopicName", "image_trigger"))
