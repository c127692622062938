"""Gazebo's physics properties (get/set_physics_properties, Physics.cfg) without ROS.

``time_step`` is the physics step (s); ``max_update_rate`` the steps per wall second Gazebo aims
for (0 = as fast as possible), so the real-time factor is ``time_step * max_update_rate``.
The ODE solver fields are kept and reported as set; those with a Bullet counterpart are applied
(``bullet_parameters``): sor_pgs_iters -> numSolverIterations, erp -> erp and contactERP,
cfm -> globalCFM. The others (ODE-only) change nothing here.
"""
import math
from dataclasses import dataclass, field, fields, replace
from typing import Tuple

from ..files import limits

MIN_TIME_STEP, MAX_TIME_STEP = limits.MIN_TIME_STEP, limits.MAX_TIME_STEP   # s, as SimConfig
# Each ODE field's physical range (low, high, unit); a value outside is refused, never passed on
# (pybullet takes the solver's iterations as a C int: 4294967295 would not even convert).
ODE_RANGES = {
    "sor_pgs_precon_iters": (0, limits.MAX_SOLVER_ITERATIONS, ""),
    "sor_pgs_iters": (1, limits.MAX_SOLVER_ITERATIONS, ""),
    "sor_pgs_w": (0.0, 2.0, ""),                          # successive over-relaxation factor
    "sor_pgs_rms_error_tol": (0.0, limits.MAX_ODE_VALUE, ""),
    "contact_surface_layer": (0.0, 1.0, "m"),
    "contact_max_correcting_vel": (0.0, limits.MAX_ODE_VALUE, "m/s"),
    # Bullet's constraint force mixing softens every contact: past 0.1 a Waffle sinks 8 mm into
    # the floor, at 1 by 6 cm, and from 2 every body falls through the world (measured)
    "cfm": (0.0, 0.1, ""),
    "erp": (0.0, 1.0, ""),
    "max_contacts": (0, limits.MAX_CONTACTS, ""),
}


@dataclass(frozen=True)
class OdeConfig:
    """gazebo_msgs/ODEPhysics; defaults are the TurtleBot3 worlds' (doc/turtlebot3.md 2.6) except
    the applied ones, which start as this simulator runs."""

    auto_disable_bodies: bool = False
    sor_pgs_precon_iters: int = 0
    sor_pgs_iters: int = 20
    sor_pgs_w: float = 1.4
    sor_pgs_rms_error_tol: float = 0.0
    contact_surface_layer: float = 0.01
    contact_max_correcting_vel: float = 2000.0
    cfm: float = 0.0
    erp: float = 0.2
    max_contacts: int = 20


@dataclass(frozen=True)
class PhysicsProperties:
    time_step: float = 0.0025
    max_update_rate: float = 400.0
    gravity: Tuple[float, float, float] = (0.0, 0.0, -9.8)
    ode: OdeConfig = field(default_factory=OdeConfig)

    @property
    def real_time_factor(self) -> float:
        """Sim seconds per wall second aimed at; 0 = as fast as possible."""
        return self.time_step * self.max_update_rate

    @staticmethod
    def for_factor(time_step: float, real_time_factor: float, ode: OdeConfig,
                   gravity=(0.0, 0.0, -9.8)) -> "PhysicsProperties":
        """The properties of a sim stepping ``time_step`` at ``real_time_factor`` (0 = max)."""
        return PhysicsProperties(time_step, real_time_factor / time_step, tuple(gravity), ode)


def validate(props: PhysicsProperties) -> None:
    """ValueError (one line) for properties this simulator cannot run."""
    if not (math.isfinite(props.time_step)
            and MIN_TIME_STEP <= props.time_step <= MAX_TIME_STEP):
        raise ValueError("time_step %r s is outside %g..%g"
                         % (props.time_step, MIN_TIME_STEP, MAX_TIME_STEP))
    if not (math.isfinite(props.max_update_rate) and props.max_update_rate >= 0):
        raise ValueError("max_update_rate %r must be >= 0 (0 = as fast as possible)"
                         % props.max_update_rate)
    from .pacing import MIN_REAL_TIME_FACTOR, too_slow  # the slowest pace the loop runs
    # (a positive rate whose product with the step underflows to 0 is too slow too, not "as
    # fast as possible": 5e-324 Hz)
    if too_slow(props.real_time_factor) or (props.max_update_rate > 0
                                            and props.real_time_factor == 0):
        raise ValueError("max_update_rate %r is below %g at time_step %g (a real-time factor "
                         "of at least %g; 0 = as fast as possible)"
                         % (props.max_update_rate, MIN_REAL_TIME_FACTOR / props.time_step,
                            props.time_step, MIN_REAL_TIME_FACTOR))
    problem = limits.symmetric("gravity", props.gravity, limits.MAX_GRAVITY, "m/s^2")
    if problem:
        raise ValueError(problem)
    for f in fields(OdeConfig):
        value = getattr(props.ode, f.name)
        if isinstance(value, float) and not math.isfinite(value):
            raise ValueError("ode_config.%s %r must be finite" % (f.name, value))
        if f.name in ODE_RANGES:
            low, high, unit = ODE_RANGES[f.name]
            if f.type in (int, "int") and value != int(value):
                raise ValueError("ode_config.%s %r must be a whole number" % (f.name, value))
            problem = limits.outside("ode_config." + f.name, value, low, high, unit)
            if problem:
                raise ValueError(problem)


def bullet_parameters(ode: OdeConfig) -> dict:
    """setPhysicsEngineParameter keywords for the ODE fields that Bullet has."""
    return {"numSolverIterations": int(ode.sor_pgs_iters), "erp": float(ode.erp),
            "contactERP": float(ode.erp), "globalCFM": float(ode.cfm)}


def updated(props: PhysicsProperties, **changes) -> PhysicsProperties:
    """A copy with ``changes``; ODE fields by their own names (as Physics.cfg lists them)."""
    ode_names = {f.name for f in fields(OdeConfig)}
    ode = replace(props.ode, **{k: v for k, v in changes.items() if k in ode_names})
    gravity = list(props.gravity)
    for i, axis in enumerate("xyz"):
        gravity[i] = changes.get("gravity_" + axis, gravity[i])
    top = {k: v for k, v in changes.items() if k in ("time_step", "max_update_rate")}
    return replace(props, ode=ode, gravity=tuple(gravity), **top)
