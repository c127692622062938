"""The lights of a world (world_lights), read once with the world by world_sdf into
World.lights; a light value that cannot be read keeps SDF's default, with one warning line.
No ROS, no pybullet."""
import pytest

from tutorial_turtlebot.sim.files.meshes.mesh_file import cache_clear
from tutorial_turtlebot.sim.files.sdf.world_lights import (Light, light_of, light_pose,
                                                           lights_by_name)
from tutorial_turtlebot.sim.files.sdf.world_catalogue import resolve_world
from tutorial_turtlebot.sim.files.sdf.world_sdf import load_world
from tutorial_turtlebot.sim.files.xml_reader import parse
from tutorial_turtlebot.sim.kinematics import IDENTITY, pose_from_xyz_rpy

SUN_SDF = ('<sdf version="1.6"><light type="directional" name="sun"><diffuse>0.8 0.8 0.8 1'
           '</diffuse><attenuation><constant>0.9</constant></attenuation></light></sdf>')


@pytest.fixture(autouse=True)
def model_path(tmp_path, monkeypatch):
    monkeypatch.setenv("GAZEBO_MODEL_PATH", str(tmp_path / "models"))
    cache_clear()


def sun_model(tmp_path, sdf=SUN_SDF):
    sun = tmp_path / "models" / "sun"
    sun.mkdir(parents=True)
    (sun / "model.config").write_text(
        '<?xml version="1.0"?><model><name>Sun</name><sdf version="1.6">model.sdf</sdf></model>')
    (sun / "model.sdf").write_text(sdf)
    return str(sun / "model.sdf")


def world_file(tmp_path, body):
    path = tmp_path / "w.world"
    path.write_text('<sdf version="1.6">\n<world name="default">\n%s\n</world>\n</sdf>\n' % body)
    return str(path)


class Notes:
    """A ``warn`` that keeps its lines as world_sdf's do: "<line>: <message>"."""

    def __init__(self):
        self.lines = []

    def __call__(self, node, message):
        self.lines.append("%d: %s" % (node.line, message))


def test_lights_of_an_included_sun_and_the_worlds_own(tmp_path):
    sun_model(tmp_path)
    world = load_world(world_file(
        tmp_path, '<include><uri>model://sun</uri></include><light type="point" name="lamp">'
                  '<pose>1 2 3 0 0 0</pose></light>'))
    assert [light.name for light in world.lights] == ["sun", "lamp"]
    assert world.models == () and world.warnings == ()
    lights = lights_by_name(world.lights)
    assert list(lights) == ["sun", "lamp"]
    assert lights["sun"].kind == "directional" and lights["sun"].attenuation_constant == 0.9
    assert lights["sun"].attenuation_linear == 1.0          # SDF's default
    assert lights["lamp"].pose[0] == (1.0, 2.0, 3.0)


def test_an_includes_name_and_pose_replace_the_lights_own(tmp_path):
    sun_model(tmp_path)
    world = load_world(world_file(
        tmp_path, '<include><uri>model://sun</uri><name>sol</name><pose>0 0 9 0 0 0</pose>'
                  '</include>'))
    [sol] = world.lights
    assert sol.name == "sol" and sol.pose == pose_from_xyz_rpy((0, 0, 9, 0, 0, 0))


def test_a_packaged_world_keeps_its_sun():
    path, _ = resolve_world("empty")
    sun = lights_by_name(load_world(path).lights)["sun"]
    assert sun.diffuse == (0.8, 0.8, 0.8, 1.0)
    assert (sun.attenuation_constant, sun.attenuation_linear,
            sun.attenuation_quadratic) == (0.9, 0.01, 0.001)


def test_lights_by_name_copies_first_of_a_name_wins_nameless_left_out():
    first, second, nameless = Light("a", diffuse=(1, 0, 0, 1)), Light("a"), Light("")
    lights = lights_by_name([first, second, nameless])
    assert list(lights) == ["a"] and lights["a"] == first and lights["a"] is not first
    lights["a"].diffuse = (0.0, 0.0, 0.0, 1.0)              # a client's set_light
    assert first.diffuse == (1, 0, 0, 1)                    # the world's stays as loaded


def test_a_malformed_light_value_is_one_warning_line_and_keeps_the_default(tmp_path):
    path = world_file(
        tmp_path, '<light type="spot" name="lamp">\n<diffuse>1 0 0</diffuse>\n'
                  '<cast_shadows>maybe</cast_shadows>\n<attenuation><range>far</range>'
                  '<linear>0.5</linear></attenuation>\n<pose>1 2</pose>\n</light>')
    world = load_world(path)
    [lamp] = world.lights
    assert lamp.kind == "spot" and lamp.attenuation_linear == 0.5
    assert (lamp.diffuse, lamp.cast_shadows, lamp.attenuation_range, lamp.pose) == (
        Light("x").diffuse, False, 10.0, IDENTITY)
    assert list(world.warnings) == [
        "%s:5: light: <cast_shadows> must be true or false, got 'maybe': SDF's default is "
        "used" % path,
        "%s:4: light: <diffuse> must be 4 numbers, got '1 0 0': SDF's default is used" % path,
        "%s:6: light: <range> must be a number, got 'far': SDF's default is used" % path,
        "%s:7: light: <pose> must be 6 numbers, got '1 2': SDF's default is used" % path]


def test_a_malformed_light_in_a_light_model_names_that_file(tmp_path):
    sdf = sun_model(tmp_path, '<sdf version="1.6">\n<light name="sun">\n'
                              '<direction>down</direction>\n</light>\n</sdf>')
    path = world_file(tmp_path, '<include><uri>model://sun</uri><pose>nowhere</pose></include>')
    world = load_world(path)
    [sun] = world.lights
    assert sun.direction == (0.0, 0.0, -1.0) and sun.pose == IDENTITY
    assert list(world.warnings) == [
        "%s:3: light: <pose> must be 6 numbers, got 'nowhere': SDF's default is used" % path,
        "%s:3: light: <direction> must be 3 numbers, got 'down': SDF's default is used" % sdf]


def test_light_of_and_light_pose_read_an_element():
    notes = Notes()
    elem = parse('<light name="l" type="directional">\n<cast_shadows>TRUE</cast_shadows>\n'
                 '<specular>0.2 0.2 0.2 1</specular><direction>0 1 0</direction>\n'
                 '<pose>0 0 5 0 0 0</pose></light>', "text")
    light = light_of(elem, notes)
    assert (light.name, light.kind, light.cast_shadows) == ("l", "directional", True)
    assert light.specular == (0.2, 0.2, 0.2, 1.0) and light.direction == (0.0, 1.0, 0.0)
    assert light.pose == pose_from_xyz_rpy((0, 0, 5, 0, 0, 0))
    override = pose_from_xyz_rpy((1, 0, 0, 0, 0, 0))
    assert light_of(elem, notes, "other", override).name == "other"
    assert light_of(elem, notes, "other", override).pose == override
    assert notes.lines == []
    assert light_pose(None, notes) == IDENTITY
    assert light_pose(parse("<pose>a b c</pose>", "text"), notes) == IDENTITY
    assert notes.lines == ["1: light: <pose> must be 6 numbers, got 'a b c': SDF's default is "
                           "used"]
