"""set_joint_properties through sim/world_properties (and the Body methods under it in
engine/bodies), with the real pybullet physics: damping slows a joint and get_joint_properties
reports it, the stops hold it, the velocity motor drives it, ODE's own fields are taken and
left, and a bad request is refused in one line with nothing changed. No ROS master."""
import math
import os

import pytest

from tutorial_turtlebot.errors import RequestError
from tutorial_turtlebot.sim.engine.bodies import NO_STOP
from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
from tutorial_turtlebot.sim.world.world_control import WorldControl
from tutorial_turtlebot.sim.world.world_properties import joint_config_problem

from unit_helpers import ROBOT, WHEEL, at, run

with open(os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, os.pardir,
                       os.pardir, "fixtures", "hinge.urdf")) as _f:
    HINGE = _f.read()   # a flap on a vertical revolute joint (stops +-1.5 rad) over a heavy base
# a 0.05 kg disc of radius 0.02 m on a vertical joint of a 1 kg block: 1e-5 kg m^2 about its
# axis, so a damping of 0.02 takes out 5 times its rate in one 2.5 ms step (explicitly: unstable)
LIGHT_WHEEL = """<robot name="light"><link name="block"><inertial><mass value="1"/>
<inertia ixx="0.002" iyy="0.002" izz="0.002" ixy="0" ixz="0" iyz="0"/></inertial>
<collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
<joint name="axle" type="continuous"><parent link="block"/><child link="disc"/>
<origin xyz="0 0 0.08"/><axis xyz="0 0 1"/></joint>
<link name="disc"><inertial><mass value="0.05"/>
<inertia ixx="0.000005" iyy="0.000005" izz="0.00001" ixy="0" ixz="0" iyz="0"/></inertial>
</link></robot>"""


@pytest.fixture
def world():
    """An empty world without a robot, and the world API over it: (sim, wc)."""
    sim = Simulation(SimConfig(world="empty", spawn_robot=False))
    yield sim, WorldControl(sim)
    sim.close()


def joint(wc, name):
    props = wc.get_joint_properties(name)
    return props.damping[0], props.position[0], props.rate[0]


# --- damping ---------------------------------------------------------------------------------

def test_damping_is_reported_and_holds_the_joint_to_effort_over_damping(world):
    """The disc (0.02 kg m^2 about its axis) under 0.02 N m: free, 1 rad/s^2; damped by
    0.1 N m s/rad, it settles at 0.02 / 0.1 = 0.2 rad/s."""
    sim, wc = world
    wc.spawn("w", WHEEL, at(0, 0, 0.06), kind="urdf")
    assert joint(wc, "spin")[0] == 0.0
    wc.set_joint_properties("spin", {"damping": [0.1]})
    assert joint(wc, "spin")[0] == 0.1
    assert joint(wc, "w::spin")[0] == 0.1
    wc.apply_joint_effort("spin", 0.02, 0, -1)
    run(sim, 3.0)
    assert joint(wc, "spin")[2] == pytest.approx(0.2, rel=0.05)
    wc.set_joint_properties("spin", {"damping": [0.0]})      # free again: it speeds up
    run(sim, 1.0)
    assert joint(wc, "spin")[2] == pytest.approx(1.2, rel=0.1)


def test_a_damping_too_strong_for_one_step_stops_a_light_joint_instead_of_spinning_it_up(world):
    """pybullet damps explicitly: 0.02 N m s/rad on 1e-5 kg m^2 would take out 5 times the rate
    in a step and spin the disc up to its speed limit; held to what stops it in a step, it
    stops, and get_joint_properties still reports the damping asked."""
    sim, wc = world
    wc.spawn("light", LIGHT_WHEEL, at(0, 0, 0.05), kind="urdf")
    wc.apply_joint_effort("axle", 0.001, 0, 100_000_000)        # 0.1 s: up to ~10 rad/s
    run(sim, 0.1)
    before = abs(joint(wc, "axle")[2])
    assert before > 5.0
    wc.set_joint_properties("axle", {"damping": [0.02]})
    run(sim, 0.5)
    damping, _, rate = joint(wc, "axle")
    assert damping == 0.02
    assert math.isfinite(rate) and abs(rate) < 0.01 * before


# --- stops -------------------------------------------------------------------------------------

def test_stops_hold_the_joint_and_a_side_not_given_keeps_its_stop(world):
    sim, wc = world
    wc.spawn("h", HINGE, at(0, 0, 0.06), kind="urdf")
    wc.set_joint_properties("hinge", {"hiStop": [0.3]})
    wc.apply_joint_effort("hinge", 0.5, 0, -1)
    run(sim, 1.0)
    assert joint(wc, "hinge")[1] == pytest.approx(0.3, abs=0.01)   # the URDF's stop is 1.5
    wc.set_joint_properties("hinge", {"loStop": [-0.2]})         # hiStop stays at 0.3
    run(sim, 0.5)
    assert joint(wc, "hinge")[1] == pytest.approx(0.3, abs=0.01)
    wc.clear_joint_forces("hinge")
    wc.apply_joint_effort("hinge", -0.5, 0, -1)
    run(sim, 1.0)
    assert joint(wc, "hinge")[1] == pytest.approx(-0.2, abs=0.01)
    body = wc.models.get("h").parts[0].body
    assert body.joint_stops(0) == (-0.2, 0.3)


def test_a_joint_without_stops_gets_one_and_keeps_none_on_the_other_side(world):
    sim, wc = world
    wc.spawn("w", WHEEL, at(0, 0, 0.06), kind="urdf")     # "spin" is continuous
    body = wc.models.get("w").parts[0].body
    assert body.joint_stops(0) == (-NO_STOP, NO_STOP)
    wc.set_joint_properties("spin", {"hiStop": [0.5]})
    wc.apply_joint_effort("spin", 0.2, 0, -1)
    run(sim, 1.5)
    assert joint(wc, "spin")[1] == pytest.approx(0.5, abs=0.01)
    wc.clear_joint_forces("spin")
    wc.apply_joint_effort("spin", -0.2, 0, -1)
    run(sim, 3.0)
    assert joint(wc, "spin")[1] < -10.0                      # no stop below


# --- the velocity motor --------------------------------------------------------------------------

def test_vel_and_fmax_drive_the_joint_and_a_side_not_given_keeps_its_value(world):
    sim, wc = world
    wc.spawn("w", WHEEL, at(0, 0, 0.06), kind="urdf")
    wc.set_joint_properties("spin", {"vel": [2.0], "fmax": [1.0]})
    run(sim, 0.5)
    assert joint(wc, "spin")[2] == pytest.approx(2.0, abs=0.01)
    wc.set_joint_properties("spin", {"vel": [-1.0]})          # fmax stays 1 N m
    run(sim, 0.5)
    assert joint(wc, "spin")[2] == pytest.approx(-1.0, abs=0.01)
    wc.set_joint_properties("spin", {"fmax": [0.0]})          # no motor: it coasts
    run(sim, 0.5)
    assert joint(wc, "spin")[2] == pytest.approx(-1.0, abs=0.05)
    wc.set_joint_properties("spin", {"fmax": [0.01]})         # 0.5 rad/s^2 towards -1 rad/s
    wc.set_joint_properties("spin", {"vel": [0.0]})
    run(sim, 1.0)
    assert joint(wc, "spin")[2] == pytest.approx(-0.5, abs=0.05)


def test_odes_own_fields_are_taken_and_change_nothing(world):
    sim, wc = world
    wc.spawn("w", WHEEL, at(0, 0, 0.06), kind="urdf")
    client = sim.physics.client
    wc.set_joint_properties("spin", {"erp": [0.2], "cfm": [1e-5], "stop_erp": [0.2],
                                     "stop_cfm": [0.0], "fudge_factor": [1.0], "damping": []})
    assert client.joints_set == {}
    assert joint(wc, "spin")[0] == 0.0


# --- refusals ------------------------------------------------------------------------------------

@pytest.mark.parametrize("config, words", [
    ({"damping": [float("nan")]}, "^SetJointProperties: ode_joint_config.damping\\[0\\]: NaN or "
                                  "infinite value$"),
    ({"hiStop": [1.0, float("inf")]}, "hiStop\\[1\\]: NaN or infinite"),
    ({"damping": [-0.1]}, "^SetJointProperties: ode_joint_config.damping\\[0\\] -0.1 is outside "
                          "\\[0, 1e\\+06\\] N m s/rad or N s/m$"),
    ({"loStop": [-2e6]}, "loStop\\[0\\] -2e\\+06 is outside \\[-1e\\+06, 1e\\+06\\] rad or m"),
    ({"fmax": [-1.0]}, "fmax\\[0\\] -1 is outside \\[0, 1e\\+06\\] N m or N"),
    ({"vel": [1e4]}, "vel\\[0\\] 10000 is outside \\[-1000, 1000\\] rad/s or m/s"),
    ({"cfm": [float("-inf")]}, "cfm\\[0\\]: NaN or infinite"),
    ({"loStop": [0.5], "hiStop": [0.2]}, "^SetJointProperties: loStop 0.5 is above hiStop 0.2 "
                                         "\\(rad or m\\): the joint would have no range; keep "
                                         "loStop <= hiStop$"),
    ({"loStop": [2.0]}, "loStop 2 is above hiStop 1.5"),        # the URDF's upper stop
])
def test_a_bad_value_is_refused_in_one_line_and_nothing_changes(world, config, words):
    sim, wc = world
    wc.spawn("h", HINGE, at(0, 0, 0.06), kind="urdf")
    wc.set_joint_properties("hinge", {"damping": [0.2]})
    before = dict(sim.physics.client.joints_set)
    with pytest.raises(RequestError, match=words) as err:
        wc.set_joint_properties("hinge", dict(config, damping=config.get("damping", [0.7]),
                                              vel=config.get("vel", [3.0])))
    assert "\n" not in str(err.value)
    assert sim.physics.client.joints_set == before
    assert joint(wc, "hinge")[0] == 0.2


def test_an_unknown_joint_is_gazebos_answer(world):
    _, wc = world
    wc.spawn("h", HINGE, at(0, 0, 0.06), kind="urdf")
    for name in ("elbow", "nobody::hinge", "h::elbow"):
        with pytest.raises(RequestError, match="^SetJointProperties: joint not found$"):
            wc.set_joint_properties(name, {"damping": [1.0]})
    with pytest.raises(RequestError, match="^SetJointProperties: joint_name is 300 characters"):
        wc.set_joint_properties("j" * 300, {})


def test_a_long_array_is_checked_whole_and_only_its_first_element_counts(world):
    _, wc = world
    wc.spawn("h", HINGE, at(0, 0, 0.06), kind="urdf")
    wc.set_joint_properties("hinge", {"damping": [0.3] + [5.0] * 100_000})
    assert joint(wc, "hinge")[0] == 0.3
    assert joint_config_problem({"erp": [0.0] * 99_999 + [float("nan")]}) == (
        "ode_joint_config.erp[99999]: NaN or infinite value")


# --- what lasts, what goes ----------------------------------------------------------------------

def test_a_reset_keeps_what_was_set_and_a_deleted_models_body_comes_back_as_built(world):
    """As in Gazebo, reset_world keeps the joints' settings. A deleted model's body is parked
    for the next spawn of the same text (body_pool): that spawn gets the URDF's joint."""
    sim, wc = world
    wc.spawn("h", HINGE, at(0, 0, 0.06), kind="urdf")
    body = wc.models.get("h").parts[0].body
    wc.set_joint_properties("hinge", {"hiStop": [0.3], "damping": [0.4], "vel": [0.5],
                                      "fmax": [0.2]})
    sim.reset_world()
    wc.apply_joint_effort("hinge", 0.5, 0, -1)
    run(sim, 1.0)
    assert joint(wc, "hinge")[:2] == (0.4, pytest.approx(0.3, abs=0.01))
    wc.delete("h")
    assert sim.physics.client.joints_set == {}
    wc.spawn("h", HINGE, at(0, 0, 0.06), kind="urdf")
    assert wc.models.get("h").parts[0].body == body            # the same body, reused
    assert body.joint_stops(0) == (-1.5, 1.5) and body.joint_motor(0) == (0.0, 0.0)
    wc.apply_joint_effort("hinge", 0.5, 0, -1)
    run(sim, 1.0)
    damping, position, _ = joint(wc, "hinge")
    assert damping == 0.0 and position == pytest.approx(1.5, abs=0.01)


def test_a_robots_wheel_takes_damping_and_its_drive_keeps_its_motor(empty):
    """A TurtleBot3's wheel joint is found as get_joint_properties finds it; the robot's drive
    sets its wheels' motors at every tick, as gazebo_ros_diff_drive does, and still drives."""
    sim, wc = empty
    wc.set_joint_properties("wheel_left_joint", {"damping": [0.01], "vel": [5.0],
                                                 "fmax": [10.0]})
    assert joint(wc, ROBOT + "::wheel_left_joint")[0] == 0.01
    sim.robot.command(0.1, 0.0)
    run(sim, 1.0)
    assert joint(wc, "wheel_left_joint")[2] == pytest.approx(3.03, rel=0.05)
    assert joint(wc, "wheel_right_joint")[0] == 0.0
