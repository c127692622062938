"""Forces the world API adds at every physics step, without ROS: gazebo_ros's timed body wrenches
(apply_body_wrench) and joint efforts (apply_joint_effort), and links whose gravity is off
(set_link_properties gravity_mode false).

pybullet clears external forces and joint torques after each ``stepSimulation``, so
``AppliedForces.apply(now_ns)`` runs once before every step while ``active`` is true; with
nothing to apply ``Simulation.step`` only reads that one attribute.

Timing (sim time, integer ns): a job acts during every step that starts at ``now`` with
``start_ns <= now < end_ns`` (``end_ns`` None: until cleared), so a job of duration ``d`` acts
for ``d / step`` steps and gives the impulse ``F * d``; it is dropped once ``now >= end_ns``.
A job that starts later waits (after reset_simulation sends the time back, it waits again).

- A wrench is held constant in world axes: ``force`` acts at the link's centre of mass and
  ``torque`` (which already holds the moment of the force about that point) turns the link.
- An effort is the joint's own torque (N m, or N on a prismatic joint), applied as pybullet's
  TORQUE_CONTROL: it adds to whatever else acts on the joint, as Gazebo's Joint::SetForce does.
  A TurtleBot3 wheel keeps its diff drive's velocity motor, which holds the commanded wheel
  speed with up to the plugin's wheelTorque (as gazebo_ros_diff_drive's joint motor does), so a
  smaller effort on a wheel is held, a larger one turns it against the motor.
- A link without gravity gets ``-mass * gravity`` at its centre of mass at every step.
Units: N, N m, kg, m/s^2; vectors (x, y, z) in the world frame.
"""
from dataclasses import dataclass
from typing import Callable, Dict, List, Optional, Tuple

from .bullet import pybullet
from .client import Client

Vector3 = Tuple[float, float, float]


@dataclass
class WrenchJob:
    """A force and torque on one link (pybullet ``body``, link ``index``; -1 = the base)."""

    model: str
    link: str          # scoped "model::link", as clear_body_wrenches names it
    body: int
    index: int
    force: Vector3
    torque: Vector3
    start_ns: int
    end_ns: Optional[int]


@dataclass
class EffortJob:
    """An effort on one joint (pybullet ``body``, joint ``index``)."""

    model: str
    joint: str         # the joint's name, as clear_joint_forces names it
    body: int
    index: int
    effort: float
    start_ns: int
    end_ns: Optional[int]


@dataclass
class Weightless:
    """A link whose gravity is off: ``mass`` (kg) is lifted at every step."""

    model: str
    body: int
    index: int
    mass: float


def _com(body: int, index: int, client: Client):
    """World position of a link's centre of mass (pybullet's link frame is the inertial one)."""
    if index < 0:
        return client.getBasePositionAndOrientation(body)[0]
    return client.getLinkState(body, index)[0]


class AppliedForces:
    """The active wrenches, efforts and weightless links of one pybullet client."""

    def __init__(self, client: Client, gravity: Callable[[], Vector3]):
        """``gravity()`` gives the world's gravity now (m/s^2); it can change at run time."""
        self.client = client
        self.gravity = gravity
        self.wrenches: List[WrenchJob] = []
        self.efforts: List[EffortJob] = []
        self.weightless: Dict[Tuple[int, int], Weightless] = {}
        self.active = False          # anything to apply: the one check Simulation.step makes

    def _update(self) -> None:
        self.active = bool(self.wrenches or self.efforts or self.weightless)

    # --- jobs ----------------------------------------------------------------------------------

    def add_wrench(self, job: WrenchJob) -> None:
        self.wrenches.append(job)
        self._update()

    def add_effort(self, job: EffortJob) -> None:
        self.efforts.append(job)
        self._update()

    def clear_wrenches(self, link: str) -> int:
        """Drop every wrench on scoped link ``link``; how many there were."""
        before = len(self.wrenches)
        self.wrenches = [w for w in self.wrenches if w.link != link]
        self._update()
        return before - len(self.wrenches)

    def clear_efforts(self, joint: str) -> int:
        """Drop every effort on joint ``joint`` (its name, or "model::joint"); how many."""
        before = len(self.efforts)
        self.efforts = [e for e in self.efforts
                        if e.joint != joint and e.model + "::" + e.joint != joint]
        self._update()
        return before - len(self.efforts)

    def set_gravity(self, model: str, body: int, index: int, on: bool, mass: float) -> None:
        """Gravity on (the default) or off for one link of ``mass`` kg."""
        if on:
            self.weightless.pop((body, index), None)
        else:
            self.weightless[(body, index)] = Weightless(model, body, index, mass)
        self._update()

    def has_gravity(self, body: int, index: int) -> bool:
        return (body, index) not in self.weightless

    def forget_model(self, model: str) -> None:
        """Everything acting on ``model`` goes (delete_model)."""
        self.wrenches = [w for w in self.wrenches if w.model != model]
        self.efforts = [e for e in self.efforts if e.model != model]
        self.weightless = {k: v for k, v in self.weightless.items() if v.model != model}
        self._update()

    # --- every step ----------------------------------------------------------------------------

    def apply(self, now_ns: int) -> None:
        """Apply what acts during the step that starts at ``now_ns``; drop what has ended."""
        client = self.client
        world = pybullet.WORLD_FRAME
        if self.wrenches:
            if any(w.end_ns is not None and now_ns >= w.end_ns for w in self.wrenches):
                self.wrenches = [w for w in self.wrenches
                                 if w.end_ns is None or now_ns < w.end_ns]
            for w in self.wrenches:
                if w.start_ns <= now_ns:
                    client.applyExternalForce(w.body, w.index, w.force,
                                              _com(w.body, w.index, client), world)
                    client.applyExternalTorque(w.body, w.index, w.torque, world)
        if self.efforts:
            if any(e.end_ns is not None and now_ns >= e.end_ns for e in self.efforts):
                self.efforts = [e for e in self.efforts if e.end_ns is None or now_ns < e.end_ns]
            totals: Dict[Tuple[int, int], float] = {}
            for e in self.efforts:
                if e.start_ns <= now_ns:
                    key = (e.body, e.index)
                    totals[key] = totals.get(key, 0.0) + e.effort
            for (body, index), effort in totals.items():
                client.setJointMotorControl2(body, index, pybullet.TORQUE_CONTROL,
                                             force=effort)
        if self.weightless:
            gx, gy, gz = self.gravity()
            for w in self.weightless.values():
                client.applyExternalForce(w.body, w.index,
                                          (-w.mass * gx, -w.mass * gy, -w.mass * gz),
                                          _com(w.body, w.index, client), world)
        self._update()
