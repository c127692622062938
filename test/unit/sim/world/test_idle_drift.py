"""A robot told nothing stands still: ten simulated minutes without a command move no robot's
base_footprint by 1 mm or turn it by 1 mrad, for each model alone and for three Burgers where
multi_turtlebot3.launch puts them in the house (one of them stopped after a short drive). No
ROS master.

Gazebo's diff drive holds an idle robot's wheels at velocity 0 with its wheelTorque and ODE's
static friction keeps it in place; on the lab's floor an idle robot does not move either.
Drift is measured from where the robot rests once the spawn drop (or the stop) has settled
(1 s); settling from the spawn pose must stay under a millimetre too.
"""
import math
import time

import pybullet
import pytest

from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
from tutorial_turtlebot.sim.files.urdf.urdf_file import read_urdf, urdf_path

SETTLE = 1.0           # s: the spawn drop (SPAWN_CLEARANCE) and the tip onto the caster
IDLE = 600.0           # s of sim time without a command
MAX_DRIFT = 0.001      # m of base_footprint's x, y
MAX_YAW_DRIFT = 0.001  # rad
# multi_turtlebot3.launch: (x, y, yaw) of tb3_0, tb3_1, tb3_2 in turtlebot3_house
MULTI_TB3 = {"tb3_0": (-7.0, -1.0, 1.57), "tb3_1": (7.0, -1.0, 1.57), "tb3_2": (0.5, 3.0, 0.0)}


def planar(robot):
    """(x, y, yaw) of the robot's base_footprint in the world."""
    (x, y, _), orn = robot.ground_truth()
    return x, y, pybullet.getEulerFromQuaternion(orn)[2]


def run(sim, seconds):
    """Step ``seconds`` of sim time: each robot's diff drive control tick (SimRobot.before_step)
    and the physics step, as Simulation.step does, without the bookkeeping of outputs that
    nobody reads here (a quarter of a step's time)."""
    robots, physics, step_ns = list(sim.robots.values()), sim.physics, sim.step_ns
    now = sim.time_ns
    for _ in range(round(seconds / sim.config.time_step)):
        for robot in robots:
            robot.before_step(now)
        physics.step()
        now += step_ns
    sim.time_ns = now


def assert_still(sim, spawned):
    """Settle SETTLE s, idle IDLE s; every robot must stay put. ``spawned``: {robot name:
    its spawn (x, y), or None for one that has driven since}."""
    start = time.monotonic()
    run(sim, SETTLE)
    rest = {name: planar(sim.robots[name]) for name in spawned}
    run(sim, IDLE)
    failures = []
    for name, spawn_xy in spawned.items():
        x0, y0, yaw0 = rest[name]
        x, y, yaw = planar(sim.robots[name])
        settle = math.hypot(x0 - spawn_xy[0], y0 - spawn_xy[1]) if spawn_xy else 0.0
        drift = math.hypot(x - x0, y - y0)
        turn = math.remainder(yaw - yaw0, math.tau)
        line = ("%s: settled %.3f mm from spawn, then drifted %.3f mm and %.3f mrad in %g s"
                % (name, settle * 1e3, drift * 1e3, turn * 1e3, IDLE))
        print(line)
        if settle >= MAX_DRIFT or drift >= MAX_DRIFT or abs(turn) >= MAX_YAW_DRIFT:
            failures.append(line)
    print("%g s of sim time in %.1f s" % (SETTLE + IDLE, time.monotonic() - start))
    assert not failures, "\n".join(failures)


@pytest.mark.parametrize("model", ["burger", "waffle", "waffle_pi"])
def test_an_idle_robot_alone_stands_still(model):
    sim = Simulation(SimConfig(world="empty", model=model, camera=False))
    try:
        assert_still(sim, {sim.robot.name: (0.0, 0.0)})
    finally:
        sim.close()


def test_three_idle_burgers_in_the_house_stand_still():
    """multi_turtlebot3.launch: the house, three Burgers by spawn_model in tb3_0..tb3_2; tb3_2
    first drives an arc and is told to stop (its wheels then stop where they are)."""
    sim = Simulation(SimConfig(world="turtlebot3_house", spawn_robot=False))
    try:
        for name, (x, y, yaw) in MULTI_TB3.items():
            pose = ((x, y, 0.0), (0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2)))
            sim.add_robot(name, name, read_urdf(urdf_path("burger")), pose)
        sim.robots["tb3_2"].command(0.15, 0.5)
        run(sim, 1.5)
        sim.robots["tb3_2"].command(0.0, 0.0)
        assert planar(sim.robots["tb3_2"])[2] > 0.3      # it did drive
        assert_still(sim, {"tb3_0": MULTI_TB3["tb3_0"][:2], "tb3_1": MULTI_TB3["tb3_1"][:2],
                           "tb3_2": None})
    finally:
        sim.close()
