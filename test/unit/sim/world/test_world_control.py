"""Link and joint properties, set_model_configuration, the world's lights and Gazebo's collision
names (geom_names) through sim/world_control, with the real pybullet physics. No ROS master."""
import math
import os

import pytest

from tutorial_turtlebot.errors import RequestError
from tutorial_turtlebot.package_data import data_dir
from tutorial_turtlebot.sim.files.urdf.urdf_file import read_urdf, read_urdf_text

from unit_helpers import CUBE, ROBOT, WHEEL, at, box_sdf, run

BURGER_GEOMS = ["base_footprint_fixed_joint_lump__base_link_collision",
                "base_footprint_fixed_joint_lump__caster_back_link_collision_1",
                "base_footprint_fixed_joint_lump__base_scan_collision_2",
                "wheel_left_link_collision", "wheel_right_link_collision"]


# --- geom_names ------------------------------------------------------------------------------

def test_robot_geom_names_are_gazebos_collision_names(empty):
    _, wc = empty
    props = wc.model_properties(ROBOT)
    assert props.geom_names == BURGER_GEOMS
    assert props.body_names == ["base_footprint", "wheel_left_link", "wheel_right_link"]


def test_waffle_geom_names():
    names = read_urdf(os.path.join(data_dir("urdf"), "turtlebot3_waffle.urdf")).collision_names()
    assert names["base_footprint"] == [
        "base_footprint_fixed_joint_lump__base_link_collision",
        "base_footprint_fixed_joint_lump__camera_link_collision_1",
        "base_footprint_fixed_joint_lump__caster_back_left_link_collision_2",
        "base_footprint_fixed_joint_lump__caster_back_right_link_collision_3",
        "base_footprint_fixed_joint_lump__base_scan_collision_4"]


def test_collision_naming_rules():
    urdf = """<robot name="r">
      <link name="base"><collision name="bumper"/><collision/></link>
      <joint name="b_fix" type="fixed"><parent link="base"/><child link="shell"/></joint>
      <joint name="a_fix" type="fixed"><parent link="base"/><child link="base_plate"/></joint>
      <link name="shell"><collision/></link>
      <link name="base_plate"><collision/></link>
      <joint name="arm" type="continuous"><parent link="shell"/><child link="arm_link"/></joint>
      <link name="arm_link"><collision/><collision/></link>
    </robot>"""
    shape = '<geometry><sphere radius="0.1"/></geometry></collision>'
    urdf = urdf.replace('"bumper"/>', '"bumper">' + shape).replace("<collision/>",
                                                                   "<collision>" + shape)
    # base's own two, then its fixed children in joint-name order (a_fix before b_fix); a name
    # that starts with the holding link's name is not prefixed (base_plate), as sdformat does
    assert read_urdf_text(urdf, "r").collision_names() == {
        "base": ["base_fixed_joint_lump__bumper_collision", "base_collision_1",
                 "base_plate_collision_2", "base_fixed_joint_lump__shell_collision_3"],
        "arm_link": ["arm_link_collision", "arm_link_collision_1"]}


def test_spawned_urdf_geom_names(empty):
    _, wc = empty
    wc.spawn("w", WHEEL, at(1.5, 0, 0.06), kind="urdf")
    props = wc.model_properties("w")
    assert props.geom_names == ["base_collision", "disc_collision"]
    assert props.joint_names == ["spin"]


# --- link properties -------------------------------------------------------------------------

def test_link_properties_get_and_set(empty):
    sim, wc = empty
    wc.spawn("box", CUBE, at(2, 2, 0.075))
    p = wc.get_link_properties("box::link")
    assert p.mass == pytest.approx(2.0)
    assert p.gravity_mode is True
    assert p.com == pytest.approx((0, 0, 0), abs=1e-6)
    assert p.inertia == pytest.approx((0.0075, 0, 0, 0.0075, 0, 0.0075), abs=1e-9)
    wc.set_link_properties("box::link", p.com, True, 3.0, (0.01, 0, 0, 0.02, 0, 0.03))
    q = wc.get_link_properties("box::link")
    assert q.mass == pytest.approx(3.0)
    assert q.inertia == pytest.approx((0.01, 0, 0, 0.02, 0, 0.03), abs=1e-9)
    # the robot's root link holds every lumped link's mass; its centre of mass is off its frame
    base = wc.get_link_properties(ROBOT + "::base_footprint")
    wheel = wc.get_link_properties(ROBOT + "::wheel_left_link")
    assert 0.5 < base.mass < 1.5 and 0.0 < wheel.mass < 0.1
    assert base.com[2] > 0.01
    wc.set_link_properties(ROBOT + "::base_footprint", base.com, True, base.mass * 1.5,
                           base.inertia)
    assert wc.get_link_properties(ROBOT + "::base_footprint").mass == pytest.approx(
        base.mass * 1.5)
    run(sim, 0.2)


def test_link_property_refusals(empty):
    _, wc = empty
    wc.spawn("box", CUBE, at(2, 2, 0.075))
    p = wc.get_link_properties("box::link")
    cases = [
        (lambda: wc.get_link_properties("box"), "GetLinkProperties: link not found, did you "
                                                "forget to scope the link by model name"),
        (lambda: wc.set_link_properties("box::nolink", p.com, True, 1.0, p.inertia),
         "SetLinkProperties: link not found"),
        (lambda: wc.set_link_properties("box::link", p.com, True, -1.0, p.inertia),
         "SetLinkProperties: mass -1 kg must be > 0"),
        (lambda: wc.set_link_properties("box::link", p.com, True, 0.0, p.inertia),
         "must be > 0"),
        (lambda: wc.set_link_properties("box::link", p.com, True, float("nan"), p.inertia),
         "NaN or infinite"),
        (lambda: wc.set_link_properties("box::link", p.com, True, 1.0, (1, 0, 0, -1, 0, 1)),
         "positive definite"),
        (lambda: wc.set_link_properties("box::link", (0.1, 0, 0), True, 1.0, p.inertia),
         "the centre of mass cannot be moved here"),
        (lambda: wc.set_link_properties("box::link", p.com, True, 1.0,
                                        (0.01, 0.002, 0, 0.01, 0, 0.01)),
         "products of inertia"),
        (lambda: wc.set_link_properties("ground_plane::link", (0, 0, 0), True, 1.0, p.inertia),
         "static"),
    ]
    for call, words in cases:
        with pytest.raises(RequestError, match=words) as err:
            call()
        assert "\n" not in str(err.value)
    assert wc.get_link_properties("box::link") == p    # nothing changed
    static = wc.get_link_properties("ground_plane::link")
    assert static.mass == 0.0 and static.gravity_mode is True


# --- joints --------------------------------------------------------------------------------

def test_joint_properties(empty):
    sim, wc = empty
    run(sim, 0.1)
    j = wc.get_joint_properties("wheel_left_joint")
    assert j.kind == "revolute"
    assert len(j.damping) == len(j.position) == len(j.rate) == 1
    assert abs(j.position[0]) < 0.05 and abs(j.rate[0]) < 0.1
    assert wc.get_joint_properties(ROBOT + "::wheel_right_joint").kind == "revolute"
    sim.robot.command(0.1, 0.0)
    run(sim, 1.0)          # 0.1 m/s on 0.033 m wheels: 3 rad/s
    assert wc.get_joint_properties("wheel_left_joint").rate[0] == pytest.approx(3.03, rel=0.05)
    with pytest.raises(RequestError, match="^GetJointProperties: joint not found$"):
        wc.get_joint_properties("elbow")
    with pytest.raises(RequestError, match="joint not found"):
        wc.get_joint_properties("nobody::wheel_left_joint")


HINGED_SDF = ("<sdf version='1.6'><model name='x'><link name='frame'><collision name='c'>"
              "<geometry><box><size>0.4 0.4 0.1</size></box></geometry></collision></link>"
              "<link name='door'><pose>0 0 0.3 0 0 0</pose><collision name='c'><geometry><box>"
              "<size>0.4 0.05 0.4</size></box></geometry></collision></link>"
              "<joint name='hinge' type='revolute'><parent>frame</parent><child>door</child>"
              "<axis><xyz>0 0 1</xyz></axis></joint>"
              "<joint name='weld' type='fixed'><parent>frame</parent><child>door</child></joint>"
              "</model></sdf>")


def test_an_sdf_joint_that_get_model_properties_lists_has_properties(empty):
    """An SDF model's joints are listed; the hinge is simulated, the weld that gives the door
    a second parent is left out of the tree (listed, still, at its <joint type>)."""
    sim, wc = empty
    wc.spawn("cabinet", HINGED_SDF, at(2, 2, 0.05))
    assert wc.model_properties("cabinet").joint_names == ["hinge", "weld"]
    for name, kind in (("hinge", "revolute"), ("cabinet::hinge", "revolute"),
                       ("cabinet::weld", "fixed")):
        j = wc.get_joint_properties(name)
        assert (j.kind, j.damping, j.position, j.rate) == (kind, [0.0], [0.0], [0.0])
    wc.apply_joint_effort("cabinet::hinge", 0.5, 0, int(0.2e9))
    run(sim, 0.3)
    assert wc.get_joint_properties("cabinet::hinge").position[0] > 0.01     # it swings
    assert wc.get_joint_properties("cabinet::weld").position == [0.0]
    with pytest.raises(RequestError, match="^GetJointProperties: joint not found$"):
        wc.get_joint_properties("cabinet::elbow")


def test_set_model_configuration(empty):
    sim, wc = empty
    run(sim, 0.51)         # standing still a while (off the 30 Hz control ticks)
    status = wc.set_model_configuration(ROBOT, ["wheel_left_joint", "wheel_right_joint"],
                                        [1.0, -2.0])
    assert status == "SetModelConfiguration: success"
    assert wc.get_joint_properties("wheel_left_joint").position == [pytest.approx(1.0)]
    assert wc.get_joint_properties("wheel_right_joint").position == [pytest.approx(-2.0)]
    (x, y, _), _ = sim.robot.ground_truth()
    run(sim, 0.5)
    (x1, y1, _), _ = sim.robot.ground_truth()
    assert math.hypot(x1 - x, y1 - y) < 0.01     # the robot stays; its wheels were turned
    # and they stay turned (an idle robot's drive holds them where they are)
    assert wc.get_joint_properties("wheel_left_joint").position[0] == pytest.approx(1.0, abs=0.05)
    assert wc.get_joint_properties("wheel_right_joint").position[0] == pytest.approx(-2.0,
                                                                                     abs=0.05)
    wc.spawn("w", WHEEL, at(1.5, 0, 0.06), kind="urdf")
    wc.set_model_configuration("w", ["spin"], [0.7])
    run(sim, 0.5)
    assert wc.get_joint_properties("spin").position[0] == pytest.approx(0.7, abs=0.01)
    # names the model does not have are ignored, as Gazebo does, and named in the answer
    status = wc.set_model_configuration("w", ["spin", "base_joint"], [0.2, 0.3])
    assert status.startswith("SetModelConfiguration: success")
    assert "base_joint" in status and "\n" not in status
    assert wc.get_joint_properties("spin").position[0] == pytest.approx(0.2)
    # wheel_left_joint is the robot's, not w's
    assert "wheel_left_joint" in wc.set_model_configuration("w", ["wheel_left_joint"], [3.0])
    assert wc.get_joint_properties("wheel_left_joint").position[0] != pytest.approx(3.0)


def test_set_model_configuration_refusals(empty):
    _, wc = empty
    for call, words in [
            (lambda: wc.set_model_configuration("nobody", ["a"], [1.0]),
             "^SetModelConfiguration: model does not exist$"),
            (lambda: wc.set_model_configuration(ROBOT, ["wheel_left_joint"], [1.0, 2.0]),
             "^SetModelConfiguration: joint name and position list have different lengths$"),
            (lambda: wc.set_model_configuration(ROBOT, ["wheel_left_joint"], [float("nan")]),
             "NaN or infinite")]:
        with pytest.raises(RequestError, match=words):
            call()
    assert abs(wc.get_joint_properties("wheel_left_joint").position[0]) < 0.05


# --- lights --------------------------------------------------------------------------------

def test_lights_get_and_set(empty):
    _, wc = empty
    sun = wc.get_light("sun")
    assert sun.diffuse == (0.8, 0.8, 0.8, 1.0)
    assert (sun.attenuation_constant, sun.attenuation_linear,
            sun.attenuation_quadratic) == (0.9, 0.01, 0.001)
    wc.set_light("sun", False, (0.1, 0.2, 0.3, 1.0), (0.5, 0.5, 0.5, 1.0), (0.5, 0.02, 0.0),
                 (0.0, 0.0, -1.0), ((1.0, 2.0, 20.0), (0.0, 0.0, 0.0, 0.0)))
    sun = wc.get_light("sun")
    assert sun.diffuse == (0.1, 0.2, 0.3, 1.0) and sun.cast_shadows is False
    assert (sun.attenuation_constant, sun.attenuation_linear) == (0.5, 0.02)
    assert sun.pose == ((1.0, 2.0, 20.0), (0.0, 0.0, 0.0, 1.0))   # all-zero: identity
    with pytest.raises(RequestError, match="^getLightProperties: Requested light moon not "
                                           "found!$"):
        wc.get_light("moon")
    with pytest.raises(RequestError, match="^setLightProperties: Requested light moon not "
                                           "found!$"):
        wc.set_light("moon", False, (1, 1, 1, 1), (1, 1, 1, 1), (1, 0, 0), (0, 0, -1),
                     ((0, 0, 0), (0, 0, 0, 1)))
    with pytest.raises(RequestError, match="NaN or infinite"):
        wc.set_light("sun", False, (float("nan"), 1, 1, 1), (1, 1, 1, 1), (1, 0, 0),
                     (0, 0, -1), ((0, 0, 0), (0, 0, 0, 1)))
    assert wc.get_light("sun").diffuse == (0.1, 0.2, 0.3, 1.0)


# --- deleted models' bodies: parked for reuse, a bounded number of them ---------------------------

def test_parked_bodies_are_bounded_and_the_newest_reused(empty):
    """Spawning and deleting 100 boxes of distinct sizes leaves at most MAX_PARKED_BODIES bodies
    waiting (each costs every step); the last text deleted is built again from its parked body."""
    from tutorial_turtlebot.sim.engine.bullet import pybullet
    from tutorial_turtlebot.sim.engine.body_pool import MAX_PARKED_BODIES
    sim, wc = empty
    cid = sim.physics.client
    before = pybullet.getNumBodies(physicsClientId=cid)
    for k in range(100):
        wc.spawn("box%d" % k, box_sdf(size=0.1 + k * 1e-3), at(3.0, 3.0, 0.5))
        wc.delete("box%d" % k)
    pool = sim.physics.body_pool
    assert pool.parked_bodies == MAX_PARKED_BODIES
    assert pybullet.getNumBodies(physicsClientId=cid) == before + MAX_PARKED_BODIES
    wc.spawn("again", box_sdf(size=0.1 + 99e-3), at(3.0, 3.0, 0.5))   # the newest text
    assert pool.parked_bodies == MAX_PARKED_BODIES - 1
    assert pybullet.getNumBodies(physicsClientId=cid) == before + MAX_PARKED_BODIES
    wc.spawn("first", box_sdf(size=0.1), at(-3.0, 3.0, 0.5))            # removed long ago
    assert pybullet.getNumBodies(physicsClientId=cid) == before + MAX_PARKED_BODIES + 1


def test_a_spawned_models_texture_warnings_are_returned_to_be_logged(empty, monkeypatch):
    """A textured crate spawned into a texture budget of 300 px: its image is halved, and the
    line that says so comes back from spawn (the world API logs it), not lost."""
    import unit_paths
    from tutorial_turtlebot.sim.engine import texture_budget
    monkeypatch.setenv("GAZEBO_MODEL_PATH", os.path.join(unit_paths.FIXTURES, "gazebo_models"))
    monkeypatch.setattr(texture_budget, "MAX_TEXTURE_PIXELS", 300)
    sim, wc = empty
    xml = ('<sdf version="1.6"><model name="c"><include><uri>model://max_style_crate</uri>'
           '</include></model></sdf>')
    [line] = wc.spawn("crate", xml, at(2.0, 2.0, 0.5))
    assert "texture budget of 300 px" in line and len(line) <= 200
    assert wc.spawn("box", box_sdf(), at(-2.0, 2.0, 0.5)) == []


@pytest.mark.parametrize("bad", [(math.nan, 0, 0, 1), (0, 0, 0, math.inf), (0, -math.inf, 0, 1)])
def test_a_nan_or_infinite_orientation_is_refused_in_every_field(empty, bad):
    """Every request field that is an orientation: set_model_state and set_link_state poses,
    a spawn's pose, set_link_properties' com orientation (otherwise ignored, as Gazebo
    ignores it), set_light_properties' pose: one line, nothing changed."""
    sim, wc = empty
    wc.spawn("box", CUBE, at(2, 2, 0.075))
    before = wc.get_model_state("box")[0]
    zero = ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0))
    link = wc.get_link_properties("box::link")
    light = next(iter(wc.lights()))
    for call in (lambda: wc.set_model_state("box", ((2, 2, 0.075), bad), zero),
                 lambda: wc.set_link_state("box::link", ((2, 2, 0.075), bad), zero),
                 lambda: wc.spawn("other", CUBE, ((1, 1, 0.1), bad)),
                 lambda: wc.set_link_properties("box::link", link.com, True, 2.0, link.inertia,
                                                com_orientation=bad),
                 lambda: wc.set_light(light, True, (1, 1, 1, 1), (0.1, 0.1, 0.1, 1),
                                      (0.9, 0.01, 0.001), (0, 0, -1), ((0, 0, 10), bad))):
        with pytest.raises(RequestError) as caught:
            call()
        assert "\n" not in str(caught.value)
    assert "other" not in sim.models
    assert wc.get_model_state("box")[0] == before
    assert wc.get_link_properties("box::link").mass == pytest.approx(2.0)
