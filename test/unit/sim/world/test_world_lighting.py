"""delete_light through sim/world_lighting: the light is gone for get/set_light_properties and
stays gone through the resets; Gazebo's answers. No ROS master."""
import pytest

from tutorial_turtlebot.errors import RequestError


def test_delete_light_takes_the_sun_out_and_says_so_as_gazebo(empty):
    sim, wc = empty
    assert wc.get_light("sun").diffuse == (0.8, 0.8, 0.8, 1.0)
    assert wc.delete_light("sun") == "DeleteLight: sun successfully deleted"
    with pytest.raises(RequestError, match="^getLightProperties: Requested light sun not "
                                           "found!$"):
        wc.get_light("sun")
    with pytest.raises(RequestError, match="^setLightProperties: Requested light sun not "
                                           "found!$"):
        wc.set_light("sun", False, (1, 1, 1, 1), (1, 1, 1, 1), (1, 0, 0), (0, 0, -1),
                     ((0, 0, 0), (0, 0, 0, 1)))
    with pytest.raises(RequestError, match="^DeleteLight: Requested light sun not found!$"):
        wc.delete_light("sun")
    sim.reset_world()
    sim.reset_simulation()
    assert "sun" not in wc.lights()          # a reset brings no deleted light back
    assert [light.name for light in sim.world.lights] == ["sun"]   # the loaded world's stays


def test_delete_light_refuses_an_overlong_name_in_one_line(empty):
    _, wc = empty
    with pytest.raises(RequestError, match="^DeleteLight: light_name is 300 characters, more "
                                           "than the 256 allowed$"):
        wc.delete_light("x" * 300)
    assert wc.get_light("sun").diffuse == (0.8, 0.8, 0.8, 1.0)
