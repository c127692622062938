"""Command line of ``move_turtlebot LINEAR ANGULAR`` (no rospy here)."""
import math
from typing import Dict, List, Sequence, Tuple

import yaml

from rosgraph.names import is_legal_remap

from ..errors import UserError

USAGE = ("usage: move_turtlebot LINEAR ANGULAR [_rate:=HZ] [_duration:=S]   (m/s forward, "
         "rad/s counter-clockwise; publish at HZ, default 10; stop after S s of ROS time, "
         "default 0 = at Ctrl-C; e.g. move_turtlebot 0.2 0.5 _duration:=5)")
SETTINGS = ("rate", "duration")  # the private parameters move_turtlebot reads


def user_args(argv: Sequence[str]) -> List[str]:
    """``argv`` (without the program name) less ROS's own arguments: remappings such as
    ``cmd_vel:=x``, ``__name:=y``, ``_rate:=5``, as rospy.myargv drops them."""
    return [arg for arg in argv if not is_legal_remap(arg)]


def command_line_settings(argv: Sequence[str]) -> Tuple[Dict[str, object], List[str]]:
    """The ``_name:=value`` arguments of ``argv`` as {name: value} (value read as YAML, as rospy
    reads them), and ``argv`` without them. rospy would store them on the parameter server,
    where the next run would find them; given to init_node without them, they live only for
    this run."""
    settings, rest = {}, []
    for arg in argv:
        name, sep, text = arg.partition(":=")
        if sep and name.startswith("_") and not name.startswith("__") and is_legal_remap(arg):
            try:
                settings[name[1:]] = yaml.safe_load(text)
            except yaml.YAMLError:
                settings[name[1:]] = text
        else:
            rest.append(arg)
    return settings, rest


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
