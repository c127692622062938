"""What Gazebo's world API does to the world, without ROS.

``WorldControl`` answers the requests of gazebo_ros_api_plugin against a ``Simulation``: model
and link states (with reference frames), world and model properties, spawn and delete, physics
properties, body wrenches and joint efforts (applied at every step by the simulation's
``AppliedForces``), link and joint properties, joint positions (set_model_configuration) and
the world's lights. Every refusal raises ``RequestError`` whose text is Gazebo's status
message, one line; nothing here leaves the world half changed. Call it between two physics
steps. Poses and twists as in reference_frames; times in integer ns of sim time.

Each group of requests is a class of its own module, and ``WorldControl`` is all of them over
one simulation, with the look-ups they share: world_states (model and link states),
world_properties (model, link and joint properties), world_spawns (spawn and delete),
world_physics (physics properties), world_forces (wrenches and joint efforts),
world_configuration (set_model_configuration), world_lighting (lights); request_checks holds
the checks of their fields.
"""
from typing import Dict, List, Optional, Tuple

from ...errors import RequestError
from ..engine.bodies import Body, Joint
from ..files.sdf.world_lights import Light
from . import reference_frames as rf
from .reference_frames import Pose, Twist
from .world_configuration import ConfigurationRequests
from .world_forces import ForceRequests
from .world_lighting import LightRequests
from .world_models import LinkPart, ModelRegistry, WorldModel
from .world_physics import PhysicsRequests
from .world_properties import PropertyRequests
from .world_spawns import SpawnRequests
from .world_states import StateRequests


class WorldControl(StateRequests, PropertyRequests, SpawnRequests, PhysicsRequests,
                   ForceRequests, ConfigurationRequests, LightRequests):
    """The world API's semantics over a Simulation (``sim.models``, ``sim.physics``)."""

    def __init__(self, sim):
        self.sim = sim
        self._get_counts = {}
        self._lights: Optional[Dict[str, Light]] = None   # copied from the loaded world
        # spawned model -> (its text, its bodies): delete parks them for the next spawn of that
        # text (body_pool.BodyPool: pybullet frees little of a removed body)
        self._spawned: Dict[str, Tuple[tuple, List[int]]] = {}

    @property
    def models(self) -> ModelRegistry:
        return self.sim.models

    # --- the look-ups the request groups share ---------------------------------------------

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
