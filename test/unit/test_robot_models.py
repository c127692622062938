"""The TurtleBot3 facts shared by the simulator and the lab's nodes (robot_models), against
doc/turtlebot3.md. Units: m, m/s, rad/s."""
import math
import os

import pytest

from tutorial_turtlebot.errors import ModelError
from tutorial_turtlebot.robot_models import (MODEL_NAMES, MODELS, get_model, model_limits,
                                             turn_radius, turtlebot3_model_of, urdf_path)


def test_turn_radius():
    assert turn_radius("burger") == pytest.approx(0.15)
    assert turn_radius("waffle") == turn_radius("waffle_pi") == pytest.approx(0.26)
    assert turn_radius("hovercraft") == max(m.turn_radius for m in MODELS.values())
    # Each is at least the farthest corner of the navigation footprint (doc/turtlebot3.md 1.1).
    assert turn_radius("burger") >= math.hypot(0.105, 0.105)
    assert turn_radius("waffle") >= math.hypot(0.205, 0.155)


def test_speed_limits_as_teleop_key_picks_them():
    assert model_limits("burger") == (0.22, 2.84)
    assert model_limits("waffle") == model_limits("waffle_pi") == (0.26, 1.82)
    assert model_limits("hovercraft") == model_limits("burger")


def test_unknown_model_is_one_line_naming_the_valid_ones():
    with pytest.raises(ModelError) as err:
        get_model("hovercraft")
    assert all(name in str(err.value) for name in MODEL_NAMES) and "\n" not in str(err.value)


def test_urdf_files_exist_and_a_camera_burger_is_the_autorace_one():
    for name in MODEL_NAMES:
        assert os.path.isfile(urdf_path(name))
    assert urdf_path("burger", with_camera=True).endswith("turtlebot3_burger_for_autorace.urdf")
    assert urdf_path("waffle_pi", with_camera=True) == urdf_path("waffle_pi")


@pytest.mark.parametrize("robot, model", [
    ("turtlebot3_waffle_pi", "waffle_pi"), ("turtlebot3_burger_for_autorace", "burger"),
    ("turtlebot3_waffle", "waffle"), ("my_robot", None), ("", None)])
def test_the_model_a_robot_name_names(robot, model):
    assert turtlebot3_model_of(robot) == model
