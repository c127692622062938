"""The checks of a world request's fields that come before anything looks them up: names and
strings (check_names), times (check_times), poses and twists (checked_state, and
checked_world_state once put in the world). Each refusal raises ``RequestError``, its text one
line (the request's name and limits' words)."""
from typing import Tuple

from ...errors import RequestError
from ..files import limits
from . import reference_frames as rf
from .reference_frames import Pose, Twist


def checked_state(name: str, pose: Pose, twist: Twist) -> Tuple[Pose, Twist]:
    """(pose, twist) with the quaternion normalised (all-zero: identity); RequestError naming
    the field and the limit for NaN, inf or a number beyond limits."""
    if not rf.finite(pose[0], pose[1], twist[0], twist[1]):
        raise RequestError("%s: NaN or infinite value in the pose or twist" % name)
    problem = (limits.position_problem("pose.position", pose[0])
               or limits.twist_problem("twist", twist))
    if problem:
        raise RequestError("%s: %s" % (name, problem))
    return ((tuple(float(v) for v in pose[0]), limits.unit_quaternion(pose[1])),
            (tuple(float(v) for v in twist[0]), tuple(float(v) for v in twist[1])))


def checked_world_state(name: str, pose: Pose, twist: Twist) -> None:
    """RequestError if a state given in a reference frame lands beyond limits in the world."""
    problem = (limits.position_problem("pose.position (in the world)", pose[0])
               or limits.twist_problem("twist (in the world)", twist))
    if problem:
        raise RequestError("%s: %s" % (name, problem))


def check_names(prefix: str, **names) -> None:
    """RequestError (``prefix`` and limits' one line) if a name or string field of a request
    is longer than limits.MAX_NAME, before anything looks it up or a message repeats it."""
    problem = limits.first(limits.name_problem(field, value) for field, value in names.items())
    if problem:
        raise RequestError(prefix + problem)


def check_times(what: str, start_ns, duration_ns) -> None:
    """RequestError unless start and duration (ns) are whole numbers within limits."""
    for field, value in (("start_time", start_ns), ("duration", duration_ns)):
        problem = limits.outside(field, value, -limits.MAX_DURATION_NS, limits.MAX_DURATION_NS,
                                 "ns")
        if problem or value != int(value):
            raise RequestError("%s: %s" % (what, problem or "%s %r ns must be a whole number"
                                           % (field, value)))
