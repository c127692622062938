"""A saved world's ``<state>``: the model poses Gazebo starts the world in. A world saved by
Gazebo carries a ``<state>`` whose ``<model>``s say where each one stood; world_sdf reads the
world's top-level models with those poses in place of their own. No ROS, no pybullet.
"""
import math
from typing import Callable, Dict, Optional

from .. import limits, xml_reader
from ..xml_reader import Element


def saved_poses(world: Element,
                warn: Optional[Callable[[Element, str], None]] = None) -> Dict[str, Element]:
    """The ``<pose>`` of each model in the world's first ``<state>`` (a world saved by Gazebo),
    by model name. Gazebo starts the world in that state: a model it names stands there, not
    where its own ``<pose>`` puts it; models the state names that are not in the world, its
    links' poses and its sim time are not used here. A saved position beyond
    limits.MAX_POSITION (a model that had fallen out of the world when it was saved, millions
    of metres down) is not used: the model stands where its own pose puts it, with one
    ``warn(node, message)``."""
    state = world.child("state")
    if state is None:
        return {}
    poses = {}
    for model in state.all("model"):
        pose = model.child("pose")
        name = model.attrib.get("name")
        if not (name and pose is not None and pose.value):
            continue
        far = _beyond_limits(pose.value)
        if far is not None:
            if warn is not None:
                warn(pose, "model %r: its saved <state> pose is %g m out, beyond the %g m this "
                     "simulator holds (it had fallen out of the world); it stands where its "
                     "own <pose> puts it" % (name, far, limits.MAX_POSITION))
            continue
        poses[name] = pose
    return poses


def _beyond_limits(text: str) -> Optional[float]:
    """The farthest coordinate of the pose ``text`` ("x y z r p y") when it is beyond
    limits.MAX_POSITION, else None (a malformed pose is left to the loader's checks)."""
    try:
        xyz = [abs(float(v)) for v in text.split()[:3]]
    except ValueError:
        return None
    far = max(xyz, default=0.0)
    return far if math.isfinite(far) and far > limits.MAX_POSITION else None


def with_saved_pose(node: Element, saved: Dict[str, Element]) -> Element:
    """A top-level ``<model>``, ``<actor>`` or named ``<include>`` with its pose from the
    saved state."""
    if node.tag in ("model", "actor"):
        name = node.attrib.get("name", "")
    else:
        name_node = node.child("name")
        name = name_node.value if name_node is not None else ""
    pose = saved.get(name) if name else None
    if pose is None:
        return node
    children = [c for c in node.children if c.tag != "pose"] + [pose]
    return xml_reader.element(node.tag, node.attrib, node.line, children)
