"""Every number that enters the world is used or refused in one line naming the field and the
limit (sim/limits), on every path: SDF, URDF, the spawn pose, the world API's services, the
physics properties, cmd_vel. With the real pybullet physics, no ROS master."""
import math

import numpy as np
import pytest

from tutorial_turtlebot.errors import UserError
from tutorial_turtlebot.sim.files import limits
from tutorial_turtlebot.sim.devices.diff_drive import SAFE_ANGULAR, SAFE_LINEAR, sanitize_command
from tutorial_turtlebot.sim.world.physics_properties import OdeConfig, PhysicsProperties
from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
from tutorial_turtlebot.sim.files.urdf.urdf_file import read_urdf_text
from tutorial_turtlebot.sim.world.world_control import RequestError, WorldControl
from tutorial_turtlebot.sim.files.sdf.world_sdf import load_model_xml

from unit_helpers import CUBE, ROBOT, at, run

NAN = float("nan")
REST = ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0))


def urdf(mass="1", ixx="1", size="1 1 1", xyz="0 0 0"):
    return ('<robot name="u"><link name="l"><inertial><origin xyz="%s"/><mass value="%s"/>'
            '<inertia ixx="%s" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>'
            '<collision><geometry><box size="%s"/></geometry></collision></link></robot>'
            % (xyz, mass, ixx, size))


def sdf_box(size="0.2 0.2 0.2", mass="2", pose="0 0 0 0 0 0"):
    return ("<sdf version='1.6'><model name='x'><pose>%s</pose><link name='link'><inertial>"
            "<mass>%s</mass></inertial><collision name='c'><geometry><box><size>%s</size>"
            "</box></geometry></collision></link></model></sdf>" % (pose, mass, size))


@pytest.fixture(scope="module")
def world():
    sim = Simulation(SimConfig(model="burger", world="empty"))
    wc = WorldControl(sim)
    wc.spawn("box", CUBE, at(2, 2, 0.075))
    yield sim, wc
    sim.close()


def physics(**ode):
    return PhysicsProperties(ode=OdeConfig(**ode))


# (what is sent, the field its refusal names); the list first
REFUSED = [
    ("twist 1e200", lambda wc: wc.set_model_state(ROBOT, at(0, 0), ((1e200, 0, 0), (0, 0, 0))),
     "twist.linear.x"),
    ("twist 1e308", lambda wc: wc.set_model_state(ROBOT, at(0, 0), ((0, 0, 0), (0, 0, 1e308))),
     "twist.angular.z"),
    ("spawn at 1e308", lambda wc: wc.spawn("far", sdf_box(), ((1e308, 0, 0), (0, 0, 0, 1))),
     "initial_pose.position.x"),
    ("SDF mass 1e308", lambda wc: wc.spawn("heavy", sdf_box(mass="1e308"), at(1, 1, 0.1)),
     "<mass>"),
    ("URDF mass -1", lambda wc: wc.spawn("u", urdf(mass="-1"), at(1, 1, 1), kind="urdf"),
     "mass"),
    ("URDF mass NaN", lambda wc: wc.spawn("u", urdf(mass="nan"), at(1, 1, 1), kind="urdf"),
     "mass"),
    ("URDF inertia -1", lambda wc: wc.spawn("u", urdf(ixx="-1"), at(1, 1, 1), kind="urdf"),
     "ixx"),
    ("URDF inertia NaN", lambda wc: wc.spawn("u", urdf(ixx="nan"), at(1, 1, 1), kind="urdf"),
     "ixx"),
    ("URDF box NaN", lambda wc: wc.spawn("u", urdf(size="nan 1 1"), at(1, 1, 1), kind="urdf"),
     "size"),
    ("URDF box -1", lambda wc: wc.spawn("u", urdf(size="-1 1 1"), at(1, 1, 1), kind="urdf"),
     "size"),
    ("SDF box 1e308", lambda wc: wc.spawn("big", sdf_box(size="1e308 1 1"), at(1, 1, 0.5)),
     "<size>"),
    ("sor_pgs_iters 4294967295",
     lambda wc: wc.set_physics_properties(physics(sor_pgs_iters=4294967295)), "sor_pgs_iters"),
    # and the other paths
    ("set_model_state at 1e308",
     lambda wc: wc.set_model_state(ROBOT, ((1e308, 0, 0), (0, 0, 0, 1)), REST),
     "pose.position.x"),
    ("set_link_state twist 1e308",
     lambda wc: wc.set_link_state("box::link", at(2, 2, 0.1), ((0, 1e308, 0), (0, 0, 0))),
     "twist.linear.y"),
    ("set_model_state in a frame, lands beyond",
     lambda wc: wc.set_model_state(ROBOT, ((0, 9e5, 0), (0, 0, 0, 1)), REST, "box")
     if wc.set_model_state("box", ((0, 9e5, 0.075), (0, 0, 0, 1)), REST) is None else None,
     "pose.position (in the world).y"),
    ("URDF origin 1e308",
     lambda wc: wc.spawn("u", urdf(xyz="1e308 0 0"), at(1, 1, 1), kind="urdf"), "xyz"),
    ("SDF pose 1e308",
     lambda wc: wc.spawn("p", sdf_box(pose="0 0 1e308 0 0 0"), at(1, 1, 0.1)), "<pose>"),
    ("wrench 1e300", lambda wc: wc.apply_body_wrench("box::link", "", (0, 0, 0),
                                                     (1e300, 0, 0), (0, 0, 0)),
     "wrench.force.x"),
    ("torque 1e7", lambda wc: wc.apply_body_wrench("box::link", "", (0, 0, 0), (0, 0, 0),
                                                   (0, 0, 1e7)), "wrench.torque.z"),
    ("wrench point 1e300", lambda wc: wc.apply_body_wrench("box::link", "", (1e300, 0, 0),
                                                           (1, 0, 0), (0, 0, 0)),
     "reference_point.x"),
    ("wrench duration NaN", lambda wc: wc.apply_body_wrench("box::link", "", (0, 0, 0),
                                                            (1, 0, 0), (0, 0, 0), 0, NAN),
     "duration"),
    ("effort 1e300", lambda wc: wc.apply_joint_effort("wheel_left_joint", 1e300), "effort"),
    ("link mass 1e308", lambda wc: wc.set_link_properties(
        "box::link", wc.get_link_properties("box::link").com, True, 1e308,
        wc.get_link_properties("box::link").inertia), "mass"),
    ("link inertia 1e308", lambda wc: wc.set_link_properties(
        "box::link", wc.get_link_properties("box::link").com, True, 1.0,
        (1e308, 0, 0, 1e308, 0, 1e308)), "ixx"),
    ("joint position 1e300", lambda wc: wc.set_model_configuration(
        ROBOT, ["wheel_left_joint"], [1e300]), "joint_positions[0]"),
    ("gravity 1e300", lambda wc: wc.set_physics_properties(
        PhysicsProperties(gravity=(0.0, 0.0, -1e300))), "gravity.z"),
    ("erp 2", lambda wc: wc.set_physics_properties(physics(erp=2.0)), "erp"),
    ("max_contacts 4294967295",
     lambda wc: wc.set_physics_properties(physics(max_contacts=4294967295)), "max_contacts"),
]


@pytest.mark.parametrize("label, send, field", REFUSED, ids=[r[0] for r in REFUSED])
def test_a_number_beyond_its_limit_is_refused_in_one_line_naming_it(world, label, send, field):
    sim, wc = world
    with pytest.raises(RequestError) as err:
        send(wc)
    message = str(err.value)
    assert field in message and "\n" not in message, message
    assert "outside" in message or "must be positive" in message, message
    wc.set_model_state("box", at(2, 2, 0.075), REST)
    run(sim, 0.05)
    for name, pose, twist in wc.model_states():
        assert all(math.isfinite(v) for v in pose[0] + pose[1] + twist[0] + twist[1]), name
    assert sim.physics_properties.ode.sor_pgs_iters == 20
    assert "u" not in sim.models and "far" not in sim.models and "big" not in sim.models


@pytest.mark.parametrize("component", [1e155, 1e200, 1e308])
def test_a_huge_quaternion_is_normalised_without_overflow(world, component):
    sim, wc = world
    for q in ((component, 0, 0, component), (0, 0, component, component * 0.5)):
        wc.set_model_state(ROBOT, ((0, 0, 0.3), q), REST)
        expected = np.array(q, dtype=float) / max(q)
        expected /= np.linalg.norm(expected)
        pose, _, _ = wc.get_model_state(ROBOT)
        assert np.allclose(np.abs(np.dot(pose[1], expected)), 1.0, atol=1e-6)
        run(sim, 0.2)
        pose, twist, _ = wc.get_model_state(ROBOT)
        assert all(math.isfinite(v) for v in pose[0] + pose[1] + twist[0] + twist[1])
    sim.reset_world()


def test_quaternions_nan_refused_zero_is_identity():
    assert limits.unit_quaternion((0, 0, 0, 0)) == (0.0, 0.0, 0.0, 1.0)
    assert limits.unit_quaternion((0.0, 0.0, 2.0, 2.0)) == pytest.approx(
        (0.0, 0.0, math.sqrt(0.5), math.sqrt(0.5)))
    assert limits.unit_quaternion((1e308, 1e308, 1e308, 1e308)) == pytest.approx((0.5,) * 4)
    for bad in ((NAN, 0, 0, 1), (math.inf, 0, 0, 1)):
        with pytest.raises(ValueError, match="orientation"):
            limits.unit_quaternion(bad)


@pytest.mark.parametrize("linear, angular", [(1e9, 0.0), (0.0, -1e9), (1e308, 1e308)])
def test_cmd_vel_of_1e9_is_clamped(linear, angular):
    out_linear, out_angular, problems = sanitize_command(linear, angular, SAFE_LINEAR,
                                                         SAFE_ANGULAR)
    assert abs(out_linear) <= SAFE_LINEAR and abs(out_angular) <= SAFE_ANGULAR
    assert problems


def test_sdf_and_urdf_word_the_same_fault_alike():
    """A size, mass or inertia beyond the limit reads the same in SDF and URDF."""
    cases = [("size", sdf_box(size="-1 1 1"), urdf(size="-1 1 1"),
              "-1 must be positive, at most 10000 m"),
             ("size", sdf_box(size="1e308 1 1"), urdf(size="1e308 1 1"),
              "1e+308 must be positive, at most 10000 m"),
             ("mass", sdf_box(mass="1e308"), urdf(mass="1e308"), "1e+308 "),
             ]
    for field, sdf, robot, phrase in cases:
        with pytest.raises(UserError) as sdf_err:
            load_model_xml(sdf, "model_xml", "m")
        with pytest.raises(UserError) as urdf_err:
            read_urdf_text(robot, "model_xml")
        assert phrase in str(sdf_err.value) and phrase in str(urdf_err.value)
        assert field in str(sdf_err.value) and field in str(urdf_err.value)
    with pytest.raises(UserError, match="<mass> 0 must be positive"):
        load_model_xml(sdf_box(mass="0"), "model_xml", "m")
    read_urdf_text(urdf(mass="0", ixx="0"), "model_xml")   # a bare frame, as ROS allows


def test_urdf_mass_0_stays_allowed_and_sane_values_pass(world):
    _, wc = world
    wc.spawn("light", urdf(mass="0.5"), at(-2, -2, 0.6), kind="urdf")
    wc.delete("light")


@pytest.mark.parametrize("links", [100, 200])
def test_a_long_one_line_urdf_spawns(world, links):
    sim, wc = world
    text = "".join('<link name="l%d"><inertial><mass value="0.1"/><inertia ixx="0.001" '
                   'iyy="0.001" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial><collision>'
                   '<geometry><box size="0.05 0.05 0.05"/></geometry></collision></link>' % i
                   for i in range(links))
    text += "".join('<joint name="j%d" type="fixed"><parent link="l%d"/><child link="l%d"/>'
                    '<origin xyz="0.06 0 0"/></joint>' % (i, i - 1, i) for i in range(1, links))
    xml = '<robot name="chain">%s</robot>' % text
    assert "\n" not in xml and len(xml) > 30000
    wc.spawn("chain", xml, at(-3, 3, 0.5), kind="urdf")
    run(sim, 0.1)
    assert wc.get_model_state("chain")[0][0][2] < 0.5
    wc.delete("chain")


def test_limits_phrasing():
    assert limits.outside("x", 1, 0, 2) is None
    assert limits.outside("mass", -1.0, 0.0, 1e6, "kg", low_open=True) == \
        "mass -1 must be positive, at most 1e+06 kg"
    assert limits.outside("erp", 2.0, 0.0, 1.0) == "erp 2 is outside [0, 1]"
    assert limits.outside("v", "zero", 0, 1) == "v 'zero' is outside [0, 1]"
    assert limits.scale_problem((1, 0, 1)) == "scale 0 must not be zero"


@pytest.mark.parametrize("attributes, field", [
    ('lower="-1e308" upper="1"', "lower -1e+308 is outside"),
    ('lower="0" upper="nan"', "upper='nan' is not a number"),
    ('effort="-5" velocity="1"', "effort -5 is outside [0, 1e+06]"),
    ('effort="1" velocity="1e200"', "velocity 1e+200 is outside [0, 1000]"),
])
def test_urdf_joint_limits_are_checked(attributes, field):
    text = ('<robot name="r"><link name="a"/><link name="b"/><joint name="j" type="revolute">'
            '<parent link="a"/><child link="b"/><axis xyz="0 0 1"/><limit %s/></joint></robot>'
            % attributes)
    with pytest.raises(UserError) as err:
        read_urdf_text(text, "model_xml")
    assert field in str(err.value) and "joint 'j'" in str(err.value)
    assert "\n" not in str(err.value)
    fine = text.replace("<limit %s/>" % attributes,
                        '<limit lower="-1.57" upper="1.57" effort="10" velocity="2"/>')
    assert read_urdf_text(fine, "model_xml").joints["j"].type == "revolute"


# --- names (a 10 MB model_name was once taken, and said again in every model_states) ---------

LONG = "m" * 10_000_000
NAMED = [
    ("spawn model_name", lambda wc: wc.spawn(LONG, sdf_box(), at(1, 1, 0.1)),
     "SpawnModel: Failure - model_name is 10000000 characters, more than the 256 allowed"),
    ("spawn robot_namespace", lambda wc: wc.spawn("r", urdf(), at(1, 1, 1), kind="urdf",
                                                  robot_namespace="n" * 300),
     "SpawnModel: Failure - robot_namespace is 300 characters"),
    ("spawn reference_frame", lambda wc: wc.spawn("r", sdf_box(), at(1, 1, 0.1), LONG),
     "SpawnModel: Failure - reference_frame is 10000000 characters"),
    ("get_model_state", lambda wc: wc.get_model_state(LONG),
     "GetModelState: model_name is 10000000 characters"),
    ("get_model_state relative", lambda wc: wc.get_model_state(ROBOT, LONG),
     "GetModelState: relative_entity_name is 10000000 characters"),
    ("set_model_state frame", lambda wc: wc.set_model_state(ROBOT, at(0, 0), REST, LONG),
     "SetModelState: reference_frame is 10000000 characters"),
    ("get_link_state", lambda wc: wc.get_link_state(LONG), "GetLinkState: link_name is"),
    ("delete_model", lambda wc: wc.delete(LONG), "DeleteModel: model_name is"),
    ("get_model_properties", lambda wc: wc.model_properties(LONG),
     "GetModelProperties: model_name is"),
    ("wrench", lambda wc: wc.apply_body_wrench("box::link", LONG, (0, 0, 0), (1, 0, 0),
                                               (0, 0, 0)), "ApplyBodyWrench: reference_frame"),
    ("joint effort", lambda wc: wc.apply_joint_effort(LONG, 1.0), "ApplyJointEffort: joint_name"),
    ("joint properties", lambda wc: wc.get_joint_properties(LONG),
     "GetJointProperties: joint_name"),
    ("link properties", lambda wc: wc.get_link_properties(LONG), "GetLinkProperties: link_name"),
    ("model configuration", lambda wc: wc.set_model_configuration(ROBOT, ["j", LONG], [0, 0]),
     "SetModelConfiguration: joint_names[1] is 10000000 characters"),
    ("light", lambda wc: wc.get_light(LONG), "getLightProperties: light_name is"),
    ("SDF link name", lambda wc: wc.spawn("r", sdf_box().replace("name='link'",
                                                                 "name='%s'" % ("l" * 300)),
                                          at(1, 1, 0.1)), "<link> name is 300 characters"),
    ("URDF link name", lambda wc: wc.spawn("r", urdf().replace('name="l"', 'name="%s"'
                                                               % ("l" * 300)),
                                           at(1, 1, 1), kind="urdf"),
     "<link>: name is 300 characters, more than the 256 allowed"),
]


@pytest.mark.parametrize("label, send, words", NAMED, ids=[n[0] for n in NAMED])
def test_a_name_longer_than_its_limit_is_refused_in_one_line(world, label, send, words):
    sim, wc = world
    with pytest.raises(RequestError) as err:
        send(wc)
    message = str(err.value)
    assert words in message and "\n" not in message and len(message) < 1000, message[:1000]
    assert "r" not in sim.models and LONG not in sim.models


def test_a_name_of_the_limit_is_taken(world):
    sim, wc = world
    name = "n" * limits.MAX_NAME
    wc.spawn(name, sdf_box(), at(1, -1, 0.1))
    assert wc.model_properties(name).body_names == ["link"]
    wc.delete(name)
