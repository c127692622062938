"""Body wrenches, joint efforts and weightless links (sim/applied_forces through
world_control's apply_body_wrench / apply_joint_effort) with the real pybullet physics in the
empty world. No ROS master."""
import math

import pytest

from tutorial_turtlebot.errors import RequestError

from unit_helpers import ROBOT, WHEEL, at, box_sdf, run

NS = 1_000_000_000
MASS = 2.0
SIZE = 0.15
IZZ = MASS * SIZE * SIZE / 6       # a solid cube: 0.0075 kg m^2
BOX = box_sdf(SIZE, MASS, visual=False)


def weightless(wc, link, on=False):
    """Switch gravity off (or on) for ``link``, keeping its mass and inertia."""
    p = wc.get_link_properties(link)
    wc.set_link_properties(link, p.com, on, p.mass, p.inertia)


@pytest.fixture
def floating_box(empty):
    """A 2 kg box 1 m above the floor, gravity off: nothing touches it."""
    sim, wc = empty
    wc.spawn("box", BOX, at(2, 2, 1.0))
    weightless(wc, "box::link")
    return sim, wc


def state(wc, name="box"):
    pose, twist, _ = wc.get_model_state(name)
    return pose, twist


def test_nothing_to_apply_costs_one_check(empty):
    sim, _ = empty
    assert sim.forces.active is False
    run(sim, 0.1)
    assert sim.forces.active is False


def test_a_wrench_moves_a_free_box_as_f_equals_ma_and_stops_after_its_duration(floating_box):
    sim, wc = floating_box
    x0 = state(wc)[0][0][0]
    wc.apply_body_wrench("box::link", "", (0, 0, 0), (4.0, 0, 0), (0, 0, 0), 0, NS // 2)
    run(sim, 0.5)                             # a = F/m = 2 m/s^2 for 0.5 s
    (pos, _), (lin, ang) = state(wc)
    assert pos[0] - x0 == pytest.approx(0.5 * 2.0 * 0.25, rel=0.03)
    assert lin[0] == pytest.approx(1.0, rel=0.01)
    assert pos[2] == pytest.approx(1.0, abs=1e-3)     # weightless: it stays up
    assert max(abs(w) for w in ang) < 1e-6            # through the centre of mass: no turn
    run(sim, 0.5)                             # ended: it coasts at 1 m/s
    (pos, _), (lin, _) = state(wc)
    assert lin[0] == pytest.approx(1.0, rel=0.01)
    assert pos[0] - x0 == pytest.approx(0.25 + 0.5, rel=0.03)
    assert sim.forces.wrenches == [] and sim.forces.active is True   # still weightless


def test_until_cleared(floating_box):
    sim, wc = floating_box
    wc.apply_body_wrench("box::link", "world", (0, 0, 0), (0, 2.0, 0), (0, 0, 0), 0, -NS)
    run(sim, 0.25)
    assert state(wc)[1][0][1] == pytest.approx(0.25, rel=0.02)
    assert wc.clear_body_wrenches("box::link") == 1
    assert wc.clear_body_wrenches("box::link") == 0
    assert wc.clear_body_wrenches("no::such") == 0
    run(sim, 0.25)
    assert state(wc)[1][0][1] == pytest.approx(0.25, rel=0.02)


def test_a_torque_turns_the_box(floating_box):
    sim, wc = floating_box
    wc.apply_body_wrench("box::link", "", (0, 0, 0), (0, 0, 0), (0, 0, 0.015), 0, NS // 2)
    run(sim, 0.5)                             # alpha = 0.015 / 0.0075 = 2 rad/s^2
    _, (lin, ang) = state(wc)
    assert ang[2] == pytest.approx(1.0, rel=0.02)
    assert max(abs(v) for v in lin) < 1e-6


def test_the_reference_point_is_where_the_force_acts(floating_box):
    sim, wc = floating_box
    # world frame: the point is an offset from the centre of mass in world axes
    wc.apply_body_wrench("box::link", "", (0.1, 0, 0), (0, 1.0, 0), (0, 0, 0), 0, NS // 10)
    run(sim, 0.1)
    _, (lin, ang) = state(wc)
    assert lin[1] == pytest.approx(1.0 / MASS * 0.1, rel=0.02)
    assert ang[2] == pytest.approx(0.1 * 1.0 / IZZ * 0.1, rel=0.03)


def test_another_bodys_frame_gives_the_axes_and_the_point(floating_box):
    sim, wc = floating_box
    wc.spawn("marker", BOX, at(-2, 2, 1.0, yaw=math.pi / 2))
    weightless(wc, "marker::link")
    # marker's x is the world's +y, its y the world's -x: the box centre (2, 2, 1) is at
    # (0, -4, 0) in marker's frame, and (0.1, -4, 0) is 0.1 m along world +y from it
    wc.apply_body_wrench("box::link", "marker", (0.1, -4.0, 0), (0, 1.0, 0), (0, 0, 0), 0,
                         NS // 10)
    run(sim, 0.1)
    _, (lin, ang) = state(wc)
    assert lin[0] == pytest.approx(-1.0 / MASS * 0.1, rel=0.02)
    assert abs(lin[1]) < 1e-6
    # the force (-1, 0, 0) acts 0.1 m along +y of the centre: torque z = -(0.1 * -1) = +0.1
    assert ang[2] == pytest.approx(0.1 / IZZ * 0.1, rel=0.03)
    # a model's frame: the robot faces +x, so its axes are the world's
    wc.apply_body_wrench("box::link", ROBOT, (0, 0, 0), (0, 0, 2.0), (0, 0, 0), 0, NS // 10)
    run(sim, 0.1)
    assert state(wc)[1][0][2] == pytest.approx(2.0 / MASS * 0.1, rel=0.02)


def test_a_later_start_waits_and_a_past_one_starts_now(floating_box):
    sim, wc = floating_box
    start = sim.time_ns + NS // 5
    wc.apply_body_wrench("box::link", "", (0, 0, 0), (2.0, 0, 0), (0, 0, 0), start, NS // 5)
    run(sim, 0.2)
    assert abs(state(wc)[1][0][0]) < 1e-9
    run(sim, 0.2)
    assert state(wc)[1][0][0] == pytest.approx(0.2, rel=0.02)
    wc.apply_body_wrench("box::link", "", (0, 0, 0), (-2.0, 0, 0), (0, 0, 0), 1, NS // 5)
    run(sim, 0.2)
    assert abs(state(wc)[1][0][0]) < 1e-3
    sim.step()                                # the step after its end drops it
    assert sim.forces.wrenches == []


def test_a_heavier_link_answers_less(floating_box):
    sim, wc = floating_box
    p = wc.get_link_properties("box::link")
    wc.set_link_properties("box::link", p.com, False, 2 * p.mass,
                           tuple(2 * v for v in p.inertia))
    wc.apply_body_wrench("box::link", "", (0, 0, 0), (4.0, 0, 0), (0, 0, 0.015), 0, NS // 2)
    run(sim, 0.5)
    _, (lin, ang) = state(wc)
    assert lin[0] == pytest.approx(0.5, rel=0.01)
    assert ang[2] == pytest.approx(0.5, rel=0.02)


def test_gravity_off_and_on_again(empty):
    sim, wc = empty
    wc.spawn("box", BOX, at(2, 2, 1.0))
    weightless(wc, "box::link")
    assert wc.get_link_properties("box::link").gravity_mode is False
    run(sim, 0.5)
    assert state(wc)[0][0][2] == pytest.approx(1.0, abs=1e-3)
    weightless(wc, "box::link", on=True)
    assert sim.forces.active is False
    run(sim, 0.3)
    assert state(wc)[0][0][2] < 0.6


def test_delete_drops_what_acted_on_the_model(floating_box):
    sim, wc = floating_box
    wc.apply_body_wrench("box::link", "", (0, 0, 0), (1.0, 0, 0), (0, 0, 0), 0, -1)
    assert sim.forces.active
    wc.delete("box")
    assert sim.forces.active is False
    run(sim, 0.05)


def test_joint_effort_spins_a_free_wheel(empty):
    sim, wc = empty
    wc.spawn("w", WHEEL, at(1.5, 0, 0.06), kind="urdf")
    run(sim, 0.2)
    assert abs(wc.get_joint_properties("spin").rate[0]) < 1e-3   # no brake, no push
    wc.apply_joint_effort("spin", 0.02, 0, NS)
    run(sim, 1.0)                             # alpha = 0.02 / 0.02 = 1 rad/s^2
    joint = wc.get_joint_properties("spin")
    assert joint.rate[0] == pytest.approx(1.0, rel=0.05)
    assert joint.position[0] == pytest.approx(0.5, rel=0.05)
    run(sim, 0.5)
    assert wc.get_joint_properties("spin").rate[0] == pytest.approx(joint.rate[0], rel=0.02)
    wc.apply_joint_effort("w::spin", -0.02, 0, -1)
    run(sim, 0.5)
    assert wc.clear_joint_forces("spin") == 1
    rate = wc.get_joint_properties("spin").rate[0]
    assert rate == pytest.approx(joint.rate[0] - 0.5, rel=0.1)
    run(sim, 0.5)
    assert wc.get_joint_properties("spin").rate[0] == pytest.approx(rate, rel=0.02)


def test_a_robot_wheel_effort_is_held_by_its_diff_drive(empty):
    """gazebo_ros_diff_drive's joint motor holds the commanded wheel speed with up to the
    plugin's wheelTorque (10 N m on a TurtleBot3): a smaller effort does not turn the wheel."""
    sim, wc = empty
    run(sim, 0.5)
    before = wc.get_joint_properties("wheel_left_joint").position[0]
    (x0, y0, _), _ = sim.robot.ground_truth()
    wc.apply_joint_effort("wheel_left_joint", 5.0, 0, NS)
    run(sim, 1.0)
    assert abs(wc.get_joint_properties("wheel_left_joint").position[0] - before) < 0.02
    (x, y, z), _ = sim.robot.ground_truth()
    assert math.hypot(x - x0, y - y0) < 0.01 and abs(z) < 0.01
    # driving, the effort on one wheel still leaves the robot's motion to the drive
    wc.apply_joint_effort("wheel_left_joint", 1.0, 0, NS)
    sim.robot.command(0.1, 0.0)
    run(sim, 1.0)
    (x1, y1, _), _ = sim.robot.ground_truth()
    assert x1 - x > 0.05 and abs(y1 - y) < 0.01


def test_timing_in_steps(floating_box):
    """A job of duration d acts d / step times: the impulse is F d."""
    sim, wc = floating_box
    wc.apply_body_wrench("box::link", "", (0, 0, 0), (2.0, 0, 0), (0, 0, 0), 0,
                         3 * sim.step_ns)
    run(sim, 0.05)
    assert state(wc)[1][0][0] == pytest.approx(2.0 / MASS * 3 * sim.config.time_step,
                                               rel=1e-3)


def test_refusals_are_one_line(empty):
    sim, wc = empty
    wc.spawn("box", BOX, at(2, 2, 0.075))
    nan = float("nan")
    cases = [
        (lambda: wc.apply_body_wrench("box", "", (0, 0, 0), (1, 0, 0), (0, 0, 0)),
         "ApplyBodyWrench: body does not exist"),
        (lambda: wc.apply_body_wrench("nobox::link", "", (0, 0, 0), (1, 0, 0), (0, 0, 0)),
         "ApplyBodyWrench: body does not exist"),
        (lambda: wc.apply_body_wrench("box::link", "", (0, 0, 0), (nan, 0, 0), (0, 0, 0)),
         "NaN or infinite"),
        (lambda: wc.apply_body_wrench("box::link", "moon", (0, 0, 0), (1, 0, 0), (0, 0, 0)),
         "ApplyBodyWrench: reference_frame not found"),
        (lambda: wc.apply_body_wrench("ground_plane::link", "", (0, 0, 0), (1, 0, 0),
                                      (0, 0, 0)), "is static"),
        (lambda: wc.apply_joint_effort("no_joint", 1.0), "ApplyJointEffort: joint not found"),
        (lambda: wc.apply_joint_effort("wheel_left_joint", math.inf), "NaN or infinite"),
    ]
    for call, words in cases:
        with pytest.raises(RequestError, match=words) as err:
            call()
        assert "\n" not in str(err.value)
    assert sim.forces.active is False
