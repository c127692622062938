"""Every collider's collision filter, kept per pybullet client in the order it was first set,
so that a reset can drop every contact and leave the broadphase as a newly built world has it.

Bullet keeps the contacts of two colliders (their points, and the impulses that warm-start the
next step's solver) for as long as their bounding boxes overlap, and carries them over a
teleport: a world put back where it started then steps differently from a new one (a spinning
obstacle of learning stage 3 pressed 16 remembered points into the floor). pybullet has one call
that drops them: setting a collider's filter gives it a new broadphase entry, without the pairs
and contacts of the old one. ``renew_contacts`` does that for every collider in the order in
which they were first given a filter, which is the order a world built anew gives them: no
contact is left, and the pairs are found in a new world's order at the next step.

Every filter of the simulator is set through ``set_filter`` (the engine's builders, the robots,
the body pool), and a body's removal is told with ``forget_body``. A collider's filter is a
(group, mask) pair of bits (world_bullet's collision groups).
"""
from collections import OrderedDict
from typing import Dict, Tuple

from .client import Client

Collider = Tuple[int, int]     # (body id, link index; -1 for the base)


def track(client: Client) -> None:
    """Keep the filters of ``client``, newly connected, from now on (``client.filters``)."""
    client.filters = OrderedDict()


def forget_client(client: Client) -> None:
    """``client`` is disconnected."""
    client.filters = None


def set_filter(client: Client, body: int, link: int, group: int, mask: int) -> None:
    """Give collider (``body``, ``link``) the collision ``group`` and ``mask`` (pybullet's
    setCollisionFilterGroupMask, which also drops the collider's contacts), and remember it:
    a collider keeps the place of the first filter it was given. A link with no collision
    shape has no collider: nothing is done (pybullet's call on one leaves a state that
    restoreState then refuses: "didn't find bodyUniqueId")."""
    if not has_collider(client, body, link):
        return
    client.setCollisionFilterGroupMask(body, link, group, mask)
    filters = client.filters
    if filters is not None:
        filters[(body, link)] = (group, mask)


def has_collider(client: Client, body: int, link: int) -> bool:
    """Whether link ``link`` of ``body`` (-1: its base) has a collision shape: pybullet gives
    one without a box of a single point (getCollisionShapeData would print its failure)."""
    low, high = client.getAABB(body, link)
    return low != high


def forget_body(client: Client, body: int) -> None:
    """``body`` was removed from ``client``: its colliders are gone."""
    filters = client.filters
    if filters is not None:
        for collider in [c for c in filters if c[0] == body]:
            del filters[collider]


def renew_contacts(client: Client) -> None:
    """Drop every contact of ``client``: each collider gets its filter again, in the order of
    their first filters (the broadphase's entries then stand in the order of a new world).

    A static rigid body (world_bullet's static meshes and planes) keeps its entry: static
    colliders never pair with each other (the world's mask leaves out the world's group), so
    renewing the others drops its contacts too; and pybullet's restoreState no longer finds a
    rigid body whose entry was renewed after the state was saved ("didn't find
    bodyUniqueId"), where a multibody's link is found."""
    for (body, link), (group, mask) in (client.filters or {}).items():
        if not _static_rigid(client, body, link):
            client.setCollisionFilterGroupMask(body, link, group, mask)


RIGID_BODY = 1     # pybullet's body type (getDynamicsInfo's 11th field) of a plain rigid body


def _static_rigid(client: Client, body: int, link: int) -> bool:
    """Whether (``body``, ``link``) is a plain rigid body (pybullet's maximal coordinates, not a
    multibody's link) of mass 0."""
    info = client.getDynamicsInfo(body, link)
    return info[10] == RIGID_BODY and info[0] == 0.0


def colliders(client: Client) -> Dict[Collider, Tuple[int, int]]:
    """collider -> (group, mask) of ``client``, in renewal order (a copy)."""
    return OrderedDict(client.filters or {})
