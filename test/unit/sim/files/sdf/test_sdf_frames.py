"""Poses relative to named frames (sdf_frames, through world_sdf), as Gazebo 11 resolves SDFormat
1.7's <pose relative_to> (and SDF 1.6's <pose frame>): within a model and in the world. No ROS
master, no pybullet."""
import pytest

from tutorial_turtlebot.sim.files.sdf.world_sdf import load_world

from unit_helpers import world_fault
from unit_helpers import world_file as sdf_world_file


def world_file(tmp_path, body):
    """An SDFormat 1.7 world (relative_to is 1.7's)."""
    return sdf_world_file(tmp_path, body, version="1.7")


def link(name, pose="", relative=""):
    rel = ' relative_to="%s"' % relative if relative else ""
    return ('<link name="%s"><pose%s>%s</pose><collision name="c"><geometry><box><size>1 1 1'
            '</size></box></geometry></collision></link>' % (name, rel, pose or "0 0 0 0 0 0"))


def test_a_link_relative_to_a_sibling_link_and_a_frame(tmp_path):
    body = ('<model name="m"><static>true</static><pose>10 0 0 0 0 1.5707963267948966</pose>'
            '<frame name="corner" attached_to="a"><pose>0 1 0 0 0 0</pose></frame>'
            + link("b", "2 0 0 0 0 0", "a") + link("a", "1 0 0 0 0 0")
            + link("c", "0 0 3 0 0 0", "corner") + '</model>')
    world = load_world(world_file(tmp_path, body))
    # a: 1 m along the model's x, which points along the world's y
    assert world.shape("m::a::c").pose[:3] == pytest.approx((10.0, 1.0, 0.0))
    assert world.shape("m::b::c").pose[:3] == pytest.approx((10.0, 3.0, 0.0))
    # corner: 1 m along a's y (the world's -x) from a; c 3 m above it
    assert world.shape("m::c::c").pose[:3] == pytest.approx((9.0, 1.0, 3.0))


def test_a_collision_relative_to_another_link_of_its_model(tmp_path):
    body = ('<model name="m"><static>true</static>' + link("a", "0 0 1 0 0 0")
            + '<link name="b"><pose>5 0 0 0 0 0</pose><visual name="v"><pose relative_to="a">'
              '0 0 0.5 0 0 0</pose><geometry><sphere><radius>0.1</radius></sphere></geometry>'
              '</visual></link></model>')
    world = load_world(world_file(tmp_path, body))
    assert world.shape("m::b::v").pose[:3] == pytest.approx((0.0, 0.0, 1.5))


def test_a_model_relative_to_another_model_of_the_world_and_sdf_1_6_frame(tmp_path):
    body = ('<model name="second"><static>true</static><pose frame="first">0 2 0 0 0 0</pose>'
            + link("l") + '</model><model name="first"><static>true</static>'
            '<pose>3 0 0 0 0 0</pose>' + link("l") + '</model>'
            '<frame name="spot"><pose relative_to="first">0 0 1 0 0 0</pose></frame>'
            '<model name="third"><static>true</static><pose relative_to="spot">1 0 0 0 0 0'
            '</pose>' + link("l") + '</model>')
    world = load_world(world_file(tmp_path, body))
    assert world.model("second").pose[:3] == pytest.approx((3.0, 2.0, 0.0))
    assert world.model("third").pose[:3] == pytest.approx((4.0, 0.0, 1.0))
    assert world.shape("second::l::c").pose[:3] == pytest.approx((3.0, 2.0, 0.0))


def test_the_scope_frames_are_the_parent(tmp_path):
    body = ('<model name="m"><static>true</static><pose>1 1 0 0 0 0</pose>'
            + link("a", "1 0 0 0 0 0", "__model__") + '</model>'
            '<model name="n"><static>true</static><pose relative_to="world">0 5 0 0 0 0</pose>'
            + link("l") + '</model>')
    world = load_world(world_file(tmp_path, body))
    assert world.shape("m::a::c").pose[:3] == pytest.approx((2.0, 1.0, 0.0))
    assert world.model("n").pose[:3] == pytest.approx((0.0, 5.0, 0.0))


@pytest.mark.parametrize("body, words", [
    ('<model name="m">' + link("a", "", "nowhere") + '</model>',
     "<pose relative_to='nowhere'>: no frame of that name here"),
    ('<model name="m">' + link("a", "", "b") + link("b", "", "a") + '</model>',
     "placed relative to itself (a cycle of relative_to)"),
])
def test_a_frame_found_nowhere_or_a_cycle_is_refused(tmp_path, body, words):
    message = world_fault(world_file(tmp_path, body))
    assert words in message and ":4:" in message
