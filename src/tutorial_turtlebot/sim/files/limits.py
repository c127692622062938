"""The limits every number and name entering the world is held to, and their one-line refusals.

Every path that brings a number into the world (SDF and URDF files and their robot plugins,
meshes, spawn requests, the world API's services and topics, the physics properties, cmd_vel)
checks it against these constants and words its refusal with ``outside``: the field, the value
and the limit, in one line, so that the same fault reads the same whichever path it came by.
Names and string fields are held to ``MAX_NAME`` characters (``name_problem``). No ROS and no
pybullet here.

The limits are far beyond anything a TurtleBot world holds and far inside what Bullet can
step: a body farther than ~1e6 m or larger than ~1e6 m has an AABB Bullet takes out of the
simulation, a number past ~1e154 squares to infinity, and a NaN never leaves a body again.
"""
import math
from typing import Iterable, Optional, Sequence, Tuple

MAX_POSITION = 1e6          # m: a coordinate of a pose
MAX_ANGLE = 1e6             # rad: a roll, pitch or yaw (any turn is within it)
MAX_LINEAR_SPEED = 1e3      # m/s: a component of a linear velocity
MAX_ANGULAR_SPEED = 1e3     # rad/s: a component of an angular velocity
MAX_MASS = 1e6              # kg
MAX_INERTIA = 1e6           # kg m^2: a moment (or product) of inertia
MAX_SIZE = 1e4              # m: a box side, a radius, a length, a plane's side, a height
MIN_BOX_SIDE = 1e-4         # m: an SDF box side of 0 is built so (ODE takes 0; Gazebo's Bullet,
# DART and Simbody boxes take 1e-4 m too)
MAX_SCALE = 1e4             # a scale factor: a mesh's (its magnitude; negative mirrors), a scan's
# resolution
MAX_FRICTION = 1e6          # a friction coefficient
NO_SLIP_FRICTION = MAX_FRICTION   # an SDF <mu> below 0: Gazebo takes FLT_MAX, a friction that never
# gives; Bullet caps a contact's friction (the product of its two bodies') at 10 in any case
MAX_FORCE = 1e6             # N (and N m for a torque, N or N m for a joint effort)
MAX_JOINT_POSITION = 1e6    # rad or m: a joint position (set_model_configuration)
MAX_GRAVITY = 1e3           # m/s^2: a component of gravity
MAX_SOLVER_ITERATIONS = 1000    # sor_pgs_iters, sor_pgs_precon_iters
MAX_CONTACTS = 1000         # max_contacts
MAX_ODE_VALUE = 1e6         # the other ODE fields (cfm, rms error tol, correcting vel, layer)
MAX_DURATION_NS = 10 ** 18  # ns: a wrench's or effort's start or duration (~31 years)
# A robot's <gazebo> plugins and sensors (robot_plugins)
MIN_TIME_STEP, MAX_TIME_STEP = 0.0001, 0.01   # s: a physics step (max_step_size)
MAX_RATE = 1e6              # Hz: an update rate (beyond the physics' own: every physics step)
MIN_RATE = 1e-6             # Hz: the slowest update rate but 0 (0: every physics step)
MAX_RANGE = 1e6             # m: a sensor's range, clip plane or cut-off
MAX_LASER_SAMPLES = 3600    # rays per scan (0.1 degree steps), as the lidar_samples argument
MAX_IMAGE_SIDE = 4096       # px: a camera image's width or height (renderer buffers, memory)
MAX_NOISE = 1e3             # a noise's mean or standard deviation, in its sensor's unit
MAX_ACCELERATION = 1e6      # m/s^2: a wheel's acceleration
MIN_WHEEL_SIZE = 0.01       # m: a diff drive's wheel diameter and wheel separation (a wheel
# spins at the speed over its radius, a turn is rim speeds over the
# separation)
MAX_DAMPING = 1e6           # N m s/rad (N s/m): a joint's viscous damping
# A URDF's tree, bounded for what one load may cost (Gazebo has no such limits; its robots have
# tens of links): pybullet's importer merges fixed links recursively, printing a line per level
# of depth (a 400-link chain: 80 KB), and the readers here walk the tree recursively (a chain of
# 1,000 links overran Python's recursion limit)
MAX_URDF_LINKS = 1000       # links in one URDF
MAX_URDF_DEPTH = 500        # joints from the root link to the farthest link
MAX_MOVING_JOINTS = 127     # joints that are not fixed, per URDF: pybullet builds no more in one
# body (a chain of 128 revolute joints fails to load)
# Names (models, links, joints, frames, namespaces, topics) and the other string fields
MAX_NAME = 256              # characters


def _g(value) -> str:
    return "%g" % value if isinstance(value, float) else "%r" % (value,)


def outside(field: str, value, low, high, unit: str = "", low_open: bool = False,
            high_open: bool = False) -> Optional[str]:
    """The refusal of ``value`` for ``field`` unless it is a finite number in low..high
    (bounds included unless ``low_open`` / ``high_open``); None when it is. One line:
    "<field> <value> is outside [-1e+06, 1e+06] m", or for a positive quantity
    "<field> <value> must be positive, at most 1e+06 kg"."""
    try:
        number = float(value)
    except (TypeError, ValueError, OverflowError):
        number = math.nan
    fine = (math.isfinite(number)
            and (number > low if low_open else number >= low)
            and (number < high if high_open else number <= high))
    if fine:
        return None
    if low == 0 and low_open and not high_open:
        return "%s %s must be positive, at most %s%s" % (field, _g(value), _g(high),
                                                         " " + unit if unit else "")
    return "%s %s is outside %s%s, %s%s%s" % (
        field, _g(value), "(" if low_open else "[", _g(low), _g(high),
        ")" if high_open else "]", " " + unit if unit else "")


def first(problems: Iterable[Optional[str]]) -> Optional[str]:
    """The first refusal of ``problems`` (None if there is none)."""
    return next((p for p in problems if p), None)


def symmetric(field: str, values: Sequence[float], limit: float, unit: str,
              names: Sequence[str] = ("x", "y", "z")) -> Optional[str]:
    """The refusal of the first of ``values`` (named ``field``.x, .y ...) beyond +-limit."""
    return first(outside("%s.%s" % (field, n), v, -limit, limit, unit)
                 for n, v in zip(names, values))


# --- shared by the SDF and URDF readers and the world API ------------------------------------

def mass_problem(value, allow_zero: bool = False, field: str = "mass") -> Optional[str]:
    """A link's mass: (0, MAX_MASS] kg; a URDF's may be 0 (a bare frame), as ROS allows."""
    return outside(field, value, 0.0, MAX_MASS, "kg", low_open=not allow_zero)


INERTIA_NAMES = ("ixx", "iyy", "izz", "ixy", "ixz", "iyz")


def inertia_problem(moments: Sequence[float], products: Sequence[float] = (),
                    allow_zero: bool = False, names: Sequence[str] = INERTIA_NAMES,
                    allow_negative: bool = False) -> Optional[str]:
    """ixx, iyy, izz in (0, MAX_INERTIA] kg m^2 ([0, ...] for a URDF, as ROS allows; within
    +-MAX_INERTIA with ``allow_negative``, for a caller that checks positive_definite itself);
    ixy, ixz, iyz within +-MAX_INERTIA. ``names``: the six fields as the caller's format names
    them, in the order ixx iyy izz ixy ixz iyz."""
    low = -MAX_INERTIA if allow_negative else 0.0
    return first([outside(n, v, low, MAX_INERTIA, "kg m^2",
                          low_open=not (allow_zero or allow_negative))
                  for n, v in zip(names[:3], moments)]
                 + [outside(n, v, -MAX_INERTIA, MAX_INERTIA, "kg m^2")
                    for n, v in zip(names[3:], products)])


def positive_definite(moments: Sequence[float], products: Sequence[float] = (0, 0, 0)) -> bool:
    """Whether the inertia matrix of ``moments`` (ixx iyy izz) and ``products`` (ixy ixz iyz)
    is positive definite (Sylvester: every leading minor > 0)."""
    ixx, iyy, izz = moments
    ixy, ixz, iyz = products
    minor2 = ixx * iyy - ixy * ixy
    det = (ixx * (iyy * izz - iyz * iyz) - ixy * (ixy * izz - iyz * ixz)
           + ixz * (ixy * iyz - iyy * ixz))
    return ixx > 0 and minor2 > 0 and det > 0


def size_problem(field: str, values: Sequence[float]) -> Optional[str]:
    """A shape's sizes (box sides, radius, length ...): each in (0, MAX_SIZE] m."""
    return first(outside(field, v, 0.0, MAX_SIZE, "m", low_open=True) for v in values)


def scale_problem(values: Sequence[float], field: str = "scale") -> Optional[str]:
    """A mesh's scale: non-zero factors within +-MAX_SCALE."""
    for v in values:
        problem = outside(field, v, -MAX_SCALE, MAX_SCALE)
        if problem or v == 0:
            return problem or "%s 0 must not be zero" % field
    return None


def rate_problem(field: str, value) -> Optional[str]:
    """An update rate: 0 (every physics step) or MIN_RATE..MAX_RATE Hz."""
    if isinstance(value, (int, float)) and value == 0:
        return None
    problem = outside(field, value, MIN_RATE, MAX_RATE, "Hz")
    return problem and problem + " (or 0: every physics step)"


def name_problem(field: str, name) -> Optional[str]:
    """A name or string field: text of at most MAX_NAME characters."""
    if not isinstance(name, str):
        return "%s must be text, not %s" % (field, type(name).__name__)
    if len(name) > MAX_NAME:
        return "%s is %d characters, more than the %d allowed" % (field, len(name), MAX_NAME)
    return None


def position_problem(field: str, values: Sequence[float]) -> Optional[str]:
    """A position's x, y, z: each within +-MAX_POSITION m."""
    return symmetric(field, values, MAX_POSITION, "m")


def angles_problem(field: str, values: Sequence[float]) -> Optional[str]:
    """Roll, pitch, yaw: each within +-MAX_ANGLE rad."""
    return symmetric(field, values, MAX_ANGLE, "rad", ("roll", "pitch", "yaw"))


def twist_problem(field: str, twist) -> Optional[str]:
    """A twist ((vx, vy, vz), (wx, wy, wz)): linear within +-MAX_LINEAR_SPEED m/s, angular
    within +-MAX_ANGULAR_SPEED rad/s."""
    return (symmetric(field + ".linear", twist[0], MAX_LINEAR_SPEED, "m/s")
            or symmetric(field + ".angular", twist[1], MAX_ANGULAR_SPEED, "rad/s"))


def unit_quaternion(q: Sequence[float], field: str = "orientation") -> Tuple[float, ...]:
    """``q`` (x, y, z, w) scaled to unit length without overflow (divided by its largest
    component first, so that 1e308 normalises); all-zero is the identity, as in Gazebo.
    ValueError (one line naming ``field``) for NaN or infinite components."""
    values = tuple(q)
    try:
        values = tuple(float(v) for v in values)
    except (TypeError, ValueError, OverflowError):
        raise ValueError("%s %r must be four finite numbers" % (field, values)) from None
    if len(values) != 4 or not all(math.isfinite(v) for v in values):
        raise ValueError("%s (%s) must be four finite numbers (x, y, z, w)"
                         % (field, ", ".join(_g(v) for v in values)))
    largest = max(abs(v) for v in values)
    if largest == 0.0:
        return (0.0, 0.0, 0.0, 1.0)
    scaled = [v / largest for v in values]
    norm = math.sqrt(sum(v * v for v in scaled))
    return tuple(v / norm for v in scaled)
