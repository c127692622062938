"""``libgazebo_ros_joint_state_publisher.so``, a model plugin: sensor_msgs/JointState of the
joints <jointName> lists (comma-separated, spaces dropped), in that order, at <updateRate>
(default 100 Hz; 0 = every physics step), on ``joint_states`` in <robotNamespace> (default,
and when empty: the model's name). Positions and velocities are Gazebo's (a joint's first
axis: rad, rad/s or m, m/s); no frame_id, no effort. A name that is no joint of the model is
one warning and the plugin does not run (Gazebo's would fail on it).
"""
from dataclasses import dataclass
from typing import Optional, Tuple

from .model_plugin_values import NOT_RUN

JOINT_STATE_PUBLISHER = "libgazebo_ros_joint_state_publisher.so"
MODEL_FILES = (JOINT_STATE_PUBLISHER,)
HOSTS = ("robot", "world")
DRIVE = False
PARAMS = frozenset({"robotNamespace", "jointName", "updateRate", "alwaysOn"})


@dataclass(frozen=True)
class JointStatePublisherPlugin:
    """gazebo_ros_joint_state_publisher of model ``model``."""

    name: str
    model: str
    joint_names: Tuple[str, ...]
    update_rate: float = 100.0               # Hz; 0 = every physics step
    robot_namespace: str = ""                # "" = the model's name (Gazebo's default)

    @property
    def namespace(self) -> str:
        """The namespace its ``joint_states`` topic is in."""
        return self.robot_namespace or self.model


def read(reader, plugin, model: str, links, joints) -> Optional[JointStatePublisherPlugin]:
    """The plugin's settings, or None (one warning) where Gazebo would not run it."""
    if plugin.find("jointName") is None:
        reader.warn("%s has no <jointName>: %s, as in Gazebo"
                    % (reader.describe(plugin), NOT_RUN), plugin)
        return None
    text = reader.text(plugin, "jointName", "").replace(" ", "")
    names = tuple(text.split(","))
    unknown = [n for n in names if n not in joints]
    if unknown:
        reader.warn("%s: <jointName> %s: no such joint in this model (%s); %s"
                    % (reader.describe(plugin), ", ".join(repr(n) for n in unknown),
                       ", ".join(joints) or "it has none", NOT_RUN), plugin)
        return None
    return JointStatePublisherPlugin(
        name=plugin.get("name", "").strip(), model=model, joint_names=names,
        update_rate=reader.rate(plugin, "updateRate", 100.0, plugin),
        robot_namespace=reader.topic(plugin, "robotNamespace", ""))
