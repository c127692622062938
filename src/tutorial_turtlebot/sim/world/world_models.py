"""The world as Gazebo's models: names, order, bodies, links, spawn poses. Knows nothing of ROS.

A ``WorldModel`` is one entry of /gazebo/model_states: the world file's models in file order,
then the robot, then spawned models in spawn order (``ModelRegistry``). Each holds the pybullet
bodies it is made of, each placed at a fixed pose in the model frame, and its links, so that it
can say where it is, be teleported with a twist, be put back where it was spawned, or removed.

Poses are ((x, y, z), (qx, qy, qz, qw)) in the world frame; twists ((vx, vy, vz), (wx, wy, wz))
in m/s and rad/s, world frame (reference_frames).
"""
import math
from dataclasses import dataclass, field
from typing import Callable, Dict, List, Optional, Tuple

from ..engine.bullet import pybullet
from . import reference_frames as rf
from ..kinematics import pose_from_xyz_rpy
from .reference_frames import Pose, Twist
from ..files.world_sdf import World

SOURCES = ("world", "robot", "spawned")


class RequestError(Exception):
    """A world request Gazebo would refuse: ``str(err)`` is its status message, one line."""


def robot_model_name(world: str, model: str) -> str:
    """The name turtlebot3_gazebo's launches give the robot in ``world`` (doc/turtlebot3.md 4.1):
    ``turtlebot3`` in the house, ``turtlebot3_burger`` in the learning stages and AutoRace,
    else ``turtlebot3_<model>``."""
    if world == "turtlebot3_house":
        return "turtlebot3"
    if world.startswith("turtlebot3_stage_") or world == "turtlebot3_autorace":
        return "turtlebot3_burger"
    return "turtlebot3_" + model


def check_model_name(name: str) -> None:
    """RequestError unless ``name`` can name a new model (non-empty, no "::", no spaces)."""
    if not name or name != name.strip() or any(c.isspace() for c in name):
        raise RequestError("SpawnModel: Failure - model name %r must be non-empty and have no "
                           "white space" % name)
    if "::" in name:
        raise RequestError("SpawnModel: Failure - model name %r must not contain '::' (that "
                           "scopes links)" % name)


@dataclass
class BodyPart:
    """A pybullet body of a model: its base frame's pose in the model frame."""

    body: int
    in_model: Pose
    movable: bool


@dataclass
class LinkPart:
    """A link: either on a movable body (``body``, ``index`` -1 for the base whose frame is
    ``in_body`` in the body's base frame, or a jointed link's index) or fixed in the model frame
    (``body`` None, at ``in_model``)."""

    name: str
    body: Optional[int] = None
    index: int = -1
    in_body: Pose = rf.IDENTITY
    in_model: Pose = rf.IDENTITY


@dataclass
class WorldModel:
    """One model of the world, with what the world API asks of it."""

    name: str
    static: bool
    source: str                      # one of SOURCES
    parts: List[BodyPart]
    links: List[LinkPart]
    spawn_pose: Pose                 # where reset_world / reset_simulation put it
    client: int
    joints: List[str] = field(default_factory=list)
    # the kinds of joints that are listed but not simulated (an SDF model's), by name
    joint_types: Dict[str, str] = field(default_factory=dict)
    geoms: List[str] = field(default_factory=list)
    reset_hook: Optional[Callable[[], None]] = None   # the robot's own reset
    remove_hook: Optional[Callable[[], None]] = None  # the robot's own removal
    # Fresh bodies for a model whose physics state went NaN (rebuild): a new WorldModel of the
    # same spec whose parts and links replace these (a robot's hook reloads its own body).
    rebuild_hook: Optional[Callable[[], "WorldModel"]] = None
    on_rebuild: Optional[Callable[[str], None]] = None  # told the name after a rebuild
    _pose: Pose = rf.IDENTITY        # the model frame of a model without a movable body

    def __post_init__(self):
        self._pose = self.spawn_pose

    # --- reading -----------------------------------------------------------------------------

    def _movable(self) -> Optional[BodyPart]:
        return next((p for p in self.parts if p.movable), None)

    def pose(self) -> Pose:
        """World pose of the model frame."""
        part = self._movable()
        if part is None:
            return self._pose
        base = pybullet.getBasePositionAndOrientation(part.body, physicsClientId=self.client)
        return rf.compose((tuple(base[0]), tuple(base[1])), rf.inverse(part.in_model))

    def twist(self) -> Twist:
        """World-frame velocity of the canonical (first movable) body's centre of mass."""
        part = self._movable()
        if part is None:
            return rf.ZERO_TWIST
        lin, ang = pybullet.getBaseVelocity(part.body, physicsClientId=self.client)
        return tuple(lin), tuple(ang)

    def link_states(self) -> List[Tuple[str, Pose, Twist]]:
        """(scoped name "model::link", world pose of the link frame, twist) of every link."""
        out = []
        model_pose = None
        for link in self.links:
            scoped = self.name + "::" + link.name
            if link.body is None:
                if model_pose is None:
                    model_pose = self.pose()
                out.append((scoped, rf.compose(model_pose, link.in_model), rf.ZERO_TWIST))
            elif link.index < 0:
                base = pybullet.getBasePositionAndOrientation(link.body,
                                                              physicsClientId=self.client)
                lin, ang = pybullet.getBaseVelocity(link.body, physicsClientId=self.client)
                pose = rf.compose((tuple(base[0]), tuple(base[1])), link.in_body)
                out.append((scoped, pose, (tuple(lin), tuple(ang))))
            else:
                state = pybullet.getLinkState(link.body, link.index, computeLinkVelocity=1,
                                              physicsClientId=self.client)
                out.append((scoped, (tuple(state[4]), tuple(state[5])),
                            (tuple(state[6]), tuple(state[7]))))
        return out

    def link(self, name: str) -> LinkPart:
        """The link called ``name`` (unscoped); KeyError if there is none."""
        for link in self.links:
            if link.name == name:
                return link
        raise KeyError(name)

    def sound(self) -> bool:
        """Whether the pose, velocity and joint states of every movable body are finite.

        A body that once held a NaN is beyond repair in place: Bullet takes an object whose
        bounding box is not finite out of the simulation for good (it then falls through
        every floor, and rays pass it by), and finite values written back do not undo that.
        Only a new body does (rebuild)."""
        for part in self.parts:
            if not part.movable:
                continue
            cid = self.client
            pos, orn = pybullet.getBasePositionAndOrientation(part.body, physicsClientId=cid)
            lin, ang = pybullet.getBaseVelocity(part.body, physicsClientId=cid)
            values = list(pos) + list(orn) + list(lin) + list(ang)
            joints = range(pybullet.getNumJoints(part.body, physicsClientId=cid))
            for state in pybullet.getJointStates(part.body, joints, physicsClientId=cid) or ():
                values.extend(state[:2])
            if not all(math.isfinite(v) for v in values):
                return False
        return True

    def rebuild(self) -> bool:
        """Replace the bodies of a model that is not ``sound`` by new ones built from its spec
        (at its spawn pose); whatever the world API applied to it goes (``on_rebuild``).
        False if there is nothing to rebuild from (it is left as it is)."""
        if self.rebuild_hook is None:
            return False
        old = [p.body for p in self.parts]
        fresh = self.rebuild_hook()
        if self.remove_hook is None:     # a robot's hook has replaced its own body
            for body in old:
                pybullet.removeBody(body, physicsClientId=self.client)
        self.parts, self.links = fresh.parts, fresh.links
        if self.on_rebuild is not None:
            self.on_rebuild(self.name)
        return True

    def _repaired(self) -> None:
        """Rebuild the model first if its physics state is no longer finite."""
        if not self.sound():
            self.rebuild()

    # --- changing ----------------------------------------------------------------------------

    def set_state(self, pose: Pose, twist: Twist) -> None:
        """Teleport the model frame to ``pose``; every movable body gets ``twist`` (as Gazebo
        writes the model's velocity into every link; a zero twist stops it). A model whose
        state went NaN is rebuilt first (``sound``)."""
        self._repaired()
        self._pose = pose
        for part in self.parts:
            pos, orn = rf.compose(pose, part.in_model)
            pybullet.resetBasePositionAndOrientation(part.body, pos, orn,
                                                     physicsClientId=self.client)
            if part.movable:
                pybullet.resetBaseVelocity(part.body, twist[0], twist[1],
                                           physicsClientId=self.client)

    def set_link_state(self, link: LinkPart, pose: Pose, twist: Twist) -> None:
        """Teleport one link (the base of a movable body) to ``pose`` with ``twist`` (a model
        whose state went NaN is rebuilt first, its links then found by name)."""
        if not self.sound() and self.rebuild():
            link = self.link(link.name)
        body_pose = rf.compose(pose, rf.inverse(link.in_body))
        pybullet.resetBasePositionAndOrientation(link.body, *body_pose,
                                                 physicsClientId=self.client)
        pybullet.resetBaseVelocity(link.body, twist[0], twist[1], physicsClientId=self.client)

    def reset(self) -> None:
        """Back to the spawn pose, at rest (joints at 0); a model whose state went NaN is
        rebuilt first (``sound``)."""
        self._repaired()
        if self.reset_hook is not None:
            self.reset_hook()
            return
        self.set_state(self.spawn_pose, rf.ZERO_TWIST)
        for part in self.parts:
            for j in range(pybullet.getNumJoints(part.body, physicsClientId=self.client)):
                pybullet.resetJointState(part.body, j, 0.0, 0.0, physicsClientId=self.client)

    def remove(self) -> None:
        """Take the model's bodies out of the physics."""
        if self.remove_hook is not None:
            self.remove_hook()
            self.parts = []
            return
        for part in self.parts:
            pybullet.removeBody(part.body, physicsClientId=self.client)
        self.parts = []


class ModelRegistry:
    """The models in Gazebo's order: world file, robot, spawned (in spawn order)."""

    def __init__(self):
        self._models: Dict[str, WorldModel] = {}   # insertion order is the world order
        # told the name of a model whose bodies were rebuilt (WorldModel.rebuild): the
        # simulation forgets what the world API applied to the old bodies
        self.on_rebuild: Optional[Callable[[str], None]] = None

    def names(self) -> List[str]:
        return list(self._models)

    def models(self) -> List[WorldModel]:
        return list(self._models.values())

    def __contains__(self, name: str) -> bool:
        return name in self._models

    def get(self, name: str) -> WorldModel:
        """The model ``name``; KeyError if there is none."""
        return self._models[name]

    def add(self, model: WorldModel) -> None:
        """Append ``model``; RequestError if its name is taken."""
        if model.name in self._models:
            raise RequestError("SpawnModel: Failure - entity already exists.")
        if model.on_rebuild is None:
            model.on_rebuild = self._rebuilt
        self._models[model.name] = model

    def _rebuilt(self, name: str) -> None:
        if self.on_rebuild is not None:
            self.on_rebuild(name)

    def remove(self, name: str) -> WorldModel:
        """Remove model ``name`` (and its bodies); KeyError if there is none."""
        model = self._models.pop(name)
        model.remove()
        return model

    def reset(self) -> None:
        """Every model back to its spawn pose, at rest."""
        for model in self._models.values():
            model.reset()

    def frame(self, name: str) -> Tuple[Pose, Twist]:
        """Pose and twist of a reference frame: a model name or a scoped "model::link";
        KeyError if neither exists."""
        if name in self._models:
            model = self._models[name]
            return model.pose(), model.twist()
        model_name, sep, link_name = name.rpartition("::")
        if sep and model_name in self._models:
            for scoped, pose, twist in self._models[model_name].link_states():
                if scoped == name:
                    return pose, twist
        raise KeyError(name)


def _base_pose(body: int, cid: int) -> Pose:
    pos, orn = pybullet.getBasePositionAndOrientation(body, physicsClientId=cid)
    return tuple(pos), tuple(orn)


def models_of_world(world: World, bodies: Dict[str, int], cid: int,
                    source: str = "world") -> List[WorldModel]:
    """The WorldModels of a world built by world_bullet.build_world (shape name -> body)."""
    from ..engine.world_bullet import link_com_pose
    out = []
    for spec in world.model_specs:
        model_pose = pose_from_xyz_rpy(spec.pose)
        to_model = rf.inverse(model_pose)
        shapes = world.model_shapes(spec.name)
        parts: List[BodyPart] = []
        seen = set()
        for shape in shapes:
            body = bodies.get(shape.name)
            if body is None or body in seen:
                continue
            seen.add(body)
            parts.append(BodyPart(body, rf.compose(to_model, _base_pose(body, cid)),
                                  movable=not shape.static))
        link_body = {s.link: bodies[s.name] for s in shapes
                     if not s.static and s.name in bodies}
        links = []
        for link in spec.links:
            local = link.scoped[len(spec.name) + 2:]
            link_pose = pose_from_xyz_rpy(link.pose)
            body = link_body.get(link.scoped)
            if body is None:
                links.append(LinkPart(local, in_model=rf.compose(to_model, link_pose)))
            else:
                com = link_com_pose(link)
                in_body = rf.compose(rf.inverse((tuple(com[0]), tuple(com[1]))), link_pose)
                links.append(LinkPart(local, body=body, in_body=in_body))
        geoms = [s.name.rsplit("::", 1)[1] for s in shapes if s.collision]
        out.append(WorldModel(spec.name, spec.static, source, parts, links, model_pose, cid,
                              joints=list(spec.joints),
                              joint_types=dict(zip(spec.joints, spec.joint_types)), geoms=geoms,
                              rebuild_hook=_sdf_rebuilder(world, spec.name, cid, source)))
    return out


def _sdf_rebuilder(world: World, name: str, cid: int, source: str
                   ) -> Callable[[], WorldModel]:
    """A rebuild_hook: model ``name`` of ``world`` built again, alone, at its spawn pose."""
    def rebuild() -> WorldModel:
        from ..engine.world_bullet import build_world
        alone = World(world.name, world.path, (name,), world.model_shapes(name),
                      (world.model(name),))
        return models_of_world(alone, build_world(alone, cid), cid, source)[0]
    return rebuild


def model_of_urdf_body(name: str, body: int, cid: int, source: str,
                       reset_hook: Optional[Callable[[], None]] = None,
                       spawn_pose: Optional[Pose] = None,
                       remove_hook: Optional[Callable[[], None]] = None,
                       collisions: Optional[Dict[str, List[str]]] = None) -> WorldModel:
    """A WorldModel of a body loaded from a URDF: the model frame is its root link's frame;
    links are the root and every jointed link (fixed links merged, as Gazebo lumps them);
    ``collisions``: the URDF's RobotDescription.collision_names(), the model's geoms in
    link order."""
    info = pybullet.getDynamicsInfo(body, -1, physicsClientId=cid)
    com_in_root = (tuple(info[3]), tuple(info[4]))
    root = pybullet.getBodyInfo(body, physicsClientId=cid)[0].decode()
    links = [LinkPart(root, body=body, in_body=rf.inverse(com_in_root))]
    joints = []
    for j in range(pybullet.getNumJoints(body, physicsClientId=cid)):
        joint = pybullet.getJointInfo(body, j, physicsClientId=cid)
        links.append(LinkPart(joint[12].decode(), body=body, index=j))
        joints.append(joint[1].decode())
    part = BodyPart(body, com_in_root, movable=True)
    geoms = [geom for link in links for geom in (collisions or {}).get(link.name, ())]
    model = WorldModel(name, False, source, [part], links, spawn_pose or rf.IDENTITY, cid,
                       joints=joints, geoms=geoms, reset_hook=reset_hook,
                       remove_hook=remove_hook)
    if spawn_pose is None:
        model.spawn_pose = model.pose()
    return model
