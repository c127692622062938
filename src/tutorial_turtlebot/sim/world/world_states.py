"""Model and link states of Gazebo's world API: get/set_model_state, get/set_link_state and
the states of every model and link (the model_states and link_states topics), in a reference
frame (a model or a scoped link) or the world. Poses and twists as in reference_frames."""
from typing import List, Tuple

from ...errors import RequestError
from ..files import limits
from . import reference_frames as rf
from .reference_frames import Pose, Twist
from .request_checks import check_names, checked_state, checked_world_state
from .spawn_check import landed_pose


class StateRequests:
    """The state requests of the world API (its ``_get_counts``: the header seq of each model's
    get_model_state).

    A part of ``WorldControl`` (world_control), which gives it ``sim``, ``models`` and the
    shared look-ups (``_model``, ``_frame``, ``_scoped_link``, ``_joint``)."""

    def get_model_state(self, name: str, relative: str = "") -> Tuple[Pose, Twist, int]:
        """(pose, twist, header seq) of model ``name`` relative to ``relative``."""
        check_names("GetModelState: ", model_name=name, relative_entity_name=relative)
        model = self._model(name, "GetModelState")
        frame = self._frame(relative, "GetModelState")
        pose, twist = model.pose(), model.twist()
        if frame is not None:
            pose = rf.relative_pose(pose, frame[0])
            twist = rf.relative_twist(twist, frame[1], frame[0][1])
        seq = self._get_counts.get(name, 0)
        self._get_counts[name] = seq + 1
        return pose, twist, seq

    def set_model_state(self, name: str, pose: Pose, twist: Twist, reference: str = "") -> None:
        """Teleport model ``name`` (quaternion normalised, all-zero = identity) and give it
        ``twist``; with a reference frame the pose is in that frame and the twist rotated. A
        robot asked below the floor under it stands on that floor (spawn_check.landed_pose)."""
        check_names("SetModelState: ", model_name=name, reference_frame=reference)
        pose, twist = checked_state("SetModelState", pose, twist)
        model = self._model(name, "SetModelState")
        frame = self._frame(reference, "SetModelState")
        if frame is not None:
            pose = rf.compose(frame[0], pose)
            twist = rf.model_twist_to_world(twist, frame[0][1])
            checked_world_state("SetModelState", pose, twist)
            pose = (pose[0], limits.unit_quaternion(pose[1]))
        model.set_state(self._landed(name, pose), (tuple(twist[0]), tuple(twist[1])))

    def _link(self, scoped: str, what: str):
        model_name, sep, link_name = scoped.rpartition("::")
        try:
            model = self.models.get(model_name) if sep else None
            if model is None:
                raise KeyError(scoped)
            return model, model.link(link_name)
        except KeyError:
            raise RequestError("%s: link %r does not exist (links are scoped model::link)"
                               % (what, scoped)) from None

    def get_link_state(self, scoped: str, reference: str = "") -> Tuple[Pose, Twist]:
        check_names("GetLinkState: ", link_name=scoped, reference_frame=reference)
        model, _ = self._link(scoped, "GetLinkState")
        frame = self._frame(reference, "GetLinkState")
        pose, twist = next((p, t) for n, p, t in model.link_states() if n == scoped)
        if frame is not None:
            pose = rf.relative_pose(pose, frame[0])
            twist = rf.relative_twist(twist, frame[1], frame[0][1])
        return pose, twist

    def set_link_state(self, scoped: str, pose: Pose, twist: Twist, reference: str = "") -> None:
        check_names("SetLinkState: ", link_name=scoped, reference_frame=reference)
        pose, twist = checked_state("SetLinkState", pose, twist)
        model, link = self._link(scoped, "SetLinkState")
        if link.body is None or link.index >= 0:
            raise RequestError("SetLinkState: link %r cannot be moved on its own here (it is "
                               "static or jointed): move its model" % scoped)
        frame = self._frame(reference, "SetLinkState")
        if frame is not None:
            pose = rf.compose(frame[0], pose)
            twist = rf.link_twist_to_world(twist, frame[1])
            checked_world_state("SetLinkState", pose, twist)
            pose = (pose[0], limits.unit_quaternion(pose[1]))
        model.set_link_state(link, self._landed(model.name, pose), twist)

    def _landed(self, name: str, pose: Pose) -> Pose:
        """A robot's root link ``pose`` put on top of the floor under it when its z is below
        that floor (spawn_check.landed_pose); any other model's pose as given."""
        robot = self.sim.robots.get(name)
        if robot is None:
            return pose
        return landed_pose(self.sim.physics, robot.description, pose)

    def model_states(self) -> List[Tuple[str, Pose, Twist]]:
        """(name, pose, twist) of every model in world order."""
        return [(m.name, m.pose(), m.twist()) for m in self.models.models()]

    def link_states(self) -> List[Tuple[str, Pose, Twist]]:
        """(scoped name, pose, twist) of every link of every model in world order."""
        return [s for m in self.models.models() for s in m.link_states()]
