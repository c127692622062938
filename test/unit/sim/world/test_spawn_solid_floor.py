"""sim/world/spawn_check.py, the landing rule's "Inside a solid floor": a robot asked for a pose
inside a solid floor that holds its whole footprint (a 0.19 m floor box under a Waffle Pi,
0.141 m tall, at z 0) stands on top of it, level and still, by spawn, spawn_model,
set_model_state and set_link_state; a stage edge (part of the footprint), a low bench (lower
than the robot's top) and a table over the robot's head lift nothing. Real pybullet on
test/fixtures/worlds/raised_room.world, no ROS master."""
import math
import os

import numpy as np
import pybullet
import pytest

from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
from tutorial_turtlebot.sim.world.world_control import WorldControl

from unit_helpers import at, urdf_text
import unit_paths

ROOM = os.path.join(unit_paths.FIXTURES, "worlds", "raised_room.world")
ROBOT = "turtlebot3_waffle_pi"
FLOOR_TOP = 0.19                 # m: the room's floor box
AT_REST = ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0))
LEVEL = math.radians(1.0)
STILL = 0.01                     # m: how far a robot left alone may move in 5 s
STAGE_EDGE = (-0.52, 2.0)        # the root 2 cm inside the stage's edge (x -0.5): half covered
TABLE, BENCH, ROOM_TABLE = (5.0, 0.0), (5.0, -3.0), (1.5, -1.5)
TILES_SEAM = (0.0, 6.0)
BY_THE_WALL = (2.85, 0.0)        # the Waffle Pi's reach (0.238 m) ends inside the east wall


def room_sim(x, y, yaw=0.0, **config):
    return Simulation(SimConfig(world=ROOM, model="waffle_pi", x=x, y=y, yaw=yaw, **config))


def pose_of(sim, name=ROBOT):
    """(x, y, z, roll, pitch) of a robot's root link."""
    (x, y, z), q = sim.robots[name].ground_truth()
    roll, pitch, _ = pybullet.getEulerFromQuaternion(q)
    return x, y, z, roll, pitch


def step(sim, seconds):
    for _ in range(round(seconds / sim.config.time_step)):
        sim.step()


def assert_still_on_floor(sim, seconds, name=ROBOT, top=FLOOR_TOP):
    """Left alone ``seconds``, robot ``name`` stands level on the floor whose top is ``top``
    and moves less than STILL."""
    x0, y0, z0, _, _ = pose_of(sim, name)
    assert z0 == pytest.approx(top, abs=0.01), "placed at z %.4f" % z0
    step(sim, seconds)
    x, y, z, roll, pitch = pose_of(sim, name)
    assert z == pytest.approx(top, abs=0.01), "z %.4f after %g s" % (z, seconds)
    assert abs(roll) < LEVEL and abs(pitch) < LEVEL, "roll %.2f, pitch %.2f degrees" % (
        math.degrees(roll), math.degrees(pitch))
    moved = math.sqrt((x - x0) ** 2 + (y - y0) ** 2 + (z - z0) ** 2)
    assert moved < STILL, "moved %.3f m in %g s with no command" % (moved, seconds)


@pytest.fixture(scope="module")
def in_room():
    """A Waffle Pi spawned at z 0 in the room, and the world API over it: (sim, wc)."""
    sim = room_sim(0.5, 0.5)
    yield sim, WorldControl(sim)
    sim.close()


# --- inside the floor box: on top ----------------------------------------------------------------

def test_a_waffle_pi_spawned_at_z_0_in_the_floor_box_stands_on_it_level_and_still(in_room):
    sim, _ = in_room
    assert sim.spawn[2] == pytest.approx(FLOOR_TOP, abs=0.01)
    assert sim.robot.warnings == []
    assert_still_on_floor(sim, 5.0)


def test_set_model_state_to_z_0_elsewhere_in_the_floor_lands_on_top_and_stays(in_room):
    sim, wc = in_room
    for x, y, yaw in ((-1.0, -2.0, 1.0), (2.2, 1.0, -2.5), (-2.0, 0.0, 0.0)):
        wc.set_model_state(ROBOT, at(x, y, 0.0, yaw), AT_REST)
        assert wc.get_model_state(ROBOT)[0][0] == pytest.approx((x, y, FLOOR_TOP), abs=0.01)
        assert_still_on_floor(sim, 2.0)


def test_set_link_state_of_the_base_to_z_0_lands_it_too(in_room):
    sim, wc = in_room
    wc.set_link_state(ROBOT + "::base_footprint", at(0.0, -1.0, 0.0), AT_REST)
    assert_still_on_floor(sim, 1.0)


def test_spawn_model_of_a_robot_at_z_0_in_the_floor_box_stands_on_it(in_room):
    sim, wc = in_room
    wc.spawn("tb3_1", urdf_text("waffle_pi"), at(-1.0, -1.0), kind="urdf",
             robot_namespace="tb3_1")
    try:
        assert sim.robots["tb3_1"].warnings == []
        assert wc.get_model_state("tb3_1")[0][0][2] == pytest.approx(FLOOR_TOP, abs=0.01)
        assert_still_on_floor(sim, 1.0, "tb3_1")
    finally:
        wc.delete("tb3_1")


def test_under_a_table_standing_on_the_floor_box_it_lands_on_the_floor_not_the_table(in_room):
    sim, wc = in_room
    wc.set_model_state(ROBOT, at(*ROOM_TABLE), AT_REST)
    assert wc.get_model_state(ROBOT)[0][0][2] == pytest.approx(FLOOR_TOP, abs=0.01)
    assert_still_on_floor(sim, 1.0)


def test_a_floor_of_two_tiles_of_one_height_is_one_floor(in_room):
    """At the seam of two 0.19 m tiles (two colliders, one top): on top."""
    sim, wc = in_room
    wc.set_model_state(ROBOT, at(*TILES_SEAM), AT_REST)
    assert wc.get_model_state(ROBOT)[0][0][2] == pytest.approx(FLOOR_TOP, abs=0.01)
    assert_still_on_floor(sim, 1.0)


def test_any_solid_holding_the_whole_footprint_is_stood_on_however_high():
    """A Burger (reach 0.124 m) at z 0 on the axis of a turtlebot3_world pillar (a cylinder,
    radius 0.15 m, 0.5 m high): on its top, as on a floor (its edge: test_worlds_house_autorace)."""
    sim = Simulation(SimConfig(world="turtlebot3_world", x=-1.1, y=0.0))
    try:
        assert sim.spawn[2] == pytest.approx(0.5, abs=0.002) and sim.robot.warnings == []
    finally:
        sim.close()


# --- what is not inside a solid floor: as given --------------------------------------------------

def test_a_stage_edge_over_part_of_the_footprint_stays_an_overlap_with_its_warning():
    """On the floor at the stage's edge (the stage holds half the footprint): kept where asked,
    one warning naming the stage; at z 0 in the floor box there: on the floor, not the stage."""
    for z in (FLOOR_TOP, 0.0):
        sim = room_sim(*STAGE_EDGE, z=z)
        try:
            assert sim.spawn[2] == pytest.approx(FLOOR_TOP, abs=0.001)
            (warning,) = sim.robot.warnings
            assert " stage " in warning and "z_pos 0.490" in warning, warning
        finally:
            sim.close()


def test_in_the_floor_box_and_the_wall_beside_it_it_stays_an_overlap():
    """At z 0 by the east wall (x 3.0..3.1, on the ground, 1 m high), part of the footprint in
    the wall: not put on the wall's top, nor on the floor's; one warning."""
    sim = room_sim(*BY_THE_WALL)
    try:
        assert sim.spawn[2] == 0.0
        (warning,) = sim.robot.warnings
        assert "overlaps" in warning, warning
    finally:
        sim.close()


def test_a_robot_under_a_table_stays_under_it(in_room):
    """The table's top (0.285..0.315 m) is over the Waffle Pi's head (0.141 m), between the
    legs: by spawn and by teleport the robot stays on the ground."""
    sim = room_sim(*TABLE)
    try:
        assert sim.spawn[2] == 0.0 and sim.robot.warnings == []
        assert_still_on_floor(sim, 1.0, top=0.0)
    finally:
        sim.close()
    sim, wc = in_room
    wc.set_model_state(ROBOT, at(*TABLE), AT_REST)
    assert wc.get_model_state(ROBOT)[0][0][2] == pytest.approx(0.0, abs=1e-9)
    assert_still_on_floor(sim, 1.0, top=0.0)


def test_a_bench_lower_than_the_robot_top_is_an_overlap_not_a_floor(in_room):
    """The bench's top (0.12..0.18 m) holds the robot's top, not its root: it is under the
    bench, not inside a floor, and stays where asked."""
    sim = room_sim(*BENCH)
    try:
        assert sim.spawn[2] == 0.0
        (warning,) = sim.robot.warnings
        assert " bench " in warning and "z_pos 0.180" in warning, warning
    finally:
        sim.close()
    sim, wc = in_room
    wc.set_model_state(ROBOT, at(*BENCH), AT_REST)
    assert wc.get_model_state(ROBOT)[0][0][2] == pytest.approx(0.0, abs=1e-9)


def test_the_probes_find_the_floor_box_solid_and_open_space_empty(in_room):
    sim, _ = in_room
    inside, on_top, under_table, in_wall = sim.physics.solids_at(np.array([
        (2.0, 2.0, 0.1), (2.0, 2.0, FLOOR_TOP + 0.001), (5.0, 0.0, 0.1), (3.05, 0.0, 0.5)]))
    assert len(inside) == 1 and on_top == frozenset() and under_table == frozenset()
    assert len(in_wall) == 1 and in_wall != inside
