"""URDFs with mesh visuals and collisions (sim/urdf_file, sim/urdf_meshes, spawning): reading
``package://``, ``file://`` and relative mesh filenames, the URDF pybullet loads, robots and
plain models built from them, each error as one line. No ROS master."""
import os
import subprocess
import sys
import tempfile
from xml.etree import ElementTree

import numpy as np
import pybullet
import pytest

from tutorial_turtlebot.errors import RequestError, UserError
from tutorial_turtlebot.sim.files.urdf import urdf_meshes
from tutorial_turtlebot.sim.files.meshes.mesh_file import load_mesh
from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
from tutorial_turtlebot.sim.files.urdf.urdf_file import read_urdf, read_urdf_text, urdf_path
from tutorial_turtlebot.sim.world.world_control import WorldControl

from unit_helpers import run, write
import unit_paths

HERE = unit_paths.UNIT
FIXTURES = os.path.normpath(os.path.join(HERE, os.pardir, "fixtures"))
DESCRIPTION = os.path.join(FIXTURES, "turtlebot3_description")
MESHES = os.path.join(DESCRIPTION, "meshes")
PKG = "package://turtlebot3_description/meshes/"
sys.path.insert(0, MESHES)
import make_meshes  # noqa: E402  (the fixture's STL writer)


@pytest.fixture(autouse=True)
def fixture_package(monkeypatch):
    """turtlebot3_description (the fixture) on ROS_PACKAGE_PATH, as the rostests put it."""
    monkeypatch.setenv("ROS_PACKAGE_PATH", FIXTURES + ":" + os.environ.get("ROS_PACKAGE_PATH", ""))


def crate_stl(folder, name="crate.stl", half=100.0):
    """A cube 2 * half mm across, centred on its origin."""
    path = os.path.join(str(folder), name)
    make_meshes.write_stl(path, make_meshes.box((-half,) * 3, (half,) * 3), name)
    return path


ONE_LINK = """<?xml version="1.0"?>
<robot name="thing">
  <material name="red"><color rgba="0.8 0.1 0.1 1"/></material>
  <link name="body">
    <inertial><mass value="2.0"/>
      <inertia ixx="0.0133" ixy="0" ixz="0" iyy="0.0133" iyz="0" izz="0.0133"/></inertial>
    <visual>
      <geometry><mesh filename="%(visual)s" scale="%(scale)s"/></geometry>%(material)s
    </visual>
    <collision>
      <geometry><mesh filename="%(collision)s" scale="%(scale)s"/></geometry>
    </collision>
  </link>
</robot>
"""


def one_link(visual, collision=None, scale="0.001 0.001 0.001", material=""):
    return ONE_LINK % {"visual": visual, "collision": collision or visual, "scale": scale,
                       "material": material}


def mesh_burger():
    """The shipped Burger URDF with the fixture's mesh visuals (the real file's) and a mesh
    collision for its laser housing, in place of the primitive shapes."""
    with open(urdf_path("burger")) as f:
        robot = ElementTree.fromstring(f.read())
    links = {link.get("name"): link for link in robot.findall("link")}
    meshes = {"base_link": ("bases/burger_base.stl", "-0.032 0 0.0", "0 0 0"),
              "wheel_left_link": ("wheels/left_tire.stl", "0 0 0", "1.57 0 0"),
              "wheel_right_link": ("wheels/right_tire.stl", "0 0 0", "1.57 0 0"),
              "base_scan": ("sensors/lds.stl", "0 0 0", "0 0 0")}
    for name, (mesh, xyz, rpy) in meshes.items():
        visual = links[name].find("visual")
        visual.find("origin").attrib.update(xyz=xyz, rpy=rpy)
        geometry = visual.find("geometry")
        geometry.remove(geometry[0])
        ElementTree.SubElement(geometry, "mesh", filename=PKG + mesh, scale="0.001 0.001 0.001")
    collision = links["base_scan"].find("collision")
    collision.find("origin").attrib.update(xyz="0 0 0")
    geometry = collision.find("geometry")
    geometry.remove(geometry[0])
    ElementTree.SubElement(geometry, "mesh", filename=PKG + "sensors/lds.stl",
                           scale="0.001 0.001 0.001")
    return ElementTree.tostring(robot, encoding="unicode")


# --- reading -------------------------------------------------------------------------------------

def test_package_file_and_relative_mesh_filenames_are_found_on_reading(tmp_path):
    crate_stl(tmp_path)
    os.mkdir(tmp_path / "urdf")
    text = one_link(PKG + "bases/burger_base.stl", "../crate.stl")
    robot = read_urdf(write(tmp_path / "urdf", "r.urdf", text))
    visual = robot.links["body"].visuals[0].geometry
    collision = robot.links["body"].collisions[0].geometry
    assert visual.shape == "mesh" and visual.size == (0.001, 0.001, 0.001)
    assert visual.filename == os.path.join(MESHES, "bases", "burger_base.stl")
    assert visual.uri == PKG + "bases/burger_base.stl"
    assert collision.filename == str(tmp_path / "crate.stl") and collision.uri == "../crate.stl"
    uri = "file://" + str(tmp_path / "crate.stl")
    text = one_link(uri, scale="1 1 1")
    from_text = read_urdf_text(text, "model_xml of x").links["body"].visuals[0].geometry
    assert (from_text.filename, from_text.uri, from_text.size) == (str(tmp_path / "crate.stl"),
                                                                   uri, (1.0, 1.0, 1.0))


def test_a_relative_mesh_of_a_urdf_given_as_text_is_taken_from_the_working_directory(
        tmp_path, monkeypatch):
    crate_stl(tmp_path)
    monkeypatch.chdir(tmp_path)
    geometry = read_urdf_text(one_link("crate.stl"), "x").links["body"].visuals[0].geometry
    assert geometry.filename == str(tmp_path / "crate.stl")
    other = tmp_path / "elsewhere"
    other.mkdir()
    geometry = read_urdf_text(one_link("../crate.stl"), "x", base_dir=str(other)).links[
        "body"].visuals[0].geometry
    assert geometry.filename == str(tmp_path / "crate.stl")


@pytest.mark.parametrize("visual, words", [
    ("meshes/missing.stl", "meshes/missing.stl not found"),
    ("package://no_such_package/m.stl", "no ROS package 'no_such_package'"),
    (PKG + "bases/nothing.stl", "bases/nothing.stl not found"),
])
def test_a_mesh_found_nowhere_is_left_out_with_one_line(tmp_path, visual, words):
    """The visual whose file is found nowhere is left out, with one warning line naming the
    file, its line and link (and one naming the folders searched); the collision stays."""
    path = write(tmp_path, "missing.urdf", one_link(visual, PKG + "bases/burger_base.stl"))
    robot = read_urdf(path)
    link = robot.links["body"]
    assert link.visuals == () and len(link.collisions) == 1
    assert robot.root.find("link/visual") is None and robot.root.find("link/collision") \
        is not None
    first = robot.warnings[0]              # the file named by its base name if too long
    source, _, rest = first.partition(":8: ")
    assert source in (path, "missing.urdf") and rest.startswith("link 'body' <visual> left "
                                                                "out: "), first
    assert words in first and all("\n" not in w for w in robot.warnings)
    assert len(robot.warnings) <= 2


@pytest.mark.parametrize("visual, scale, words", [
    (PKG + "bases/burger_base.stl", "0.001 0.001", "scale='0.001 0.001' is not three"),
    (PKG + "bases/burger_base.stl", "0 0.001 0.001", "scale='0 0.001 0.001' is not three"),
    (PKG + "bases/burger_base.stl", "a b c", "scale='a b c' is not three"),
    ("package://turtlebot3_description/package.xml", "1 1 1", "unknown mesh format '.xml'"),
    (PKG + "bases", "1 1 1", "bases: it is a directory, not a regular file (a mesh file is "
                             "needed)"),
])
def test_each_mesh_error_is_one_line_naming_file_line_and_link(tmp_path, visual, scale, words):
    path = write(tmp_path, "bad.urdf", one_link(visual, PKG + "bases/burger_base.stl", scale))
    with pytest.raises(UserError) as err:
        read_urdf(path)
    text = str(err.value)
    line = 11 if "scale" in words else 8          # the collision is read first
    assert text.startswith("%s:%d: link 'body' <mesh>: " % (path, line)), text
    assert words in text and "\n" not in text


def test_the_fixture_xacro_files_expand_to_the_shipped_robots_with_meshes(tmp_path):
    """xacro (ROS 1's, from the venv) expands the fixture package's .urdf.xacro files; each
    has the shipped URDF's links, joints, inertials and plugins (the IMU at updateRate 0, as
    turtlebot3_description has it), with mesh visuals found through package://."""
    pytest.importorskip("xacro")
    for model in ("burger", "waffle", "waffle_pi"):
        source = os.path.join(DESCRIPTION, "urdf", "turtlebot3_%s.urdf.xacro" % model)
        out = subprocess.run([sys.executable, "-c", "import xacro; xacro.main()", source],
                             capture_output=True, text=True, env=dict(os.environ), check=True)
        robot = read_urdf(write(tmp_path, model + ".urdf", out.stdout))
        shipped = read_urdf(urdf_path(model))
        assert robot.name == shipped.name and robot.joints == shipped.joints
        assert list(robot.links) == list(shipped.links)
        assert all(robot.links[n].inertial == shipped.links[n].inertial for n in robot.links)
        assert robot.plugins.drive == shipped.plugins.drive
        assert robot.plugins.laser == shipped.plugins.laser
        assert robot.plugins.camera == shipped.plugins.camera
        assert robot.plugins.imu.update_rate == 0.0
        meshes = {v.geometry.uri for link in robot.links.values() for v in link.visuals}
        assert PKG + "wheels/left_tire.stl" in meshes and PKG + "sensors/lds.stl" in meshes
        assert (PKG + "sensors/r200.dae" in meshes) == (model == "waffle")


# --- the URDF pybullet loads ------------------------------------------------------------------

def test_mesh_visuals_become_obj_parts_in_their_colours_and_collisions_convex_hulls(tmp_path):
    urdf_meshes.cache_clear()
    text = """<robot name="r"><material name="dark"><color rgba="0.3 0.3 0.3 1"/></material>
      <link name="cam">
        <visual name="v"><geometry><mesh filename="%(r200)s"/></geometry></visual>
        <visual><geometry><mesh filename="%(r200)s"/></geometry><material name="dark"/></visual>
        <collision><geometry><mesh filename="%(lds)s" scale="0.001 0.001 0.001"/></geometry>
        </collision>
        <visual><geometry><box size="1 1 1"/></geometry></visual>
      </link></robot>""" % {"r200": PKG + "sensors/r200.dae", "lds": PKG + "sensors/lds.stl"}
    robot = ElementTree.fromstring(text)
    urdf_meshes.bullet_meshes(robot, str(tmp_path))
    visuals = robot.find("link").findall("visual")
    assert len(visuals) == 5                       # 2 parts + 2 parts + the box
    assert [v.get("name") for v in visuals[:2]] == ["v_part0", "v_part1"]
    own = [v.find("material/color").get("rgba") for v in visuals[:2]]
    assert own == ["0.2 0.2 0.2 1", "0.75 0.75 0.8 1"]           # the Collada file's colours
    assert [v.find("material").get("name") for v in visuals[2:4]] == ["dark", "dark"]
    assert visuals[2].find("material/color") is None              # the URDF's overrides
    assert visuals[4].find("geometry/box") is not None
    for visual in visuals[:4]:
        mesh = visual.find("geometry/mesh")
        assert os.path.isfile(mesh.get("filename")) and mesh.get("filename").endswith(".obj")
        assert "scale" not in mesh.attrib                        # the file is in metres
    r200 = load_mesh(os.path.join(MESHES, "sensors", "r200.dae"))
    lo, hi = r200.bounds                                           # Collada's unit: mm
    assert hi - lo == pytest.approx((0.132, 0.020, 0.012))
    hull = robot.find("link/collision/geometry/mesh")
    vertices = [line for line in open(hull.get("filename")) if line.startswith("v ")]
    assert len(vertices) == 64                     # the 32-sided cylinder's corners only
    points = np.array([[float(x) for x in line.split()[1:]] for line in vertices])
    assert np.ptp(points, axis=0) == pytest.approx((0.11, 0.11, 0.0315), abs=1e-3)


def test_converted_files_are_made_once_per_process(tmp_path):
    urdf_meshes.cache_clear()
    first = urdf_meshes.visual_parts(os.path.join(MESHES, "bases", "burger_base.stl"),
                                     (0.001,) * 3)
    again = urdf_meshes.visual_parts(os.path.join(MESHES, "bases", "burger_base.stl"),
                                     (0.001,) * 3)
    other = urdf_meshes.visual_parts(os.path.join(MESHES, "bases", "burger_base.stl"),
                                     (0.002,) * 3)
    assert first == again and first != other
    folder = os.path.dirname(first[0][0])
    assert os.path.basename(folder).startswith("tutorial_turtlebot_urdf_meshes_%d_" % os.getpid())
    urdf_meshes.cache_clear()
    assert not os.path.exists(folder)


def test_folders_of_dead_processes_are_swept(tmp_path, monkeypatch):
    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path))
    urdf_meshes.cache_clear()
    dead = subprocess.Popen([sys.executable, "-c", "pass"])
    dead.wait()
    stale = tmp_path / ("tutorial_turtlebot_urdf_meshes_%d_abc" % dead.pid)
    stale.mkdir()
    (stale / "x.obj").write_text("v 0 0 0\n")
    alive = tmp_path / ("tutorial_turtlebot_urdf_meshes_%d_abc" % os.getppid())
    alive.mkdir()
    urdf_meshes.hull_file(os.path.join(MESHES, "wheels", "left_tire.stl"))
    assert not stale.exists() and alive.exists()
    urdf_meshes.cache_clear()


# --- bodies in the simulation -----------------------------------------------------------------

@pytest.fixture(scope="module")
def sims():
    """An empty world without a robot, and one with the shipped (primitive) Burger."""
    empty = Simulation(SimConfig(world="empty", spawn_robot=False))
    burger = Simulation(SimConfig(world="empty", model="burger"))
    yield empty, burger
    empty.close()
    burger.close()


def dynamics(sim, body):
    cid = sim.physics.client
    return [pybullet.getDynamicsInfo(body, j, physicsClientId=cid)[:3]
            for j in range(-1, pybullet.getNumJoints(body, physicsClientId=cid))]


def test_a_mesh_robot_weighs_what_its_inertials_say_and_drives(sims, tmp_path, monkeypatch):
    """The Burger with mesh visuals and a mesh laser housing: the same masses, inertias and
    centre of mass as the shipped primitive Burger; it stands on its wheels and drives; the
    temporary URDF is gone after the spawn, the converted meshes are in the cache folder."""
    empty, burger = sims
    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path))
    urdf_meshes.cache_clear()
    wc = WorldControl(empty)
    wc.spawn("meshy", mesh_burger(), ((0.0, 3.0, 0.0), (0, 0, 0, 1)), kind="urdf",
             robot_namespace="meshy")
    robot = empty.robots["meshy"]
    assert dynamics(empty, robot.body.robot) == pytest.approx(
        dynamics(burger, burger.robot.body.robot), rel=1e-6)
    assert robot.body._com_in_footprint[0] == pytest.approx(
        burger.robot.body._com_in_footprint[0], abs=1e-6)
    left = [p for p in os.listdir(tmp_path)]
    assert len(left) == 1 and left[0].startswith("tutorial_turtlebot_urdf_meshes_"), left
    files = sorted(os.listdir(tmp_path / left[0]))
    assert len(files) == 5          # 4 visual meshes (one colour each) and 1 hull
    wc.spawn("meshy2", mesh_burger(), ((0.0, 4.0, 0.0), (0, 0, 0, 1)), kind="urdf",
             robot_namespace="meshy2")
    assert sorted(os.listdir(tmp_path / left[0])) == files      # made once
    run(empty, 0.5)
    assert robot.ground_truth()[0][2] == pytest.approx(0.0, abs=0.003)
    robot.command(0.2, 0.0)
    run(empty, 2.0)
    robot.command(0.0, 0.0)
    assert robot.odom().position[0] > 0.3 and abs(robot.odom().position[1] - 3.0) < 0.02
    for name in ("meshy", "meshy2"):
        wc.delete(name)


def test_a_plain_mesh_model_falls_and_rests_on_its_mesh_collision_and_is_seen(sims, tmp_path):
    """spawn_urdf_model of a 0.2 m cube whose visual and collision are one STL (file://): it
    falls from 0.5 m and rests with its centre 0.1 m up; the Burger's laser sees its face."""
    _, burger = sims
    wc = WorldControl(burger)
    uri = "file://" + crate_stl(tmp_path)
    xml = one_link(uri, material="<material name='red'/>")
    wc.spawn("crate", xml, ((1.0, 0.0, 0.5), (0, 0, 0, 1)), kind="urdf")
    run(burger, 1.5)
    (x, y, z), _ = wc.get_model_state("crate")[0]
    assert (x, y) == pytest.approx((1.0, 0.0), abs=0.01)
    assert z == pytest.approx(0.1, abs=0.003)
    ranges = burger.robot.scan()
    assert ranges[0] == pytest.approx(1.0 - 0.1 + 0.032, abs=0.04)   # base_scan: x -0.032
    wc.delete("crate")
    run(burger, 0.1)
    assert not np.isfinite(burger.robot.scan()[0])
    wc.spawn("crate2", xml, ((1.0, 0.0, 0.1), (0, 0, 0, 1)), kind="sdf")   # spawn_sdf_model
    run(burger, 0.5)
    assert wc.get_model_state("crate2")[0][0][2] == pytest.approx(0.1, abs=0.003)
    wc.delete("crate2")


def test_a_robot_urdf_file_with_relative_meshes_is_simulated(tmp_path):
    """SimConfig.urdf: relative mesh filenames are taken from the URDF file's folder."""
    crate_stl(tmp_path, "base.stl", half=60.0)
    text = mesh_burger().replace(PKG + "bases/burger_base.stl", "../base.stl")
    os.mkdir(tmp_path / "robot")
    path = write(tmp_path / "robot", "burger.urdf", text)
    sim = Simulation(SimConfig(world="empty", urdf=path))
    try:
        run(sim, 0.2)
        assert sim.robot.ground_truth()[0][2] == pytest.approx(0.0, abs=0.003)
    finally:
        sim.close()


@pytest.mark.parametrize("kind", ["plain", "robot"])
@pytest.mark.parametrize("edit, words", [
    (('scale="0.001 0.001 0.001"', 'scale="0.001 0 0.001"'), "is not three non-zero numbers"),
    ((PKG + "bases/burger_base.stl", "file://%(garbage)s"), "garbage.stl: "),
])
def test_a_bad_mesh_refuses_the_spawn_with_one_line(sims, tmp_path, kind, edit, words):
    """A plain URDF or a robot URDF with a badly scaled or unreadable mesh: the spawn is
    refused with one status line; nothing is added."""
    empty, _ = sims
    garbage = write(tmp_path, "garbage.stl", "solid nothing here\nthis is not an STL\n")
    text = mesh_burger().replace(edit[0], edit[1] % {"garbage": garbage}, 1)
    if kind == "plain":   # no plugins: a plain model
        robot = ElementTree.fromstring(text)
        for gazebo in robot.findall("gazebo"):
            robot.remove(gazebo)
        text = ElementTree.tostring(robot, encoding="unicode")
    before = empty.models.names()
    with pytest.raises(RequestError) as err:
        WorldControl(empty).spawn("bad", text, ((0.0, -2.0, 0.0), (0, 0, 0, 1)), kind="urdf",
                                  robot_namespace="bad")
    message = str(err.value)
    assert message.startswith("SpawnModel: Failure - ") and words in message, message
    assert "\n" not in message and "link 'base_link' <mesh>: " in message
    assert empty.models.names() == before and "bad" not in empty.robots


@pytest.mark.parametrize("kind", ["plain", "robot"])
def test_a_mesh_found_nowhere_is_left_out_of_the_spawn_with_a_warning(sims, kind):
    """A plain URDF or a robot URDF whose chassis mesh is found nowhere is spawned without
    that visual, its other links there; the warning names the file (a plain model's is one of
    the spawn's warnings, a robot's one of its own)."""
    empty, _ = sims
    text = mesh_burger().replace(PKG + "bases/burger_base.stl", "package://nowhere/x.stl", 1)
    if kind == "plain":
        robot = ElementTree.fromstring(text)
        for gazebo in robot.findall("gazebo"):
            robot.remove(gazebo)
        text = ElementTree.tostring(robot, encoding="unicode")
    wc, name = WorldControl(empty), "lost_" + kind
    warnings = wc.spawn(name, text, ((1.0, -2.0 if kind == "plain" else 2.0, 0.0),
                                     (0, 0, 0, 1)), kind="urdf", robot_namespace=name)
    if kind == "robot":
        assert warnings == []
        warnings = empty.robots[name].warnings
    lost = [w for w in warnings if "package://nowhere/x.stl" in w]
    assert len(lost) == 1 and "link 'base_link' <visual> left out" in lost[0], warnings
    assert "wheel_left_link" in wc.model_properties(name).body_names
    wc.delete(name)


def test_converted_files_are_kept_for_the_pairs_used_last(tmp_path, monkeypatch):
    """At most MAX_CONVERTED (file, scale) pairs keep their files; an older one's files are
    removed, and written again when it comes back."""
    import os
    from tutorial_turtlebot.sim.files.urdf import urdf_meshes
    monkeypatch.setattr(urdf_meshes, "MAX_CONVERTED", 2)
    obj = tmp_path / "t.obj"
    obj.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n")
    hulls = [urdf_meshes.hull_file(str(obj), (s, s, s)) for s in (1.0, 2.0, 3.0)]
    assert not os.path.exists(hulls[0]) and all(os.path.exists(h) for h in hulls[1:])
    again = urdf_meshes.hull_file(str(obj), (1.0, 1.0, 1.0))
    assert os.path.exists(again) and not os.path.exists(hulls[1])
    parts = [urdf_meshes.visual_parts(str(obj), (s, s, s)) for s in (1.0, 2.0, 3.0)]
    assert not os.path.exists(parts[0][0][0]) and os.path.exists(parts[2][0][0])
