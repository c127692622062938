"""set_model_configuration of Gazebo's world API: a model's joints put at given positions, at
rest, its root link where it is."""
from typing import Dict, Sequence, Tuple

from ...errors import RequestError
from ..engine.bodies import Body
from ..files import limits
from . import reference_frames as rf
from .request_checks import check_names

IDLE_WHEEL_RATE = 0.05        # rad/s: a robot whose wheels turn slower stands (its brake holds)


class ConfigurationRequests:
    """The joint position request of the world API.

    A part of ``WorldControl`` (world_control), which gives it ``sim``, ``models`` and the
    shared look-ups (``_model``, ``_frame``, ``_scoped_link``, ``_joint``)."""

    def set_model_configuration(self, name: str, joints: Sequence[str],
                                positions: Sequence[float]) -> str:
        """Put the named joints of model ``name`` at ``positions`` (rad or m), at rest; the
        model's root link stays where it is. Joints the model does not have are ignored, as
        Gazebo ignores them; the answer (Gazebo's status text) names them."""
        check_names("SetModelConfiguration: ", model_name=name)
        check_names("SetModelConfiguration: ", **{"joint_names[%d]" % i: joint
                                                  for i, joint in enumerate(joints)})
        model = self._model(name, "SetModelConfiguration")
        if len(joints) != len(positions):
            raise RequestError("SetModelConfiguration: joint name and position list have "
                               "different lengths")
        if not rf.finite(positions):
            raise RequestError("SetModelConfiguration: NaN or infinite joint position")
        problem = limits.first(limits.outside("joint_positions[%d]" % i, v,
                                              -limits.MAX_JOINT_POSITION,
                                              limits.MAX_JOINT_POSITION, "rad or m")
                               for i, v in enumerate(positions))
        if problem:
            raise RequestError("SetModelConfiguration: %s" % problem)
        movable: Dict[str, Tuple[Body, int]] = {}
        for part in model.parts:
            if part.movable:
                for joint in part.body.joints():
                    if joint.movable:
                        movable.setdefault(joint.name, (part.body, joint.index))
        wanted = dict(zip(joints, positions))   # the last of a repeated name wins, as Gazebo's
        robot = self.sim.robots.get(name)
        idle = robot is not None and robot.body.wheels and max(
            abs(v) for v in robot.body.wheel_states()[1]) < IDLE_WHEEL_RATE
        for joint, position in wanted.items():
            if joint in movable:
                body, index = movable[joint]
                body.set_joint(index, float(position), 0.0)
        if idle and any(movable[j][1] in robot.body.wheels for j in wanted if j in movable):
            # an idle robot's wheels are held where they stopped: hold them where they are now
            robot.body.set_wheel_velocities(0.0, 0.0)
        ignored = [j for j in wanted if j not in movable]
        if ignored:
            return ("SetModelConfiguration: success (ignored, as Gazebo does: model %s has no "
                    "joint %s)" % (name, ", ".join(ignored)))
        return "SetModelConfiguration: success"
