"""SDFormat 1.7's ``<pose relative_to="...">`` (``frame="..."`` in SDF 1.6 files, which sdformat 9
renames so), as Gazebo 11 resolves it: a pose relative to a named frame of the same scope. No
ROS, no pybullet.

A scope is a model (its links, nested models and ``<frame>``s, and ``__model__``, the model
frame) or the world (its models, actors, named includes and ``<frame>``s, and ``world``). A
``<frame>`` without ``relative_to`` is placed relative to its ``attached_to`` frame, else to the
scope. An element without ``relative_to`` is placed relative to its parent, as before SDF 1.7.
A name that is no frame of the scope, or a cycle of ``relative_to``, is refused (sdformat
reports both as errors). Units: metres, radians; poses kinematics.XyzRpy in the world frame.
"""
from typing import Callable, Dict, Iterable, NoReturn, Set

from ...kinematics import XyzRpy, compose_xyz_rpy
from ..xml_reader import Element

MODEL_FRAME, WORLD_FRAME = "__model__", "world"


def relative_to(node: Element) -> str:
    """The frame ``node``'s ``<pose>`` is given in ("" for its parent)."""
    pose = node.child("pose")
    if pose is None:
        return ""
    return (pose.attrib.get("relative_to") or pose.attrib.get("frame") or "").strip()


def element_name(node: Element) -> str:
    """The name ``node`` is known by in its scope: its name attribute, or an include's
    ``<name>``."""
    if node.tag == "include":
        name = node.child("name")
        return name.value if name is not None else ""
    return node.attrib.get("name", "")


class Frames:
    """The named frames of one scope, each resolved to a world pose on first use."""

    def __init__(self, scope_pose: XyzRpy, scope_frame: str, nodes: Iterable[Element],
                 local: Callable[[Element], XyzRpy],
                 fail: Callable[[Element, str], NoReturn]):
        """``scope_pose``: world pose of the scope's own frame, called ``scope_frame``;
        ``nodes``: the scope's named elements (the first of a name counts); ``local``: a node's
        pose numbers; ``fail``: the loader's one-line refusal."""
        self.scope_pose = scope_pose
        self.scope_frame = scope_frame
        self.local = local
        self.fail = fail
        self.nodes: Dict[str, Element] = {}
        for node in nodes:
            name = element_name(node)
            if name and name not in self.nodes:
                self.nodes[name] = node
        self._done: Dict[str, XyzRpy] = {}
        self._resolving: Set[str] = set()

    def place(self, node: Element, parent: XyzRpy) -> XyzRpy:
        """World pose of ``node``: its ``<pose>`` in its ``relative_to`` frame, else in
        ``parent`` (the world pose of the element around it)."""
        name = element_name(node)
        if name and self.nodes.get(name) is node and node.tag != "include":
            return self._resolve(name)
        frame = relative_to(node)
        base = self.frame(frame, node) if frame else parent
        return compose_xyz_rpy(base, self.local(node))

    def frame(self, name: str, at: Element) -> XyzRpy:
        """World pose of the frame ``name`` of this scope; refused (at ``at``'s pose) if there
        is none."""
        if name == self.scope_frame:
            return self.scope_pose
        if name not in self.nodes:
            self.fail(at.child("pose") if at.child("pose") is not None else at,
                      "<pose relative_to=%r>: no frame of that name here (a sibling link, "
                      "model or <frame>, or %s)" % (name, self.scope_frame))
        return self._resolve(name)

    def _resolve(self, name: str) -> XyzRpy:
        done = self._done.get(name)
        if done is not None:
            return done
        node = self.nodes[name]
        if name in self._resolving:
            self.fail(node.child("pose") if node.child("pose") is not None else node,
                      "<pose relative_to>: %r is placed relative to itself (a cycle of "
                      "relative_to)" % name)
        self._resolving.add(name)
        frame = relative_to(node)
        if not frame and node.tag == "frame":
            frame = node.attrib.get("attached_to", "").strip()
        base = self.frame(frame, node) if frame else self.scope_pose
        self._resolving.discard(name)
        pose = self._done[name] = compose_xyz_rpy(base, self.local(node))
        return pose
