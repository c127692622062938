"""Spawn requests: SDF and URDF model_xml, name rules, refusals (sim/world/spawn_request).
No ROS."""
import math
import os

import pytest

from tutorial_turtlebot.errors import RequestError
from tutorial_turtlebot.package_data import data_dir
from tutorial_turtlebot.sim.world.spawn_request import MAX_XML_BYTES, parse_spawn, placed
from tutorial_turtlebot.sim.world.world_models import check_model_name

from unit_helpers import at

BOX = """<sdf version="1.6">
  <model name="box">
    <pose>0 0 0.1 0 0 0</pose>
    <link name="link">
      <inertial><mass>0.2</mass><inertia><ixx>0.001</ixx><iyy>0.002</iyy><izz>0.003</izz></inertia></inertial>
      <collision name="c">
        <geometry><box><size>0.2 0.2 0.2</size></box></geometry>
        <surface><friction><ode><mu>0.4</mu></ode></friction></surface>
      </collision>
      <visual name="v"><geometry><box><size>0.2 0.2 0.2</size></box></geometry></visual>
    </link>
  </model>
</sdf>"""

URDF = """<?xml version="1.0"?>
<robot name="anything">
  <link name="base"><collision><geometry><cylinder radius="0.1" length="0.2"/></geometry>\
</collision></link>
  <link name="top"><visual><geometry><sphere radius="0.05"/></geometry></visual></link>
  <joint name="hinge" type="continuous"><parent link="base"/><child link="top"/></joint>
</robot>"""


def test_sdf_model_renamed_and_placed_with_its_inertial_and_friction():
    request = parse_spawn("crate", BOX, at(1.0, 2.0, yaw=math.pi / 2))
    world = request.world
    assert request.description is None and world.models == ("crate",)
    model = world.model("crate")
    assert not model.static and [link.scoped for link in model.links] == ["crate::link"]
    assert model.pose[:3] == pytest.approx((1.0, 2.0, 0.1))    # initial_pose * <pose>
    assert model.pose[5] == pytest.approx(math.pi / 2)
    link = model.links[0]
    assert link.inertial.mass == 0.2
    assert link.inertial.inertia[:3] == (0.001, 0.002, 0.003)
    collision = world.shape("crate::link::c")
    assert collision.mu == 0.4 and collision.link == "crate::link"


def test_sdf_defaults_are_gazebos():
    xml = BOX.replace("<inertial><mass>0.2</mass><inertia><ixx>0.001</ixx><iyy>0.002</iyy>"
                      "<izz>0.003</izz></inertia></inertial>", "").replace(
                          "<surface><friction><ode><mu>0.4</mu></ode></friction></surface>", "")
    world = parse_spawn("b", xml).world
    inertial = world.model("b").links[0].inertial
    assert (inertial.mass, inertial.inertia) == (1.0, (1.0, 1.0, 1.0, 0.0, 0.0, 0.0))
    assert world.shape("b::link::c").mu == 1.0


def test_the_goal_box_file():
    with open(data_dir("models") + "/goal_box/model.sdf") as f:
        world = parse_spawn("goal", f.read(), at(0.6, 0.0)).world
    model = world.model("goal")
    assert model.static and world.collisions == ()
    assert model.pose[5] == pytest.approx(-1.5708)


def test_urdf_with_plugins_is_a_robot():
    """A URDF whose <gazebo> blocks hold plugins is a robot: its text goes on as given, for
    Simulation.add_robot (the plugins are checked there)."""
    xml = URDF.replace("</robot>", "<gazebo><plugin name='p' filename='libx.so'/></gazebo></robot>")
    request = parse_spawn("r", xml, kind="urdf")
    assert request.robot == xml and request.world is None


def test_urdf_without_plugins():
    """A plain URDF is converted to SDF as Gazebo converts it (urdf_to_sdf) and read as an SDF
    spawn: renamed; its links without <inertial> are not modelled (one note says so)."""
    request = parse_spawn("thing", URDF, kind="urdf")
    assert request.robot is None and request.world.models == ("thing",)
    assert request.world.model("thing").links == () and request.world.shapes == ()
    (note,) = request.notes
    assert "link 'base' has no mass" in note
    massive = URDF.replace("<link name=\"base\">", "<link name=\"base\"><inertial><mass "
                           "value=\"1\"/><inertia ixx=\"1\" iyy=\"1\" izz=\"1\" ixy=\"0\" "
                           "ixz=\"0\" iyz=\"0\"/></inertial>")
    world = parse_spawn("thing", massive, kind="sdf").world   # spawn_sdf_model takes URDF too
    assert [link.scoped for link in world.model("thing").links] == ["thing::base"]
    assert [s.name for s in world.shapes] == ["thing::base::base_collision"]


@pytest.mark.parametrize("xml, words", [
    ("<sdf><model name='m'><link name='l'></model></sdf>", "model_xml:1: malformed XML"),
    ("<sdf>\n<model name='m'>\n<link name='l'>\n<visual name='v'><geometry><mesh/></geometry>"
     "</visual></link></model></sdf>", "model_xml:4: <mesh> of m::l::v needs a <uri>"),
    ("<world/>", "root element is <world>"),
    ("<sdf><model name='a'/><model name='b'/></sdf>", "exactly one <model>"),
    ("", "empty"),
    ("<!DOCTYPE x [<!ENTITY a 'aaaa'>]><sdf/>", "DOCTYPE"),
    ("<sdf>" + "<model name='m'>" * 100 + "</model>" * 100 + "</sdf>", "nested more than"),
    ("<sdf>" + " " * (MAX_XML_BYTES + 1) + "</sdf>", "more than the 1000000 allowed"),
    (URDF.replace("<sphere radius=\"0.05\"/>", "<mesh filename='%s'/>" % os.path.abspath(
        __file__)), "test_spawn_request.py: unknown mesh format '.py'"),
    (URDF.replace('<parent link="base"/>', '<parent link="nowhere"/>'),
     "model_xml:5: joint 'hinge' <parent>: link 'nowhere' is not defined"),
])
def test_refused_with_one_line(xml, words):
    with pytest.raises(RequestError) as err:
        parse_spawn("m", xml)
    text = str(err.value)
    assert text.startswith("SpawnModel: Failure - ") and words in text and "\n" not in text


def test_urdf_service_needs_a_robot():
    with pytest.raises(RequestError, match="needs a <robot>"):
        parse_spawn("m", BOX, kind="urdf")


@pytest.mark.parametrize("name", ["", " x", "a b", "m::l"])
def test_bad_names(name):
    with pytest.raises(RequestError):
        check_model_name(name)


def test_placed_in_a_frame_and_refusing_nan():
    frame = at(1.0, 0.0, yaw=math.pi / 2)
    (p, q) = placed(((1.0, 0.0, 0.0), (0.0, 0.0, 0.0, 0.0)), frame)   # all-zero quaternion
    assert p == pytest.approx((1.0, 1.0, 0.0))
    assert q == pytest.approx(frame[1])
    with pytest.raises(ValueError):
        placed(((float("nan"), 0.0, 0.0), (0.0, 0.0, 0.0, 1.0)), None)


# --- what one spawn may cost the loop (prepare_spawn) ---------------------------------------------

from tutorial_turtlebot.sim.world import spawn_request  # noqa: E402


def polyline_sdf(points):
    corners = "".join("<point>%g %g</point>" % (math.cos(a), math.sin(a))
                      for a in (2 * math.pi * k / points for k in range(points)))
    return ('<sdf version="1.6"><model name="p"><static>true</static><link name="l"><collision '
            'name="c"><geometry><polyline>%s<height>0.5</height></polyline></geometry>'
            '</collision></link></model></sdf>' % corners)


def mesh_sdf(path, static):
    return ('<sdf version="1.6"><model name="m"><static>%s</static><link name="l"><collision '
            'name="c"><geometry><mesh><uri>%s</uri></mesh></geometry></collision></link></model>'
            '</sdf>' % ("true" if static else "false", path))


def cube_obj(tmp_path):
    path = tmp_path / "cube.obj"
    corners = [(x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1)]
    faces = [(1, 2, 4), (1, 4, 3), (5, 7, 8), (5, 8, 6), (1, 5, 6), (1, 6, 2), (3, 4, 8),
             (3, 8, 7), (1, 3, 7), (1, 7, 5), (2, 6, 8), (2, 8, 4)]
    path.write_text("".join("v %d %d %d\n" % c for c in corners)
                    + "".join("f %d %d %d\n" % f for f in faces))
    return str(path)


def test_a_spawn_within_the_budgets_is_prepared_with_its_digest():
    request = spawn_request.prepare_spawn("crate", BOX)
    assert request.world is not None and len(request.digest) == 64
    assert spawn_request.prepare_spawn("p", polyline_sdf(256)).world is not None


def test_a_polyline_of_too_many_points_is_refused_before_anything_is_built():
    with pytest.raises(RequestError) as err:
        spawn_request.prepare_spawn("p", polyline_sdf(257))
    assert "polyline points: 257, more than the 256 one spawn may build" in str(err.value)


def test_too_many_shapes_are_refused(monkeypatch):
    monkeypatch.setattr(spawn_request, "MAX_SPAWN_SHAPES", 10)
    with pytest.raises(RequestError, match="shapes .*: 11, more than the 10"):
        spawn_request.prepare_spawn("p", polyline_sdf(13))     # counted as 13 - 2 triangles
    links = "".join('<link name="l%d"><inertial><mass value="1"/><inertia ixx="1" iyy="1" '
                    'izz="1" ixy="0" ixz="0" iyz="0"/></inertial><collision><geometry><sphere '
                    'radius="0.1"/></geometry></collision></link>' % k for k in range(11))
    joints = "".join('<joint name="j%d" type="fixed"><parent link="l0"/><child link="l%d"/>'
                     '</joint>' % (k, k) for k in range(1, 11))
    with pytest.raises(RequestError, match="more than 10 collisions and visuals"):
        spawn_request.prepare_spawn("u", '<robot name="r">%s%s</robot>' % (links, joints))


def test_mesh_budgets_are_checked_on_the_files_read(tmp_path, monkeypatch):
    path = cube_obj(tmp_path)
    assert spawn_request.prepare_spawn("m", mesh_sdf(path, static=False)).world is not None
    monkeypatch.setattr(spawn_request, "MAX_MOVABLE_MESH_VERTICES", 7)
    with pytest.raises(RequestError, match="vertices of a movable mesh: 8, more than the 7"):
        spawn_request.prepare_spawn("m", mesh_sdf(path, static=False))
    spawn_request.prepare_spawn("m", mesh_sdf(path, static=True))     # a static one: triangles
    monkeypatch.setattr(spawn_request, "MAX_SPAWN_TRIANGLES", 11)
    with pytest.raises(RequestError, match="mesh triangles: 12, more than the 11"):
        spawn_request.prepare_spawn("m", mesh_sdf(path, static=True))


def test_reading_that_takes_too_long_is_refused():
    with pytest.raises(RequestError, match="took more than 0 s; nothing was spawned"):
        spawn_request.prepare_spawn("crate", BOX, seconds=0.0)


NAMESPACED = """<sdf version="1.6"><model name="m"><link name="l"><inertial><mass>1</mass>
<inertia><ixx>0.01</ixx><iyy>0.01</iyy><izz>0.01</izz></inertia></inertial>
<collision name="c"><geometry><box><size>.2 .2 .2</size></box></geometry></collision></link>
<plugin name="given" filename="libgazebo_ros_p3d.so"><bodyName>l</bodyName>
<topicName>truth</topicName></plugin>
<plugin name="own" filename="libgazebo_ros_p3d.so"><robotNamespace>mine</robotNamespace>
<bodyName>l</bodyName><topicName>truth</topicName></plugin></model></sdf>"""


def test_spawn_robot_namespace_goes_to_each_sdf_plugin_without_its_own():
    """As gazebo_ros' spawn service: <robotNamespace> added where a plugin has none."""
    plugins = parse_spawn("m", NAMESPACED, robot_namespace="ns1").world.model_plugins
    assert [(p.name, p.robot_namespace) for p in plugins] == [("given", "ns1"), ("own", "mine")]
    plugins = parse_spawn("m", NAMESPACED).world.model_plugins
    assert [p.robot_namespace for p in plugins] == ["", "mine"]
