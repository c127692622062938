"""What makes a link of a movable model a rigid body, for the world loader (world_sdf): its
``<inertial>`` (mass, centre of mass, inertia) and its collisions' friction, checked as Gazebo
11 checks them. No ROS, no pybullet. Units: kg, kg m^2, m, rad.
"""
from typing import Optional

from . import limits
from .world_types import Inertial
from .xml_reader import Element


class InertiaReader:
    """The loader's reading of mass and friction, mixed into world_sdf's loader (an
    xml_reader.XmlReader with ``pose``)."""

    def inertial(self, node: Optional[Element], static: bool = False) -> Inertial:
        """A link's <inertial>, SDF's defaults for what it leaves out.

        Only a movable link's mass and inertia are checked. Gazebo 11 gives a static link no
        physics body at all (ODELink::UpdateMass returns at once without one), so a static
        model's numbers are never used: Gazebo's building editor writes mass 0 and inertia
        nan there. Here such a link keeps SDF's defaults (nothing uses them either). On a
        movable link Gazebo repairs nothing: ODELink::UpdateMass throws "Setting custom link
        ... mass to zero!" for a mass that is not > 0 (nan included), and ODE's dBodySetMass
        asserts a positive definite inertia (gzserver ends with "ODE INTERNAL ERROR ...
        dMassCheck"). So those stay refused here, with the line at fault."""
        if node is None:
            return Inertial()
        mass = Inertial.mass
        mass_node = node.child("mass")
        problems = []
        if mass_node is not None:
            mass = self.floats(mass_node, 1, finite=False)[0]
            problems.append((mass_node, limits.mass_problem(mass, field="<mass>"),
                             not mass > 0))
        inertia = list(Inertial.inertia)
        inertia_node = node.child("inertia")
        if inertia_node is not None:
            for i, tag in enumerate(limits.INERTIA_NAMES):
                value = inertia_node.child(tag)
                if value is not None:
                    inertia[i] = self.floats(value, 1, finite=False)[0]
            problems.append((inertia_node, limits.inertia_problem(
                inertia[:3], inertia[3:],
                names=tuple("<inertia> %s" % n for n in limits.INERTIA_NAMES)),
                not all(v > 0 for v in inertia[:3])))
        pose = self.pose(node)           # a pose is checked in any model: nan is garbage
        for at, problem, not_positive in problems:
            if problem and static:
                return Inertial(pose=pose)
            if problem:
                self.fail_bare(at, problem + (" (Gazebo refuses it on a link that is not static)"
                                              if not_positive else ""))
        return Inertial(mass, pose, tuple(inertia))

    def friction(self, collision: Element) -> float:
        """<surface><friction><ode><mu> of a collision (SDF's default 1)."""
        node = collision
        for tag in ("surface", "friction", "ode", "mu"):
            node = node.child(tag)
            if node is None:
                return 1.0
        mu = self.floats(node, 1, finite=False)[0]
        problem = limits.outside("<mu>", mu, 0.0, limits.MAX_FRICTION)
        if problem:
            self.fail_bare(node, problem)
        return mu
