"""hector_gazebo_plugins' ``libhector_gazebo_ros_imu.so``, a model plugin: sensor_msgs/Imu of
link <bodyName> (default: the model's first link), frame_id <frameId> (default the link's
name), on <topicName> (default "imu") in <robotNamespace>, at <updateRate> (default 0: every
physics step). Its error models, as hector's SensorModel: for accel (m/s^2) and rate (rad/s)
three numbers each of <accelOffset>, <accelDrift>, <accelDriftFrequency> (default 1/3600 Hz),
<accelGaussianNoise> (and rate...), for the heading (rad) one number each of <headingOffset>,
... (hector's older name; <yaw...> its newer one); <gaussianNoise> (not 0) sets both
gaussian noises, <rpyOffset>'s roll and pitch become accel offsets (times 9.8065) and its yaw
the heading offset where those are 0. The noise is drawn from a seeded generator
(<randomEngineSeed>, else the simulation's seed). At rest the acceleration reads minus
gravity in the link frame: +9.8 on z on level ground.
"""
from dataclasses import dataclass
from typing import Optional, Tuple

from .model_plugin_values import body_link, vector
from .sensor_reader import NOISE

HECTOR_IMU = "libhector_gazebo_ros_imu.so"
MODEL_FILES = (HECTOR_IMU,)
HOSTS = ("robot", "world")
DRIVE = False
ERROR_FIELDS = ("Offset", "Drift", "DriftFrequency", "GaussianNoise")
DRIFT_FREQUENCY = 1.0 / 3600.0      # Hz: hector's SensorModel default
GRAVITY_SCALE = 9.8065              # m/s^2 per rad of <rpyOffset> roll or pitch (hector's)
PARAMS = frozenset({"robotNamespace", "bodyName", "frameId", "topicName", "serviceName",
                    "updateRate", "updateStartTime", "gaussianNoise", "rpyOffset", "xyzOffset",
                    "randomEngineSeed", "alwaysOn", "frameName"}
                   | {p + f for p in ("accel", "rate", "heading", "yaw") for f in ERROR_FIELDS})

Vector = Tuple[float, float, float]


@dataclass(frozen=True)
class ErrorModel:
    """hector's SensorModel of one quantity, per axis: a constant offset, a drift (a
    first-order Gauss-Markov process of standard deviation ``drift`` and frequency
    ``drift_frequency``) and white gaussian noise; the unit is the quantity's."""

    offset: Vector = (0.0, 0.0, 0.0)
    drift: Vector = (0.0, 0.0, 0.0)
    drift_frequency: Vector = (DRIFT_FREQUENCY,) * 3
    gaussian_noise: Vector = (0.0, 0.0, 0.0)


@dataclass(frozen=True)
class HectorImuPlugin:
    """hector_gazebo_ros_imu of model ``model`` reading link ``body_name``."""

    name: str
    model: str
    body_name: str
    frame_id: str
    topic: str = "imu"
    update_rate: float = 0.0                 # Hz; 0 = every physics step
    accel: ErrorModel = ErrorModel()         # m/s^2
    rate: ErrorModel = ErrorModel()          # rad/s
    heading: ErrorModel = ErrorModel()       # rad (its x alone)
    seed: Optional[int] = None               # <randomEngineSeed>
    robot_namespace: str = ""


def error_model(reader, plugin, prefixes, base: ErrorModel = ErrorModel()) -> ErrorModel:
    """The error model of the parameters <PREFIX{Offset,Drift,...}> (prefix "": <offset>,
    <drift>, ...; the first prefix written wins)."""
    values = []
    for field, default in zip(ERROR_FIELDS, (base.offset, base.drift, base.drift_frequency,
                                             base.gaussian_noise)):
        names = [p + field if p else field[0].lower() + field[1:] for p in prefixes]
        tags = [t for t in names if plugin.find(t) is not None]
        values.append(vector(reader, plugin, tags[0], default) if tags else default)
    return ErrorModel(*values)


def read(reader, plugin, model: str, links, joints) -> Optional[HectorImuPlugin]:
    """The plugin's settings, or None (one warning) where Gazebo would not run it."""
    body = body_link(reader, plugin, links, next(iter(links), None),
                     "the model has no link")
    if body is None:
        return None
    accel = error_model(reader, plugin, ("accel",))
    rate = error_model(reader, plugin, ("rate",))
    heading = error_model(reader, plugin, ("heading", "yaw"))
    noise = reader.bounded(plugin, "gaussianNoise", 0.0, plugin, NOISE)
    if noise != 0.0:
        accel = ErrorModel(accel.offset, accel.drift, accel.drift_frequency, (noise,) * 3)
        rate = ErrorModel(rate.offset, rate.drift, rate.drift_frequency, (noise,) * 3)
    roll, pitch, yaw = vector(reader, plugin, "rpyOffset", (0.0, 0.0, 0.0))
    ax, ay, az = accel.offset
    if ay == 0.0 and roll != 0.0:
        ay = -roll * GRAVITY_SCALE
    if ax == 0.0 and pitch != 0.0:
        ax = pitch * GRAVITY_SCALE
    accel = ErrorModel((ax, ay, az), accel.drift, accel.drift_frequency, accel.gaussian_noise)
    if heading.offset[0] == 0.0 and yaw != 0.0:
        heading = ErrorModel((yaw,) * 3, heading.drift, heading.drift_frequency,
                             heading.gaussian_noise)
    seed = None
    if plugin.find("randomEngineSeed") is not None:
        seed = int(reader.number(plugin, "randomEngineSeed", 0, plugin)) % (2 ** 32)
    return HectorImuPlugin(
        name=plugin.get("name", "").strip(), model=model, body_name=body,
        frame_id=reader.text(plugin, "frameId", body),
        topic=reader.topic(plugin, "topicName", "imu"),
        update_rate=reader.rate(plugin, "updateRate", 0.0, plugin),
        accel=accel, rate=rate, heading=heading, seed=seed,
        robot_namespace=reader.topic(plugin, "robotNamespace", ""))
