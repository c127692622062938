"""How a movable model's links and joints become bodies: one body per tree of joined links.
Plain data, no ROS, no pybullet (engine.movable_bodies builds it, world.world_models reads it).

- ``forest`` keeps the joints that make trees: a joint whose child already has a parent, or
  that closes a loop, is left out (the first in file order is kept), so a model whose joints
  make a loop is simulated as the nearest tree (world_sdf warns once per joint left out).
- ``trees`` orders each tree for the engine. A tree is rooted at a link that is no kept joint's
  child. A joint from ``world`` anchors its child: a fixed one fixes the tree's base, another
  one moves it about a fixed, massless base at the joint.
- ``body_links`` lists a tree's links in the engine's order: index -1 the base, then one entry
  per pybullet joint, depth first (each link's children in joint order): the order in which
  pybullet numbers the links of a multibody, whatever the order they are given in. A universal
  or revolute2 joint is two revolute joints through a light link of its own (``link`` None); a
  screw or gearbox joint is held fixed (one warning where it is read).
"""
from dataclasses import dataclass, replace
from typing import Dict, List, Optional, Sequence, Tuple

from .world_types import WORLD_LINK, Joint, Link, Model

TWO_AXES = ("universal", "revolute2")
HELD_FIXED = ("screw", "gearbox")


def forest(joints: Sequence[Joint]) -> Tuple[List[Joint], List[Joint]]:
    """(kept, left out): ``joints`` (file order) less those that would give a link a second
    parent or close a loop."""
    parent_of: Dict[str, str] = {}
    kept: List[Joint] = []
    dropped: List[Joint] = []
    for joint in joints:
        if joint.child in parent_of or _reaches(parent_of, joint.parent, joint.child):
            dropped.append(joint)
            continue
        parent_of[joint.child] = joint.parent
        kept.append(joint)
    return kept, dropped


def _reaches(parent_of: Dict[str, str], link: str, target: str) -> bool:
    """Whether ``target`` is ``link`` or above it (following parent_of up)."""
    seen = set()
    while link not in seen:
        if link == target:
            return True
        seen.add(link)
        if link not in parent_of:
            return False
        link = parent_of[link]
    return False


@dataclass(frozen=True)
class BodyLink:
    """One link of a body in the engine's order: the model's link (scoped; None for the
    massless base of an anchor or the light link inside a two-axis joint), the joint that moves
    it (None for the base), which of that joint's axes (1 or 2), and its parent's index (-1:
    the base)."""

    link: Optional[str]
    joint: Optional[Joint] = None
    axis: int = 1
    parent: int = -1


@dataclass(frozen=True)
class Tree:
    """Links joined by joints: ``root`` (the base link), the joint from the world that anchors
    it (None if free) and the other joints, each after the one that joins its parent."""

    root: str
    anchor: Optional[Joint]
    joints: Tuple[Joint, ...]

    @property
    def links(self) -> Tuple[str, ...]:
        """The model's links in this tree, root first."""
        return (self.root,) + tuple(j.child for j in self.joints)

    @property
    def fixed_base(self) -> bool:
        """Whether the base does not move (anchored to the world)."""
        return self.anchor is not None

    @property
    def anchor_base(self) -> bool:
        """Whether the base is a massless frame at the anchor joint (the root then moves
        about it) rather than the root link itself."""
        return self.anchor is not None and self.anchor.kind != "fixed"

    @property
    def single(self) -> bool:
        """A lone free link: a rigid body of its own, as before joints were simulated."""
        return self.anchor is None and not self.joints

    def body_links(self) -> List[BodyLink]:
        """The body's links in the engine's order (see the module's docstring)."""
        out: List[BodyLink] = []
        index: Dict[str, int] = {}
        if self.anchor_base:
            out.append(BodyLink(None))
            index[self.root] = self._add(out, self.anchor, -1)
        else:
            out.append(BodyLink(self.root))
            index[self.root] = -1
        for joint in self.joints:
            index[joint.child] = self._add(out, joint, index[joint.parent])
        return _depth_first(out)

    @staticmethod
    def _add(out: List[BodyLink], joint: Joint, parent: int) -> int:
        """Append ``joint``'s link (and a two-axis joint's light link before it): its index."""
        if joint.kind in TWO_AXES:
            out.append(BodyLink(None, joint, 1, parent))
            parent = len(out) - 2
            out.append(BodyLink(joint.child, joint, 2, parent))
        else:
            out.append(BodyLink(joint.child, joint, 1, parent))
        return len(out) - 2


def _depth_first(links: List[BodyLink]) -> List[BodyLink]:
    """``links`` (the base, then each link after its parent) depth first, each link's children
    in their order in ``links``, parents renumbered."""
    children: Dict[int, List[int]] = {}
    for index, entry in enumerate(links[1:]):
        children.setdefault(entry.parent, []).append(index)
    order: List[int] = []
    renumbered = {-1: -1}
    todo = children.get(-1, [])[::-1]
    while todo:
        index = todo.pop()
        renumbered[index] = len(order)
        order.append(index)
        todo.extend(children.get(index, [])[::-1])
    return [links[0]] + [replace(links[index + 1], parent=renumbered[links[index + 1].parent])
                         for index in order]


def trees(model: Model) -> List[Tree]:
    """The trees of a movable ``model`` (its kept joint_specs), in the order of their root
    links in the file; a link no joint touches is a tree of its own."""
    children: Dict[str, List[Joint]] = {}
    anchors: Dict[str, Joint] = {}
    has_parent = set()
    for joint in model.joint_specs:
        if joint.parent == WORLD_LINK:
            anchors[joint.child] = joint
        else:
            children.setdefault(joint.parent, []).append(joint)
        has_parent.add(joint.child)
    out = []
    for link in model.links:
        root = link.scoped
        if root in has_parent and root not in anchors:
            continue
        ordered: List[Joint] = []
        todo = [root]
        while todo:
            below = children.get(todo.pop(0), [])
            ordered.extend(below)
            todo.extend(j.child for j in below)
        out.append(Tree(root, anchors.get(root), tuple(ordered)))
    return out


def tree_of_links(model: Model) -> Dict[str, Tree]:
    """Scoped link name -> the tree it belongs to."""
    return {link: tree for tree in trees(model) for link in tree.links}


def link_by_name(model: Model) -> Dict[str, Link]:
    """Scoped link name -> Link of ``model``."""
    return {link.scoped: link for link in model.links}
