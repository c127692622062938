"""The one way a URDF becomes a pybullet body: robots, spawned URDFs and their meshes alike.

The text is what ``files.urdf_meshes.bullet_urdf_text`` writes (meshes as Wavefront files,
bare frames next to massless, one element a line); it is loaded with ``URDF_FLAGS``:
- fixed joints merged, as Gazebo lumps fixed links into their parent;
- the inertia as the file gives it (pybullet would otherwise compute one from the collision
  shapes);
- cylinders as true cylinders (Gazebo's ODE collides with cylinders, not with their hulls).
A model Gazebo holds in place (a static one, or one whose root link is ``world``) is loaded with
a fixed base: its base never moves but where it is put (``Body.set_pose``), and collides as the
world's static bodies do (collision_groups: robots and movable models hit it, lasers see it; the
world's other static bodies are not tested against it).
"""
import os
import tempfile

from ...errors import UserError
from ..files.urdf.urdf_meshes import textured_urdf
from . import collision_filters
from .bodies import Body
from .bullet import pybullet, quiet_output
from .client import Client
from .collision_groups import (MOVABLE_COLLISION_GROUP, MOVABLE_COLLISION_MASK,
                               WORLD_COLLISION_GROUP, WORLD_COLLISION_MASK)
from .rendering import note_textures

URDF_FLAGS = (pybullet.URDF_MERGE_FIXED_LINKS | pybullet.URDF_USE_INERTIA_FROM_FILE
              | pybullet.URDF_USE_IMPLICIT_CYLINDER)


def load_urdf(client: Client, urdf: str, fixed_base: bool = False) -> int:
    """A new body of URDF text ``urdf`` in pybullet ``client`` (its root link at the
    origin; with ``fixed_base``, a base that never moves): the body id. UserError (one line)
    when pybullet cannot load it. A URDF with a textured mesh makes the client's cameras draw
    textures from then on."""
    if textured_urdf(urdf):
        note_textures(client)
    fd, path = tempfile.mkstemp(suffix=".urdf", prefix="tutorial_turtlebot_")
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as f:
            f.write(urdf)
        try:
            with quiet_output():   # the importer's notes go straight to the terminal
                if fixed_base:
                    return client.loadURDF(path, flags=URDF_FLAGS, useFixedBase=True)
                return client.loadURDF(path, flags=URDF_FLAGS)
        except pybullet.error as err:
            raise UserError("pybullet could not load the URDF: %s" % err) from None
    finally:
        os.unlink(path)


def load_movable(client: Client, urdf: str, fixed_base: bool = False) -> Body:
    """``load_urdf`` of a spawned model without robot plugins, set up as Gazebo moves one: it
    collides with the world, the robots and other movable models, slides with friction 1, has
    no damping, never sleeps, and its joints turn freely but for their URDF <dynamics friction>
    (pybullet's default motors would brake them; its joint damping is not simulated). With
    ``fixed_base`` (a model held in place), its base is fixed and collides as a static world
    body."""
    body = load_urdf(client, urdf, fixed_base)
    setup_movable(client, body, fixed_base)
    return Body(client, body)


def setup_movable(client: Client, body: int, fixed_base: bool = False) -> None:
    """The set-up of ``load_movable``, of a body already loaded (or taken from the pool)."""
    for link in range(-1, client.getNumJoints(body)):
        if fixed_base and link < 0:
            collision_filters.set_filter(client, body, link, WORLD_COLLISION_GROUP,
                                         WORLD_COLLISION_MASK)
        else:
            collision_filters.set_filter(client, body, link, MOVABLE_COLLISION_GROUP,
                                         MOVABLE_COLLISION_MASK)
        client.changeDynamics(body, link, linearDamping=0.0, angularDamping=0.0,  # none in Gazebo
                              activationState=pybullet.ACTIVATION_STATE_DISABLE_SLEEPING)
        # a call of its own: with the arguments above pybullet drops the friction of a jointed
        # link (it stays at its default 0.5)
        client.changeDynamics(body, link, lateralFriction=1.0)
        if link >= 0:   # the URDF's <dynamics friction> (N m or N) holds it, as Gazebo's
            friction = client.getJointInfo(body, link)[7]
            client.setJointMotorControl2(body, link, pybullet.VELOCITY_CONTROL, force=friction)
