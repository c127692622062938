"""A saved world's ``<state>``: the model poses Gazebo starts the world in. A world saved by
Gazebo carries a ``<state>`` whose ``<model>``s say where each one stood; world_sdf reads the
world's top-level models with those poses in place of their own. No ROS, no pybullet.
"""
from typing import Dict

from .. import xml_reader
from ..xml_reader import Element


def saved_poses(world: Element) -> Dict[str, Element]:
    """The ``<pose>`` of each model in the world's first ``<state>`` (a world saved by Gazebo),
    by model name. Gazebo starts the world in that state: a model it names stands there, not
    where its own ``<pose>`` puts it; models the state names that are not in the world, its
    links' poses and its sim time are not used here."""
    state = world.child("state")
    if state is None:
        return {}
    poses = {}
    for model in state.all("model"):
        pose = model.child("pose")
        if model.attrib.get("name") and pose is not None and pose.value:
            poses[model.attrib["name"]] = pose
    return poses


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
