"""``libgazebo_ros_bumper.so`` on a ``<sensor type="contact">``: one gazebo_msgs/ContactsState
a tick of the contacts of the sensor's ``<contact><collision>``s, read into ``BumperSensor``
with gazebo_ros_bumper's defaults: topic "bumper_states" (in <robotNamespace>), frame "world".
The collisions are scoped as Gazebo's ContactSensor scopes them: "model::link::collision". The
rate is the sensor's <update_rate> (the plugin publishes at each of its updates; 0: every
physics step). Runs on world models and on robots (world.robot_sensors: a robot's
collisions are named as Gazebo's URDF conversion names them, its frame is its link).
Units: Hz.
"""
from dataclasses import dataclass
from typing import Tuple

from .. import limits
from ...kinematics import ZERO_XYZ_RPY, XyzRpy

BUMPER = "libgazebo_ros_bumper.so"
SENSORS = {BUMPER: "contact"}
HOSTS = ("robot", "world")
PARAMS = frozenset({"robotNamespace", "bumperTopicName", "frameName", "updateRate", "alwaysOn"})


@dataclass(frozen=True)
class BumperSensor:
    """A contact sensor with gazebo_ros_bumper: the contacts of ``collisions`` (scoped) with
    anything, each pair one ContactState."""

    name: str
    link: str                               # the scoped link: "model::link"
    collisions: Tuple[str, ...]             # "model::link::collision", file order
    topic: str = "bumper_states"            # bumperTopicName
    frame: str = "world"                    # frameName: the header's frame_id
    rate: float = 0.0                       # Hz of sim time, the sensor's <update_rate>
    plugin: str = ""
    robot_namespace: str = ""
    pose: XyzRpy = ZERO_XYZ_RPY
    plugin_file: str = BUMPER


def read(reader, sensor, plugin, link: str) -> BumperSensor:
    """The bumper of the contact ``sensor`` on ``link`` with its ``plugin``."""
    reader.check_params(plugin, BUMPER, PARAMS)
    contact = sensor.find("contact")
    names = []
    for elem in contact.findall("collision") if contact is not None else ():
        problem = limits.name_problem("<collision>", elem.value)
        if problem:
            reader.fail(elem, problem, sensor)
        names.append(elem.value)
    return BumperSensor(
        name=sensor.get("name"), link=link,
        collisions=tuple("%s::%s" % (link, name) for name in names if name),
        topic=reader.topic(plugin, "bumperTopicName", "bumper_states"),
        frame=reader.frame(plugin, link, "world"),
        rate=reader.rate(sensor, "update_rate", 0.0, sensor),
        plugin=plugin.get("name", "").strip(),
        robot_namespace=reader.topic(plugin, "robotNamespace", ""),
        pose=reader.sensor_pose(sensor))
