"""Resets are exact: after reset_simulation or reset_world, the same commands give the same
trajectory, to the last bit, as a world built anew (Simulation.reset_world): bodies, joints,
contacts and the solver's warm start, with spawned and deleted models too."""
import os
import struct

import pytest

from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
from tutorial_turtlebot.sim.world.world_control import WorldControl

from unit_helpers import ROBOT, at, box_sdf
import unit_paths

# (linear m/s, angular rad/s, steps of 2.5 ms): from 0.4 m before the pillar at (-1.1, 0) of
# turtlebot3_world the Burger drives into it, turns against it and backs away: wheels on the
# floor, the chassis on a pillar, contacts made and broken.
COMMANDS = [(0.22, 0.0, 900), (0.1, 2.0, 300), (0.22, -1.0, 500), (-0.2, 0.5, 400),
            (0.0, 0.0, 200)]


def world_config():
    """The Burger in turtlebot3_world, 0.4 m before a pillar, facing it."""
    return SimConfig(model="burger", world="turtlebot3_world", x=-1.6, y=0.0, yaw=0.0)


def trajectory(sim, commands=COMMANDS, every=1):
    """The robot's world pose (7 float64) after every ``every``-th step and every scan that fell
    due, as bytes: two equal trajectories are the same to the last bit. The laser's noise is
    drawn from seed 0 (as in a new world): a reset leaves the noise generator as it is."""
    sim.robot.reseed(0)
    out = bytearray()
    step = 0
    for linear, angular, steps in commands:
        sim.robot.command(linear, angular)
        for _ in range(steps):
            for robot, name in sim.step():
                if name == "scan":
                    out += robot.scan().tobytes()
            step += 1
            if step % every == 0:
                position, orientation = sim.robot.ground_truth()
                out += struct.pack("<7d", *position, *orientation)
    return bytes(out)


def drive(sim, steps, linear=0.22, angular=0.3):
    sim.robot.command(linear, angular)
    for _ in range(steps):
        sim.step()


@pytest.fixture(scope="module")
def fresh():
    """The trajectory of a world built anew (the Burger in turtlebot3_world)."""
    sim = Simulation(world_config())
    try:
        return trajectory(sim)
    finally:
        sim.close()


def test_the_trajectory_touches_the_world(fresh):
    """The commands make contacts beside the wheels': the robot is stopped by a pillar (it
    moves less than it was told), so a reset has real contacts to forget."""
    sim = Simulation(world_config())
    try:
        start = sim.robot.ground_truth()[0]
        drive(sim, 900, 0.22, 0.0)
        travelled = sim.robot.ground_truth()[0][0] - start[0]
    finally:
        sim.close()
    assert travelled < 0.22 * 900 * 0.0025 - 0.1


@pytest.mark.parametrize("steps", [1, 2, 7, 60, 700, 1500])
def test_reset_simulation_after_any_run_steps_as_a_new_world(fresh, steps):
    """Reset after 1 step (contacts just made) to 1,500 (pressed against a pillar)."""
    sim = Simulation(world_config())
    try:
        drive(sim, steps)
        sim.reset_simulation()
        assert sim.time_ns == 0
        assert trajectory(sim) == fresh
        sim.reset_simulation()
        assert trajectory(sim) == fresh
    finally:
        sim.close()


def test_reset_world_steps_as_a_new_world_while_time_runs_on(fresh):
    sim = Simulation(world_config())
    try:
        drive(sim, 1000)
        sim.reset_world()
        assert sim.time_ns == 1000 * sim.step_ns
        assert trajectory(sim) == fresh
    finally:
        sim.close()


def stage_3():
    """Learning stage 3's world: its obstacle is a movable model resting on the floor."""
    sim = Simulation(SimConfig(model="burger", world="turtlebot3_stage_3"))
    return sim, WorldControl(sim)


def spin(sim, wc, steps):
    """Step with the obstacle spun at 0.5 rad/s (set_model_state every 0.1 s, as stage 3's
    obstacle node does): its contacts with the floor slide."""
    for step in range(steps):
        if step % 40 == 0:
            pose = wc.get_model_state("obstacle")[0]
            wc.set_model_state("obstacle", pose, ((0.0, 0.0, 0.0), (0.0, 0.0, 0.5)))
        sim.step()


@pytest.fixture(scope="module")
def stage_3_fresh():
    sim, _ = stage_3()
    try:
        return trajectory(sim)
    finally:
        sim.close()


@pytest.mark.parametrize("steps", [1, 2, 10, 100])
def test_a_spinning_obstacle_is_reset_exactly(stage_3_fresh, steps):
    sim, wc = stage_3()
    try:
        spin(sim, wc, steps)
        sim.reset_simulation()
        assert trajectory(sim) == stage_3_fresh
    finally:
        sim.close()


def test_the_old_reset_was_not_exact(stage_3_fresh, monkeypatch):
    """The test above can fail: putting the bodies back without the saved state and without
    dropping the contacts (the reset before) leaves the obstacle's sliding contacts with the
    floor, and gives another trajectory."""
    from tutorial_turtlebot.sim.engine import physics

    monkeypatch.setattr(physics.WorldPhysics, "restore_state", lambda self, state: None)
    monkeypatch.setattr(physics.WorldPhysics, "renew_contacts", lambda self: None)
    sim, wc = stage_3()
    try:
        spin(sim, wc, 10)
        sim.models.reset()      # what restore_state would have done, by hand
        sim.reset_simulation()
        assert trajectory(sim) != stage_3_fresh
    finally:
        sim.close()


def spawned_world():
    """The Burger in turtlebot3_world with a box spawned in its way (the world API)."""
    sim = Simulation(world_config())
    wc = WorldControl(sim)
    wc.spawn("box", box_sdf(0.2, 0.5), at(-1.3, 0.3, 0.1))
    return sim, wc


def test_a_spawned_model_is_reset_exactly():
    """A box spawned after the start and pushed about: reset_simulation steps as a world
    built anew with the box spawned, then reset (the saved state no longer fits: every model
    is put back and the contacts dropped; that state is what later resets restore)."""
    ref_sim, _ = spawned_world()
    try:
        ref_sim.reset_simulation()
        reference = trajectory(ref_sim)
    finally:
        ref_sim.close()
    sim, wc = spawned_world()
    try:
        drive(sim, 600, 0.22, 0.0)
        assert wc.get_model_state("box")[0][0] != (-1.3, 0.3, 0.1)
        sim.reset_simulation()
        assert trajectory(sim) == reference
        drive(sim, 3)
        sim.reset_simulation()     # from the state saved at the reset before
        assert trajectory(sim) == reference
    finally:
        sim.close()


def test_a_deleted_model_is_reset_exactly():
    """A model deleted after running: the reset steps as a new world with it deleted, reset."""
    def without_a_pillar():
        sim = Simulation(world_config())
        wc = WorldControl(sim)
        name = next(n for n in sim.models.names() if n != ROBOT)
        return sim, wc, name

    ref_sim, ref_wc, name = without_a_pillar()
    try:
        ref_wc.delete(name)
        ref_sim.reset_simulation()
        reference = trajectory(ref_sim)
    finally:
        ref_sim.close()
    sim, wc, name = without_a_pillar()
    try:
        drive(sim, 5)
        wc.delete(name)
        drive(sim, 300)
        sim.reset_simulation()
        assert trajectory(sim) == reference
    finally:
        sim.close()


def test_a_robot_spawned_and_deleted_leaves_the_reset_exact(fresh):
    """A second robot that came and went (its body parked, not in the world): the first
    robot's trajectory after the reset is the fresh world's."""
    from unit_helpers import urdf_text

    sim = Simulation(world_config())
    wc = WorldControl(sim)
    try:
        wc.spawn("other", urdf_text("burger"), at(1.5, 1.5), kind="urdf", robot_namespace="tb2")
        drive(sim, 100)
        wc.delete("other")
        sim.reset_simulation()
        assert "other" not in sim.models
        assert trajectory(sim) == fresh
    finally:
        sim.close()


def test_a_goal_of_visuals_alone_respawned_every_episode_keeps_the_reset_exact():
    """turtlebot3_dqn's episode on stage 1: reset_simulation, the goal (a static model of one
    visual, no collision) deleted and spawned again. Its body comes back from the pool and
    the state saved with it restores: parking a body of no collider once broke that."""
    goal = ('<sdf version="1.6"><model name="goal"><static>1</static><link name="goal">'
            '<visual name="v"><geometry><box><size>0.5 0.5 0.001</size></box></geometry>'
            '</visual></link></model></sdf>')
    sim = Simulation(SimConfig(model="burger", world="turtlebot3_stage_1"))
    wc = WorldControl(sim)
    try:
        firsts = []
        for episode in range(4):
            sim.reset_simulation()
            if "goal" in sim.models.names():
                wc.delete("goal")
            wc.spawn("goal", goal, at(0.6, 0.0, 0.0))
            drive(sim, 100)
            firsts.append(wc.get_model_state(ROBOT)[0][0])
        # from the second episode on the reset restores the same saved state: one trajectory
        assert firsts[1] == firsts[2] == firsts[3]
    finally:
        sim.close()


def test_a_world_of_static_meshes_and_a_plane_resets_again_and_again():
    """Static meshes and planes are plain static rigid bodies (world_bullet), which pybullet's
    restoreState no longer finds once their broadphase entries are renewed: the renewal leaves
    them out (collision_filters), and the third reset steps as the first."""
    floors = os.path.join(unit_paths.FIXTURES, "worlds", "floors", "floors.world")
    commands = [(0.22, 0.8, 400), (-0.1, 0.0, 200)]
    sim = Simulation(SimConfig(model="burger", world=floors, x=-8.0, y=0.0))  # the walls mesh
    try:
        first = trajectory(sim, commands)
        for _ in range(3):
            sim.reset_world()
            assert trajectory(sim, commands) == first
    finally:
        sim.close()
