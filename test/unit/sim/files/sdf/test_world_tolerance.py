"""Worlds from the wild (world_sdf with asset_uri and mesh_file): what Gazebo tolerates loads,
with one warning line where something is left out; real garbage is still refused. The files
are written here, small; none is copied from anywhere."""
import os

import numpy as np
import pytest

from tutorial_turtlebot.sim.files.meshes.mesh_file import cache_clear
from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
from tutorial_turtlebot.sim.world.world_control import WorldControl
from tutorial_turtlebot.sim.files.sdf.world_sdf import load_model_xml, load_world
from tutorial_turtlebot.sim.files.world_types import Inertial

from unit_helpers import world_fault, world_file
import unit_paths

BOX = '<box><size>1 1 1</size></box>'


@pytest.fixture(autouse=True)
def no_model_path(tmp_path, monkeypatch):
    monkeypatch.setenv("GAZEBO_MODEL_PATH", str(tmp_path / "models"))
    monkeypatch.delenv("GAZEBO_RESOURCE_PATH", raising=False)
    monkeypatch.chdir(tmp_path)
    cache_clear()


def link(inertial="", geometry=BOX, extra=""):
    return ('<link name="l"><inertial>%s</inertial><collision name="c"><geometry>%s</geometry>'
            '</collision>%s</link>' % (inertial, geometry, extra))


def model(body, static="true", name="m", pose="0 0 0.5 0 0 0"):
    return ('<model name="%s"><static>%s</static><pose>%s</pose>%s</model>'
            % (name, static, pose, body))


BUILDING_EDITOR = ('<mass>0</mass><inertia><ixx>nan</ixx><ixy>0</ixy><ixz>0</ixz><iyy>0</iyy>'
                   '<iyz>0</iyz><izz>0</izz></inertia>')


# --- 1. values Gazebo does not use are not checked ------------------------------------------

@pytest.mark.parametrize("inertial", [
    BUILDING_EDITOR,
    "<mass>0</mass>",
    "<mass>nan</mass>",
    "<mass>-3</mass><inertia><ixx>-1</ixx><iyy>0</iyy><izz>inf</izz></inertia>",
])
def test_a_static_models_inertial_is_not_checked(tmp_path, inertial):
    world = load_world(world_file(tmp_path, model(link(inertial))))
    assert world.models == ("m",) and world.warnings == ()
    assert world.model("m").links[0].inertial == Inertial()    # unused: SDF's defaults


def test_a_static_outer_model_makes_a_nested_ones_inertial_unused_too(tmp_path):
    world = load_world(world_file(tmp_path, model(model(link(BUILDING_EDITOR), static="false",
                                                        name="inner"))))
    assert world.shape("m::inner::l::c").static


@pytest.mark.parametrize("where", ["model", "inertial"])
def test_a_nan_pose_is_still_refused_in_a_static_model(tmp_path, where):
    if where == "model":
        body = model(link(), pose="0 nan 0 0 0 0")
    else:
        body = model(link("<pose>0 0 nan 0 0 0</pose>" + BUILDING_EDITOR))
    assert "<pose>" in world_fault(world_file(tmp_path, body))


# --- 2. values Gazebo uses are refused where Gazebo refuses them ----------------------------

@pytest.mark.parametrize("inertial, words", [
    ("<mass>0</mass>", "<mass> 0 must be positive"),
    ("<mass>-1</mass>", "<mass> -1 must be positive"),
    ("<mass>nan</mass>", "<mass> nan must be positive"),
    (BUILDING_EDITOR, "<mass> 0 must be positive"),
])
def test_a_movable_links_bad_mass_is_refused_as_gazebo_refuses_it(tmp_path, inertial, words):
    """Gazebo's ODELink::UpdateMass throws for a mass that is not > 0."""
    message = world_fault(world_file(tmp_path, model(link(inertial), static="false")))
    assert words in message and "Gazebo refuses it on a link that is not static" in message


def test_a_movable_links_nan_inertia_is_refused_by_our_bound(tmp_path):
    inertial = "<mass>1</mass><inertia><ixx>1</ixx><iyy>nan</iyy><izz>1</izz></inertia>"
    message = world_fault(world_file(tmp_path, model(link(inertial), static="false")))
    assert "<inertia> iyy nan is outside [-1e+06, 1e+06] kg m^2" in message


ZERO_INERTIA = ("<mass>0.2</mass><inertia><ixx>0</ixx><ixy>0</ixy><ixz>0</ixz><iyy>0</iyy>"
                "<iyz>0</iyz><izz>0</izz></inertia>")


@pytest.mark.parametrize("inertia", [
    "<ixx>0</ixx><iyy>0</iyy><izz>0</izz>",
    "<ixx>-1</ixx><iyy>1</iyy><izz>1</izz>",
    "<ixx>1</ixx><iyy>1</iyy><izz>1</izz><ixy>2</ixy>",     # positive moments, not definite
])
def test_a_movable_links_inertia_that_is_not_positive_definite_is_odes_fallback(tmp_path,
                                                                                inertia):
    """ODE's dBodySetMass (Gazebo 11's copy) gives such a body an identity inverse inertia
    with a message and goes on: each moment 1 kg m^2 here too, one warning per file."""
    inertial = "<mass>0.2</mass><inertia>%s</inertia>" % inertia
    body = (model(link(inertial), static="false", name="can")
            + model(link(inertial), static="false", name="can_2", pose="2 0 0.5 0 0 0"))
    world = load_world(world_file(tmp_path, body))
    assert world.models == ("can", "can_2")
    for name in world.models:
        assert world.model(name).links[0].inertial.inertia == (1.0, 1.0, 1.0, 0.0, 0.0, 0.0)
        assert world.model(name).links[0].inertial.mass == 0.2
    [message] = world.warnings
    assert "inertia is not positive definite" in message and "1 kg m^2" in message
    assert message.startswith(str(tmp_path / "test.world") + ":4: ") and "\n" not in message


def test_a_positive_definite_inertia_is_kept(tmp_path):
    inertial = ("<mass>0.2</mass><inertia><ixx>0.1</ixx><iyy>0.2</iyy><izz>0.3</izz>"
                "<ixy>0.01</ixy></inertia>")
    world = load_world(world_file(tmp_path, model(link(inertial), static="false")))
    assert world.model("m").links[0].inertial.inertia == (0.1, 0.2, 0.3, 0.01, 0.0, 0.0)
    assert world.warnings == ()


def test_a_body_of_zero_inertia_stands_and_turns_in_the_physics(tmp_path):
    """Built in pybullet with the fallback inertia: it falls onto the floor and stays."""
    body = ('<include><uri>model://ground_plane</uri></include>'
            + model(link(ZERO_INERTIA), static="false", name="can", pose="1 1 0.6 0 0 0.3"))
    sim = Simulation(SimConfig(world=world_file(tmp_path, body), spawn_robot=False))
    try:
        wc = WorldControl(sim)
        for _ in range(800):
            sim.step()
        (x, _, z), _ = wc.get_model_state("can")[0]
        assert abs(z - 0.5) < 0.01 and abs(x - 1) < 0.01
        pose = wc.get_model_state("can")[0]
        wc.set_model_state("can", ((1, 1, 1.5), pose[1]), ((0, 0, 0), (0, 0, 2.0)))
        sim.step()
        assert abs(wc.get_model_state("can")[1][1][2] - 2.0) < 0.05   # it turns, at 2 rad/s
    finally:
        sim.close()


def test_a_movable_links_huge_mass_is_refused_by_our_bound_not_gazebos(tmp_path):
    message = world_fault(world_file(tmp_path, model(link("<mass>1e9</mass>"), static="false")))
    assert "<mass> 1e+09 must be positive, at most 1e+06 kg" in message
    assert "Gazebo" not in message


# --- 3. a missing model or mesh is one warning; the rest loads ------------------------------

def mesh(uri):
    return "<mesh><uri>%s</uri></mesh>" % uri


def test_a_missing_mesh_is_one_warning_and_the_link_loads_without_it(tmp_path):
    body = (model(link(geometry=mesh("model://mailbox/meshes/mailbox.dae"),
                       extra='<visual name="v"><geometry>%s</geometry></visual>'
                             '<collision name="b"><geometry>%s</geometry></collision>'
                       % (mesh("model://mailbox/meshes/mailbox.dae"), BOX)))
            + model(link(), name="other", pose="3 0 0.5 0 0 0"))
    world = load_world(world_file(tmp_path, body))
    assert world.models == ("m", "other")
    assert [s.name for s in world.model_shapes("m")] == ["m::l::b"]   # the box stays
    [message, searched] = world.warnings   # the same file twice: one line; the folders once
    assert "\n" not in message and message.startswith(str(tmp_path / "test.world") + ":4: ")
    assert message.endswith("m::l::c left out: model://mailbox/meshes/mailbox.dae not found")
    assert len(message) <= 200
    assert searched.startswith("model:// searched GAZEBO_MODEL_PATH (%s)" % (tmp_path / "models"))
    assert "download it and add its folder to GAZEBO_MODEL_PATH" in searched


def test_a_mesh_named_in_another_letter_case_is_named_as_such(tmp_path):
    (tmp_path / "meshes").mkdir()
    (tmp_path / "meshes" / "mailbox.dae").write_text("<COLLADA/>")
    world = load_world(world_file(tmp_path, model(link(geometry=mesh("meshes/Mailbox.DAE")))))
    assert world.model_shapes("m") == ()
    [message, searched] = world.warnings
    assert "meshes/Mailbox.DAE not found" in message and len(message) <= 200
    assert ("%s exists (its name differs in letter case)"
            % (tmp_path / "meshes" / "mailbox.dae")) in message
    assert searched.startswith("relative paths searched ")


@pytest.mark.parametrize("content", ["not xml at all", "<COLLADA><asset>\n<unit meter=",
                                     '<?xml version="1.0"?><COLLADA xmlns="http://www.collada.'
                                     'org/2005/11/COLLADASchema" version="1.4.1"/>'])
def test_a_collada_file_that_cannot_be_read_is_one_warning(tmp_path, content):
    (tmp_path / "broken.dae").write_text(content)
    body = model(link(geometry=mesh("broken.dae"),
                      extra='<visual name="v"><geometry>%s</geometry></visual>' % BOX))
    world = load_world(world_file(tmp_path, body))
    assert [s.name for s in world.model_shapes("m")] == ["m::l::v"]
    [message] = world.warnings
    assert "m::l::c left out: %s: " % (tmp_path / "broken.dae") in message
    assert "\n" not in message


def test_a_mesh_scaled_by_zero_is_left_out_with_one_warning(tmp_path):
    """A factor 0 leaves a mesh with no extent: Gazebo draws and hits nothing there."""
    (tmp_path / "meshes").mkdir()
    (tmp_path / "meshes" / "plate.stl").write_text(
        "solid p\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
        "vertex 0 1 0\nendloop\nendfacet\nendsolid p\n")
    geometry = "<mesh><uri>meshes/plate.stl</uri><scale>1 0 0</scale></mesh>"
    world = load_world(world_file(tmp_path, model(link(geometry=geometry))))
    assert world.models == ("m",) and world.model_shapes("m") == ()
    [message] = world.warnings
    assert "m::l::c left out: its <scale> 1 0 0 has a factor 0" in message
    assert len(message) <= 200
    assert "<scale>" in world_fault(world_file(
        tmp_path, model(link(geometry=geometry.replace("1 0 0", "1 nan 0")))))


def test_a_second_top_level_model_of_a_name_is_left_out_as_gazebo_leaves_it(tmp_path):
    """Gazebo 11's World::LoadModel inserts the first model of a name ("already exists"): a
    world that includes one model twice without a <name> has it once, where the first
    stands; so does one with two <model>s of a name."""
    (tmp_path / "models" / "goal").mkdir(parents=True)
    (tmp_path / "models" / "goal" / "model.sdf").write_text(
        '<sdf version="1.6">%s</sdf>' % model(link(), name="Goal", pose="0 0 0.5 0 0 0"))
    (tmp_path / "models" / "goal" / "model.config").write_text(
        '<model><name>goal</name><sdf version="1.6">model.sdf</sdf></model>')
    body = ('<include><pose>-4.5 0 0 0 0 3.1416</pose><uri>model://goal</uri></include>'
            '<include><pose>4.5 0 0 0 0 0</pose><uri>model://goal</uri></include>'
            + model(link(), name="wall", pose="0 2 0.5 0 0 0")
            + model(link(), name="wall", pose="0 -2 0.5 0 0 0")
            + '<include><uri>model://goal</uri><name>goal_2</name></include>')
    world = load_world(world_file(tmp_path, body))
    assert world.models == ("Goal", "wall", "goal_2")
    assert [s.name for s in world.shapes] == ["Goal::l::c", "wall::l::c", "goal_2::l::c"]
    assert world.shape("Goal::l::c").pose[0] == pytest.approx(-4.5)
    assert world.shape("wall::l::c").pose[1] == pytest.approx(2.0)
    first, second = world.warnings
    assert first.startswith(str(tmp_path / "test.world") + ":4: ")
    assert first.endswith('a second model named Goal is left out, as Gazebo leaves it out '
                          '("already exists")')
    assert "a second model named wall is left out" in second


def test_a_spawned_models_missing_mesh_is_a_warning_of_its_world(tmp_path):
    sdf = ('<sdf version="1.6"><model name="x"><static>true</static>%s</model></sdf>'
           % link(geometry=mesh("model://cafe_table/meshes/table.dae")))
    world = load_model_xml(sdf, "model_xml", "table")
    assert world.models == ("table",) and world.model_shapes("table") == ()
    [missing, searched] = world.warnings
    assert "model://cafe_table" in missing and searched.startswith("model:// searched ")


def test_the_world_runs_without_what_was_left_out(tmp_path):
    """Built in pybullet: a movable link whose only geometry was left out, a missing include,
    an unreadable Collada file; the rest stands."""
    (tmp_path / "broken.dae").write_text("not xml")
    body = ('<include><uri>model://ground_plane</uri></include>'
            '<include><uri>model://mailbox</uri></include>'
            + model(link("<mass>1</mass>", geometry=mesh("broken.dae")), static="false",
                    name="crate", pose="1 1 0.5 0 0 0")
            + model(link(), name="wall", pose="-2 0 0.5 0 0 0"))
    sim = Simulation(SimConfig(world=world_file(tmp_path, body), spawn_robot=False))
    try:
        assert len(sim.world.warnings) == 3       # the include, its search, the Collada file
        assert sim.world.models == ("ground_plane", "crate", "wall")
        for _ in range(50):
            sim.step()
    finally:
        sim.close()


# --- 5b. a world saved by Gazebo starts in its saved <state> ---------------------------------

STATE = ('<state world_name="w"><sim_time>116 345000000</sim_time>%s</state>')


def saved(name, pose):
    return ('<model name="%s"><pose frame="">%s</pose><scale>1 1 1</scale>'
            '<link name="l"><pose frame="">9 9 9 0 0 0</pose></link></model>' % (name, pose))


def test_the_saved_state_places_the_models_it_names(tmp_path):
    (tmp_path / "models" / "sign").mkdir(parents=True)
    (tmp_path / "models" / "sign" / "model.sdf").write_text(
        '<sdf version="1.6">%s</sdf>' % model(link(), name="sign", pose="0 0 0 0 0 0"))
    (tmp_path / "models" / "sign" / "model.config").write_text(
        '<model><name>sign</name><sdf version="1.6">model.sdf</sdf></model>')
    body = (model(link(), name="barrier", pose="5 5 0.5 0 0 0")
            + model(link(), name="wall", pose="-2 0 0.5 0 0 0")
            + '<include><uri>model://sign</uri><name>sign_2</name><pose>1 1 0 0 0 0</pose>'
              '</include>'
            + STATE % (saved("barrier", "1 -1.5 0.15 0 0 1.5") + saved("sign_2", "0 3 0 0 0 0")
                       + saved("unit_box", "7 7 7 0 0 0")))
    world = load_world(world_file(tmp_path, body))
    assert world.models == ("barrier", "wall", "sign_2")       # unit_box is not in the world
    assert world.model("barrier").pose == (1.0, -1.5, 0.15, 0.0, 0.0, 1.5)
    assert world.model("wall").pose == (-2.0, 0.0, 0.5, 0.0, 0.0, 0.0)   # not in the state
    assert world.model("sign_2").pose == (0.0, 3.0, 0.0, 0.0, 0.0, 0.0)
    box = world.model_shapes("barrier")[0]
    assert box.pose[:2] == pytest.approx((1.0, -1.5))           # the shapes moved with it
    assert world.warnings == ()


def test_two_collisions_of_one_name_in_a_link_both_collide(tmp_path):
    # a world Gazebo saved (mlherd's factory): the second keeps its place under another name
    second = ('<collision name="c"><pose>3 0 0 0 0 0</pose><geometry>%s</geometry></collision>'
              % BOX)
    world = load_world(world_file(tmp_path, model(link(extra=second))))
    assert [s.name for s in world.shapes if s.collision] == ["m::l::c", "m::l::c~2"]
    assert [s.pose[0] for s in world.shapes if s.collision] == [0.0, 3.0]
    assert len(world.warnings) == 1 and "the second is m::l::c~2 here" in world.warnings[0]
    sim = Simulation(SimConfig(world=world_file(tmp_path, model(link(extra=second))),
                               spawn_robot=False))
    try:
        hit = sim.physics.ray_distances(np.array([3.0, 0.0, 5.0]), np.array([[0.0, 0.0, -1.0]]),
                                        10.0)
        assert hit[0] == pytest.approx(4.0, abs=0.01)    # the second box's top at z 1
    finally:
        sim.close()


def test_a_saved_pose_fallen_out_of_the_world_leaves_the_model_where_it_was(tmp_path):
    # a pallet saved while falling, 3.3e6 m down: Gazebo loads it; here it keeps its own pose
    body = (model(link(), name="pallet", pose="7 -3 0.1 0 0 0")
            + STATE % saved("pallet", "7.4 -3.9 -3.29559e+06 -2.97 -0.84 0.11"))
    world = load_world(world_file(tmp_path, body))
    assert world.model("pallet").pose == (7.0, -3.0, 0.1, 0.0, 0.0, 0.0)
    assert len(world.warnings) == 1
    assert ("model 'pallet': its saved <state> pose is 3.29559e+06 m out, beyond the 1e+06 m"
            in world.warnings[0])


# --- 5c. the fixture worlds made as turtlebot3_gazebo's house and autorace worlds are -------

FIXTURES = unit_paths.FIXTURES


@pytest.mark.parametrize("name, models, left_out", [
    ("house_like", ("ground_plane", "house_like"),
     ["house_like::Mailbox::link::collision left out: model://mailbox/meshes/mailbox.dae",
      "house_like::cafe_table::link::visual left out: model://cafe_table/meshes/cafe_table.dae",
      "house_like::table_marble::link::collision left out: "
      "model:///table_marble/meshes/table_lightmap.dae",
      "house_like::table_marble::link::visual left out: "
      "model://table_marble/meshes/table_lightmap.dae"]),
    ("autorace_like", ("course", "traffic_stop", "tunnel_wall", "barrier"), []),
    ("autorace_2020_like", ("course", "traffic_stop", "traffic_stop_2", "tunnel_wall",
                            "tunnel_obstacle", "barrier_1", "barrier_2"), []),
])
def test_the_fixture_worlds_load_unmodified(monkeypatch, name, models, left_out):
    monkeypatch.setenv("GAZEBO_MODEL_PATH", os.path.join(FIXTURES, "gazebo_models"))
    world = load_world(os.path.join(FIXTURES, "worlds", name + ".world"))
    assert world.models == models
    searched = [w for w in world.warnings if w.startswith("model:// searched ")]
    left = [w for w in world.warnings if w not in searched]
    assert len(left) == len(left_out)     # one line for each thing left out
    for warning, start in zip(left, left_out):
        assert start in warning and "\n" not in warning and len(warning) <= 200
    assert len(searched) == (1 if left_out else 0)                # the folders searched once
    assert all("github.com/osrf/gazebo_models" in s for s in searched)   # where to get them
    if name != "house_like":   # the saved state moved the barrier 1 m ahead of the spawn
        barrier = "barrier" if name == "autorace_like" else "barrier_1"
        assert world.model(barrier).pose[:2] == (1.0, -1.5)
    else:                      # the bookshelf, nested in the static house, is static too
        assert world.model("house_like").static


# --- 6. real garbage is still refused ---------------------------------------------------------

def test_a_mesh_that_is_no_regular_file_is_still_refused(tmp_path):
    os.mkfifo(str(tmp_path / "pipe.dae"))
    message = world_fault(world_file(tmp_path, model(link(geometry=mesh("pipe.dae")))))
    assert "pipe.dae" in message and "FIFO" in message


def test_an_stl_that_cannot_be_read_is_still_refused(tmp_path):
    (tmp_path / "bad.stl").write_bytes(b"solid nothing\nendsolid\n")
    assert "bad.stl" in world_fault(world_file(tmp_path, model(link(geometry=mesh("bad.stl")))))


def test_malformed_world_xml_is_still_refused(tmp_path):
    path = tmp_path / "broken.world"
    path.write_text('<sdf version="1.6"><world name="w"><model name="m"></world></sdf>')
    assert "malformed XML" in world_fault(str(path))
