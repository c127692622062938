"""What the model plugins' readers (their modules of ``table``) share: vectors of three
numbers, the link a plugin reads, an SDF model's joints a drive names, and the words of a
plugin Gazebo would not run. No ROS, no
pybullet.
"""
import math
from typing import Collection, Mapping, Optional, Tuple

from .. import limits

NOT_RUN = "Gazebo loads it but it does not run"


def vector(reader, plugin, tag: str, default: Tuple[float, float, float],
           high: float = limits.MAX_NOISE) -> Tuple[float, float, float]:
    """The optional <tag> of three numbers (one number: the same on x, y and z), each within
    +-``high``."""
    elem = plugin.find(tag)
    if elem is None:
        return default
    try:
        values = tuple(float(v) for v in elem.value.split())
    except ValueError:
        values = ()
    if len(values) == 1:
        values = values * 3
    if len(values) != 3 or not all(map(math.isfinite, values)):
        reader.fail(elem, "must be one or three numbers, got %r" % elem.value, plugin)
    problem = limits.symmetric("<%s>" % tag, values, high, "")
    if problem:
        reader.fail(elem, problem, plugin)
    return values


def body_link(reader, plugin, links: Collection[str], default: Optional[str],
              what: str) -> Optional[str]:
    """The link <bodyName> names (a leading "/" dropped), else ``default`` (None: required);
    None with one warning when there is no such link (Gazebo's plugin then stops loading)."""
    elem = plugin.find("bodyName")
    if elem is None:
        if default is None:
            reader.warn("%s has no <bodyName>: %s, as in Gazebo (%s)"
                        % (reader.describe(plugin), NOT_RUN, what), plugin)
        return default
    name = reader.text(plugin, "bodyName", "").strip()
    name = name[1:] if name.startswith("/") else name
    if name not in links:
        reader.warn("%s: <bodyName> %r is not a link of this model: %s, as in Gazebo"
                    % (reader.describe(plugin), name, NOT_RUN), plugin)
        return None
    return name


def joints_found(reader, plugin, model: str, joints: Collection[str],
                 tags: Mapping[str, str]) -> bool:
    """Whether every joint the plugin's <tag>s name (``tags``: tag -> Gazebo's default) is one
    of SDF model ``model``'s ``joints``; one warning for the first that is not (the drive
    then does not run: Gazebo's stops loading)."""
    for tag, default in tags.items():
        joint = reader.text(plugin, tag, default)
        if joint not in joints:
            reader.warn("%s: <%s> %r is not a joint of model %r (its joints: %s): %s, as in "
                        "Gazebo" % (reader.describe(plugin), tag, joint, model,
                                    ", ".join(joints) or "none", NOT_RUN), plugin)
            return False
    return True
