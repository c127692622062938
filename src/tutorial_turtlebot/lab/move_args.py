"""Command line of ``move_turtlebot LINEAR ANGULAR`` (no rospy here)."""
import math
from typing import List, Sequence, Tuple

from rosgraph.names import is_legal_remap

from ..errors import UserError

USAGE = ("usage: move_turtlebot LINEAR ANGULAR   "
         "(m/s forward, rad/s counter-clockwise; e.g. move_turtlebot 0.2 0.5)")


def user_args(argv: Sequence[str]) -> List[str]:
    """``argv`` (without the program name) less ROS's own arguments: remappings such as
    ``cmd_vel:=x``, ``__name:=y``, ``_rate:=5``, as rospy.myargv drops them."""
    return [arg for arg in argv if not is_legal_remap(arg)]


def wants_help(args: Sequence[str]) -> bool:
    """True when the user asked for help (``-h`` or ``--help``)."""
    return any(arg in ("-h", "--help") for arg in args)


def _speed(name: str, text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise UserError("%s must be a number, got %r" % (name, text)) from None
    if not math.isfinite(value):
        raise UserError("%s must be a finite number, got %r" % (name, text))
    return value


def parse(args: Sequence[str]) -> Tuple[float, float]:
    """(linear m/s, angular rad/s) from the user's arguments; UserError saying what is wrong."""
    if len(args) != 2:
        raise UserError("expected 2 arguments, LINEAR and ANGULAR, got %d" % len(args))
    return _speed("LINEAR", args[0]), _speed("ANGULAR", args[1])
