"""The world as Gazebo's models: names, order, bodies, links, spawn poses. Knows nothing of ROS.

A ``WorldModel`` is one entry of /gazebo/model_states: the world file's models in file order,
then the robot, then spawned models in spawn order (``ModelRegistry``). Each holds the pybullet
bodies it is made of, each placed at a fixed pose in the model frame, and its links, so that it
can say where it is, be teleported with a twist, be put back where it was spawned, or removed.

Poses are ((x, y, z), (qx, qy, qz, qw)) in the world frame; twists ((vx, vy, vz), (wx, wy, wz))
in m/s and rad/s, world frame (reference_frames).
"""
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import Any, Callable, Dict, List, Optional, Tuple

from ...errors import RequestError, UserError
from ..engine.bodies import Body
from ..engine.client import Client
from ..engine.movable_bodies import body_link_frames, movable_trees
from ..engine.world_bullet import build_world, link_com_pose
from . import reference_frames as rf
from ..kinematics import pose_from_xyz_rpy
from .reference_frames import Pose, Twist
from ..files.world_types import World


SPAWN_FAILURE = "SpawnModel: Failure - "   # how Gazebo's spawn services begin a refusal
ENTITY_EXISTS = SPAWN_FAILURE + "entity already exists."


def spawn_failure(problem: str) -> RequestError:
    """The RequestError of a spawn refused for ``problem`` (one line)."""
    return RequestError(SPAWN_FAILURE + problem)


@contextmanager
def spawn_refusal():
    """Turn a UserError raised inside into the spawn's refusal: a RequestError of its line (a
    RequestError, already a refusal, goes on as it is)."""
    try:
        yield
    except RequestError:
        raise
    except UserError as err:
        raise spawn_failure(str(err)) from None


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
        raise spawn_failure("model name %r must be non-empty and have no white space" % name)
    if "::" in name:
        raise spawn_failure("model name %r must not contain '::' (that scopes links)" % name)


@dataclass
class BodyPart:
    """A body of a model: its base frame's pose in the model frame."""

    body: Body
    in_model: Pose
    movable: bool


@dataclass
class LinkPart:
    """A link: either on a movable body (``body``; ``index`` -1 for the base, else a jointed
    link's index; the link frame is ``in_body`` in that link's body frame: the base's centre of
    mass, a jointed link's joint frame) or fixed in the model frame (``body`` None, at
    ``in_model``)."""

    name: str
    body: Optional[Body] = None
    index: int = -1
    in_body: Pose = rf.IDENTITY
    in_model: Pose = rf.IDENTITY


@dataclass
class WorldModel:
    """One model of the world, with what the world API asks of it. Its kind (SdfModel,
    RobotModel) knows how its bodies are reset, removed and built again."""

    name: str
    static: bool
    parts: List[BodyPart]
    links: List[LinkPart]
    spawn_pose: Pose                 # where reset_world / reset_simulation put it
    joints: List[str] = field(default_factory=list)
    # the kinds of joints that are listed but not simulated (an SDF model's), by name
    joint_types: Dict[str, str] = field(default_factory=dict)
    geoms: List[str] = field(default_factory=list)
    on_rebuild: Optional[Callable[[str], None]] = None  # told the name (ModelRegistry.add)
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
        return rf.compose(part.body.pose(), rf.inverse(part.in_model))

    def twist(self) -> Twist:
        """World-frame velocity of the canonical (first movable) body's centre of mass."""
        part = self._movable()
        return rf.ZERO_TWIST if part is None else part.body.twist()

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
                out.append((scoped, rf.compose(link.body.pose(), link.in_body),
                            link.body.twist()))
            else:     # a jointed link: its body frame (a URDF's link frame, an SDF joint's)
                pose, twist = link.body.link_frame(link.index)
                if link.in_body is not rf.IDENTITY:
                    pose = rf.compose(pose, link.in_body)
                out.append((scoped, pose, twist))
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
        return all(part.body.finite() for part in self.parts if part.movable)

    # --- changing ----------------------------------------------------------------------------

    def set_state(self, pose: Pose, twist: Twist) -> None:
        """Teleport the model frame to ``pose``; every movable body gets ``twist`` (as Gazebo
        writes the model's velocity into every link; a zero twist stops it). A model whose
        state went NaN is rebuilt first (``sound``)."""
        self._repaired()
        self._pose = pose
        for part in self.parts:
            part.body.set_pose(rf.compose(pose, part.in_model))
            if part.movable:
                part.body.set_twist(twist)

    def set_link_state(self, link: LinkPart, pose: Pose, twist: Twist) -> None:
        """Teleport one link (the base of a movable body) to ``pose`` with ``twist`` (a model
        whose state went NaN is rebuilt first, its links then found by name)."""
        if not self.sound() and self.rebuild():
            link = self.link(link.name)
        link.body.set_pose(rf.compose(pose, rf.inverse(link.in_body)))
        link.body.set_twist(twist)

    def reset(self) -> None:
        """Back to the spawn pose, at rest (joints at 0); a model whose state went NaN is
        rebuilt first (``sound``)."""
        self._repaired()
        self.set_state(self.spawn_pose, rf.ZERO_TWIST)
        for part in self.parts:
            part.body.zero_joints()

    def restarted(self) -> None:
        """The bodies were put back in the state saved at the start (WorldPhysics.restore_state):
        what the model keeps beside its bodies starts over too."""
        self._pose = self.spawn_pose

    def repair(self) -> None:
        """Rebuild the model if its physics state is no longer finite (``sound``)."""
        self._repaired()

    def body_ids(self) -> Tuple[int, ...]:
        """The pybullet ids of the model's bodies, in order."""
        return tuple(part.body.uid for part in self.parts)

    def remove(self) -> None:
        """Take the model's bodies out of the physics."""
        for part in self.parts:
            part.body.remove()
        self.parts = []

    def rebuild(self) -> bool:
        """Replace the bodies of a model that is not ``sound`` by new ones built from what it
        was made of (at its spawn pose); whatever the world API applied to it goes
        (``on_rebuild``). False if it cannot be built again (it is left as it is)."""
        fresh = self._built_again()
        if fresh is None:
            return False
        self.parts, self.links = fresh
        if self.on_rebuild is not None:
            self.on_rebuild(self.name)
        return True

    def _built_again(self) -> Optional[Tuple[List[BodyPart], List[LinkPart]]]:
        """New (parts, links) in place of the old bodies, which are gone; None if there is
        nothing to build from."""
        return None

    def _repaired(self) -> None:
        """Rebuild the model first if its physics state is no longer finite."""
        if not self.sound():
            self.rebuild()


@dataclass
class SdfModel(WorldModel):
    """A model of an SDF world file or of a spawned SDF or plain URDF (converted to SDF,
    files/urdf/urdf_to_sdf): built by engine.world_bullet from
    ``world`` (the document it came from), where it is model ``name``."""

    world: Optional[World] = None

    def _built_again(self):
        if self.world is None:
            return None
        client = next((p.body.client for p in self.parts), None)
        if client is None:
            return None
        alone = World(self.world.name, self.world.path, (self.name,),
                      self.world.model_shapes(self.name), (self.world.model(self.name),))
        fresh = models_of_world(alone, build_world(alone, client), client)[0]
        for part in self.parts:
            part.body.remove()
        return fresh.parts, fresh.links


@dataclass
class RobotModel(WorldModel):
    """A robot with its plugins (world.sim_robot.SimRobot): its body (robot_body.RobotBody)
    resets, leaves and is built again as a robot does, its wheels braked."""

    robot_body: Any = None

    def reset(self) -> None:
        self._repaired()
        self.robot_body.reset_robot()

    def restarted(self) -> None:
        self.robot_body.restart_wheels()

    def remove(self) -> None:
        self.robot_body.remove()
        self.parts = []

    def _built_again(self):
        self.robot_body.rebuild()
        parts, links, _ = urdf_parts(self.robot_body)
        return parts, links


class ModelRegistry:
    """The models in Gazebo's order: world file, robot, spawned (in spawn order)."""

    def __init__(self, on_rebuild: Optional[Callable[[str], None]] = None):
        """``on_rebuild``: told the name of a model whose bodies were built again
        (WorldModel.rebuild), so that what the world API applied to the old bodies goes."""
        self._models: Dict[str, WorldModel] = {}   # insertion order is the world order
        self.on_rebuild = on_rebuild

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
            raise RequestError(ENTITY_EXISTS)
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

    def repair(self) -> None:
        """Rebuild every model whose physics state is no longer finite."""
        for model in self._models.values():
            model.repair()

    def restarted(self) -> None:
        """Every model's bodies were put back in the state saved at the start."""
        for model in self._models.values():
            model.restarted()

    def layout(self) -> Tuple[Tuple[str, Tuple[int, ...]], ...]:
        """(name, body ids) of every model in order: a saved state fits the world while this
        is unchanged (no model spawned, deleted or rebuilt since)."""
        return tuple((name, model.body_ids()) for name, model in self._models.items())

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


def models_of_world(world: World, bodies: Dict[str, int], client: Client) -> List[SdfModel]:
    """The models of a world built by world_bullet.build_world (shape name -> body id) in
    pybullet ``client``."""
    out = []
    for spec in world.model_specs:
        model_pose = pose_from_xyz_rpy(spec.pose)
        to_model = rf.inverse(model_pose)
        shapes = world.model_shapes(spec.name)
        parts: List[BodyPart] = []
        seen = set()
        for shape in shapes:
            uid = bodies.get(shape.name)
            if uid is None or uid in seen:
                continue
            seen.add(uid)
            body = Body(client, uid)
            parts.append(BodyPart(body, rf.compose(to_model, body.pose()),
                                  movable=not shape.static))
        link_body = {s.link: bodies[s.name] for s in shapes
                     if not s.static and s.name in bodies}
        in_trees = _jointed_links(spec, link_body) if not spec.static else {}
        links = []
        for link in spec.links:
            local = link.scoped[len(spec.name) + 2:]
            link_pose = pose_from_xyz_rpy(link.pose)
            uid = link_body.get(link.scoped)
            if link.scoped in in_trees:
                uid, index, frame = in_trees[link.scoped]
                links.append(LinkPart(local, body=Body(client, uid), index=index,
                                      in_body=rf.compose(rf.inverse(frame), link_pose)))
            elif uid is None:
                links.append(LinkPart(local, in_model=rf.compose(to_model, link_pose)))
            else:
                com = link_com_pose(link)
                in_body = rf.compose(rf.inverse((tuple(com[0]), tuple(com[1]))), link_pose)
                links.append(LinkPart(local, body=Body(client, uid), in_body=in_body))
        geoms = [s.name.rsplit("::", 1)[1] for s in shapes if s.collision]
        out.append(SdfModel(spec.name, spec.static, parts, links, model_pose,
                            joints=list(spec.joints),
                            joint_types=dict(zip(spec.joints, spec.joint_types)), geoms=geoms,
                            world=world))
    return out


def _jointed_links(spec, link_body: Dict[str, int]) -> Dict[str, Tuple[int, int, Pose]]:
    """Scoped link -> (body id, link index, world pose of that link's body frame as built) of
    every link of ``spec`` built into a multibody of joined links (engine.movable_bodies);
    ``link_body``: scoped link -> body id of the links that have shapes."""
    out = {}
    links = {link.scoped: link for link in spec.links}
    trees = movable_trees(World("", "", (spec.name,), (), (spec,)))
    for tree in {id(t): t for t in trees.values()}.values():
        uid = next((link_body[link] for link in tree.links if link in link_body), None)
        if uid is None:
            continue      # no shape anywhere: not built
        frames = body_link_frames(tree, links)
        for index, (entry, frame) in enumerate(zip(tree.body_links(), frames), start=-1):
            if entry.link is not None:
                out[entry.link] = (uid, index, (tuple(frame[0]), tuple(frame[1])))
    return out


def urdf_parts(robot) -> Tuple[List[BodyPart], List[LinkPart], List[str]]:
    """(parts, links, joint names) of a robot's body (engine.robot_body.RobotBody: built from
    the SDF model of its URDF): the model frame is its root link's frame; links are the root
    and every jointed link (fixed links merged, as Gazebo lumps them)."""
    body, com_in_root = robot.body, robot.com_in_root
    links = [LinkPart(robot.root_link, body=body, in_body=rf.inverse(com_in_root))]
    joints = []
    for joint in body.joints():
        links.append(LinkPart(joint.child_link, body=body, index=joint.index))
        joints.append(joint.name)
    return [BodyPart(body, com_in_root, movable=True)], links, joints


def urdf_model(kind, name: str, robot, spawn_pose: Optional[Pose] = None,
               collisions: Optional[Dict[str, List[str]]] = None, **fields) -> WorldModel:
    """A ``kind`` (RobotModel) of a robot's body (a RobotBody), at ``spawn_pose`` (None: where
    the body is now); ``collisions``: the URDF's RobotDescription.collision_names(), the
    model's geoms in link order; ``fields``: the kind's own (robot_body)."""
    parts, links, joints = urdf_parts(robot)
    geoms = [geom for link in links for geom in (collisions or {}).get(link.name, ())]
    model = kind(name, False, parts, links, spawn_pose or rf.IDENTITY, joints=joints,
                 geoms=geoms, **fields)
    if spawn_pose is None:
        model.spawn_pose = model.pose()
    return model
