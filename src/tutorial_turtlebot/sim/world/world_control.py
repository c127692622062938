"""What Gazebo's world API does to the world, without ROS.

``WorldControl`` answers the requests of gazebo_ros_api_plugin against a ``Simulation``: model
and link states (with reference frames), world and model properties, spawn and delete, physics
properties, body wrenches and joint efforts (applied at every step by the simulation's
``AppliedForces``), link and joint properties, joint positions (set_model_configuration) and
the world's lights. Every refusal raises ``RequestError`` whose text is Gazebo's status
message, one line; nothing here leaves the world half changed. Call it between two physics
steps. Poses and twists as in reference_frames; times in integer ns of sim time.
"""
import math
import os
import tempfile
from dataclasses import dataclass, replace
from typing import Dict, List, Optional, Sequence, Tuple

import numpy as np

from ..engine import urdf_loader
from ..engine.bodies import Body, Joint
from ..engine.applied_forces import EffortJob, WrenchJob
from ..engine.bullet_shapes import ShapeBudgetError
from ..kinematics import rotation_matrix
from ..files.urdf_meshes import absolute_meshes, bullet_urdf_text, mesh_paths, urdf_text
from ..files import limits
from . import reference_frames as rf
from .physics_properties import PhysicsProperties, validate
from .reference_frames import Pose, Twist
from .spawn_check import landed_pose
from .spawn_request import SpawnRequest, placed, prepare_spawn
from ..engine.world_bullet import (body_pool, build_world, place_world_bodies,
                                   reused_world_bodies)
from ..files.world_lights import Light, lights_by_name
from .world_models import (ENTITY_EXISTS, SPAWN_FAILURE, LinkPart, ModelRegistry, RequestError,
                           UrdfModel, WorldModel, check_model_name, models_of_world,
                           spawn_failure, spawn_refusal, urdf_model)


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
# rad/s (or m/s): a joint given an effort may turn this fast. pybullet's default of 100 clamps a
# light wheel's velocity inside a step that a large effort and its motor fight over, and the
# clamp then throws the whole robot (2 N m on a TurtleBot3 wheel did).
EFFORT_JOINT_MAX_VELOCITY = 1e4
IDLE_WHEEL_RATE = 0.05        # rad/s: a robot whose wheels turn slower stands (its brake holds)


def _checked_state(name: str, pose: Pose, twist: Twist) -> Tuple[Pose, Twist]:
    """(pose, twist) with the quaternion normalised (all-zero: identity); RequestError naming
    the field and the limit for NaN, inf or a number beyond limits."""
    if not rf.finite(pose[0], pose[1], twist[0], twist[1]):
        raise RequestError("%s: NaN or infinite value in the pose or twist" % name)
    problem = (limits.position_problem("pose.position", pose[0])
               or limits.twist_problem("twist", twist))
    if problem:
        raise RequestError("%s: %s" % (name, problem))
    return ((tuple(float(v) for v in pose[0]), limits.unit_quaternion(pose[1])),
            (tuple(float(v) for v in twist[0]), tuple(float(v) for v in twist[1])))


def _checked_world_state(name: str, pose: Pose, twist: Twist) -> None:
    """RequestError if a state given in a reference frame lands beyond limits in the world."""
    problem = (limits.position_problem("pose.position (in the world)", pose[0])
               or limits.twist_problem("twist (in the world)", twist))
    if problem:
        raise RequestError("%s: %s" % (name, problem))


def _check_names(prefix: str, **names) -> None:
    """RequestError (``prefix`` and limits' one line) if a name or string field of a request
    is longer than limits.MAX_NAME, before anything looks it up or a message repeats it."""
    problem = limits.first(limits.name_problem(field, value) for field, value in names.items())
    if problem:
        raise RequestError(prefix + problem)


def _check_times(what: str, start_ns, duration_ns) -> None:
    """RequestError unless start and duration (ns) are whole numbers within limits."""
    for field, value in (("start_time", start_ns), ("duration", duration_ns)):
        problem = limits.outside(field, value, -limits.MAX_DURATION_NS, limits.MAX_DURATION_NS,
                                 "ns")
        if problem or value != int(value):
            raise RequestError("%s: %s" % (what, problem or "%s %r ns must be a whole number"
                                           % (field, value)))


class WorldControl:
    """The world API's semantics over a Simulation (``sim.models``, ``sim.physics``)."""

    def __init__(self, sim):
        self.sim = sim
        self._get_counts = {}
        self._lights: Optional[Dict[str, Light]] = None   # copied from the loaded world
        # spawned model -> (its text, its bodies): delete parks them for the next spawn of that
        # text (world_bullet.BodyPool: pybullet frees little of a removed body)
        self._spawned: Dict[str, Tuple[tuple, List[int]]] = {}

    @property
    def models(self) -> ModelRegistry:
        return self.sim.models

    def _frame(self, name: str, what: str) -> Optional[Tuple[Pose, Twist]]:
        """None for the world, else the (pose, twist) of the named model or scoped link."""
        if rf.is_world_frame(name):
            return None
        try:
            return self.models.frame(name)
        except KeyError:
            raise RequestError("%s: reference frame %r not found, did you forget to scope the "
                               "body by model name?" % (what, name)) from None

    def _model(self, name: str, what: str) -> WorldModel:
        try:
            return self.models.get(name)
        except KeyError:
            raise RequestError("%s: model does not exist" % what) from None

    # --- states ------------------------------------------------------------------------------

    def get_model_state(self, name: str, relative: str = "") -> Tuple[Pose, Twist, int]:
        """(pose, twist, header seq) of model ``name`` relative to ``relative``."""
        _check_names("GetModelState: ", model_name=name, relative_entity_name=relative)
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
        _check_names("SetModelState: ", model_name=name, reference_frame=reference)
        pose, twist = _checked_state("SetModelState", pose, twist)
        model = self._model(name, "SetModelState")
        frame = self._frame(reference, "SetModelState")
        if frame is not None:
            pose = rf.compose(frame[0], pose)
            twist = rf.model_twist_to_world(twist, frame[0][1])
            _checked_world_state("SetModelState", pose, twist)
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
        _check_names("GetLinkState: ", link_name=scoped, reference_frame=reference)
        model, _ = self._link(scoped, "GetLinkState")
        frame = self._frame(reference, "GetLinkState")
        pose, twist = next((p, t) for n, p, t in model.link_states() if n == scoped)
        if frame is not None:
            pose = rf.relative_pose(pose, frame[0])
            twist = rf.relative_twist(twist, frame[1], frame[0][1])
        return pose, twist

    def set_link_state(self, scoped: str, pose: Pose, twist: Twist, reference: str = "") -> None:
        _check_names("SetLinkState: ", link_name=scoped, reference_frame=reference)
        pose, twist = _checked_state("SetLinkState", pose, twist)
        model, link = self._link(scoped, "SetLinkState")
        if link.body is None or link.index >= 0:
            raise RequestError("SetLinkState: link %r cannot be moved on its own here (it is "
                               "static or jointed): move its model" % scoped)
        frame = self._frame(reference, "SetLinkState")
        if frame is not None:
            pose = rf.compose(frame[0], pose)
            twist = rf.link_twist_to_world(twist, frame[1])
            _checked_world_state("SetLinkState", pose, twist)
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

    # --- properties --------------------------------------------------------------------------

    def model_properties(self, name: str) -> ModelProperties:
        _check_names("GetModelProperties: ", model_name=name)
        model = self._model(name, "GetModelProperties")
        return ModelProperties([link.name for link in model.links], list(model.geoms),
                               list(model.joints), model.static)

    # --- spawn and delete --------------------------------------------------------------------

    def spawn(self, name: str, xml: str, pose: Pose, reference: str = "",
              kind: str = "sdf", robot_namespace: str = "") -> None:
        """Add model ``name`` built from ``xml`` at ``pose`` (in ``reference``); a robot URDF
        (one with plugins) becomes a robot whose topics and frames are in ``robot_namespace``.
        The three steps at once: the world API runs the middle one outside the loop."""
        pose = self.spawn_pose(name, pose, reference, robot_namespace)
        self.spawn_prepared(prepare_spawn(name, xml, pose, kind), pose, robot_namespace)

    def spawn_pose(self, name: str, pose: Pose, reference: str = "",
                   robot_namespace: str = "") -> Pose:
        """Step 1, in the loop (quick): the checks of a spawn's names, and the world pose of
        ``pose`` in ``reference``. RequestError (Gazebo's status text) if it cannot be."""
        _check_names(SPAWN_FAILURE, model_name=name, reference_frame=reference,
                     robot_namespace=robot_namespace)
        check_model_name(name)
        if name in self.models:
            raise RequestError(ENTITY_EXISTS)
        if not rf.is_world_frame(reference):
            try:
                frame = self.models.frame(reference)[0]
            except KeyError:
                raise spawn_failure("reference reference_frame %r not found, or it is not a "
                                    "model or a scoped link" % reference) from None
        else:
            frame = None
        try:
            return placed(pose, frame)
        except ValueError as err:
            raise spawn_failure(str(err)) from None

    def spawn_prepared(self, request: SpawnRequest, pose: Pose, robot_namespace: str = "") -> None:
        """Step 3, in the loop: build what ``spawn_request.prepare_spawn`` read and checked
        (step 2, anywhere) at world ``pose``: bounded work, the pybullet calls only."""
        name = request.name
        if name in self.models:       # taken since step 1
            raise RequestError(ENTITY_EXISTS)
        cid = self.sim.physics.client
        if request.robot is not None:
            self._add_robot(request, pose, robot_namespace)
            return
        pool = body_pool(self.sim.physics)
        if request.world is not None:
            key = ("sdf", request.digest)
            reused = pool.take(key)
            if reused is not None:
                bodies = reused_world_bodies(request.world, reused)
                place_world_bodies(request.world, bodies, cid)
            else:
                try:
                    bodies = build_world(request.world, cid)
                except ShapeBudgetError as err:
                    raise spawn_failure(str(err)) from None
                pool.remember(list(bodies.values()))
            model = models_of_world(request.world, bodies, cid)[0]
            built = list(dict.fromkeys(bodies.values()))
        else:
            model = self._load_urdf(request, pose)
            key, built = self._urdf_key(request), [model.parts[0].body.uid]
        self.models.add(model)
        self._spawned[name] = (key, built)

    def _add_robot(self, request: SpawnRequest, pose: Pose, namespace: str) -> None:
        """A robot with its URDF's plugins (read and checked by parse_spawn, before anything
        is built), written out with each mesh filename the absolute path of its file."""
        description = request.description
        fd, path = tempfile.mkstemp(suffix=".urdf", prefix="tutorial_turtlebot_robot_")
        try:
            with os.fdopen(fd, "w") as f:
                f.write(urdf_text(absolute_meshes(description.root, mesh_paths(description))))
            self.sim.add_robot(request.name, namespace, replace(description, path=path), pose)
        finally:
            os.unlink(path)

    @staticmethod
    def _urdf_key(request: SpawnRequest) -> tuple:
        """The BodyPool key of a plain URDF's body: its text's digest (relative meshes: from
        the working directory)."""
        return ("urdf", request.digest, os.getcwd())

    def _load_urdf(self, request: SpawnRequest, pose: Pose) -> WorldModel:
        """A model of the plain URDF of ``request`` loaded at ``pose``, written for pybullet
        one element a line (urdf_meshes.bullet_urdf_text: it cuts long lines)."""
        cid = self.sim.physics.client
        name = request.name
        collisions = request.description.collision_names()
        with spawn_refusal():   # meshes as pybullet loads them (urdf_meshes; prepared: cached)
            urdf = bullet_urdf_text(request.plain_urdf(), os.getcwd())
        pool = body_pool(self.sim.physics)
        reused = pool.take(self._urdf_key(request))
        if reused:
            urdf_loader.setup_movable(cid, reused[0])
            body = Body(cid, reused[0])
        else:
            with spawn_refusal():
                body = urdf_loader.load_movable(cid, urdf)
            pool.remember([body.uid])
        model = urdf_model(UrdfModel, name, body, spawn_pose=pose, collisions=collisions,
                           urdf=urdf)
        model.set_state(pose, rf.ZERO_TWIST)
        return model

    def delete(self, name: str) -> None:
        _check_names("DeleteModel: ", model_name=name)
        model = self._model(name, "DeleteModel")  # refuses an unknown name
        self.sim.forces.forget_model(name)   # its wrenches and efforts go with it
        key, built = self._spawned.pop(name, (None, []))
        bodies = list(dict.fromkeys(p.body.uid for p in model.parts))
        pool = body_pool(self.sim.physics)
        # its bodies wait for the next spawn of the same text, unless they were rebuilt since
        if key is not None and bodies == built and pool.park(key, bodies):
            model.parts = []
        elif key is not None:   # (a robot's body is its RobotBody's to park)
            pool.forget(bodies + built)
        self.sim.remove_model(name)

    # --- physics -----------------------------------------------------------------------------

    def physics_properties(self) -> PhysicsProperties:
        return self.sim.physics_properties

    def set_physics_properties(self, props: PhysicsProperties) -> None:
        """Apply ``props``: step, real-time factor (the caller paces), gravity, Bullet's
        counterparts of the ODE fields."""
        try:
            validate(props)
        except ValueError as err:
            raise RequestError("SetPhysicsProperties: %s" % err) from None
        self.sim.set_physics_properties(props)


    # --- wrenches and efforts ------------------------------------------------------------------

    def _scoped_link(self, scoped: str) -> Optional[Tuple[WorldModel, LinkPart]]:
        """The model and link a scoped "model::link" names; None if there is none."""
        model_name, sep, link_name = scoped.rpartition("::")
        if not sep or model_name not in self.models:
            return None
        model = self.models.get(model_name)
        try:
            return model, model.link(link_name)
        except KeyError:
            return None

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
        _check_names("ApplyBodyWrench: ", body_name=body, reference_frame=reference_frame)
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
        _check_times("ApplyBodyWrench", start_ns, duration_ns)
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

    def _joint_owners(self, name: str) -> Tuple[List[WorldModel], str]:
        """(the models a joint ``name`` may belong to, in world order; the joint's own name):
        the one model "model::joint" names, else every model."""
        model_name, sep, joint_name = name.rpartition("::")
        if sep and model_name in self.models:
            return [self.models.get(model_name)], joint_name
        return self.models.models(), name

    def _joint(self, name: str, what: str) -> Tuple[WorldModel, Body, Joint]:
        """(model, body, joint) of the movable joint ``name`` (the first model in world order
        that has one of that name, or "model::joint")."""
        candidates, joint_name = self._joint_owners(name)
        for model in candidates:
            if joint_name not in model.joints:
                continue
            for part in model.parts:
                if not part.movable:
                    continue
                for joint in part.body.joints():
                    if joint.name == joint_name and joint.movable:
                        return model, part.body, joint
        raise RequestError("%s: joint not found" % what)

    def _listed_joint(self, name: str) -> Optional[str]:
        """The <joint type> of the first model (in world order, or the one "model::joint"
        names) that lists joint ``name`` without simulating it; None if none does."""
        candidates, joint_name = self._joint_owners(name)
        for model in candidates:
            if joint_name in model.joint_types:
                return model.joint_types[joint_name]
        return None

    def apply_joint_effort(self, joint: str, effort: float, start_ns: int = 0,
                           duration_ns: int = -1) -> None:
        """Add ``effort`` (N m, or N on a prismatic joint) to ``joint`` from ``start_ns`` for
        ``duration_ns`` (< 0: until clear_joint_forces)."""
        _check_names("ApplyJointEffort: ", joint_name=joint)
        if not math.isfinite(effort):
            raise RequestError("ApplyJointEffort: NaN or infinite effort")
        problem = limits.outside("effort", effort, -limits.MAX_FORCE, limits.MAX_FORCE,
                                 "N m (N for a prismatic joint)")
        if problem:
            raise RequestError("ApplyJointEffort: %s" % problem)
        _check_times("ApplyJointEffort", start_ns, duration_ns)
        model, body, found = self._joint(joint, "ApplyJointEffort")
        body.limit_joint_rate(found.index, EFFORT_JOINT_MAX_VELOCITY)
        start, end = self._start_end(start_ns, duration_ns)
        self.sim.forces.add_effort(EffortJob(model.name, found.name, body.uid, found.index,
                                             float(effort), start, end))

    def clear_joint_forces(self, joint: str) -> int:
        """Stop every effort on ``joint``; how many there were (an unknown name: 0)."""
        return self.sim.forces.clear_efforts(joint)

    # --- link and joint properties ---------------------------------------------------------------

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
        _check_names(what + ": ", link_name=scoped)
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
        tensor = np.array([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]], dtype=float)
        if np.linalg.eigvalsh(tensor).min() <= 0:
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
        _check_names("GetJointProperties: ", joint_name=joint)
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

    def set_model_configuration(self, name: str, joints: Sequence[str],
                                positions: Sequence[float]) -> str:
        """Put the named joints of model ``name`` at ``positions`` (rad or m), at rest; the
        model's root link stays where it is. Joints the model does not have are ignored, as
        Gazebo ignores them; the answer (Gazebo's status text) names them."""
        _check_names("SetModelConfiguration: ", model_name=name)
        _check_names("SetModelConfiguration: ", **{"joint_names[%d]" % i: joint
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

    # --- lights ----------------------------------------------------------------------------------

    def lights(self) -> Dict[str, Light]:
        """The world's lights by name (copies of the loaded world's, made the first time)."""
        if self._lights is None:
            self._lights = lights_by_name(self.sim.world.lights)
        return self._lights

    def get_light(self, name: str) -> Light:
        _check_names("getLightProperties: ", light_name=name)
        light = self.lights().get(name)
        if light is None:
            raise RequestError("getLightProperties: Requested light %s not found!" % name)
        return replace(light)

    def set_light(self, name: str, cast_shadows: bool, diffuse: Sequence[float],
                  specular: Sequence[float], attenuation: Sequence[float],
                  direction: Sequence[float], pose: Pose) -> None:
        """Keep what set_light_properties gives: ``attenuation`` (constant, linear,
        quadratic); the pose's quaternion normalised (all-zero: identity)."""
        _check_names("setLightProperties: ", light_name=name)
        light = self.lights().get(name)
        if light is None:
            raise RequestError("setLightProperties: Requested light %s not found!" % name)
        if not rf.finite(diffuse, specular, attenuation, direction, pose[0], pose[1]):
            raise RequestError("setLightProperties: NaN or infinite value in the request")
        problem = limits.position_problem("pose.position", pose[0])
        if problem:
            raise RequestError("setLightProperties: %s" % problem)
        light.cast_shadows = bool(cast_shadows)
        light.diffuse = tuple(float(v) for v in diffuse)
        light.specular = tuple(float(v) for v in specular)
        light.attenuation_constant, light.attenuation_linear, light.attenuation_quadratic = (
            float(v) for v in attenuation)
        light.direction = tuple(float(v) for v in direction)
        light.pose = (tuple(float(v) for v in pose[0]), limits.unit_quaternion(pose[1]))
