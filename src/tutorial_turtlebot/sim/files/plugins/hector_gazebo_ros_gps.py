"""hector_gazebo_plugins' ``libhector_gazebo_ros_gps.so``, a model plugin: sensor_msgs/NavSatFix
on <topicName> (default "fix") and geometry_msgs/Vector3Stamped on <velocityTopicName>
(default "fix_velocity"), in <robotNamespace>, at <updateRate> (default 4 Hz), of link
<bodyName> (default: the model's first link), frame_id <frameId> (default the link's name).

Where the world frame's origin is on the WGS84 ellipsoid: <referenceLatitude> (default 49.9
deg), <referenceLongitude> (8.9 deg), <referenceAltitude> (0 m) and <referenceHeading> (0 deg),
as hector reads them: at heading 0 the world's x axis points north and y west, so 1 m along x
is 1 / (the meridian's radius of curvature) rad of latitude (about 1e-5 deg per 1.11 m). The
velocity is turned by the heading alone (x north, y west at heading 0). Error models as
hector's SensorModel: the position's <offset>, <drift>, <driftFrequency>, <gaussianNoise> (m),
the velocity's <velocityOffset>, ... (m/s); status <status> (default 0: STATUS_FIX), service
<service> (default 1: SERVICE_GPS). Units: deg, m, m/s, Hz.
"""
from dataclasses import dataclass
from typing import Optional

from .. import limits
from .hector_gazebo_ros_imu import ERROR_FIELDS, ErrorModel, error_model
from .model_plugin_values import body_link
from .sensor_reader import Bounds

HECTOR_GPS = "libhector_gazebo_ros_gps.so"
MODEL_FILES = (HECTOR_GPS,)
HOSTS = ("robot", "world")
DRIVE = False
PARAMS = frozenset({"robotNamespace", "bodyName", "frameId", "topicName", "velocityTopicName",
                    "updateRate", "updateStartTime", "referenceLatitude", "referenceLongitude",
                    "referenceHeading", "referenceAltitude", "status", "service",
                    "alwaysOn", "frameName"}
                   | {"velocity" + f for f in ERROR_FIELDS}
                   | {f[0].lower() + f[1:] for f in ERROR_FIELDS})
LATITUDE = Bounds(-90.0, 90.0, "deg")
LONGITUDE = Bounds(-360.0, 360.0, "deg")
HEADING = Bounds(-limits.MAX_ANGLE, limits.MAX_ANGLE, "deg")
ALTITUDE = Bounds(-limits.MAX_POSITION, limits.MAX_POSITION, "m")
STATUS = Bounds(-1, 2)
SERVICE = Bounds(0, 15)


@dataclass(frozen=True)
class HectorGpsPlugin:
    """hector_gazebo_ros_gps of model ``model`` reading link ``body_name``."""

    name: str
    model: str
    body_name: str
    frame_id: str
    topic: str = "fix"
    velocity_topic: str = "fix_velocity"
    update_rate: float = 4.0                 # Hz; 0 = every physics step
    reference_latitude: float = 49.9         # deg
    reference_longitude: float = 8.9         # deg
    reference_heading: float = 0.0           # deg
    reference_altitude: float = 0.0          # m
    status: int = 0                          # NavSatStatus.STATUS_FIX
    service: int = 1                         # NavSatStatus.SERVICE_GPS
    position: ErrorModel = ErrorModel()      # m
    velocity: ErrorModel = ErrorModel()      # m/s
    robot_namespace: str = ""


def read(reader, plugin, model: str, links, joints) -> Optional[HectorGpsPlugin]:
    """The plugin's settings, or None (one warning) where Gazebo would not run it."""
    body = body_link(reader, plugin, links, next(iter(links), None),
                     "the model has no link")
    if body is None:
        return None
    number = reader.bounded
    return HectorGpsPlugin(
        name=plugin.get("name", "").strip(), model=model, body_name=body,
        frame_id=reader.text(plugin, "frameId", body),
        topic=reader.topic(plugin, "topicName", "fix"),
        velocity_topic=reader.topic(plugin, "velocityTopicName", "fix_velocity"),
        update_rate=reader.rate(plugin, "updateRate", 4.0, plugin),
        reference_latitude=number(plugin, "referenceLatitude", 49.9, plugin, LATITUDE),
        reference_longitude=number(plugin, "referenceLongitude", 8.9, plugin, LONGITUDE),
        reference_heading=number(plugin, "referenceHeading", 0.0, plugin, HEADING),
        reference_altitude=number(plugin, "referenceAltitude", 0.0, plugin, ALTITUDE),
        status=int(number(plugin, "status", 0, plugin, STATUS)),
        service=int(number(plugin, "service", 1, plugin, SERVICE)),
        position=error_model(reader, plugin, ("",)),
        velocity=error_model(reader, plugin, ("velocity",)),
        robot_namespace=reader.topic(plugin, "robotNamespace", ""))
