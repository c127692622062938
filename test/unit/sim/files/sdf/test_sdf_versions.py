"""Old SDF files read as Gazebo 11 reads them (sdf_versions: libsdformat 9's conversions to SDF
1.7; a <gazebo version="1.0"> file as libsdformat 6 read it, with one warning), and two of
Gazebo's tolerances: a box side of 0 and a negative <mu>. The fixtures in test/fixtures/old_sdf/
are our own; each was refused before. No ROS master; two tests step pybullet."""
import math
import os

import pytest

from tutorial_turtlebot.errors import WorldError
from tutorial_turtlebot.sim.files import limits, xml_reader
from tutorial_turtlebot.sim.files.meshes.mesh_file import cache_clear
from tutorial_turtlebot.sim.files.sdf.sdf_versions import upgraded, version_warnings
from tutorial_turtlebot.sim.files.sdf.world_sdf import load_model_xml, load_world
from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
from tutorial_turtlebot.sim.world.world_control import WorldControl

from unit_helpers import world_fault, world_file
import unit_paths

OLD = os.path.join(unit_paths.FIXTURES, "old_sdf")


@pytest.fixture(autouse=True)
def no_model_path(tmp_path, monkeypatch):
    monkeypatch.setenv("GAZEBO_MODEL_PATH", str(tmp_path / "models"))
    monkeypatch.chdir(tmp_path)
    cache_clear()


def close(a, b, tol=1e-9):
    return len(a) == len(b) and all(abs(x - y) <= tol for x, y in zip(a, b))


def upgrade(text):
    return upgraded(xml_reader.parse(text, "t.sdf"), "t.sdf")


# --- 1. the fixtures: each loads, with the shapes, sizes and friction it writes ----------------

def test_a_gazebo_1_0_world_loads_converted_with_one_warning():
    """Refused before ("the root element is <gazebo>"); Gazebo 9 read it, Gazebo 11 does not."""
    world = load_world(os.path.join(OLD, "gazebo_1_0.world"))
    assert world.name == "old_crates" and world.models == ("floor", "crate", "ball")
    [warning] = world.warnings
    assert warning.startswith("gazebo_1_0.world:6: ") and "Gazebo 11 refuses" in warning
    crate = world.model("crate")
    assert crate.pose == (1.0, 2.0, 0.25, 0.0, 0.0, 0.5) and not crate.static
    inertial = crate.links[0].inertial
    assert inertial.mass == 2.5 and inertial.pose[2] == 0.01
    assert inertial.inertia == (0.05, 0.06, 0.07, 0.0, 0.0, 0.0)
    shell = world.shape("crate::body::shell")
    assert shell.kind == "box" and shell.size == (0.5, 0.4, 0.5) and shell.mu == 0.3
    assert shell.rgba == (0.2, 0.4, 0.8, 1.0)          # its visual twin's <diffuse rgba>
    knob = world.shape("crate::body::knob")
    assert knob.size == (0.03, 0.1) and not knob.collision
    assert world.shape("floor::plane::plane").mu == 0.8 and world.model("floor").static
    assert close(world.shape("ball::ball::ball").pose[:3], (-1.0, 0.0, 0.2))
    [lamp] = world.lights
    assert lamp.pose[0] == (0.0, 0.0, 10.0) and lamp.diffuse == (0.9, 0.8, 0.7, 1.0)
    assert lamp.direction == (0.2, 0.1, -1.0) and lamp.cast_shadows is False


def test_an_sdf_1_3_mesh_named_in_filename_is_left_out_as_gazebo_11_leaves_it():
    """Refused before ("<mesh> needs a <uri>"): Gazebo 11 says "No mesh specified" and loads
    the link without it; the same file named in <uri> loads."""
    world = load_world(os.path.join(OLD, "sdf_1_3_filename.world"))
    names = [s.name for s in world.shapes]
    assert names == ["pillars::by_filename::base", "pillars::by_uri::pillar"]
    pillar = world.shape("pillars::by_uri::pillar")
    assert pillar.mesh.endswith(os.path.join("mesh_pillar", "meshes", "pillar.stl"))
    assert pillar.size == (1.0, 1.0, 2.0)
    [warning] = world.warnings
    assert ":18: <mesh> skipped:" in warning and "<filename>" in warning
    assert warning.endswith("(and 1 more)")


def test_box_sides_of_zero_are_built_0_1_mm_with_one_warning_and_hold_a_crate():
    """Refused before ("<size> 0 must be positive"); Gazebo's ODE builds them. A crate dropped
    on the panel of side 0 rests on it."""
    path = os.path.join(OLD, "zero_box.world")
    world = load_world(path)
    side = limits.MIN_BOX_SIDE
    assert world.shape("panel::link::collision").size == (6.0, 6.0, side)
    assert world.shape("panel::link::visual").size == (6.0, 6.0, side)
    assert world.shape("marker::link::collision").size == (side, side, side)
    [warning] = world.warnings                    # two boxes of a side 0: said once per file
    assert ":15: <size> 6 6 0: a <box> side of 0 is built 0.1 mm thick" in warning
    sim = Simulation(SimConfig(world=path, spawn_robot=False))
    try:
        for _ in range(400):
            sim.step()
        (x, y, z), _ = WorldControl(sim).get_model_state("crate")[0]
        assert abs(z - 0.15) < 0.005 and math.hypot(x, y) < 0.01
    finally:
        sim.close()


def test_a_negative_mu_is_friction_that_never_gives_in_silence():
    """Refused before ("<mu> -1 is outside [0, 1e+06]"). Gazebo takes it as FLT_MAX; on a 60
    degree slope the slab of mu -1 stays, the one of mu 1 slides."""
    path = os.path.join(OLD, "negative_mu.world")
    world = load_world(path)
    assert world.warnings == ()
    assert world.shape("grippy::link::collision").mu == limits.NO_SLIP_FRICTION
    assert world.shape("slippery::link::collision").mu == 1.0
    sim = Simulation(SimConfig(world=path, spawn_robot=False))
    try:
        wc = WorldControl(sim)
        start = {name: wc.get_model_state(name)[0][0] for name in ("grippy", "slippery")}
        for _ in range(400):                      # 1 s
            sim.step()
        moved = {name: math.dist(start[name], wc.get_model_state(name)[0][0])
                 for name in start}
        assert moved["grippy"] < 0.02 and moved["slippery"] > 0.5, moved
    finally:
        sim.close()


# --- 2. versions, in worlds and spawned models -----------------------------------------------

BOX = ('<model name="m"><static>true</static><link name="l"><collision name="c"><geometry>'
       '%s</geometry>%s</collision></link></model>')


def box(size="1 1 1", surface=""):
    return BOX % ("<box><size>%s</size></box>" % size, surface)


@pytest.mark.parametrize("version", ["1.2", "1.3", "1.4", "1.5", "1.6", "1.7"])
def test_the_versions_gazebo_11_converts_load_in_silence(tmp_path, version):
    world = load_world(world_file(tmp_path, box(), version=version))
    assert world.warnings == () and world.shape("m::l::c").size == (1.0, 1.0, 1.0)


@pytest.mark.parametrize("version", ["1.8", "2.0", "1.0", "1.6.0"])
def test_a_version_gazebo_11_does_not_convert_is_read_as_it_stands_with_one_warning(
        tmp_path, version):
    world = load_world(world_file(tmp_path, box(), version=version))
    [warning] = world.warnings
    assert "test.world:2: <sdf version=\"%s\">: " % version in warning
    assert 'Unable to convert from SDF version %s to 1.7' % version in warning
    assert world.shape("m::l::c").size == (1.0, 1.0, 1.0)


def test_an_sdf_1_0_root_is_not_converted_as_libsdformat_9_converts_none(tmp_path):
    """<sdf version="1.0"> is no file Gazebo 1.x wrote: Gazebo 11 reads its elements alone, so
    an <origin pose> places nothing."""
    body = ('<model name="m"><origin pose="5 0 0 0 0 0"/><link name="l"><collision name="c">'
            '<geometry><sphere><radius>0.5</radius></sphere></geometry></collision></link>'
            '</model>')
    world = load_world(world_file(tmp_path, body, version="1.0"))
    assert world.model("m").pose == (0.0,) * 6 and len(world.warnings) == 1


def test_a_gazebo_root_without_a_version_stays_refused(tmp_path):
    path = tmp_path / "old.world"
    path.write_text('<gazebo>\n<world name="w"/>\n</gazebo>\n')
    assert "the root element is <gazebo>" in world_fault(str(path))


def test_an_included_gazebo_1_0_model_is_converted_and_named_in_its_warning(tmp_path):
    folder = tmp_path / "models" / "old_box"
    folder.mkdir(parents=True)
    (folder / "model.config").write_text('<model><sdf version="1.0">model.sdf</sdf></model>')
    (folder / "model.sdf").write_text(
        '<gazebo version="1.0">\n<model name="old_box" static="true">\n'
        '<origin pose="0 0 0.5 0 0 0"/><link name="l"><collision name="c"><geometry>'
        '<box size="1 2 1"/></geometry></collision></link></model></gazebo>\n')
    world = load_world(world_file(tmp_path, '<include><uri>model://old_box</uri></include>'))
    assert world.shape("old_box::l::c").size == (1.0, 2.0, 1.0)
    assert world.model("old_box").pose[2] == 0.5 and world.model("old_box").static
    [warning] = world.warnings
    assert "model.sdf:1: <gazebo version=\"1.0\">" in warning


def test_a_spawned_gazebo_1_0_model_is_converted_with_its_warning():
    world = load_model_xml('<gazebo version="1.0"><model name="x"><link name="l">'
                           '<collision name="c"><geometry><cylinder radius="0.2" length="2"/>'
                           '</geometry><surface><friction><ode mu="-1"/></friction></surface>'
                           '</collision></link></model></gazebo>', "model_xml", "thing")
    shape = world.shape("thing::l::c")
    assert shape.size == (0.2, 2.0) and shape.mu == limits.NO_SLIP_FRICTION
    assert [w[:28] for w in world.warnings] == ['model_xml:1: <gazebo version']


@pytest.mark.parametrize("gravity", ["0 0 -9.8", "0 0 -1.6"])
def test_an_sdf_1_5_physics_gravity_is_the_worlds_as_in_gazebo_11(tmp_path, gravity):
    """1.5 -> 1.6 moves <physics><gravity> to the world, which applies it, without a word."""
    body = "<physics type='ode'><gravity>%s</gravity></physics>%s" % (gravity, box())
    world = load_world(world_file(tmp_path, body, version="1.5"))
    assert world.gravity == tuple(float(v) for v in gravity.split())
    assert not [w for w in world.warnings if "gravity" in w]


# --- 3. the two tolerances' edges ------------------------------------------------------------

@pytest.mark.parametrize("mu, expected", [("-1", limits.NO_SLIP_FRICTION),
                                          ("-inf", limits.NO_SLIP_FRICTION), ("0", 0.0),
                                          ("0.4", 0.4)])
def test_mu_below_zero_is_the_highest_friction(tmp_path, mu, expected):
    surface = "<surface><friction><ode><mu>%s</mu><mu2>-1</mu2></ode></friction></surface>"
    world = load_world(world_file(tmp_path, box(surface=surface % mu)))
    assert world.shape("m::l::c").mu == expected and world.warnings == ()


@pytest.mark.parametrize("mu, words", [("nan", "<mu> nan is outside"),
                                       ("1e7", "<mu> 1e+07 is outside [0, 1e+06]")])
def test_mu_nan_or_beyond_the_bound_stays_refused(tmp_path, mu, words):
    surface = "<surface><friction><ode><mu>%s</mu></ode></friction></surface>" % mu
    assert words in world_fault(world_file(tmp_path, box(surface=surface)))


@pytest.mark.parametrize("size, words", [("-1 1 0", "<size> -1 must be positive"),
                                         ("nan 0 1", "<size> nan must be positive"),
                                         ("1e5 0 1", "<size> 100000 must be positive")])
def test_a_box_side_below_zero_nan_or_too_large_stays_refused(tmp_path, size, words):
    assert words in world_fault(world_file(tmp_path, box(size)))


# --- 4. the conversions, on the parsed tree ---------------------------------------------------

def test_1_0_attributes_and_origins_become_elements_on_their_lines():
    root = upgrade('<gazebo version="1.0"><model name="m" static="1">\n'
                   '<origin pose="1 2 3 0 0 0"/><link name="l" gravity="false">'
                   '<damping>0.5</damping></link>\n'
                   '<joint name="j" type="revolute"><parent link="world"/><child link="l"/>'
                   '<axis xyz="0 1 0"><limit lower="-1" upper="1"/></axis></joint>'
                   '</model></gazebo>')
    assert root.tag == "sdf" and root.get("version") == "1.0"     # sdf_joints reads it
    model = root.child("model")
    assert model.attrib == {"name": "m"} and model.child("static").value == "1"
    assert model.child("pose").value == "1 2 3 0 0 0" and model.child("pose").line == 2
    assert model.child("origin") is None
    link = model.child("link")
    assert link.child("gravity").value == "false"
    assert link.child("velocity_decay").value == "0.5"            # a model file's link only
    joint = model.child("joint")
    assert (joint.child("parent").value, joint.child("child").value) == ("world", "l")
    axis = joint.child("axis")
    assert axis.child("xyz").value == "0 1 0" and axis.child("xyz").get("expressed_in") == \
        "__model__" and axis.child("use_parent_model_frame") is None
    assert axis.child("limit").child("lower").value == "-1" and joint.line == 3
    [warning] = version_warnings(root)
    assert warning.startswith("t.sdf:1: ")


def test_1_3_physics_values_move_as_libsdformat_moves_them():
    root = upgrade('<sdf version="1.3"><world name="w"><physics type="ode">'
                   '<update_rate>500</update_rate><gravity>0 0 -3</gravity>'
                   '<magnetic_field>1 0 0</magnetic_field><ode><solver><dt>0.002</dt>'
                   '</solver></ode></physics></world></sdf>')
    world = root.child("world")
    physics = world.child("physics")
    assert physics.child("real_time_update_rate").value == "500"
    assert physics.child("max_step_size").value == "0.002"
    assert physics.child("ode").child("solver").child("dt") is None
    assert world.child("gravity").value == "0 0 -3" and physics.child("gravity") is None
    assert world.child("magnetic_field").value == "1 0 0"
    assert version_warnings(root) == ()


def test_1_4_axes_are_in_the_model_frame_where_libsdformat_puts_them():
    """use_parent_model_frame is added to a world model's and a model file's joints only (not
    a nested model's), then 1.7's expressed_in replaces it."""
    joint = ('<joint name="%s" type="revolute"><parent>a</parent><child>b</child>'
             '<axis><xyz>1 0 0</xyz></axis></joint>')
    root = upgrade('<sdf version="1.4"><world name="w"><model name="m">%s<model name="n">%s'
                   '</model></model></world></sdf>' % (joint % "top", joint % "inner"))
    model = root.child("world").child("model")
    top = model.child("joint").child("axis")
    inner = model.child("model").child("joint").child("axis")
    assert top.child("xyz").get("expressed_in") == "__model__"
    assert inner.child("xyz").get("expressed_in") is None
    assert top.child("use_parent_model_frame") is None


@pytest.mark.parametrize("flag, expressed_in", [("true", "__model__"), ("1", "__model__"),
                                                ("false", None)])
def test_1_6_frames_and_model_frame_axes_become_1_7s(flag, expressed_in):
    root = upgrade('<sdf version="1.6"><model name="m"><link name="l"><pose frame="m">1 0 0 0 0'
                   ' 0</pose></link><plugin name="p" filename="p.so"><pose frame="x"/>'
                   '</plugin><joint name="j" type="revolute"><axis><use_parent_model_frame>%s'
                   '</use_parent_model_frame></axis></joint></model></sdf>' % flag)
    model = root.child("model")
    assert model.child("link").child("pose").attrib == {"relative_to": "m"}
    assert model.child("plugin").child("pose").attrib == {"frame": "x"}   # plugins untouched
    axis = model.child("joint").child("axis")
    assert axis.child("use_parent_model_frame") is None
    xyz = axis.child("xyz")
    assert (xyz.get("expressed_in") if xyz is not None else None) == expressed_in


def test_1_5_imu_noise_is_copied_to_each_axis():
    root = upgrade('<sdf version="1.5"><model name="m"><link name="l"><sensor name="s" '
                   'type="imu"><imu><noise><type>gaussian</type><rate><mean>0.1</mean>'
                   '<stddev>0.2</stddev></rate><accel><stddev>0.3</stddev></accel></noise>'
                   '</imu></sensor></link></model></sdf>')
    imu = root.child("model").child("link").child("sensor").child("imu")
    assert imu.child("noise") is None
    for axis in "xyz":
        rate = imu.child("angular_velocity").child(axis).child("noise")
        accel = imu.child("linear_acceleration").child(axis).child("noise")
        assert rate.get("type") == "gaussian" and accel.get("type") == "gaussian"
        assert (rate.child("mean").value, rate.child("stddev").value) == ("0.1", "0.2")
        assert accel.child("stddev").value == "0.3" and accel.child("mean") is None


def test_a_tree_is_converted_once():
    """A second upgrade (the passes of load_world share one tree) adds nothing: the 1.5 step
    adds an IMU's groups whatever it holds."""
    root = upgrade('<sdf version="1.5"><model name="m"><link name="l"><sensor name="s" '
                   'type="imu"><imu/></sensor></link></model></sdf>')
    assert upgraded(root, "t.sdf") is root
    imu = root.child("model").child("link").child("sensor").child("imu")
    assert [c.tag for c in imu] == ["angular_velocity", "linear_acceleration"]


def test_an_unconverted_zero_box_in_a_1_0_file_is_refused_nowhere():
    """Both tolerances and the 1.0 conversion together: <box size="2 2 0"/>, <ode mu="-1"/>."""
    world = load_model_xml('<gazebo version="1.0"><model name="x" static="true"><link name="l">'
                           '<collision name="c"><geometry><box size="2 2 0"/></geometry>'
                           '<surface><friction><ode mu="-1"/></friction></surface></collision>'
                           '</link></model></gazebo>', "model_xml", "panel")
    shape = world.shape("panel::l::c")
    assert shape.size == (2.0, 2.0, limits.MIN_BOX_SIDE)
    assert shape.mu == limits.NO_SLIP_FRICTION and len(world.warnings) == 2
    with pytest.raises(WorldError):
        load_model_xml('<gazebo version="1.0"><model name="x"><link name="l"><collision '
                       'name="c"><geometry><box size="-2 2 0"/></geometry></collision></link>'
                       '</model></gazebo>', "model_xml", "panel")
