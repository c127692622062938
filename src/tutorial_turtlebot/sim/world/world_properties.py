"""Model, link and joint properties of Gazebo's world API: get_model_properties,
get/set_link_properties (mass, inertia, gravity) and get/set_joint_properties."""
from dataclasses import dataclass
from typing import List, Mapping, Sequence, Tuple

import numpy as np

from ...errors import RequestError
from ..engine.bodies import NO_STOP, ONE_AXIS
from ..files import limits
from ..kinematics import rotation_matrix
from . import reference_frames as rf
from .physics_properties import MAX_TIME_STEP
from .request_checks import check_names
from .world_models import LinkPart, WorldModel


@dataclass
class ModelProperties:
    """get_model_properties' answer."""

    body_names: List[str]
    geom_names: List[str]
    joint_names: List[str]
    is_static: bool


@dataclass
class LinkProperties:
    """get_link_properties' answer: the centre of mass in the link frame (x, y, z), m; the
    inertia tensor about it in the link's axes (ixx, ixy, ixz, iyy, iyz, izz), kg m^2."""

    com: Tuple[float, float, float]
    gravity_mode: bool
    mass: float
    inertia: Tuple[float, float, float, float, float, float]


@dataclass
class JointProperties:
    """get_joint_properties' answer: ``kind`` revolute, prismatic or ball; one value per axis:
    damping (N m s/rad or N s/m), position (rad or m), rate (rad/s or m/s)."""

    kind: str
    damping: List[float]
    position: List[float]
    rate: List[float]


JOINT_KINDS = ("revolute", "prismatic", "ball")   # what get_joint_properties names (else revolute)
COM_TOLERANCE = 1e-6          # m: a set com.position this close to the present one is unchanged
# set_joint_properties' ode_joint_config (gazebo_msgs/ODEJointProperties): each array's field
# name -> the bounds (low, high) and unit every element is held to. Gazebo sets element i on
# axis i; the joints here have one axis, so the first element is what counts (damping, hiStop,
# loStop, fmax, vel are applied; erp, cfm, stop_erp, stop_cfm, fudge_factor are ODE's own).
JOINT_CONFIG_FIELDS = {
    "damping": (0.0, limits.MAX_DAMPING, "N m s/rad or N s/m"),
    "hiStop": (-limits.MAX_JOINT_POSITION, limits.MAX_JOINT_POSITION, "rad or m"),
    "loStop": (-limits.MAX_JOINT_POSITION, limits.MAX_JOINT_POSITION, "rad or m"),
    "erp": (-limits.MAX_ODE_VALUE, limits.MAX_ODE_VALUE, ""),
    "cfm": (-limits.MAX_ODE_VALUE, limits.MAX_ODE_VALUE, ""),
    "stop_erp": (-limits.MAX_ODE_VALUE, limits.MAX_ODE_VALUE, ""),
    "stop_cfm": (-limits.MAX_ODE_VALUE, limits.MAX_ODE_VALUE, ""),
    "fudge_factor": (-limits.MAX_ODE_VALUE, limits.MAX_ODE_VALUE, ""),
    "fmax": (0.0, limits.MAX_FORCE, "N m or N"),
    "vel": (-limits.MAX_ANGULAR_SPEED, limits.MAX_ANGULAR_SPEED, "rad/s or m/s")}


def joint_config_problem(config: Mapping[str, Sequence[float]]) -> str:
    """The refusal of the first element of ``config`` (ODEJointProperties' field name -> its
    array) that is NaN, infinite or out of JOINT_CONFIG_FIELDS' bounds; "" if there is none.
    Every element is checked (at numpy's pace: an array may be long)."""
    for field, (low, high, unit) in JOINT_CONFIG_FIELDS.items():
        values = config.get(field, ())
        if len(values) == 0:
            continue
        try:
            array = np.asarray(values, dtype=float).reshape(-1)
        except (TypeError, ValueError, OverflowError):
            return "ode_joint_config.%s must be numbers" % field
        bad = np.flatnonzero(~(np.isfinite(array) & (array >= low) & (array <= high)))
        if bad.size:
            i = int(bad[0])
            if not np.isfinite(array[i]):
                return "ode_joint_config.%s[%d]: NaN or infinite value" % (field, i)
            return limits.outside("ode_joint_config.%s[%d]" % (field, i), float(array[i]),
                                  low, high, unit)
    return ""


class PropertyRequests:
    """The property requests of the world API.

    A part of ``WorldControl`` (world_control), which gives it ``sim``, ``models`` and the
    shared look-ups (``_model``, ``_frame``, ``_scoped_link``, ``_joint``)."""

    def model_properties(self, name: str) -> ModelProperties:
        check_names("GetModelProperties: ", model_name=name)
        model = self._model(name, "GetModelProperties")
        return ModelProperties([link.name for link in model.links], list(model.geoms),
                               list(model.joints), model.static)

    @staticmethod
    def _inertial(link: LinkPart):
        """(mass, com position in the link frame, rotation of pybullet's inertia axes in the
        link frame as a 3x3, principal moments) of a movable link."""
        inertial = link.body.inertial(link.index)
        com = rf.inverse(link.in_body) if link.index < 0 else \
            rf.compose(rf.inverse(link.in_body), inertial.com)
        rotation = rotation_matrix(com[1])
        return inertial.mass, tuple(com[0]), rotation, np.array(inertial.moments, dtype=float)

    def _properties_link(self, scoped: str, what: str) -> Tuple[WorldModel, LinkPart]:
        """(model, link) that ``scoped`` ("model::link") names for service ``what``;
        RequestError (Gazebo's text) if the name is bad or there is none."""
        check_names(what + ": ", link_name=scoped)
        found = self._scoped_link(scoped)
        if found is None:
            raise RequestError("%s: link not found, did you forget to scope the link by model "
                               "name?" % what)
        return found

    def get_link_properties(self, scoped: str) -> LinkProperties:
        found = self._properties_link(scoped, "GetLinkProperties")
        _, link = found
        if link.body is None:   # part of a static model: nothing moves it
            return LinkProperties((0.0, 0.0, 0.0), True, 0.0, (0.0,) * 6)
        mass, com, rotation, moments = self._inertial(link)
        t = rotation @ np.diag(moments) @ rotation.T
        return LinkProperties(tuple(float(v) for v in com),
                              self.sim.forces.has_gravity(link.body.uid, link.index),
                              float(mass),
                              tuple(float(v) for v in (t[0, 0], t[0, 1], t[0, 2], t[1, 1],
                                                       t[1, 2], t[2, 2])))

    def set_link_properties(self, scoped: str, com: Sequence[float], gravity_mode: bool,
                            mass: float, inertia: Sequence[float],
                            com_orientation: Sequence[float] = (0.0, 0.0, 0.0, 1.0)) -> None:
        """Set a link's mass (kg), inertia (ixx, ixy, ixz, iyy, iyz, izz about its centre of
        mass, link axes, kg m^2) and whether gravity pulls it. ``com`` (the centre of mass in
        the link frame, m) must stay where it is: pybullet cannot move it in a built body;
        ``com_orientation`` (a quaternion x y z w) must be finite and is otherwise ignored, as
        Gazebo ignores it."""
        found = self._properties_link(scoped, "SetLinkProperties")
        model, link = found
        if not rf.finite(com, (mass,), inertia, com_orientation):
            raise RequestError("SetLinkProperties: NaN or infinite value in the request")
        if link.body is None:
            raise RequestError("SetLinkProperties: link %r is static here: it has no mass to set"
                               % scoped)
        if mass <= 0:
            raise RequestError("SetLinkProperties: mass %g kg must be > 0" % mass)
        ixx, ixy, ixz, iyy, iyz, izz = inertia
        if not limits.positive_definite((ixx, iyy, izz), (ixy, ixz, iyz)):
            raise RequestError("SetLinkProperties: the inertia tensor (ixx %g iyy %g izz %g "
                               "ixy %g ixz %g iyz %g) must be positive definite"
                               % (ixx, iyy, izz, ixy, ixz, iyz))
        problem = (limits.mass_problem(mass)
                   or limits.inertia_problem((ixx, iyy, izz), (ixy, ixz, iyz))
                   or limits.position_problem("com.position", com))
        if problem:
            raise RequestError("SetLinkProperties: %s" % problem)
        _, present, rotation, _ = self._inertial(link)
        if max(abs(a - b) for a, b in zip(com, present)) > COM_TOLERANCE:
            raise RequestError("SetLinkProperties: the centre of mass cannot be moved here: keep "
                               "com.position at %.6g %.6g %.6g" % present)
        tensor = np.array([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]], dtype=float)
        local = rotation.T @ tensor @ rotation     # in pybullet's inertia axes of the link
        off = max(abs(local[0, 1]), abs(local[0, 2]), abs(local[1, 2]))
        if off > 1e-6 * max(abs(np.diag(local))):
            raise RequestError("SetLinkProperties: products of inertia off the link's inertia "
                               "axes are not supported here (the axes cannot turn)")
        link.body.set_inertial(link.index, float(mass), tuple(np.diag(local)))
        self.sim.forces.set_gravity(model.name, link.body.uid, link.index, bool(gravity_mode),
                                    float(mass))

    def get_joint_properties(self, joint: str) -> JointProperties:
        """A movable joint's kind, damping, position and rate; a joint get_model_properties
        lists that is not simulated (an SDF model's: its links do not move about it) is of its
        <joint type>, at 0 and still."""
        check_names("GetJointProperties: ", joint_name=joint)
        try:
            _, body, found = self._joint(joint, "GetJointProperties")
        except RequestError:
            kind = self._listed_joint(joint)
            if kind is None:
                raise
            return JointProperties(kind, [0.0], [0.0], [0.0])
        position, rate = body.joint_state(found.index)
        kind = found.kind if found.kind in JOINT_KINDS else "revolute"
        return JointProperties(kind, [body.joint_damping(found.index)], [float(position)],
                               [float(rate)])

    def set_joint_properties(self, joint: str, config: Mapping[str, Sequence[float]]) -> None:
        """Set what Gazebo's set_joint_properties sets of a joint (found as get_joint_properties
        finds it), from ``config``: ODEJointProperties' field name -> its array, of which the
        first element counts (an empty array changes nothing). A one-axis joint (revolute,
        prismatic) takes damping (N m s/rad or N s/m), hiStop and loStop (rad or m; the side not
        given keeps its stop) and fmax and vel (its velocity motor: at most fmax N m or N
        towards vel rad/s or m/s; the side not given keeps its value); erp, cfm, stop_erp,
        stop_cfm and fudge_factor are checked and left (ODE's own). Every element must be
        finite and within JOINT_CONFIG_FIELDS' bounds, and the stops must leave a range (loStop
        <= hiStop): else RequestError, and nothing is changed. A joint that is listed but not
        simulated (an SDF model's) takes the request and nothing moves."""
        check_names("SetJointProperties: ", joint_name=joint)
        try:
            _, body, found = self._joint(joint, "SetJointProperties")
        except RequestError:
            if self._listed_joint(joint) is None:
                raise
            body = found = None
        problem = joint_config_problem(config)
        if problem:
            raise RequestError("SetJointProperties: %s" % problem)
        if found is None or found.kind not in ONE_AXIS:
            return
        first = {field: float(values[0]) for field, values in config.items()
                 if field in JOINT_CONFIG_FIELDS and len(values) > 0}
        index = found.index
        stops = None
        if "hiStop" in first or "loStop" in first:
            lower, upper = body.joint_stops(index)
            lower, upper = first.get("loStop", lower), first.get("hiStop", upper)
            if lower > upper:
                raise RequestError(
                    "SetJointProperties: loStop %s is above hiStop %s (rad or m): the joint "
                    "would have no range; keep loStop <= hiStop" % (
                        _stop_text(lower), _stop_text(upper)))
            stops = lower, upper
        if "damping" in first:
            body.set_joint_damping(index, first["damping"], MAX_TIME_STEP)
        if stops is not None:
            body.set_joint_stops(index, *stops)
        if "vel" in first or "fmax" in first:
            velocity, max_force = body.joint_motor(index)
            body.set_joint_motor(index, first.get("vel", velocity), first.get("fmax", max_force))


def _stop_text(value: float) -> str:
    """A stop as a refusal names it: "none" for a side without a stop."""
    return "none" if abs(value) >= NO_STOP else "%g" % value
