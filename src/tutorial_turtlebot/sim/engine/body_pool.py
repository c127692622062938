"""Deleted models' bodies kept for reuse (``BodyPool``, one per world: ``physics.body_pool``).

pybullet frees little of a body on removeBody: its collision shapes (and, with the EGL
renderer, the renderer's copy of its visuals) stay until the client closes. Measured per
spawn/delete cycle: about 2 KB (a box) and 20 KB (a Burger) of RSS, 16 and 70 KB with EGL.
A deleted body is parked instead (far below the world, asleep, colliding with nothing) and
the next spawn of the same text takes it back, so that RSS stays flat under churn.
At most MAX_PARKED_BODIES wait, the least recently parked removed first: each costs the
step a little however asleep it is (2,000 parked boxes: 7 times the CPU of the empty world;
64: 1.26 times; 16: 1.10), and most churn repeats a few texts (the hostile soak: 21).
"""
from collections import OrderedDict
from typing import Dict, List, Optional, Sequence

import numpy as np

from . import collision_filters
from .bodies import Body
from .bullet import pybullet
from .client import Client

PARK_DEPTH = 1e4     # m below the world origin
PARK_SPACING = 10.0  # m between parked bodies (by body id): they never touch
MAX_PARKED_BODIES = 32


class BodyPool:
    """Bodies of deleted models by the text they were built from (a key: its digest), to be
    reused; at most MAX_PARKED_BODIES of them, least recently parked removed first."""

    def __init__(self, client: Client):
        self.client = client
        self._parked: "OrderedDict[object, List[List[int]]]" = OrderedDict()
        self._pristine: Dict[int, list] = {}   # body -> (mass, inertia) of each link, as built
        self.parked_bodies = 0

    def remember(self, bodies: Sequence[int]) -> None:
        """Note the mass and inertia of new ``bodies`` (set_link_properties may change them
        before they are parked: they come back as they were built)."""
        client = self.client
        for body in dict.fromkeys(bodies):
            self._pristine[body] = [
                client.getDynamicsInfo(body, link)[:3:2]
                for link in range(-1, client.getNumJoints(body))]

    def park(self, key, bodies: Sequence[int]) -> bool:
        """Park ``bodies`` (of one model) under ``key``; False (nothing done) if one of them
        was not ``remember``ed or its state is not finite: the caller removes them."""
        client = self.client
        bodies = list(dict.fromkeys(bodies))
        for body in bodies:
            if body not in self._pristine:
                return False
            pos, orn = client.getBasePositionAndOrientation(body)
            lin, ang = client.getBaseVelocity(body)
            if not np.all(np.isfinite(pos + orn + lin + ang)):
                return False
        for body in bodies:
            Body(client, body).restore_joints()   # as built: set_joint_properties' undone
            client.resetBasePositionAndOrientation(
                body, (PARK_SPACING * body, 0.0, -PARK_DEPTH), (0, 0, 0, 1))
            client.resetBaseVelocity(body, (0, 0, 0), (0, 0, 0))
            for link in range(-1, client.getNumJoints(body)):
                collision_filters.set_filter(client, body, link, 0, 0)
                client.changeDynamics(body, link, activationState=(
                    pybullet.ACTIVATION_STATE_ENABLE_SLEEPING | pybullet.ACTIVATION_STATE_SLEEP))
        self._parked.setdefault(key, []).append(bodies)
        self._parked.move_to_end(key)
        self.parked_bodies += len(bodies)
        while self.parked_bodies > MAX_PARKED_BODIES:
            self._remove_oldest()
        return True

    def _remove_oldest(self) -> None:
        """Remove the bodies parked longest ago from pybullet."""
        key, groups = next(iter(self._parked.items()))
        bodies = groups.pop(0)
        if not groups:
            del self._parked[key]
        for body in bodies:
            self.client.removeBody(body)
            collision_filters.forget_body(self.client, body)
            self.client.built_joints.pop(body, None)
        self.forget(bodies)
        self.parked_bodies -= len(bodies)

    def take(self, key) -> Optional[List[int]]:
        """Bodies parked under ``key`` (None if none), awake, at rest, every joint at 0, with
        the dynamics they were built with. The caller places them and sets their collision
        groups (parked bodies collide with nothing)."""
        parked = self._parked.get(key)
        if not parked:
            return None
        bodies = parked.pop()
        if not parked:
            del self._parked[key]
        self.parked_bodies -= len(bodies)
        client = self.client
        for body in bodies:
            for link, built in zip(range(-1, len(self._pristine[body]) - 1),
                                   self._pristine[body]):
                if client.getDynamicsInfo(body, link)[:3:2] != built:
                    client.changeDynamics(body, link, mass=built[0],
                                          localInertiaDiagonal=built[1])
                client.changeDynamics(body, link, frictionAnchor=0, activationState=(
                    pybullet.ACTIVATION_STATE_WAKE_UP | pybullet.ACTIVATION_STATE_DISABLE_SLEEPING))
                if link >= 0:
                    client.resetJointState(body, link, 0.0, 0.0)
        return bodies

    def forget(self, bodies: Sequence[int]) -> None:
        """``bodies`` were removed from pybullet (their ids may be given to new bodies)."""
        for body in bodies:
            self._pristine.pop(body, None)
