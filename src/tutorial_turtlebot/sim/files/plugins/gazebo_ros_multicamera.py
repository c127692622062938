"""``libgazebo_ros_multicamera.so`` on a ``<sensor type="multicamera">`` of a world model: each
<camera> whose name holds "left" or "right" publishes as a gazebo_ros_camera named
``<cameraName>/left`` or ``<cameraName>/right`` (image_raw, camera_info), both drawn at one
tick with one stamp, at each camera's own <pose> in the sensor. The right camera's CameraInfo
has the plugin's hackBaseline (P[3] = -f * baseline), the left's 0, as the plugin hard-codes
them; both take the plugin's frameName. A <camera> named otherwise is one warning (the plugin
leaves it unloaded). Read into a camera_types.WorldCamera whose ``cameras`` are the two.
Runs on world models and on robots (world.robot_sensors). Units: m.
"""
from dataclasses import replace

from .camera_types import MULTICAMERA, WorldCamera
from .gazebo_ros_camera import WORLD_PARAMS, read_world_camera
from .sensor_reader import BASELINE

SENSORS = {MULTICAMERA: "multicamera"}
HOSTS = ("robot", "world")
PARAMS = WORLD_PARAMS


def read(reader, sensor, plugin, link: str) -> WorldCamera:
    """The multicamera of ``sensor`` on ``link`` with its ``plugin``."""
    reader.check_params(plugin, reader.plugin_id(plugin)[1], PARAMS)
    baseline = reader.bounded(plugin, "hackBaseline", 0.0, plugin, BASELINE)
    cameras = []
    for camera in sensor.findall("camera"):
        name = camera.get("name", "")
        if "left" in name:
            side = ("/left", 0.0)
        elif "right" in name:
            side = ("/right", baseline)
        else:
            reader.warn("%s: <camera name=%r> is neither left nor right: %s leaves it "
                        "unloaded" % (reader.sensor_id(sensor), name, MULTICAMERA), camera)
            continue
        cameras.append(read_world_camera(reader, sensor, plugin, link, PARAMS, camera=camera,
                                         suffix=side[0], baseline=side[1]))
    if not cameras:
        reader.fail(sensor, "a multicamera needs a <camera> named left or right")
    return replace(cameras[0], cameras=tuple(cameras))
