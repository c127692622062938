"""Model, link and joint properties of Gazebo's world API: get_model_properties,
get/set_link_properties (mass, inertia, gravity) and get_joint_properties."""
from dataclasses import dataclass
from typing import List, Sequence, Tuple

import numpy as np

from ...errors import RequestError
from ..files import limits
from ..kinematics import rotation_matrix
from . import reference_frames as rf
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
        com = rf.inverse(link.in_body) if link.index < 0 else inertial.com
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
        return JointProperties(kind, [found.damping], [float(position)], [float(rate)])
