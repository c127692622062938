"""Robots driven by the drive plugins besides the diff drive (world.robot_drives), in a
Simulation: test/fixtures/drives' skid steer, planar move, tricycle and force-based move,
spawned as spawn_model spawns them, commanded as cmd_vel commands them. Units: m, s, rad."""
import math
from pathlib import Path

import pytest

from tutorial_turtlebot.sim.kinematics import yaw_from_quat
from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
from tutorial_turtlebot.sim.world.world_control import WorldControl

from unit_helpers import at, run
import unit_paths

DRIVES = Path(unit_paths.FIXTURES) / "drives"


@pytest.fixture
def world():
    sim = Simulation(SimConfig(world="empty", spawn_robot=False))
    yield sim, WorldControl(sim)
    sim.close()


def spawned(world, fixture, name, x=0.0, y=0.0):
    """The robot of ``fixture``.urdf spawned in namespace ``name``, settled for 0.5 s."""
    sim, wc = world
    wc.spawn(name, (DRIVES / (fixture + ".urdf")).read_text(), at(x, y), kind="urdf",
             robot_namespace=name)
    robot = sim.robots[name]
    assert robot.warnings == []
    run(sim, 0.5)
    return robot


def pose(robot):
    """(x, y, yaw) of the robot's root link in the world."""
    (x, y, _), orientation = robot.ground_truth()
    return x, y, yaw_from_quat(orientation)


def test_a_skid_steer_drives_forward_and_turns_in_place(world):
    """0.3 m/s for 1 s: 0.3 m within 10 %, straight; 1 rad/s: it turns where it stands."""
    sim, _ = world
    skid = spawned(world, "skid_steer", "skid")
    x0, y0, yaw0 = pose(skid)
    skid.command(0.3, 0.0)
    counts = run(sim, 1.0)
    x, y, yaw = pose(skid)
    assert x - x0 == pytest.approx(0.3, rel=0.1)
    assert abs(y - y0) < 0.01 and abs(yaw - yaw0) < 0.02
    assert counts[("skid", "odom")] == 100                  # its updateRate
    odom = skid.odom()                                      # the world pose, a forward twist
    assert odom.position[:2] == pytest.approx((x, y), abs=1e-3)
    assert odom.linear[0] == pytest.approx(0.3, rel=0.1)
    skid.command(0.0, 1.0)
    run(sim, 2.0)
    x2, y2, yaw2 = pose(skid)
    assert math.remainder(yaw2 - yaw, 2 * math.pi) > 0.5    # it turned left ...
    assert math.hypot(x2 - x, y2 - y) < 0.05                # ... in place
    assert skid.odom().angular[2] > 0.3
    skid.command(0.0, 0.0)
    run(sim, 0.5)
    held = pose(skid)
    run(sim, 1.0)
    assert pose(skid) == pytest.approx(held, abs=1e-3)      # stopped, it stands still


def test_a_planar_move_follows_x_y_and_yaw_rates(world):
    """linear.x 0.2, linear.y 0.1 m/s in its heading, angular.z 0.5 rad/s for 2 s: the pose
    the rates integrate to, within 5 %; its odometry's twist is the command."""
    sim, _ = world
    planar = spawned(world, "planar_move", "planar")
    x0, y0, yaw0 = pose(planar)
    vx, vy, w, t = 0.2, 0.1, 0.5, 2.0
    planar.command(vx, w, lateral=vy)
    counts = run(sim, t)
    x, y, yaw = pose(planar)
    want_x = (vx * math.sin(w * t) + vy * (math.cos(w * t) - 1.0)) / w
    want_y = (vx * (1.0 - math.cos(w * t)) + vy * math.sin(w * t)) / w
    travelled = math.hypot(want_x, want_y)
    assert math.hypot(x - x0 - want_x, y - y0 - want_y) < 0.05 * travelled
    assert yaw - yaw0 == pytest.approx(w * t, rel=0.05)
    assert counts[("planar", "odom")] == pytest.approx(40, abs=1)   # odometryRate 20 Hz
    odom = planar.odom()
    assert odom.linear[:2] == pytest.approx((vx, vy), rel=0.05)
    assert odom.angular[2] == pytest.approx(w, rel=0.05)
    sim.reset_world()                                      # a reset stops it, as Gazebo's
    run(sim, 0.5)
    start = pose(planar)
    run(sim, 0.5)
    assert pose(planar) == pytest.approx(start, abs=1e-3)


def test_a_tricycle_drives_forward_and_turns(world):
    """linear.x 0.3 m/s at the front wheel: 0.3 m in 1 s within 10 %; angular.z 0.5 is its
    steering angle: the yaw rate 0.3 sin(0.5) / 0.4 (its wheelbase) within 10 %."""
    sim, _ = world
    tricycle = spawned(world, "tricycle", "tricycle")
    x0, y0, _ = pose(tricycle)
    tricycle.command(0.3, 0.0)
    run(sim, 1.0)
    x, y, yaw = pose(tricycle)
    assert x - x0 == pytest.approx(0.3, rel=0.1) and abs(y - y0) < 0.01
    tricycle.command(0.3, 0.5)
    run(sim, 0.5)                                          # the steering turns
    _, _, yaw1 = pose(tricycle)
    run(sim, 1.0)
    _, _, yaw2 = pose(tricycle)
    assert yaw2 - yaw1 == pytest.approx(0.3 * math.sin(0.5) / 0.4, rel=0.1)
    assert tricycle.body.joint_state("front_steering_joint")[0] == pytest.approx(0.5, abs=0.01)


def test_a_force_based_move_is_pushed_to_the_commanded_velocity(world):
    """0.3 m/s forward, 0.1 m/s left and 0.5 rad/s: reached within 5 % after 1 s."""
    sim, _ = world
    robot = spawned(world, "force_based_move", "force")
    robot.command(0.3, 0.5, lateral=0.1)
    run(sim, 1.0)
    (vx, vy, _), (_, _, wz) = robot.body.velocity()
    yaw = pose(robot)[2]
    forward = vx * math.cos(yaw) + vy * math.sin(yaw)
    left = vy * math.cos(yaw) - vx * math.sin(yaw)
    assert (forward, left, wz) == pytest.approx((0.3, 0.1, 0.5), rel=0.05)
    assert robot.odom().linear == pytest.approx((0.3, 0.0, 0.0), rel=0.05)


def test_a_tricycles_encoder_odometry_starts_at_zero_and_follows_the_wheels(world):
    """odometrySource encoder: odometry integrated from the encoder wheels, from (0, 0, 0)
    wherever it was spawned; 0.3 m/s for 1 s reads about 0.3 m forward, left turns positive."""
    sim, wc = world
    text = (DRIVES / "tricycle.urdf").read_text().replace(
        "<odometrySource>world</odometrySource>", "<odometrySource>encoder</odometrySource>")
    wc.spawn("enc", text, at(2.0, 1.0), kind="urdf", robot_namespace="enc")
    robot = sim.robots["enc"]
    run(sim, 0.5)
    robot.command(0.3, 0.0)
    run(sim, 1.0)
    odom = robot.odom()
    assert odom.position[0] == pytest.approx(0.3, rel=0.1)
    assert abs(odom.position[1]) < 0.01
    robot.command(0.3, 0.5)
    run(sim, 1.0)
    assert yaw_from_quat(robot.odom().orientation) > 0.1
