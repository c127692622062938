"""The SDF elements Gazebo 11 reads (sdf_elements): none refuses a world; what is not simulated is
one warning line per kind and world (at most 200 characters); doc/worlds.md's table says the
same as the code. No ROS master, no pybullet."""
import os
import re

import pytest

from tutorial_turtlebot.sim.files.meshes.mesh_file import cache_clear
from tutorial_turtlebot.sim.files.sdf.sdf_elements import (APPROXIMATED, MAX_WARNING_CHARS,
                                                           SIMULATED, SKIPPED, TABLE, one_line)
from tutorial_turtlebot.sim.files.sdf.world_catalogue import WORLD_DIR
from tutorial_turtlebot.sim.files.sdf.world_sdf import load_world

from unit_helpers import world_file
import unit_paths

BOX = '<geometry><box><size>1 1 1</size></box></geometry>'


@pytest.fixture(autouse=True)
def no_model_path(tmp_path, monkeypatch):
    monkeypatch.setenv("GAZEBO_MODEL_PATH", str(tmp_path / "models"))
    monkeypatch.chdir(tmp_path)
    cache_clear()


def model(body, name="m", static="true", link_extra="", geometry=BOX):
    return ('<model name="%s"><static>%s</static><link name="l">%s<collision name="c">%s'
            '</collision></link>%s</model>' % (name, static, link_extra, geometry, body))


# one of each kind Gazebo reads and this sim leaves out, as a world writes it
SKIPPED_KINDS = {
    "<plugin> skipped: world plugins": '<plugin name="p" filename="libp.so"/>',
    "<road> skipped": '<road name="r"><width>2</width><point>0 0 0</point>'
                      '<point>5 0 0</point></road>',
    "<population> skipped": '<population name="p"><model name="x"/><pose>0 0 0 0 0 0</pose>'
                            '<distribution><type>grid</type></distribution></population>',
    "<joint> skipped: a joint between world models":
        '<joint name="j" type="fixed"><parent>world</parent><child>m</child></joint>',
    "<sensor> of a link skipped": model("", link_extra='<sensor name="cam" type="sonar"/>'),
    "<projector> of a link skipped": model("", name="p2",
                                           link_extra='<projector name="pr"/>'),
    "<light> of a link skipped": model("", name="lamp", link_extra='<light name="bulb"/>'),
    "<heightmap> skipped": model("", name="hills", geometry='<geometry><heightmap>'
                                 '<uri>terrain.png</uri></heightmap></geometry>'),
    "<image> skipped": model("", name="maze", geometry='<geometry><image><uri>m.png</uri>'
                             '<height>1</height></image></geometry>'),
    "<plugin> of a model skipped": model('<plugin name="door" filename="libdoor.so"/>',
                                         name="door"),
    "<gripper> of a model skipped": model('<gripper name="g"/>', name="hand"),
    "<kinematic> of a link skipped": model("", name="k", static="false",
                                           link_extra="<kinematic>true</kinematic>"),
    "<gravity> of a link skipped": model("", name="g", static="false",
                                         link_extra="<gravity>0</gravity>"),
    "<velocity_decay> of a link skipped": model("", name="v", static="false",
                                                link_extra="<velocity_decay><linear>0.1"
                                                           "</linear></velocity_decay>"),
}


def test_each_kind_gazebo_reads_and_this_sim_leaves_out_is_one_warning(tmp_path):
    world = load_world(world_file(tmp_path, "\n".join(SKIPPED_KINDS.values())))
    assert len(world.warnings) == len(SKIPPED_KINDS)
    for words in SKIPPED_KINDS:
        [line] = [w for w in world.warnings if words in w]
        assert line.startswith(str(tmp_path / "test.world") + ":")
        assert len(line) <= MAX_WARNING_CHARS and "\n" not in line
    assert "hills" in world.models and world.model_shapes("hills") == ()   # left out
    assert world.model_shapes("part") == ()


def test_many_of_a_kind_are_one_warning_that_counts_them(tmp_path):
    sensors = "".join(model("", name="m%d" % i, link_extra='<sensor name="s" type="sonar"/>')
                      for i in range(5))
    world = load_world(world_file(tmp_path, sensors))
    [line] = world.warnings
    assert ":4: <sensor> of a link skipped: " in line and line.endswith("(and 4 more)")
    assert len(line) <= MAX_WARNING_CHARS


def test_what_is_simulated_or_approximated_loads_in_silence(tmp_path):
    """What every Gazebo-saved world has (physics, scene, gui, a default gravity, the
    magnetic field ...), and the default values of a link's physics flags."""
    body = '''<physics type="ode"><max_step_size>0.001</max_step_size></physics>
      <scene><shadows>true</shadows></scene><gui fullscreen="0"/><gravity>0 0 -9.8</gravity>
      <magnetic_field>6e-06 2.3e-05 -4.2e-05</magnetic_field><atmosphere type="adiabatic"/>
      <wind/><audio><device>default</device></audio><spherical_coordinates>
      <surface_model>EARTH_WGS84</surface_model></spherical_coordinates>
      <frame name="f"><pose>1 0 0 0 0 0</pose></frame>''' + model(
        '<joint name="j" type="fixed"><parent>l</parent><child>l</child></joint>'
        '<self_collide>0</self_collide><allow_auto_disable>1</allow_auto_disable>',
        link_extra='<gravity>1</gravity><kinematic>0</kinematic><self_collide>0</self_collide>')
    world = load_world(world_file(tmp_path, body))
    assert world.warnings == () and world.models == ("m",)


def test_a_static_models_physics_flags_need_no_warning(tmp_path):
    world = load_world(world_file(tmp_path, model("", link_extra="<gravity>0</gravity>"
                                                                 "<kinematic>1</kinematic>")))
    assert world.warnings == ()


@pytest.mark.parametrize("path", sorted(
    os.path.join(WORLD_DIR, f) for f in os.listdir(WORLD_DIR) if f.endswith(".world")),
    ids=os.path.basename)
def test_the_shipped_worlds_load_without_a_warning(path):
    assert load_world(path).warnings == ()


def test_a_long_path_is_cut_to_its_file_name_in_a_warning():
    line = one_line("/" + "deep/" * 60 + "w.world", 7, "<road> skipped: roads are not drawn")
    assert line == "w.world:7: <road> skipped: roads are not drawn"
    assert len(one_line("w.world", 1, "x" * 300)) == MAX_WARNING_CHARS


# --- doc/worlds.md's table is the code's ------------------------------------------------------

def doc_rows():
    """{(parent, element): mark} of the element table in doc/worlds.md."""
    with open(os.path.join(unit_paths.ROOT, "doc", "worlds.md"), encoding="utf-8") as f:
        text = f.read()
    rows = {}
    for match in re.finditer(r"^\| `<(\w+)>` in `<(\w+)>` \| (\w+)", text, re.M):
        rows[(match.group(2), match.group(1))] = match.group(3)
    return rows


def test_doc_worlds_md_marks_every_element_as_the_loader_does():
    rows = doc_rows()
    expected = {(parent, tag): rule.mark for parent, children in TABLE.items()
                for tag, rule in children.items()}
    assert rows == expected
    assert set(rows.values()) <= {SIMULATED, APPROXIMATED, SKIPPED}
