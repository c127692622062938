"""What Gazebo's world API does to the world, without ROS (gazebo_api.md 2.3-2.6).

``WorldControl`` answers the requests of gazebo_ros_api_plugin against a ``Simulation``: model
and link states (with reference frames), world and model properties, spawn and delete, physics
properties. Every refusal raises ``RequestError`` whose text is Gazebo's status message, one
line; nothing here leaves the world half changed. Call it between two physics steps.
Poses and twists as in reference_frames.
"""
import os
import tempfile
from dataclasses import dataclass, replace
from typing import List, Optional, Tuple

from ..errors import UserError
from .bullet import pybullet, quiet_output
from .urdf_file import read_urdf_text
from . import reference_frames as rf
from .physics_properties import PhysicsProperties, validate
from .reference_frames import Pose, Twist
from .spawn_request import parse_spawn, placed
from .world_bullet import MOVABLE_COLLISION_GROUP, MOVABLE_COLLISION_MASK, build_world
from .world_models import (ModelRegistry, RequestError, WorldModel, check_model_name,
                           model_of_urdf_body, models_of_world)


@dataclass
class ModelProperties:
    """get_model_properties' answer."""

    body_names: List[str]
    geom_names: List[str]
    joint_names: List[str]
    is_static: bool


def _finite_state(name: str, pose: Pose, twist: Twist) -> None:
    if not rf.finite(pose[0], pose[1], twist[0], twist[1]):
        raise RequestError("%s: NaN or infinite value in the pose or twist" % name)


class WorldControl:
    """The world API's semantics over a Simulation (``sim.models``, ``sim.physics``)."""

    def __init__(self, sim):
        self.sim = sim
        self._get_counts = {}

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
        ``twist``; with a reference frame the pose is in that frame and the twist rotated."""
        _finite_state("SetModelState", pose, twist)
        model = self._model(name, "SetModelState")
        frame = self._frame(reference, "SetModelState")
        pose = (tuple(pose[0]), rf.normalized(pose[1]))
        if frame is not None:
            pose = rf.compose(frame[0], pose)
            twist = rf.model_twist_to_world(twist, frame[0][1])
        model.set_state(pose, (tuple(twist[0]), tuple(twist[1])))

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
        model, _ = self._link(scoped, "GetLinkState")
        frame = self._frame(reference, "GetLinkState")
        pose, twist = next((p, t) for n, p, t in model.link_states() if n == scoped)
        if frame is not None:
            pose = rf.relative_pose(pose, frame[0])
            twist = rf.relative_twist(twist, frame[1], frame[0][1])
        return pose, twist

    def set_link_state(self, scoped: str, pose: Pose, twist: Twist, reference: str = "") -> None:
        _finite_state("SetLinkState", pose, twist)
        model, link = self._link(scoped, "SetLinkState")
        if link.body is None or link.index >= 0:
            raise RequestError("SetLinkState: link %r cannot be moved on its own here (it is "
                               "static or jointed): move its model" % scoped)
        frame = self._frame(reference, "SetLinkState")
        pose = (tuple(pose[0]), rf.normalized(pose[1]))
        if frame is not None:
            pose = rf.compose(frame[0], pose)
            twist = rf.link_twist_to_world(twist, frame[1])
        model.set_link_state(link, pose, twist)

    def model_states(self) -> List[Tuple[str, Pose, Twist]]:
        """(name, pose, twist) of every model in world order."""
        return [(m.name, m.pose(), m.twist()) for m in self.models.models()]

    def link_states(self) -> List[Tuple[str, Pose, Twist]]:
        """(scoped name, pose, twist) of every link of every model in world order."""
        return [s for m in self.models.models() for s in m.link_states()]

    # --- properties --------------------------------------------------------------------------

    def model_properties(self, name: str) -> ModelProperties:
        model = self._model(name, "GetModelProperties")
        return ModelProperties([link.name for link in model.links], list(model.geoms),
                               list(model.joints), model.static)

    # --- spawn and delete --------------------------------------------------------------------

    def spawn(self, name: str, xml: str, pose: Pose, reference: str = "",
              kind: str = "sdf", robot_namespace: str = "") -> None:
        """Add model ``name`` built from ``xml`` at ``pose`` (in ``reference``); a robot URDF
        (one with plugins) becomes a robot whose topics and frames are in ``robot_namespace``."""
        check_model_name(name)
        if name in self.models:
            raise RequestError("SpawnModel: Failure - entity already exists.")
        if not rf.is_world_frame(reference):
            try:
                frame = self.models.frame(reference)[0]
            except KeyError:
                raise RequestError("SpawnModel: Failure - reference reference_frame %r not "
                                   "found, or it is not a model or a scoped link"
                                   % reference) from None
        else:
            frame = None
        try:
            pose = placed(pose, frame)
        except ValueError as err:
            raise RequestError("SpawnModel: Failure - %s" % err) from None
        request = parse_spawn(name, xml, pose, kind)
        cid = self.sim.physics.client
        if request.robot is not None:
            self._add_robot(name, request.robot, pose, robot_namespace)
            return
        if request.world is not None:
            bodies = build_world(request.world, cid)
            model = models_of_world(request.world, bodies, cid, source="spawned")[0]
        else:
            model = self._load_urdf(name, request.urdf, pose)
        self.models.add(model)

    def _add_robot(self, name: str, urdf: str, pose: Pose, namespace: str) -> None:
        """A robot with its URDF's plugins; its <gazebo> blocks are checked before anything
        is built (a bad one refuses the spawn naming the element)."""
        fd, path = tempfile.mkstemp(suffix=".urdf", prefix="tutorial_turtlebot_robot_")
        try:
            with os.fdopen(fd, "w") as f:
                f.write(urdf)
            try:
                description = read_urdf_text(urdf, "model_xml of %s" % name)
            except UserError as err:
                raise RequestError("SpawnModel: Failure - %s" % err) from None
            self.sim.add_robot(name, namespace, replace(description, path=path), pose)
        finally:
            os.unlink(path)

    def _load_urdf(self, name: str, urdf: str, pose: Pose) -> WorldModel:
        cid = self.sim.physics.client
        fd, path = tempfile.mkstemp(suffix=".urdf", prefix="tutorial_turtlebot_spawn_")
        try:
            with os.fdopen(fd, "w") as f:
                f.write(urdf)
            try:
                with quiet_output():
                    body = pybullet.loadURDF(path, flags=pybullet.URDF_MERGE_FIXED_LINKS
                                             | pybullet.URDF_USE_INERTIA_FROM_FILE,
                                             physicsClientId=cid)
            except pybullet.error as err:
                raise RequestError("SpawnModel: Failure - pybullet could not load the URDF: %s"
                                   % err) from None
        finally:
            os.unlink(path)
        for link in range(-1, pybullet.getNumJoints(body, physicsClientId=cid)):
            pybullet.setCollisionFilterGroupMask(body, link, MOVABLE_COLLISION_GROUP,
                                                 MOVABLE_COLLISION_MASK, physicsClientId=cid)
            pybullet.changeDynamics(body, link, lateralFriction=1.0,
                                    activationState=pybullet.ACTIVATION_STATE_DISABLE_SLEEPING,
                                    physicsClientId=cid)
        model = model_of_urdf_body(name, body, cid, "spawned", spawn_pose=pose)
        model.set_state(pose, rf.ZERO_TWIST)
        return model

    def delete(self, name: str) -> None:
        self._model(name, "DeleteModel")  # refuses an unknown name
        self.models.remove(name)

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

