"""The one line-numbered XML reader (sim/xml_reader): lines, typed values, one error form for
URDF and SDF alike, and a spawn that parses its description exactly once."""
import os

import pytest
from xml.etree import ElementTree

from tutorial_turtlebot.errors import UrdfError, UserError, WorldError
from tutorial_turtlebot.sim.files import xml_reader
from tutorial_turtlebot.package_data import data_dir
from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
from tutorial_turtlebot.sim.world.spawn_request import parse_spawn
from tutorial_turtlebot.sim.files.urdf.urdf_file import read_urdf_text
from tutorial_turtlebot.sim.world.world_control import WorldControl
from tutorial_turtlebot.sim.files.sdf.world_sdf import load_model_xml

DOCTYPE = '<?xml version="1.0"?>\n<!DOCTYPE x [<!ENTITY a "aaaa">]>\n'
PLAIN_URDF = """<robot name="thing">
  <link name="base"><inertial><mass value="1"/>
    <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
    <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link>
</robot>"""
BOX_SDF = """<sdf version="1.6"><model name="box"><static>true</static>
  <link name="l"><collision name="c"><geometry><box><size>1 1 1</size></box></geometry>
  </collision></link></model></sdf>"""


def at(x, y, z=0.0):
    return (x, y, z), (0.0, 0.0, 0.0, 1.0)


def test_elements_know_their_lines_and_text():
    root = xml_reader.parse("<a>\n  <b> 1 2 </b>\n  <b/>\n</a>", "t")
    assert root.line == 1 and [b.line for b in root.all("b")] == [2, 3]
    assert root.child("b").value == "1 2" and root.all("b")[1].value == ""


def test_typed_values_and_their_one_line_errors():
    root = xml_reader.parse('<s>\n<n>1.5</n><i>3</i><f>TRUE</f><p>1 2 3 0 0 1</p>\n'
                            '<bad>x</bad><o xyz="1 2"/></s>', "doc.xml")
    reader = xml_reader.XmlReader("doc.xml", WorldError)
    assert reader.number(root, "n", 0.0) == 1.5 and reader.number(root, "none", 7.0) == 7.0
    assert reader.integer(root, "i", 1) == 3 and reader.flag(root, "f", False) is True
    assert reader.xyz_rpy(root, "p", None) == (1.0, 2.0, 3.0, 0.0, 0.0, 1.0)
    with pytest.raises(WorldError, match=r"^doc.xml:3: <bad>: must be a number, got 'x'$"):
        reader.number(root, "bad", 0.0)
    with pytest.raises(WorldError, match=r"^doc.xml:3: <o>: xyz='1 2' is not 3 numbers$"):
        reader.attr_floats(root.child("o"), "xyz", 3)
    with pytest.raises(WorldError, match=r"^doc.xml:1: <s>: missing <q>$"):
        reader.child(root, "q")


@pytest.mark.parametrize("read, error", [
    (lambda text: read_urdf_text(text, "model_xml"), UrdfError),
    (lambda text: load_model_xml(text, "model_xml", "m"), WorldError),
])
def test_urdf_and_sdf_refuse_a_doctype_alike(read, error):
    with pytest.raises(error) as err:
        read(DOCTYPE + "<robot/>")
    assert str(err.value) == "model_xml:2: a DOCTYPE (entity definitions) is not supported"


def test_malformed_and_too_deep_xml_have_the_same_form():
    with pytest.raises(UserError, match=r"^x:2: malformed XML: mismatched tag \(column 3\)$"):
        xml_reader.parse("<a>\n</b>", "x")
    with pytest.raises(UserError, match=r"^x:1: elements nested more than 64 deep$"):
        xml_reader.parse("<a>" * 70 + "</a>" * 70, "x")


@pytest.fixture
def control():
    sim = Simulation(SimConfig(model="burger", world="empty", spawn_robot=False))
    yield WorldControl(sim)
    sim.close()


@pytest.fixture
def parses(monkeypatch):
    """The sources xml_reader.parse is called with, one entry a parse."""
    calls = []
    real = xml_reader.parse

    def counting(data, source, *args, **kwargs):
        calls.append(source)
        return real(data, source, *args, **kwargs)
    monkeypatch.setattr(xml_reader, "parse", counting)

    def elementtree_parse(source, *args, **kwargs):   # any reader going round xml_reader
        calls.append("ElementTree.parse %s" % source)
        return real_elementtree_parse(source, *args, **kwargs)
    real_elementtree_parse = ElementTree.parse
    monkeypatch.setattr(ElementTree, "parse", elementtree_parse)
    return calls


def test_a_spawned_urdf_is_parsed_once(control, parses):
    """One parse of model_xml gives the one RobotDescription that the checks, the pybullet
    text and the geom names all come from."""
    request = parse_spawn("thing", PLAIN_URDF, at(1.0, 0.0, 0.2), kind="urdf")
    assert parses == ["model_xml"] and request.description.name == "thing"
    del parses[:]
    control.spawn("thing", PLAIN_URDF, at(1.0, 0.0, 0.2), kind="urdf")
    assert parses == ["model_xml"]
    assert control.model_properties("thing").geom_names == ["base_collision"]


def test_a_spawned_robot_is_parsed_once(control, parses):
    with open(os.path.join(data_dir("urdf"), "turtlebot3_burger.urdf")) as f:
        text = f.read()
    control.spawn("tb3", text, at(0.0, 0.0), kind="urdf", robot_namespace="tb3")
    assert parses == ["model_xml"]
    assert control.model_properties("tb3").geom_names[-1] == "wheel_right_link_collision"


def test_a_spawned_sdf_is_parsed_once(control, parses):
    control.spawn("box", BOX_SDF, at(2.0, 2.0, 0.5))
    assert parses == ["model_xml"]


@pytest.mark.parametrize("data", ["\n\n<?xml version='1.0'?>\n<a>\n<b/></a>",
                                  "<!--\n a comment\n-->\n<?xml version='1.0'?><a>\n<b/></a>",
                                  b"  \r\n\n<?xml version=\"1.0\" encoding=\"UTF-8\"?>"
                                  b"\n<a>\n<b/></a>"])
def test_blank_lines_before_the_declaration_are_read_and_lines_keep_their_numbers(data):
    """Published worlds begin with blank lines before <?xml ...?>: Gazebo's TinyXML reads
    them (expat alone refuses them)."""
    root = xml_reader.parse(data, "blank.world")
    assert root.tag == "a" and root.line == 4
    assert root.find("b").line == 5
