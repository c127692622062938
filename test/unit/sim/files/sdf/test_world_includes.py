"""<include> of model folders, as Gazebo resolves them (world_sdf with asset_uri): no pybullet."""
import math
import os
import stat

import pytest

from tutorial_turtlebot.errors import WorldError
from tutorial_turtlebot.sim.files.sdf.world_sdf import MAX_INCLUDE_DEPTH, load_world

from unit_helpers import within, world_file

BOX = ('<link name="l"><pose>0 0 0.5 0 0 0</pose><collision name="c"><geometry><box>'
       '<size>1 1 1</size></box></geometry></collision></link>')


def model_folder(root, name, body, pose="1 2 0 0 0 0", static="false"):
    """A Gazebo model folder root/name: model.config and a model.sdf holding ``body``."""
    folder = root / name
    folder.mkdir(parents=True)
    (folder / "model.config").write_text(
        '<?xml version="1.0"?><model><name>%s</name><sdf version="1.6">model.sdf</sdf></model>'
        % name)
    (folder / "model.sdf").write_text(
        '<?xml version="1.0"?>\n<sdf version="1.6">\n<model name="%s">\n<pose>%s</pose>\n'
        '<static>%s</static>\n%s\n</model>\n</sdf>\n' % (name, pose, static, body))
    return folder


@pytest.fixture
def models(tmp_path, monkeypatch):
    """A model folder on GAZEBO_MODEL_PATH."""
    root = tmp_path / "models"
    monkeypatch.setenv("GAZEBO_MODEL_PATH", str(root))
    return root


def fault(path):
    with pytest.raises(WorldError) as err:
        load_world(path)
    message = str(err.value)
    assert "\n" not in message
    return message


def test_an_include_is_the_model_of_its_folder(tmp_path, models):
    model_folder(models, "crate", BOX)
    world = load_world(world_file(tmp_path, '<include><uri>model://crate</uri></include>'))
    assert world.models == ("crate",)
    crate = world.model("crate")
    assert crate.pose == (1.0, 2.0, 0.0, 0.0, 0.0, 0.0) and not crate.static
    assert [link.scoped for link in crate.links] == ["crate::l"]
    assert world.shape("crate::l::c").pose[:3] == (1.0, 2.0, 0.5)


def test_include_overrides_name_pose_and_static(tmp_path, models):
    model_folder(models, "crate", BOX)
    world = load_world(world_file(tmp_path, '''
      <include><uri>model://crate</uri></include>
      <include><uri>model://crate</uri><name>crate_2</name>
        <pose>5 0 0 0 0 1.5707963267948966</pose><static>true</static></include>'''))
    assert world.models == ("crate", "crate_2")
    second = world.model("crate_2")
    assert second.static and second.pose[:2] == (5.0, 0.0)
    assert math.isclose(second.pose[5], math.pi / 2)
    shape = world.shape("crate_2::l::c")
    assert shape.static and shape.pose[:3] == (5.0, 0.0, 0.5)
    assert not world.shape("crate::l::c").static


def test_includes_nest_inside_models_and_other_includes(tmp_path, models):
    model_folder(models, "leg", BOX, pose="0 0 0 0 0 0")
    model_folder(models, "table", '<include><uri>model://leg</uri><name>front</name>'
                                  '<pose>0.5 0 0 0 0 0</pose></include>', pose="10 0 0 0 0 0")
    world = load_world(world_file(tmp_path, '''
      <model name="room"><static>true</static>
        <include><uri>model://table</uri></include></model>'''))
    assert world.models == ("room",)
    assert [link.scoped for link in world.model("room").links] == ["room::table::front::l"]
    shape = world.shape("room::table::front::l::c")
    assert shape.pose[:3] == (10.5, 0.0, 0.5) and shape.static   # static from the outer model


def test_ground_plane_and_sun_need_no_model_path(tmp_path, monkeypatch):
    monkeypatch.delenv("GAZEBO_MODEL_PATH", raising=False)
    world = load_world(world_file(tmp_path, '<include><uri>model://sun</uri></include>'
                                            '<include><uri>model://ground_plane</uri></include>'))
    assert world.models == ("ground_plane",)
    plane = world.shape("ground_plane::link::collision")
    assert plane.kind == "plane" and plane.size == (100.0, 100.0) and plane.static


def test_a_missing_include_is_one_warning_naming_the_uri_and_the_search(tmp_path, models):
    """Gazebo (sdformat) skips an include it cannot find: the rest of the world loads."""
    model_folder(models, "crate", BOX)
    world = load_world(world_file(tmp_path, '<include><uri>model://cafe_table</uri></include>'
                                            '<include><uri>model://crate</uri></include>'
                                            '<include><uri>model://mailbox</uri></include>'))
    assert world.models == ("crate",)
    # one line a missing model, of at most 200 characters; the folders searched once
    [searched] = [w for w in world.warnings if w.startswith("model:// searched ")]
    [table, mailbox] = [w for w in world.warnings if w != searched]
    assert "\n" not in "".join(world.warnings) and len(table) <= 200 and len(mailbox) <= 200
    assert table.endswith("test.world:4: <include> left out: model://cafe_table not found")
    assert mailbox.endswith("<include> left out: model://mailbox not found")
    assert searched.startswith("model:// searched GAZEBO_MODEL_PATH (%s)" % models)
    assert "https://github.com/osrf/gazebo_models" in searched
    assert "add its folder to GAZEBO_MODEL_PATH" in searched


def test_an_include_with_the_name_in_another_case_says_so(tmp_path, models):
    model_folder(models, "mailbox", BOX)
    world = load_world(world_file(tmp_path, '<include><uri>model://Mailbox</uri></include>'))
    assert world.models == ()
    [message, searched] = world.warnings
    assert "%s exists (its name differs in letter case)" % (models / "mailbox") in message
    assert searched.startswith("model:// searched ") and len(message) <= 200


def test_a_model_folder_without_model_config_is_one_warning(tmp_path, models):
    """sdformat 9 (resolveFileNameFromUri): "Unable to resolve uri ... since it does not
    contain a model.config file", and the include is skipped; the rest of the world loads."""
    (models / "empty").mkdir(parents=True)
    model_folder(models, "crate", BOX)
    world = load_world(world_file(tmp_path, '<include><uri>model://empty</uri></include>'
                                            '<include><uri>model://crate</uri></include>'))
    assert world.models == ("crate",)
    [message] = world.warnings
    assert "test.world:4: <include> left out: " in message and "has no model.config" in message


def test_the_fixture_model_config_with_a_bare_ampersand_loads(tmp_path, monkeypatch):
    """test/fixtures/gazebo_models/curtain_rail: "rail & closed curtain", &nbsp; and an unquoted
    attribute, as TinyXML (Gazebo 11) reads them; expat alone refuses the file."""
    import unit_paths
    monkeypatch.setenv("GAZEBO_MODEL_PATH", os.path.join(unit_paths.FIXTURES, "gazebo_models"))
    world = load_world(world_file(tmp_path, '<include><uri>model://curtain_rail</uri>'
                                            '<pose>3 2 0 0 0 0</pose></include>'))
    assert world.models == ("curtain_rail",) and world.warnings == ()
    assert world.shape("curtain_rail::curtain::collision").pose[:3] == (3.0, 2.0, 1.0)


def test_a_model_config_tinyxml_cannot_read_is_one_short_warning(tmp_path, models):
    folder = model_folder(models, "broken", BOX)
    (folder / "model.config").write_text('<model>\n<sdf version="1.6">model.sdf</model>\n')
    model_folder(models, "crate", BOX)
    world = load_world(world_file(tmp_path, '<include><uri>model://broken</uri></include>'
                                            '<include><uri>model://crate</uri></include>'))
    assert world.models == ("crate",)
    [message] = world.warnings
    assert "<include> left out: broken/model.config:2: malformed XML: mismatched tag" in message
    assert len(message) <= 200


def test_an_include_of_itself_is_refused(tmp_path, models):
    model_folder(models, "loop", '<include><uri>model://loop</uri></include>')
    message = fault(world_file(tmp_path, '<include><uri>model://loop</uri></include>'))
    assert "nested more than %d deep" % MAX_INCLUDE_DEPTH in message


def test_errors_inside_an_included_model_name_its_file(tmp_path, models):
    model_folder(models, "bad", '<link name="l"><collision name="c"><geometry><box><size>1 x 1'
                                '</size></box></geometry></collision></link>')
    message = fault(world_file(tmp_path, '<include><uri>model://bad</uri></include>'))
    assert "bad/model.sdf:6: <size>: must be 3 numbers" in message


# --- under abuse: only regular files are read -----------------------------------------------------

@pytest.mark.parametrize("target", ["/dev/stdin", "/dev/zero", "fifo"])
def test_an_include_of_what_is_no_regular_file_is_refused_at_its_line(tmp_path, target):
    if target == "fifo":
        target = str(tmp_path / "pipe.sdf")
        os.mkfifo(target)
    elif not os.path.exists(target) or stat.S_ISREG(os.stat(target).st_mode):
        pytest.skip("no %s here, or a regular file" % target)
    path = world_file(tmp_path, "<include>\n<uri>%s</uri>\n</include>" % target)
    message = within(10, fault, path)
    assert message.startswith("%s:4: <include> of %s: " % (path, target)), message
    assert message.endswith("not a regular file")


def test_a_model_config_linked_to_dev_zero_is_refused(tmp_path, models):
    folder = model_folder(models, "crate", BOX)
    os.unlink(str(folder / "model.config"))
    (folder / "model.config").symlink_to("/dev/zero")
    path = world_file(tmp_path, "<include><uri>model://crate</uri></include>")
    message = within(10, fault, path)
    assert message.endswith("model.config: cannot read model.config: it is a character "
                            "device, not a regular file"), message


def test_a_model_sdf_that_is_a_fifo_is_refused(tmp_path, models):
    folder = model_folder(models, "crate", BOX)
    os.unlink(str(folder / "model.sdf"))
    os.mkfifo(str(folder / "model.sdf"))
    message = within(10, fault, world_file(tmp_path, "<include><uri>model://crate</uri>"
                                                     "</include>"))
    assert message.endswith("its model.config names model.sdf: it is a FIFO, not a regular "
                            "file"), message


def fan_out(models, width):
    """A row model of ``width`` boxes, included ``width`` times: width * width boxes."""
    model_folder(models, "box", BOX, static="true")
    model_folder(models, "row", "".join(
        "<include><uri>model://box</uri><name>b%d</name><pose>%d 0 0 0 0 0</pose></include>"
        % (k, k) for k in range(width)), static="true")
    return "".join("<include><uri>model://row</uri><name>r%d</name><pose>0 %d 0 0 0 0</pose>"
                   "</include>" % (k, k) for k in range(width))


def test_includes_that_fan_out_stop_at_the_shape_budget(tmp_path, models, monkeypatch):
    """A 155-character request of three small models once became 10,000 boxes: reading stops
    at the first shape beyond the budget, with one line."""
    from tutorial_turtlebot.sim.files.sdf import world_sdf
    path = world_file(tmp_path, fan_out(models, 10))
    assert len(load_world(path).shapes) == 100
    monkeypatch.setattr(world_sdf, "MAX_WORLD_SHAPES", 50)
    assert "more than 50 collisions and visuals in all (do includes fan out?)" in fault(path)


def test_includes_that_fan_out_stop_at_the_include_budget(tmp_path, models, monkeypatch):
    from tutorial_turtlebot.sim.files.sdf import world_sdf
    monkeypatch.setattr(world_sdf, "MAX_INCLUDES", 20)
    message = fault(world_file(tmp_path, fan_out(models, 10)))
    assert "more than 20 includes in all (do includes fan out?)" in message


def test_a_spawn_stops_reading_at_its_own_budget(models):
    from tutorial_turtlebot.sim.files.sdf.world_sdf import load_model_xml
    body = fan_out(models, 10)
    xml = '<sdf version="1.6"><model name="m"><static>true</static>%s</model></sdf>' % body
    with pytest.raises(WorldError, match="more than 30 collisions and visuals in all"):
        load_model_xml(xml, "model_xml", "m", max_shapes=30)
