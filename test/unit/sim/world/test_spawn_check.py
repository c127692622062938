"""sim/world/spawn_check.py: spawns and teleports where Gazebo would have them. No spawn is
refused for overlap; a robot asked below the floor under it (a raised floor of any kind: box,
closed or open mesh, cylinder, polyline) stands on top of it, level, its laser seeing only what
stands in the free space; a table above the robot is not climbed onto; an overlap is one
warning naming the model and a z_pos. Real pybullet on test/fixtures/worlds/floors/ (written by
test/fixtures/make_floor_fixtures.py), no ROS master."""
import math
import os

import numpy as np
import pybullet
import pytest

from tutorial_turtlebot.sim.files.urdf.urdf_file import read_urdf, urdf_path
from tutorial_turtlebot.sim.kinematics import quat_from_rpy
from tutorial_turtlebot.sim.world import spawn_check
from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
from tutorial_turtlebot.sim.world.spawn_check import (LIFT_TOLERANCE, collision_points,
                                                      landed_pose, robot_extent)
from tutorial_turtlebot.sim.world.world_control import WorldControl

from unit_helpers import at, box_sdf, urdf_text
import unit_paths

FLOORS = os.path.join(unit_paths.FIXTURES, "worlds", "floors", "floors.world")
ROBOT = "turtlebot3_burger"
AT_REST = ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0))
# name: (x, y, yaw) on it, its top (m); make_floor_fixtures.py's layout
RAISED = {
    "floor_box": ((0.0, 0.0, 0.0), 0.19),
    "slab": ((6.0, 0.0, 0.0), 0.034),            # a closed mesh 0.12 thick, mostly sunk
    "thin_floor": ((12.0, 0.0, 0.0), 0.01),
    "track": ((19.3, 0.0, math.pi / 2), 0.10),   # an open ring mesh, along its lane
    "round_floor": ((24.0, 0.0, 0.0), 0.08),     # a cylinder
    "hex_floor": ((30.0, 0.0, 0.0), 0.06),       # a polyline
}
TABLE = (36.0, 0.0)
WALL = (42.0, 0.08)       # the Burger's body overlaps the wall (y -0.05..0.05) by 4 cm
ROOM = (-8.0, 0.0)        # the centre of the open walls mesh (walls at x -10, -6 and y -2, 2)
LEVEL = math.radians(0.5)        # a Burger on flat ground leans back 0.3 degrees (its caster)


def stand(sim, seconds=1.0):
    """Step ``seconds``; the robot's (x, y, z, roll, pitch)."""
    for _ in range(round(seconds / sim.config.time_step)):
        sim.step()
    (x, y, z), q = sim.robot.ground_truth()
    roll, pitch, _ = pybullet.getEulerFromQuaternion(q)
    return x, y, z, roll, pitch


def assert_on(sim, top, what):
    """The robot stands level on a floor whose top is ``top`` and its laser sees nothing within
    its range (every floor stands alone in 6 m of free space)."""
    _, _, z, roll, pitch = stand(sim)
    assert z == pytest.approx(top, abs=0.003), "%s: z %.4f, the floor's top %.3f" % (what, z, top)
    assert abs(roll) < LEVEL and abs(pitch) < LEVEL, \
        "%s: roll %.2f, pitch %.2f degrees" % (what, math.degrees(roll), math.degrees(pitch))
    scan = np.asarray(sim.robot.scan(), dtype=float)
    assert not np.isfinite(scan).any(), "%s: the laser sees %d rays at %.2f m and more" % (
        what, np.isfinite(scan).sum(), np.nanmin(np.where(np.isfinite(scan), scan, np.nan)))


def floors_sim(x, y, yaw=0.0, **config):
    return Simulation(SimConfig(world=FLOORS, x=x, y=y, yaw=yaw, **config))


def home(wc):
    """The robot back in the room, clear of what a test spawns."""
    wc.set_model_state(ROBOT, at(*ROOM), AT_REST)


@pytest.fixture(scope="module")
def in_room():
    """A Burger in the open walls room, and the world API over it: (sim, wc)."""
    sim = floors_sim(*ROOM)
    yield sim, WorldControl(sim)
    sim.close()


# --- the open walls mesh -------------------------------------------------------------------------

def room_range(x, y, bearing):
    """Distance (m) from (x, y) in the room along ``bearing`` (rad) to its walls."""
    c, s = math.cos(bearing), math.sin(bearing)
    to_x = ((-6.0 if c > 0 else -10.0) - x) / c if abs(c) > 1e-9 else math.inf
    to_y = ((2.0 if s > 0 else -2.0) - y) / s if abs(s) > 1e-9 else math.inf
    return min(to_x, to_y)


def test_a_clear_spawn_in_an_open_walls_mesh_is_taken_and_stands_on_the_ground():
    """The walls are one open mesh (no floor, no ceiling): a ray from inside crosses it once,
    which the old parity test took for "inside" (7 of 10 clear poses of a real world refused)."""
    sim = floors_sim(*ROOM)
    try:
        assert sim.robot is not None and sim.robot.warnings == []
        x, y, z, roll, pitch = stand(sim)
        assert (x, y, z) == pytest.approx(ROOM + (0.0,), abs=0.003)
        scan = np.asarray(sim.robot.scan(), dtype=float)
        laser = sim.robot.body.frame_pose("base_scan")[0]
        bearings = np.linspace(0.0, 6.28319, len(scan))
        expected = np.array([room_range(laser[0], laser[1], b) for b in bearings])
        assert np.isfinite(scan).all()
        assert np.median(np.abs(scan - expected)) < 0.02 and np.abs(scan - expected).max() < 0.05
    finally:
        sim.close()


@pytest.mark.parametrize("dx, dy", [(1.0, 0.0), (-1.0, 0.0), (0.0, 1.0), (0.0, -1.0),
                                    (1.0, 1.0), (-1.0, -1.0), (1.4, -0.6), (-0.5, 1.3),
                                    (0.7, 0.7), (-1.5, 1.5)])
def test_every_clear_pose_in_the_room_is_taken(dx, dy):
    sim = floors_sim(ROOM[0] + dx, ROOM[1] + dy, yaw=dx)
    try:
        assert sim.spawn[2] == 0.0 and sim.robot.warnings == []
        assert stand(sim, 0.25)[2] == pytest.approx(0.0, abs=0.003)
    finally:
        sim.close()


# --- raised floors -------------------------------------------------------------------------------

@pytest.mark.parametrize("floor", sorted(RAISED))
def test_a_spawn_at_z_0_stands_on_a_raised_floor_of_each_kind(floor):
    (x, y, yaw), top = RAISED[floor]
    sim = floors_sim(x, y, yaw)
    try:
        assert sim.spawn[2] == pytest.approx(top, abs=0.002)
        assert sim.robot.warnings == []
        assert_on(sim, top, floor)
    finally:
        sim.close()


@pytest.mark.parametrize("floor", sorted(RAISED))
def test_a_teleport_at_z_0_lands_on_a_raised_floor_of_each_kind(in_room, floor):
    sim, wc = in_room
    (x, y, yaw), top = RAISED[floor]
    wc.set_model_state(ROBOT, at(x, y, 0.0, yaw), AT_REST)
    assert wc.get_model_state(ROBOT)[0][0][2] == pytest.approx(top, abs=0.002)
    assert_on(sim, top, floor)


def test_set_link_state_of_the_robot_lands_it_too(in_room):
    sim, wc = in_room
    (x, y, yaw), top = RAISED["slab"]
    wc.set_link_state(ROBOT + "::base_footprint", at(x, y, -0.05, yaw), AT_REST)
    assert_on(sim, top, "slab by set_link_state")


def test_a_teleport_above_the_floor_is_honoured_and_the_robot_falls_onto_it(in_room):
    sim, wc = in_room
    (x, y, _), top = RAISED["floor_box"]
    wc.set_model_state(ROBOT, at(x, y, 0.4), AT_REST)
    # to 0.1 um: the root link's pose goes through pybullet's transforms to the base and back
    assert wc.get_model_state(ROBOT)[0][0][2] == pytest.approx(0.4, abs=1e-7)
    assert_on(sim, top, "fallen onto floor_box")


def test_spawn_model_of_a_robot_at_z_0_lands_on_the_floor(in_room):
    sim, wc = in_room
    home(wc)
    (x, y, _), top = RAISED["track"]
    wc.spawn("tb3_1", urdf_text("burger"), at(x, y), kind="urdf", robot_namespace="tb3_1")
    try:
        assert sim.robots["tb3_1"].warnings == []
        assert wc.get_model_state("tb3_1")[0][0][2] == pytest.approx(top, abs=0.002)
        for _ in range(400):
            sim.step()
        assert wc.get_model_state("tb3_1")[0][0][2] == pytest.approx(top, abs=0.003)
    finally:
        wc.delete("tb3_1")


def test_the_reset_puts_a_landed_robot_back_on_its_floor():
    (x, y, yaw), top = RAISED["slab"]
    sim = floors_sim(x, y, yaw)
    try:
        wc = WorldControl(sim)
        wc.set_model_state(ROBOT, at(x + 0.3, y, 0.3), AT_REST)
        stand(sim, 0.5)
        sim.reset_world()
        assert wc.get_model_state(ROBOT)[0][0] == pytest.approx((x, y, top), abs=0.002)
        assert_on(sim, top, "slab after reset_world")
    finally:
        sim.close()


# --- what is no floor ----------------------------------------------------------------------------

def test_a_robot_under_a_table_stays_on_the_ground(in_room):
    """The table's top (0.285..0.315 m) is above the Burger's top (0.191 m): it stands under
    it, by spawn and by teleport."""
    sim = floors_sim(*TABLE)
    try:
        assert sim.spawn[2] == 0.0 and sim.robot.warnings == []
        assert stand(sim)[2] == pytest.approx(0.0, abs=0.003)
    finally:
        sim.close()
    sim, wc = in_room
    wc.set_model_state(ROBOT, at(*TABLE), AT_REST)
    assert wc.get_model_state(ROBOT)[0][0][2] == pytest.approx(0.0, abs=1e-7)
    assert stand(sim)[2] == pytest.approx(0.0, abs=0.003)


def test_a_movable_model_is_no_floor(in_room):
    sim, wc = in_room
    home(wc)
    wc.spawn("crate", box_sdf(0.15, 2.0), at(3.0, 3.0, 0.075))
    try:
        wc.set_model_state(ROBOT, at(3.0, 3.0), AT_REST)
        assert wc.get_model_state(ROBOT)[0][0][2] == pytest.approx(0.0, abs=1e-7)
    finally:
        wc.delete("crate")


def test_a_floor_higher_than_the_robot_holding_its_footprint_is_stood_on():
    """A Waffle's top is 0.141 m: at z 0 the 0.19 m floor box holds its whole body, over its
    whole footprint. It stands on top, as at z_pos 0.19 (test_spawn_solid_floor.py has more)."""
    (x, y, yaw), top = RAISED["floor_box"]
    sim = floors_sim(x, y, yaw, model="waffle")
    try:
        assert sim.spawn[2] == pytest.approx(top, abs=0.002)
        assert sim.robot.warnings == []
        assert_on(sim, top, "waffle at z_pos 0")
    finally:
        sim.close()
    sim = floors_sim(x, y, yaw, model="waffle", z=top)
    try:
        assert sim.robot.warnings == []
        assert_on(sim, top, "waffle at z_pos 0.19")
    finally:
        sim.close()


def terrain_world(tmp_path, height=0.3):
    """A world of one open mesh, a 20 m square of two triangles at ``height`` m, with no ground
    plane under it (as an outdoor world's landscape mesh is)."""
    (tmp_path / "terrain.obj").write_text(
        "v -10 -10 0\nv 10 -10 0\nv 10 10 0\nv -10 10 0\nf 1 2 3\nf 1 3 4\n")
    geometry = "<geometry><mesh><uri>terrain.obj</uri></mesh></geometry>"
    path = tmp_path / "terrain.world"
    path.write_text('<?xml version="1.0"?><sdf version="1.6"><world name="w"><model '
                    'name="landscape"><static>true</static><pose>0 0 %g 0 0 0</pose><link '
                    'name="link"><collision name="c">%s</collision><visual name="v">%s'
                    '</visual></link></model></world></sdf>' % (height, geometry, geometry))
    return str(path)


def test_a_robot_under_a_terrain_with_no_ground_below_stands_on_the_terrain(tmp_path):
    """Spawned and teleported at z 0 under a landscape mesh 0.3 m up, higher than the robot
    and with nothing beneath it: on the landscape, not falling through the world."""
    sim = Simulation(SimConfig(world=terrain_world(tmp_path), model="waffle", x=1.0, y=2.0))
    try:
        assert sim.spawn[2] == pytest.approx(0.3)
        _, _, z, roll, pitch = stand(sim)
        assert z == pytest.approx(0.3, abs=0.003) and abs(roll) < LEVEL and abs(pitch) < LEVEL
        wc = WorldControl(sim)
        wc.set_model_state("turtlebot3_waffle", at(-3.0, 1.0, 0.0), AT_REST)
        x, y, z, _, _ = stand(sim)
        assert (x, y, z) == (pytest.approx(-3.0, abs=0.01), pytest.approx(1.0, abs=0.01),
                             pytest.approx(0.3, abs=0.003))
    finally:
        sim.close()


# --- overlap -------------------------------------------------------------------------------------

def test_a_spawn_overlapping_a_wall_is_taken_with_one_warning():
    sim = floors_sim(*WALL)
    try:
        assert ROBOT in sim.models and sim.spawn == WALL + (0.0, 0.0)
        (warning,) = sim.robot.warnings
        line = "%s: %s" % (ROBOT, warning)     # as the node logs it (sim_node.sync_robots)
        assert "\n" not in line and len(line) <= 200, line
        assert " wall " in warning and "z_pos 1.000" in warning, warning
        assert "(42.0, 0.08, 0.0)" in warning
    finally:
        sim.close()


def test_spawn_model_of_a_robot_into_the_wall_warns_once_and_spawns(in_room):
    sim, wc = in_room
    home(wc)
    wc.spawn("tb3_2", urdf_text("burger"), at(42.5, -0.08), kind="urdf",
             robot_namespace="tb3_2")
    try:
        (warning,) = sim.robots["tb3_2"].warnings
        assert " wall " in warning and "z_pos 1.000" in warning, warning
    finally:
        wc.delete("tb3_2")


def test_a_long_model_name_keeps_the_warning_to_one_short_line(tmp_path):
    name = "w" * 250
    with open(FLOORS) as f:
        text = f.read().replace("name='wall'", "name='%s'" % name)
    path = tmp_path / "long.world"
    path.write_text(text.replace("meshes/", os.path.dirname(FLOORS) + "/meshes/"))
    sim = Simulation(SimConfig(world=str(path), x=WALL[0], y=WALL[1]))
    try:
        (warning,) = sim.robot.warnings
        assert len("%s: %s" % (ROBOT, warning)) <= 200 and "www..." in warning
    finally:
        sim.close()


# --- the rule, measured --------------------------------------------------------------------------

class RaysDown:
    """A stand-in for WorldPhysics: a flat floor at ``floor`` m, recording the rays asked."""

    def __init__(self, floor):
        self.floor = floor
        self.asked = []

    def surfaces_below(self, points, top, bottom, static_only=True, lowest=False):
        self.asked.append((np.asarray(points), top, bottom))
        return np.full(len(points), self.floor if bottom <= self.floor <= top else np.nan)

    def solids_at(self, points):
        """No solid: the floor is a surface."""
        return [frozenset()] * len(points)


def test_the_rays_run_from_the_robot_top_to_the_requested_z_over_its_footprint():
    burger = read_urdf(urdf_path("burger"))
    top, reach = robot_extent(collision_points(burger), (0.0, 0.0, 0.0, 1.0))
    assert top == pytest.approx(0.19125, abs=1e-4)            # the top of its laser
    assert reach == pytest.approx(spawn_check.footprint_radius(burger), abs=0.005)
    rays = RaysDown(0.05)
    assert landed_pose(rays, burger, at(1.0, 2.0, 0.0)) == ((1.0, 2.0, 0.05), at(0, 0)[1])
    points, start, end = rays.asked[0]
    assert (start, end) == (pytest.approx(top), -spawn_check.BURIED_DEPTH)
    assert len(rays.asked) == 1          # a floor met: one cast
    assert np.hypot(points[:, 0] - 1.0, points[:, 1] - 2.0).max() == pytest.approx(reach)
    assert len(points) > 16
    # a floor no higher than LIFT_TOLERANCE: the pose as given
    for floor in (LIFT_TOLERANCE, -0.1):
        pose = at(1.0, 2.0, 0.0)
        assert landed_pose(RaysDown(floor), burger, pose) is pose
    # the only surface above the robot's top, nothing below it: under the ground, onto it
    rays = RaysDown(0.25)
    assert landed_pose(rays, burger, at(1.0, 2.0, 0.0)) == ((1.0, 2.0, 0.25), at(0, 0)[1])
    assert [(start, end) for _, start, end in rays.asked] == [
        (pytest.approx(top), -spawn_check.BURIED_DEPTH),
        (spawn_check.BURIED_DEPTH, pytest.approx(top))]
    # on its back (pitched 90 degrees) its top is the back of its chassis, 0.102 m from the root
    rays = RaysDown(-1.0)
    landed_pose(rays, burger, ((0.0, 0.0, 0.3), quat_from_rpy(0.0, math.pi / 2, 0.0)))
    assert rays.asked[0][1] == pytest.approx(0.3 + 0.102, abs=1e-3)
