"""A movable model's <joint>s read into world_types.Joint (sdf_joints, through world_sdf): their
frames, axes, limits and dynamics as Gazebo 11 reads them, a loop's closing joint left out with
one warning, and the refusals Gazebo makes too. The worlds are written here."""
import pytest

from tutorial_turtlebot.sim.files.model_tree import trees
from tutorial_turtlebot.sim.files.sdf.world_sdf import load_model_xml, load_world
from tutorial_turtlebot.sim.files.world_types import UNLIMITED, WORLD_LINK

from unit_helpers import world_fault, world_file

INERTIAL = ('<inertial><mass>1</mass><inertia><ixx>0.01</ixx><iyy>0.01</iyy><izz>0.01</izz>'
            '</inertia></inertial>')


def link(name, pose="0 0 0 0 0 0"):
    return ('<link name="%s"><pose>%s</pose>%s<collision name="c"><geometry><box><size>'
            '0.1 0.1 0.1</size></box></geometry></collision></link>' % (name, pose, INERTIAL))


def joint(name, kind, parent, child, extra=""):
    return ('<joint name="%s" type="%s"><parent>%s</parent><child>%s</child>%s</joint>'
            % (name, kind, parent, child, extra))


def model(body, pose="0 0 0 0 0 0", static="false", name="m"):
    return ('<model name="%s"><static>%s</static><pose>%s</pose>%s</model>'
            % (name, static, pose, body))


def load(tmp_path, body, version="1.6"):
    return load_world(world_file(tmp_path, body, version=version))


def close(a, b, tol=1e-9):
    return all(abs(x - y) < tol for x, y in zip(a, b))


def test_joint_frame_is_its_pose_in_the_child_link(tmp_path):
    world = load(tmp_path, model(link("a") + link("b", "1 0 0 0 0 1.5707963267948966")
                                 + joint("j", "revolute", "a", "b",
                                         "<pose>0.5 0 0 0 0 0</pose>"), pose="0 0 2 0 0 0"))
    [spec] = world.model("m").joint_specs
    assert (spec.parent, spec.child) == ("m::a", "m::b")
    # the child link is turned 90 degrees about z: its x is the world's y
    assert close(spec.pose[:3], (1.0, 0.5, 2.0))


def test_axis_in_the_joint_frame_by_default(tmp_path):
    body = (link("a") + link("b", "0 0 0 0 0 1.5707963267948966")
            + joint("j", "revolute", "a", "b", "<axis><xyz>1 0 0</xyz></axis>"))
    [spec] = load(tmp_path, model(body)).model("m").joint_specs
    assert close(spec.axis, (0.0, 1.0, 0.0))


@pytest.mark.parametrize("axis", [
    "<axis><xyz>1 0 0</xyz><use_parent_model_frame>true</use_parent_model_frame></axis>",
    '<axis><xyz expressed_in="__model__">1 0 0</xyz></axis>'])
def test_axis_in_the_model_frame_where_the_file_says(tmp_path, axis):
    body = link("a") + link("b", "0 0 0 0 0 1.5707963267948966") + joint("j", "revolute", "a",
                                                                         "b", axis)
    # the model is turned 90 degrees about x: its x stays the world's x
    [spec] = load(tmp_path, model(body, pose="0 0 0 1.5707963267948966 0 0")).model(
        "m").joint_specs
    assert close(spec.axis, (1.0, 0.0, 0.0))


def test_sdf_1_4_axes_are_in_the_model_frame(tmp_path):
    body = (link("a") + link("b", "0 0 0 0 0 1.5707963267948966")
            + joint("j", "revolute", "a", "b", "<axis><xyz>1 0 0</xyz></axis>"))
    [old] = load(tmp_path, model(body), version="1.4").model("m").joint_specs
    [new] = load(tmp_path, model(body), version="1.5").model("m").joint_specs
    assert close(old.axis, (1.0, 0.0, 0.0)) and close(new.axis, (0.0, 1.0, 0.0))


def test_limits_and_dynamics(tmp_path):
    axis = ('<axis><xyz>0 0 1</xyz><limit><lower>-0.5</lower><upper>0.7</upper><effort>3'
            '</effort><velocity>2</velocity></limit><dynamics><damping>0.2</damping><friction>'
            '0.1</friction></dynamics></axis>')
    body = link("a") + link("b") + joint("j", "revolute", "a", "b", axis)
    [spec] = load(tmp_path, model(body)).model("m").joint_specs
    assert (spec.lower, spec.upper, spec.effort, spec.velocity) == (-0.5, 0.7, 3.0, 2.0)
    assert (spec.damping, spec.friction) == (0.2, 0.1)


def test_no_limit_written_and_a_continuous_joint_are_unlimited(tmp_path):
    limited = '<axis><xyz>0 0 1</xyz><limit><lower>-1</lower><upper>1</upper></limit></axis>'
    body = (link("a") + link("b") + link("c") + joint("free", "revolute", "a", "b")
            + joint("spin", "continuous", "b", "c", limited))
    free, spin = load(tmp_path, model(body)).model("m").joint_specs
    assert (free.lower, free.upper) == (-UNLIMITED, UNLIMITED)
    assert (spin.lower, spin.upper) == (-UNLIMITED, UNLIMITED)


def test_a_joint_to_the_world_anchors_its_child(tmp_path):
    world = load(tmp_path, model(link("a") + joint("pin", "fixed", "world", "a")))
    [spec] = world.model("m").joint_specs
    assert spec.parent == WORLD_LINK
    [tree] = trees(world.model("m"))
    assert tree.fixed_base and not tree.anchor_base


def test_nested_model_links_are_scoped(tmp_path):
    inner = '<model name="arm">%s</model>' % link("upper")
    world = load(tmp_path, model(link("base") + inner
                                 + joint("shoulder", "revolute", "base", "arm::upper")))
    [spec] = world.model("m").joint_specs
    assert spec.child == "m::arm::upper"


def test_a_loop_keeps_the_nearest_tree_with_one_warning(tmp_path):
    body = (link("a") + link("b", "1 0 0 0 0 0") + link("c", "2 0 0 0 0 0")
            + joint("ab", "revolute", "a", "b") + joint("bc", "revolute", "b", "c")
            + joint("ca", "revolute", "c", "a"))
    world = load(tmp_path, model(body))
    assert [j.name for j in world.model("m").joint_specs] == ["ab", "bc"]
    assert world.model("m").joints == ("ab", "bc", "ca")       # all still listed
    assert sum("joint ca closes a loop" in w for w in world.warnings) == 1


def test_a_second_parent_is_a_loop_too(tmp_path):
    body = (link("a") + link("b") + link("c") + joint("ac", "revolute", "a", "c")
            + joint("bc", "revolute", "b", "c"))
    world = load(tmp_path, model(body))
    assert [j.name for j in world.model("m").joint_specs] == ["ac"]


def test_screw_joint_is_held_fixed_with_one_warning(tmp_path):
    world = load(tmp_path, model(link("a") + link("b") + joint("s", "screw", "a", "b")))
    assert any("a screw joint is held fixed" in w for w in world.warnings)


def test_static_model_joints_are_listed_not_simulated(tmp_path):
    world = load(tmp_path, model(link("a") + link("b") + joint("j", "revolute", "a", "b"),
                                 static="true"))
    assert world.model("m").joints == ("j",) and world.model("m").joint_specs == ()
    assert not any("<joint>" in w for w in world.warnings)


def test_spawned_sdf_reads_joints_too():
    text = ('<sdf version="1.6">%s</sdf>'
            % model(link("a") + link("b") + joint("j", "prismatic", "a", "b")))
    world = load_model_xml(text, "spawn_sdf_model x", "x")
    [spec] = world.model("x").joint_specs
    assert (spec.kind, spec.parent, spec.child) == ("prismatic", "x::a", "x::b")


@pytest.mark.parametrize("body, words", [
    (joint("j", "revolute", "a", "nowhere"), "child link 'nowhere' is no link"),
    (joint("j", "hinge", "a", "b"), "type 'hinge' is not one of"),
    (joint("j", "revolute", "a", "a"), "joins link m::a to itself"),
    (joint("j", "revolute", "a", "b", "<axis><xyz>0 0 0</xyz></axis>"), "must be a direction"),
    (joint("j", "revolute", "a", "b", "<axis><dynamics><damping>-1</damping></dynamics></axis>"),
     "damping"),
])
def test_refused_as_gazebo_refuses(tmp_path, body, words):
    error = world_fault(world_file(tmp_path, model(link("a") + link("b") + body)))
    assert words in error and "test.world:" in error
    assert "\n" not in error
