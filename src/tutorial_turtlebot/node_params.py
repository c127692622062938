"""The one check of a node's parameter values, for the /gazebo node and the lab's nodes (no ROS
here: the nodes read the values, these say whether they will do). Each refusal is a UserError of
one line in one form: ``parameter NAME must be WHAT, got VALUE``."""
import math
from typing import Optional

from .errors import UserError

_KIND_WORDS = {bool: "true or false", int: "a whole number", float: "a number", str: "a string"}


def converted(name: str, value, kind):
    """``value`` of parameter ``name`` as a ``kind`` (bool, int, float, str): a bool only from a
    bool or "true"/"false" (any case), a number never from a bool, an int only from a whole
    number."""
    try:
        if kind is bool:
            if isinstance(value, str) and value.lower() in ("true", "false"):
                return value.lower() == "true"
            if isinstance(value, bool):
                return value
            raise ValueError
        if kind in (int, float) and isinstance(value, bool):
            raise ValueError
        if kind is int and not float(value).is_integer():
            raise ValueError
        return kind(value)
    except (TypeError, ValueError, OverflowError):
        raise UserError("parameter %s must be %s, got %r"
                        % (name, _KIND_WORDS.get(kind, kind.__name__), value)) from None


def checked_number(name: str, value, unit: str, above: Optional[float] = None,
                   at_least: Optional[float] = None, at_most: Optional[float] = None) -> float:
    """``value`` of parameter ``name`` as a float, if it is a finite number with
    ``value > above``, ``value >= at_least`` and ``value <= at_most`` (where given)."""
    bounds = []
    if above is not None:
        bounds.append("> %g" % above)
    if at_least is not None:
        bounds.append(">= %g" % at_least)
    if at_most is not None:
        bounds.append("<= %g" % at_most)
    good = (isinstance(value, (int, float)) and not isinstance(value, bool)
            and math.isfinite(value)
            and (above is None or value > above)
            and (at_least is None or value >= at_least)
            and (at_most is None or value <= at_most))
    if not good:
        raise UserError("parameter %s must be a number%s (%s), got %r"
                        % (name, "".join(" " + b if i == 0 else " and " + b
                                         for i, b in enumerate(bounds)), unit, value))
    return float(value)
