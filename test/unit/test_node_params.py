"""The one check of node parameters (node_params): conversions and ranges, each refusal one
line of one form."""
import math

import pytest

from tutorial_turtlebot.errors import UserError
from tutorial_turtlebot.node_params import checked_number, converted


@pytest.mark.parametrize("value, kind, expected", [
    ("true", bool, True), ("False", bool, False), (True, bool, True), ("0.5", float, 0.5),
    (2, float, 2.0), (3.0, int, 3), ("7", int, 7), (12, str, "12")])
def test_converted(value, kind, expected):
    result = converted("~x", value, kind)
    assert result == expected and type(result) is kind


@pytest.mark.parametrize("value, kind, words", [
    ("yes", bool, "true or false"), (1, bool, "true or false"), (True, float, "a number"),
    (2.5, int, "a whole number"), ("fast", float, "a number"), (float("inf"), int, "whole")])
def test_refused_conversions_are_one_line(value, kind, words):
    with pytest.raises(UserError) as err:
        converted("~speed", value, kind)
    text = str(err.value)
    assert text.startswith("parameter ~speed must be ") and words in text
    assert text.endswith("got %r" % (value,)) and "\n" not in text


def test_checked_number_bounds():
    assert checked_number("/wander/speed", 0.2, "m/s", above=0.0, at_most=0.22) == 0.2
    for bad in (0.0, 0.3, math.nan, math.inf, True, "0.1", None):
        with pytest.raises(UserError) as err:
            checked_number("/wander/speed", bad, "m/s", above=0.0, at_most=0.22)
        assert str(err.value) == ("parameter /wander/speed must be a number > 0 and <= 0.22 "
                                  "(m/s), got %r" % (bad,))
    with pytest.raises(UserError, match=r"must be a number \(Hz\), got 'x'$"):
        checked_number("~f", "x", "Hz")
