"""What every running model plugin of world.model_plugins is: ``RunningPlugin`` (its data, its
model, its topics' namespace, its schedule, its noise; its ``tick`` and ``restart``), the
``Odometry`` that p3d and the drives report, and the joints a model simulates by name
(``movable_joints``, ``find_joints``). Knows nothing of ROS. Frames: world (z up) unless said.
Units: m, s, rad.
"""
from typing import Callable, Dict, List, NamedTuple, Sequence, Tuple

import numpy as np

from .. import kinematics
from . import reference_frames as rf
from .schedule import RateSchedule

NS_PER_S = 1e9
Vec = Tuple[float, float, float]


class Odometry(NamedTuple):
    """p3d's message: pose (position, orientation x y z w) of the body in the frame, twist
    (linear, angular), and the variance on both covariances' diagonals."""

    position: Vec
    orientation: Tuple[float, float, float, float]
    linear: Vec
    angular: Vec
    variance: float


class RunningPlugin:
    """One model plugin of a model: its data (``spec``), the model, the namespace its topics
    are in ("" = the node's), its schedule and its own noise."""

    kind = ""

    def __init__(self, spec, model, namespace: str, step_rate: float, rng: np.random.Generator,
                 gravity: Callable[[], Vec]):
        self.spec = spec
        self.model = model
        self.namespace = namespace
        self.rng = rng
        self.gravity = gravity
        self.schedule = RateSchedule(self.rate(step_rate))

    def rate(self, step_rate: float) -> float:
        """Its ticks' rate (Hz of sim time): its <updateRate>, at most the physics' own
        (``step_rate``); 0 is every physics step."""
        return min(self.spec.update_rate or step_rate, step_rate)

    @property
    def name(self) -> str:
        """"model::plugin"."""
        return "%s::%s" % (self.model.name, self.spec.name)

    def link(self, name: str) -> Tuple[rf.Pose, rf.Twist]:
        """World pose and twist of link ``name`` (below the model) now (a robot's link that a
        fixed joint joins to its parent: from the root link's); KeyError if the model no
        longer has it."""
        states = {link: (pose, twist) for link, pose, twist in self.model.link_states()}
        found = states.get(self.model.name + "::" + name)
        if found is not None:
            return found
        body = getattr(self.model, "robot_body", None)     # a robot's link joined by a fixed
        description = getattr(body, "description", None)   # joint: in its root link's body
        if description is None or name not in description.links:
            raise KeyError(name)
        (root_position, root_orientation), (linear, angular) = states[
            self.model.name + "::" + description.root_link]
        in_root = description.transform(description.root_link, name)
        lever = rf.rotate(root_orientation, in_root[:3, 3])
        pose = rf.compose((root_position, root_orientation),
                          (tuple(in_root[:3, 3]), kinematics.quat_from_matrix(in_root[:3, :3])))
        return pose, (tuple(np.add(linear, np.cross(angular, lever))), angular)

    def restart(self) -> None:
        """Its state as when it was loaded (reset_world, reset_simulation)."""

    def tick(self, now_ns: int) -> None:
        """What it does at each of its ticks, before it is read (a drive's control)."""


def movable_joints(model) -> Dict[str, Tuple[object, int]]:
    """{name: (body, joint index)} of the movable joints of ``model``'s movable bodies, as
    Body.joints() names them (the first of a name)."""
    found: Dict[str, Tuple[object, int]] = {}
    for part in model.parts:
        if part.movable:
            for joint in part.body.joints():
                if joint.movable:
                    found.setdefault(joint.name, (part.body, joint.index))
    return found


def find_joints(model, names: Sequence[str]) -> List[Tuple[object, int]]:
    """(body, joint index) of each of the movable joints ``names`` of ``model``'s bodies;
    KeyError for one the model does not simulate."""
    found = movable_joints(model)
    return [found[name] for name in names]
