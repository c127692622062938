"""Wrenches and joint efforts of Gazebo's world API: apply_body_wrench, clear_body_wrenches,
apply_joint_effort, clear_joint_forces. Each becomes a job of the Simulation's
``AppliedForces`` (applied_forces), applied at every step from its start for its duration."""
import math
from typing import Optional, Sequence, Tuple

import numpy as np

from ...errors import RequestError
from ..engine.applied_forces import EffortJob, WrenchJob
from ..files import limits
from . import reference_frames as rf
from .request_checks import check_names, check_times
from .world_models import LinkPart


# rad/s (or m/s): a joint given an effort may turn this fast. pybullet's default of 100 clamps a
# light wheel's velocity inside a step that a large effort and its motor fight over, and the
# clamp then throws the whole robot (2 N m on a TurtleBot3 wheel did).
EFFORT_JOINT_MAX_VELOCITY = 1e4


class ForceRequests:
    """The wrench and effort requests of the world API.

    A part of ``WorldControl`` (world_control), which gives it ``sim``, ``models`` and the
    shared look-ups (``_model``, ``_frame``, ``_scoped_link``, ``_joint``)."""

    @staticmethod
    def _link_com(link: LinkPart) -> np.ndarray:
        return np.array(link.body.link_com(link.index))

    def _start_end(self, start_ns: int, duration_ns: int) -> Tuple[int, Optional[int]]:
        """A job's (start, end) in sim ns: a start of 0 or in the past is now; a negative
        duration lasts until cleared (end None)."""
        start = max(int(start_ns), self.sim.time_ns)
        return start, (None if duration_ns < 0 else start + int(duration_ns))

    def apply_body_wrench(self, body: str, reference_frame: str, point: Sequence[float],
                          force: Sequence[float], torque: Sequence[float], start_ns: int = 0,
                          duration_ns: int = -1) -> None:
        """Push link ``body`` ("model::link") with ``force`` (N) and ``torque`` (N m) from
        ``start_ns`` for ``duration_ns`` (< 0: until clear_body_wrenches).

        ``reference_frame`` "" or world: force and torque in world axes, and ``point`` (where
        the force acts) is an offset from the link's centre of mass in world axes, as Gazebo
        adds ``point x force`` to the torque about it. Another model or scoped link: force,
        torque and ``point`` are in that frame's axes and ``point`` is a position in it. The
        wrench is turned into world axes once, now, and then held (Gazebo holds it too)."""
        check_names("ApplyBodyWrench: ", body_name=body, reference_frame=reference_frame)
        found = self._scoped_link(body)
        if found is None:
            raise RequestError("ApplyBodyWrench: body does not exist")
        model, link = found
        if not rf.finite(point, force, torque):
            raise RequestError("ApplyBodyWrench: NaN or infinite value in the wrench or the "
                               "reference point")
        problem = (limits.symmetric("wrench.force", force, limits.MAX_FORCE, "N")
                   or limits.symmetric("wrench.torque", torque, limits.MAX_FORCE, "N m")
                   or limits.position_problem("reference_point", point))
        if problem:
            raise RequestError("ApplyBodyWrench: %s" % problem)
        check_times("ApplyBodyWrench", start_ns, duration_ns)
        if link.body is None:
            raise RequestError("ApplyBodyWrench: body %r is static: a wrench cannot move it"
                               % body)
        if not rf.is_world_frame(reference_frame):
            try:
                frame_pose = self.models.frame(reference_frame)[0]
            except KeyError:
                raise RequestError("ApplyBodyWrench: reference_frame not found") from None
        else:
            frame_pose = None
        f, t, r = (np.array(v, dtype=float) for v in (force, torque, point))
        if frame_pose is None:
            force_w, torque_w = f, t + np.cross(r, f)
        else:
            origin = np.array(frame_pose[0])
            force_w = np.array(rf.rotate(frame_pose[1], f))
            acts_at = origin + np.array(rf.rotate(frame_pose[1], r))
            torque_w = (np.array(rf.rotate(frame_pose[1], t))
                        + np.cross(acts_at - self._link_com(link), force_w))
        start, end = self._start_end(start_ns, duration_ns)
        self.sim.forces.add_wrench(WrenchJob(model.name, body, link.body.uid, link.index,
                                             tuple(force_w), tuple(torque_w), start, end))

    def clear_body_wrenches(self, body: str) -> int:
        """Stop every wrench on ``body``; how many there were (an unknown name: 0)."""
        return self.sim.forces.clear_wrenches(body)

    def apply_joint_effort(self, joint: str, effort: float, start_ns: int = 0,
                           duration_ns: int = -1) -> None:
        """Add ``effort`` (N m, or N on a prismatic joint) to ``joint`` from ``start_ns`` for
        ``duration_ns`` (< 0: until clear_joint_forces)."""
        check_names("ApplyJointEffort: ", joint_name=joint)
        if not math.isfinite(effort):
            raise RequestError("ApplyJointEffort: NaN or infinite effort")
        problem = limits.outside("effort", effort, -limits.MAX_FORCE, limits.MAX_FORCE,
                                 "N m (N for a prismatic joint)")
        if problem:
            raise RequestError("ApplyJointEffort: %s" % problem)
        check_times("ApplyJointEffort", start_ns, duration_ns)
        model, body, found = self._joint(joint, "ApplyJointEffort")
        body.limit_joint_rate(found.index, EFFORT_JOINT_MAX_VELOCITY)
        start, end = self._start_end(start_ns, duration_ns)
        self.sim.forces.add_effort(EffortJob(model.name, found.name, body.uid, found.index,
                                             float(effort), start, end))

    def clear_joint_forces(self, joint: str) -> int:
        """Stop every effort on ``joint``; how many there were (an unknown name: 0)."""
        return self.sim.forces.clear_efforts(joint)
