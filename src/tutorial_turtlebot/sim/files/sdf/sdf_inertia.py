"""What makes a link of a movable model a rigid body, for the world loader (world_sdf): its
``<inertial>`` (mass, centre of mass, inertia) and its collisions' friction, checked as Gazebo
11 checks them. No ROS, no pybullet. Units: kg, kg m^2, m, rad.
"""
from typing import Optional

from .. import limits
from ..world_types import Inertial
from ..xml_reader import Element

# What ODE's dBodySetMass falls back to for an inertia that is not positive definite: an
# identity inverse inertia (kg m^2: ixx iyy izz ixy ixz iyz)
IDENTITY_INERTIA = (1.0, 1.0, 1.0, 0.0, 0.0, 0.0)
INERTIA_REPLACED = "a movable link's inertia is not positive definite"


class InertiaReader:
    """The loader's reading of mass and friction, mixed into world_sdf's loader (an
    xml_reader.XmlReader with ``pose``)."""

    def inertial(self, node: Optional[Element], static: bool = False) -> Inertial:
        """A link's <inertial>, SDF's defaults for what it leaves out.

        Only a movable link's mass and inertia are checked. Gazebo 11 gives a static link no
        physics body at all (ODELink::UpdateMass returns at once without one), so a static
        model's numbers are never used: Gazebo's building editor writes mass 0 and inertia
        nan there. Here such a link keeps SDF's defaults (nothing uses them either). On a
        movable link a mass that is not > 0 (nan included) stays refused, with the line at
        fault: ODELink::UpdateMass throws "Setting custom link ... mass to zero!". An inertia
        that is finite but not positive definite (all moments 0, say) is not refused there:
        ODE's dBodySetMass says "inertia must be positive definite!" and gives the body an
        identity inverse inertia, so the link turns as if each moment were 1 kg m^2. This
        sim does the same, with one warning per file."""
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
                inertia[:3], inertia[3:], allow_zero=True, allow_negative=True,
                names=tuple("<inertia> %s" % n for n in limits.INERTIA_NAMES)), False))
        pose = self.pose(node)           # a pose is checked in any model: nan is garbage
        for at, problem, not_positive in problems:
            if problem and static:
                return Inertial(pose=pose)
            if problem:
                self.fail_bare(at, problem + (" (Gazebo refuses it on a link that is not static)"
                                              if not_positive else ""))
        if not static and not limits.positive_definite(inertia[:3], inertia[3:]):
            self._inertia_replaced(inertia_node, inertia)
            inertia = list(IDENTITY_INERTIA)
        return Inertial(mass, pose, tuple(inertia))

    def _inertia_replaced(self, at: Element, inertia) -> None:
        """One warning per file: a movable link's inertia is not positive definite."""
        if any(self.path in w and INERTIA_REPLACED in w for w in self.warnings):
            return
        self.warn(at, "%s (ixx %g iyy %g izz %g ixy %g ixz %g iyz %g): %s"
                  % (INERTIA_REPLACED, *inertia, "each moment taken as 1 kg m^2, as Gazebo's "
                     "ODE takes it (said once per file)"))

    def friction(self, collision: Element) -> float:
        """<surface><friction><ode><mu> of a collision (SDF's default 1). A negative one is
        limits.NO_SLIP_FRICTION, in silence: Gazebo's FrictionPyramid::SetMu takes it as FLT_MAX
        (ODE's friction that never gives). <mu2> is not read (Bullet has one friction)."""
        node = collision
        for tag in ("surface", "friction", "ode", "mu"):
            node = node.child(tag)
            if node is None:
                return 1.0
        mu = self.floats(node, 1, finite=False)[0]
        mu = limits.NO_SLIP_FRICTION if mu < 0 else mu     # -inf too; nan stays refused
        problem = limits.outside("<mu>", mu, 0.0, limits.MAX_FRICTION)
        if problem:
            self.fail_bare(node, problem)
        return mu
