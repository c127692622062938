"""What a link's contact and inertial sensors read from the engine, as plain data: the contact
points of one body's link at the last step (Bullet's manifolds, with the forces the solver
applied) and the world's gravity. Units: m, N, m/s^2; world frame (z up).
"""
from typing import List, NamedTuple, Tuple

Vec = Tuple[float, float, float]


class ContactPoint(NamedTuple):
    """One point where the link touches another collider, at the last physics step."""

    other_body: int       # the other collider's body id
    other_link: int       # its link index (-1: the base)
    position: Vec         # m, world: midway between the two surfaces' points
    normal: Vec           # unit, world: from the other collider into the link
    depth: float          # m, how far they overlap (0 or more)
    force: Vec            # N, world: the force on the link here (normal and friction)


def link_contacts(client, body: int, link: int = -1) -> List[ContactPoint]:
    """The contact points of link ``link`` of body ``body`` (-1: its base, or a rigid body)
    with every other collider, from the last step."""
    points = []
    for found in client.getContactPoints(bodyA=body, linkIndexA=link) or ():
        (_, _, other, _, other_link, on_a, on_b, normal, distance, normal_force,
         friction1, direction1, friction2, direction2) = found[:14]
        force = tuple(normal_force * n + friction1 * d1 + friction2 * d2
                      for n, d1, d2 in zip(normal, direction1, direction2))
        points.append(ContactPoint(
            other, other_link, tuple((a + b) / 2.0 for a, b in zip(on_a, on_b)),
            tuple(normal), max(0.0, -distance), force))
    return points


def gravity(client) -> Vec:
    """The world's gravity now (m/s^2, world frame), as the last setGravity set it."""
    params = client.getPhysicsEngineParameters()
    return tuple(float(params["gravityAcceleration" + axis]) for axis in "XYZ")
