"""A URDF converted into an SDF model as Gazebo 11 converts it (sim/files/urdf/urdf_to_sdf.py,
sdformat 9's parser_urdf rules), then read by world_sdf.load_model_xml as any SDF model: links
at their composed poses, joints with axis, limits and dynamics, a root link "world", fixed
joints lumped (inertia merged, Gazebo's names), <gazebo> extensions placed. No ROS master, no
pybullet."""
import math

import numpy as np
import pytest

from tutorial_turtlebot.sim.files.sdf.world_sdf import load_model_xml
from tutorial_turtlebot.sim.files.urdf.urdf_file import read_urdf_text
from tutorial_turtlebot.sim.files.urdf.urdf_to_sdf import urdf_to_sdf
from tutorial_turtlebot.sim.kinematics import compose_xyz_rpy

BOX = '<geometry><box size="0.1 0.2 0.3"/></geometry>'


def inertial(mass=1.0, xyz="0 0 0", i=0.01):
    return ('<inertial><origin xyz="%s"/><mass value="%g"/><inertia ixx="%g" iyy="%g" izz="%g" '
            'ixy="0" ixz="0" iyz="0"/></inertial>' % (xyz, mass, i, i, i))


def link(name, mass=1.0, shapes=True, xyz="0 0 0"):
    body = "<collision>%s</collision><visual>%s</visual>" % (BOX, BOX) if shapes else ""
    return '<link name="%s">%s%s</link>' % (name, inertial(mass, xyz) if mass else "", body)


def joint(name, parent, child, kind="fixed", xyz="0 0 0", rpy="0 0 0", extra=""):
    return ('<joint name="%s" type="%s"><parent link="%s"/><child link="%s"/>'
            '<origin xyz="%s" rpy="%s"/>%s</joint>' % (name, kind, parent, child, xyz, rpy, extra))


LIMIT = '<limit lower="-1" upper="2" effort="3" velocity="4"/>'


def convert(*parts):
    """(the World load_model_xml reads of the converted model "m", the conversion's warnings,
    the <model> element)."""
    description = read_urdf_text('<robot name="r">%s</robot>' % "".join(parts), "model_xml")
    sdf, warnings = urdf_to_sdf(description)
    model = sdf.find("model")
    return load_model_xml(sdf, "model_xml", "m"), warnings, model


def links(world):
    return {link.name: link for link in world.model("m").links}


def test_links_and_joints_with_poses_composed_along_the_chain():
    world, warnings, _ = convert(
        link("base"), joint("shoulder", "base", "upper", "revolute", "0 0 0.5", "0 0 1.0",
                            '<axis xyz="0 1 0"/>' + LIMIT + '<dynamics damping="0.2" '
                                                            'friction="0.1"/>'),
        link("upper"), joint("elbow", "upper", "fore", "continuous", "1 0 0", "0.3 0 0",
                             '<axis xyz="0 0 1"/>'),
        link("fore"), joint("slide", "fore", "tip", "prismatic", "0 0.5 0", extra=LIMIT),
        link("tip"))
    assert warnings == []
    model = world.model("m")
    assert [k.name for k in model.links] == ["base", "upper", "fore", "tip"]
    assert model.joints == ("shoulder", "elbow", "slide")
    assert model.joint_types == ("revolute", "revolute", "prismatic")   # continuous: revolute
    upper = compose_xyz_rpy((0, 0, 0, 0, 0, 0), (0, 0, 0.5, 0, 0, 1.0))
    fore = compose_xyz_rpy(upper, (1, 0, 0, 0.3, 0, 0))
    tip = compose_xyz_rpy(fore, (0, 0.5, 0, 0, 0, 0))
    for name, pose in (("upper", upper), ("fore", fore), ("tip", tip)):
        assert links(world)[name].pose == pytest.approx(pose)
    shoulder, elbow, slide = model.joint_specs
    assert (shoulder.lower, shoulder.upper, shoulder.effort, shoulder.velocity) == (-1, 2, 3, 4)
    assert (shoulder.damping, shoulder.friction) == (0.2, 0.1)
    assert shoulder.pose == pytest.approx(upper)              # the joint frame: the child's
    # the axis, in the joint frame, is turned by the link's yaw of 1 rad in the world
    assert shoulder.axis == pytest.approx((-math.sin(1.0), math.cos(1.0), 0.0))
    assert abs(elbow.lower) > 1e15 and abs(elbow.upper) > 1e15   # continuous: no limits
    assert slide.kind == "prismatic" and (slide.lower, slide.upper) == (-1, 2)
    # collisions and visuals: Gazebo's names, at their link
    assert [s.name for s in world.shapes if s.link == "m::tip"] == [
        "m::tip::tip_collision", "m::tip::tip_visual"]


def test_swapped_limits_are_swapped_back_with_a_warning():
    world, warnings, _ = convert(link("a"), joint("j", "a", "b", "revolute", extra=(
        '<limit lower="1" upper="-1" effort="1" velocity="1"/>')), link("b"))
    (spec,) = world.model("m").joint_specs
    assert (spec.lower, spec.upper) == (-1, 1)
    (warning,) = warnings
    assert "lower limit 1 > upper limit -1: swapped" in warning


def test_a_root_link_world_joins_the_model_to_the_world():
    world, _, model = convert('<link name="world"/>',
                              joint("anchor", "world", "post", "fixed", "0 0 1"), link("post"),
                              joint("pan", "post", "head", "revolute", "0 0 0.5", extra=LIMIT),
                              link("head"))
    assert [k.name for k in world.model("m").links] == ["post", "head"]   # world is no link
    anchor, pan = world.model("m").joint_specs
    assert (anchor.parent, anchor.child, anchor.kind) == ("world", "m::post", "fixed")
    assert links(world)["head"].pose[2] == pytest.approx(1.5)
    assert model.find("joint/parent").text == "world"


def test_fixed_joints_are_lumped_with_gazebos_names_and_merged_inertia():
    world, _, _ = convert(
        link("base", 2.0), joint("mount", "base", "plate", "fixed", "0.3 0 0", "0 0 1.5"),
        link("plate", 1.0, xyz="0.1 0 0"),
        joint("hinge", "plate", "lid", "revolute", "0 0 0.2", extra=LIMIT), link("lid"),
        joint("fix", "base", "camera", "fixed", "0 0 0.4"), link("camera", 0.0, shapes=False))
    model = world.model("m")
    assert [k.name for k in model.links] == ["base", "lid"]      # plate, camera lumped
    assert model.joints == ("hinge",)
    (hinge,) = model.joint_specs
    assert hinge.parent == "m::base"                             # re-parented to the base
    assert links(world)["lid"].pose == pytest.approx(compose_xyz_rpy(
        (0.3, 0, 0, 0, 0, 1.5), (0, 0, 0.2, 0, 0, 0)))
    assert [s.name.split("::")[-1] for s in world.shapes if s.collision] == [
        "base_collision", "base_fixed_joint_lump__plate_collision_1", "lid_collision"]
    assert [s.name.split("::")[-1] for s in world.shapes if not s.collision] == [
        "base_visual", "base_fixed_joint_lump__plate_visual_1", "lid_visual"]
    plate = world.shape("m::base::base_fixed_joint_lump__plate_collision_1")
    assert plate.pose == pytest.approx((0.3, 0, 0, 0, 0, 1.5))
    # 2 kg at 0 and 1 kg at (0.3 + 0.1 cos 1.5, 0.1 sin 1.5): 3 kg at their mean
    base = links(world)["base"].inertial
    com = np.array([0.3 + 0.1 * math.cos(1.5), 0.1 * math.sin(1.5), 0.0]) / 3.0
    assert base.mass == pytest.approx(3.0)
    assert base.pose[:3] == pytest.approx(tuple(com))
    d_base, d_plate = -com, np.array([0.3 + 0.1 * math.cos(1.5), 0.1 * math.sin(1.5), 0]) - com
    izz = 0.02 + 2.0 * (d_base[0] ** 2 + d_base[1] ** 2) + (d_plate[0] ** 2 + d_plate[1] ** 2)
    ixx, iyy, izz_read, ixy = base.inertia[0], base.inertia[1], base.inertia[2], base.inertia[3]
    assert izz_read == pytest.approx(izz)
    assert ixx == pytest.approx(0.02 + 2.0 * d_base[1] ** 2 + d_plate[1] ** 2)
    assert ixy == pytest.approx(-(2.0 * d_base[0] * d_base[1] + d_plate[0] * d_plate[1]))
    assert iyy == pytest.approx(0.02 + 2.0 * d_base[0] ** 2 + d_plate[0] ** 2)


def test_preserved_and_unlumped_fixed_joints():
    gazebo = ('<gazebo reference="keep"><preserveFixedJoint>true</preserveFixedJoint></gazebo>'
              '<gazebo reference="turn"><disableFixedJointLumping>true'
              '</disableFixedJointLumping></gazebo>')
    world, _, _ = convert(link("a"), joint("keep", "a", "b"), link("b"), joint("turn", "a", "c"),
                          link("c"), gazebo)
    model = world.model("m")
    assert [k.name for k in model.links] == ["a", "b", "c"]
    assert dict(zip(model.joints, model.joint_types)) == {"keep": "fixed", "turn": "revolute"}
    turn = model.joint_specs[1]
    assert (turn.lower, turn.upper) == (0.0, 0.0)               # held at 0


def test_a_massless_link_is_not_modelled_nor_what_hangs_below_it():
    world, warnings, _ = convert(link("base"), joint("j", "base", "bare", "revolute", extra=LIMIT),
                                 link("bare", 0.0), joint("k", "bare", "arm", "revolute",
                                                          extra=LIMIT), link("arm"))
    assert [k.name for k in world.model("m").links] == ["base"]
    assert world.model("m").joints == ()
    (warning,) = warnings
    assert warning.startswith("model_xml:1: links bare, arm left out") and "no mass" in warning


def test_a_floating_joint_makes_no_joint_its_child_is_free():
    world, _, _ = convert(link("a"), joint("float", "a", "b", "floating", "1 0 0"), link("b"))
    assert [k.name for k in world.model("m").links] == ["a", "b"]
    assert world.model("m").joints == ()
    assert links(world)["b"].pose[0] == pytest.approx(1.0)


def test_gazebo_blocks_go_into_the_model_links_collisions_visuals_and_joints():
    blocks = """
    <gazebo><static>true</static><plugin name="p" filename="libgazebo_ros_p3d.so">
      <bodyName>a</bodyName><topicName>odom</topicName></plugin></gazebo>
    <gazebo reference="a"><mu1>0.3</mu1><mu2>0.4</mu2><kp>1e6</kp><kd>10</kd>
      <material>Gazebo/Red</material><selfCollide>true</selfCollide>
      <turnGravityOff>true</turnGravityOff></gazebo>
    <gazebo reference="j"><provideFeedback>true</provideFeedback>
      <implicitSpringDamper>1</implicitSpringDamper></gazebo>"""
    world, _, model = convert(link("a"), joint("j", "a", "b", "revolute", extra=LIMIT),
                              link("b"), blocks)
    assert world.model("m").static is True
    assert model.find("plugin/bodyName").text == "a"
    assert [p.model for p in world.model_plugins] == ["m"]
    a = model.find("link")
    collision = a.find("collision")
    assert collision.find("surface/friction/ode/mu").text == "0.3"
    assert collision.find("surface/friction/ode/mu2").text == "0.4"
    assert collision.find("surface/contact/ode/kp").text == "1e6"
    assert collision.find("surface/contact/ode/kd").text == "10"
    assert world.shape("m::a::a_collision").mu == 0.3
    assert a.find("visual/material/script/name").text == "Gazebo/Red"
    assert world.shape("m::a::a_visual").rgba == (1.0, 0.0, 0.0, 1.0)
    assert (a.find("gravity").text, a.find("self_collide").text) == ("false", "1")
    b = model.findall("link")[1]                  # the other link takes none of it
    assert b.find("collision/surface") is None and b.find("gravity") is None
    j = model.find("joint")
    assert j.find("physics/provide_feedback").text == "true"
    assert j.find("physics/ode/implicit_spring_damper").text == "true"


CAMERA = """<gazebo reference="cam"><sensor type="camera" name="eye">
  <pose>%s</pose><update_rate>10</update_rate>
  <camera><horizontal_fov>1</horizontal_fov><image><width>64</width><height>48</height></image>
  <clip><near>0.05</near><far>10</far></clip></camera>
  <plugin name="c" filename="libgazebo_ros_camera.so"><cameraName>eye</cameraName></plugin>
</sensor></gazebo>"""


def test_a_sensor_of_a_link_is_read_as_a_world_models_sensor():
    world, warnings, _ = convert(link("base"), joint("pan", "base", "cam", "revolute", "0 0 1",
                                                     extra=LIMIT),
                                 link("cam"), CAMERA % "0.1 0 0 0 0 0")
    (sensor,) = world.sensors
    assert sensor.link == "m::cam" and sensor.pose == pytest.approx((0.1, 0, 0, 0, 0, 0))
    assert warnings == []


def test_a_lumped_links_sensor_moves_to_the_parent_where_the_link_stood():
    world, warnings, _ = convert(link("base"),
                                 joint("mount", "base", "cam", "fixed", "0.5 0 0.25", "0 0.1 0"),
                                 link("cam", 0.0, shapes=False), CAMERA % "0.1 0 0 0 0 0")
    (sensor,) = world.sensors
    assert sensor.link == "m::base"
    assert sensor.pose == pytest.approx((0.5, 0, 0.25, 0, 0.1, 0))   # as Gazebo 11 puts it
    (warning,) = warnings
    assert "<sensor> 'eye': its <pose> in link 'cam' is dropped" in warning
    world, warnings, _ = convert(link("base"), joint("mount", "base", "cam", "fixed", "0.5 0 0"),
                                 link("cam", 0.0, shapes=False), CAMERA % "0 0 0 0 0 0")
    assert warnings == [] and world.sensors[0].pose == pytest.approx((0.5, 0, 0, 0, 0, 0))


def test_a_lumped_links_extensions_go_to_its_collisions_only():
    world, _, model = convert(link("base"), joint("mount", "base", "pad", "fixed", "0 0 -0.1"),
                              link("pad"), '<gazebo reference="pad"><mu1>0.05</mu1></gazebo>')
    assert world.shape("m::base::base_fixed_joint_lump__pad_collision_1").mu == 0.05
    assert world.shape("m::base::base_collision").mu == 1.0


def test_missing_meshes_stay_left_out_and_meshes_keep_file_and_scale(tmp_path):
    mesh = tmp_path / "cube.obj"
    mesh.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 2 4\nf 1 3 4\nf 2 3 4\n")
    shape = '<geometry><mesh filename="%s" scale="2 2 2"/></geometry>'
    text = ('<robot name="r"><link name="a">%s<collision>%s</collision><visual>%s</visual>'
            '</link></robot>' % (inertial(), shape % mesh, shape % (tmp_path / "gone.stl")))
    description = read_urdf_text(text, "model_xml")
    sdf, _ = urdf_to_sdf(description)
    world = load_model_xml(sdf, "model_xml", "m")
    (collision,) = world.shapes
    assert collision.mesh == str(mesh) and collision.size == (2.0, 2.0, 2.0)
    assert len(description.warnings) == 1 and "gone.stl" in description.warnings[0]
