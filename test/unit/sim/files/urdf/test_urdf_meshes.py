"""URDFs with mesh visuals and collisions (sim/urdf_file, spawning): reading
``package://``, ``file://`` and relative mesh filenames, robots and plain models built from
them, each error as one line. No ROS master."""
import os
import subprocess
import sys
import tempfile
from xml.etree import ElementTree

import numpy as np
import pybullet
import pytest

from tutorial_turtlebot.errors import RequestError, UserError
from tutorial_turtlebot.sim.files.meshes.mesh_file import load_mesh
from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
from tutorial_turtlebot.sim.files.urdf.urdf_file import read_urdf, read_urdf_text, urdf_path
from tutorial_turtlebot.sim.world.world_control import WorldControl

from unit_helpers import run, urdf_body, write
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


# --- a robot's mesh body ------------------------------------------------------------------------

def test_mesh_visuals_are_drawn_in_their_files_colours_and_collisions_are_convex_hulls(client):
    """A robot's mesh visual is drawn as any model's is: its file's colour parts (a URDF
    <material> colour is not converted, as Gazebo 11 converts URDF), Collada's unit applied;
    its mesh collision collides as the mesh's convex hull."""
    text = """<robot name="r"><material name="dark"><color rgba="0.3 0.3 0.3 1"/></material>
      <link name="cam"><inertial><mass value="1"/>
        <inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
        <visual><geometry><mesh filename="%(r200)s"/></geometry><material name="dark"/></visual>
        <collision><geometry><mesh filename="%(lds)s" scale="0.001 0.001 0.001"/></geometry>
        </collision>
      </link></robot>""" % {"r200": PKG + "sensors/r200.dae", "lds": PKG + "sensors/lds.stl"}
    body = urdf_body(client, text)
    colours = sorted(tuple(round(c, 2) for c in v[7])
                     for v in pybullet.getVisualShapeData(body, physicsClientId=client))
    assert colours == [(0.2, 0.2, 0.2, 1.0), (0.75, 0.75, 0.8, 1.0)]   # the Collada file's
    r200 = load_mesh(os.path.join(MESHES, "sensors", "r200.dae"))
    lo, hi = r200.bounds                                           # Collada's unit: mm
    assert hi - lo == pytest.approx((0.132, 0.020, 0.012))
    [shape] = pybullet.getCollisionShapeData(body, -1, physicsClientId=client)
    assert shape[2] == pybullet.GEOM_MESH
    low, high = pybullet.getAABB(body, -1, physicsClientId=client)   # 2 mm more a side
    assert np.subtract(high, low) - 0.004 == pytest.approx((0.11, 0.11, 0.0315), abs=1e-3)


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
    centre of mass as the shipped primitive Burger; it stands on its wheels and drives; no
    file of its building is left in the temporary folder."""
    empty, burger = sims
    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path))
    wc = WorldControl(empty)
    wc.spawn("meshy", mesh_burger(), ((0.0, 3.0, 0.0), (0, 0, 0, 1)), kind="urdf",
             robot_namespace="meshy")
    robot = empty.robots["meshy"]
    assert dynamics(empty, robot.body.robot) == pytest.approx(
        dynamics(burger, burger.robot.body.robot), rel=1e-6)
    assert robot.body.com_in_root[0] == pytest.approx(burger.robot.body.com_in_root[0],
                                                      abs=1e-6)
    wc.spawn("meshy2", mesh_burger(), ((0.0, 4.0, 0.0), (0, 0, 0, 1)), kind="urdf",
             robot_namespace="meshy2")
    assert os.listdir(tmp_path) == []
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
