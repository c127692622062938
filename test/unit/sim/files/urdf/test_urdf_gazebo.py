"""What Gazebo's URDF conversion adds to a URDF (sim/files/urdf/urdf_gazebo.py, urdf_file.py):
a reference-less <gazebo> block's <static>, a root link "world" (Gazebo's links, geom names),
mesh files found nowhere left out with one warning each (then one line for the rest). The
conversion itself: test_urdf_to_sdf.py. No ROS master, no pybullet."""
import os
from xml.etree import ElementTree

import pytest

from tutorial_turtlebot.sim.files.urdf.urdf_file import read_urdf, read_urdf_text
from tutorial_turtlebot.sim.files.urdf.urdf_gazebo import MAX_MISSING_LINES

import unit_paths

ANCHORS = os.path.normpath(os.path.join(unit_paths.UNIT, os.pardir, "fixtures", "urdf_anchors"))
BOX = '<geometry><box size="0.1 0.1 0.1"/></geometry>'
INERTIAL = ('<inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" '
            'ixz="0" iyz="0"/></inertial>')


def link(name, shape=BOX):
    return '<link name="%s">%s<collision>%s</collision></link>' % (name, INERTIAL, shape)


def joint(name, parent, child, kind="fixed"):
    limit = '<limit lower="-1" upper="1" effort="1" velocity="1"/>' if kind == "revolute" else ""
    return ('<joint name="%s" type="%s"><parent link="%s"/><child link="%s"/>%s</joint>'
            % (name, kind, parent, child, limit))


def robot(*parts):
    return read_urdf_text('<robot name="r">%s</robot>' % "".join(parts), "model_xml")


# --- <gazebo><static> -----------------------------------------------------------------------------

@pytest.mark.parametrize("block, static", [
    ("<gazebo><static>true</static></gazebo>", True),
    ("<gazebo>\n  <static> TRUE </static>\n</gazebo>", True),
    ("<gazebo><static>1</static></gazebo>", True),
    ("<gazebo><static>yes</static></gazebo>", True),
    ("<gazebo reference=''><static>true</static></gazebo>", True),
    ("<gazebo><static value='true'/></gazebo>", True),
    ("<gazebo><static>false</static></gazebo>", False),
    ("<gazebo><static>on</static></gazebo>", False),            # parser_urdf's false
    ("<gazebo reference='a'><static>true</static></gazebo>", False),   # a link's: not the model's
    ("", False),
])
def test_a_reference_less_gazebo_block_says_whether_the_model_is_static(block, static):
    description = robot(link("a"), block)
    assert description.static is static and description.warnings == ()


def test_the_last_reference_less_block_decides_with_one_warning():
    """A later <gazebo> without <static> makes the model not static again, as parser_urdf
    does; one line says so, naming both blocks' lines."""
    text = ('<robot name="r">\n%s\n<gazebo><static>true</static></gazebo>\n'
            '<gazebo><self_collide>1</self_collide></gazebo>\n</robot>' % link("a"))
    description = read_urdf_text(text, "model_xml")
    assert description.static is False
    (warning,) = description.warnings
    assert warning.startswith("model_xml:4: ") and "line 3" in warning and "\n" not in warning
    again = read_urdf_text(text.replace("<self_collide>1</self_collide>",
                                        "<static>1</static>"), "model_xml")
    assert again.static is True and again.warnings == ()


# --- a root link "world" --------------------------------------------------------------------------

def test_a_root_world_is_no_link_of_the_model():
    description = robot('<link name="world"/>', link("post"), link("plate"), link("arm"),
                        link("hand"), joint("world_joint", "world", "post"),
                        joint("weld", "post", "plate"), joint("shoulder", "post", "arm",
                                                              "revolute"),
                        joint("wrist", "arm", "hand"))
    assert description.model_links() == ["post", "arm"]            # plate, hand lumped
    # the post is not lumped into world: it holds its collisions and its plate's
    assert description.collision_names() == {
        "post": ["post_collision", "post_fixed_joint_lump__plate_collision_1"],
        "arm": ["arm_collision", "arm_fixed_joint_lump__hand_collision_1"]}


def test_the_fixtures():
    env = read_urdf(os.path.join(ANCHORS, "static_env.urdf"))
    assert env.static and env.root_link == "base"
    assert env.model_links() == ["base", "gate"]
    post = read_urdf(os.path.join(ANCHORS, "world_anchored.urdf"))
    assert not post.static and post.root_link == "world"
    assert post.model_links() == ["post", "head"]


# --- mesh files found nowhere ---------------------------------------------------------------------

def mesh(name):
    return '<geometry><mesh filename="/no/such/folder/%s"/></geometry>' % name


def test_the_fixtures_missing_barn_is_one_warning_and_the_rest_is_there():
    env = read_urdf(os.path.join(ANCHORS, "static_env.urdf"))
    (warning,) = env.warnings          # its collision (read first) and visual: one file, one line
    assert "link 'barn' <collision> left out: " in warning and "barn.dae not found" in warning
    assert env.links["barn"].visuals == () and env.links["barn"].collisions == ()
    assert env.links["barn"].mass == 100.0        # the link stays, with its inertial
    assert len(env.links["trough"].collisions) == 1 and len(env.links["crate"].visuals) == 1
    barn = next(e for e in env.root.findall("link") if e.get("name") == "barn")
    assert barn.find("visual") is None and barn.find("collision") is None
    assert barn.find("inertial") is not None


def test_many_missing_files_are_one_line_each_up_to_a_few_then_one_line():
    names = ["m%d.stl" % i for i in range(MAX_MISSING_LINES + 4)]
    links = [link("l%d" % i, mesh(n)) for i, n in enumerate(names)]
    links.append(link("again", mesh(names[0])))   # a file missing twice: said once
    joints = [joint("j%d" % i, "l0", "l%d" % i) for i in range(1, len(names))]
    description = robot(*links, joint("j_again", "l0", "again"), *joints)
    warnings = description.warnings
    assert len(warnings) == MAX_MISSING_LINES + 1 and all(len(w) <= 200 for w in warnings)
    for number, line in enumerate(warnings[:-1]):
        assert "link 'l%d' <collision> left out" % number in line and names[number] in line
    assert warnings[-1].startswith("model_xml: 4 more mesh files not found")
    assert all(n in warnings[-1] for n in names[MAX_MISSING_LINES:])
    assert all(not description.links[name].collisions for name in description.links)


def test_a_urdf_without_missing_meshes_keeps_its_parsed_root():
    description = robot(link("a"))
    again = read_urdf_text(ElementTree.tostring(description.root, encoding="unicode"), "x")
    assert again.links == description.links and description.warnings == ()
