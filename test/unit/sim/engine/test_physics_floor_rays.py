"""WorldPhysics.surfaces_below, solids_at and overlaps (engine/physics.py), what
sim/world/spawn_check.py lands robots and names overlaps with: rays straight down on the
collision geometry as pybullet has it, and Bullet's penetration depths. On the world of raised
floors test/fixtures/worlds/floors/ (make_floor_fixtures.py). No ROS master."""
import os

import numpy as np
import pybullet
import pytest

from tutorial_turtlebot.sim.engine.physics import WorldPhysics
from tutorial_turtlebot.sim.engine.world_bullet import MOVABLE_COLLISION_GROUP
from tutorial_turtlebot.sim.files.sdf.world_sdf import load_world

import unit_paths

FLOORS = os.path.join(unit_paths.FIXTURES, "worlds", "floors", "floors.world")


@pytest.fixture(scope="module")
def physics():
    made = WorldPhysics(load_world(FLOORS), 0.0025)
    yield made
    made.close()


def cube(physics, centre, half):
    """A movable cube (1 kg) in the movable bodies' collision group."""
    cid = physics.client
    shape = pybullet.createCollisionShape(pybullet.GEOM_BOX, halfExtents=(half,) * 3,
                                          physicsClientId=cid)
    body = pybullet.createMultiBody(1.0, shape, basePosition=centre, physicsClientId=cid)
    pybullet.setCollisionFilterGroupMask(body, -1, MOVABLE_COLLISION_GROUP, (1 << 28) - 1,
                                         physicsClientId=cid)
    return body


def test_the_highest_surface_under_each_point_is_found_on_every_kind_of_floor(physics):
    points = np.array([(0.0, 0.0), (6.0, 0.0), (12.0, 0.0), (19.3, 0.0), (24.0, 0.0),
                       (30.0, 0.0), (-8.0, 0.0), (36.0, 0.0)])
    tops = physics.surfaces_below(points, 0.5, -0.2)
    # box, closed mesh (its bottom is hit too: the highest counts), box, open mesh, cylinder,
    # polyline (its hull's margin: 1 mm), the ground in the open walls room, a table's top
    assert tops == pytest.approx([0.19, 0.034, 0.01, 0.10, 0.08, 0.061, 0.0, 0.315], abs=1e-3)
    # out in the open, 70 m away: the ground (a plane without end), and nothing above it
    assert physics.surfaces_below(np.array([(70.0, 0.0)]), 0.5, -0.2) == pytest.approx([0.0])
    assert np.isnan(physics.surfaces_below(np.array([(70.0, 0.0)]), 0.5, 0.05)).all()


def test_only_surfaces_between_the_two_heights_count(physics):
    # under the table's top (0.285..0.315): the ground; above the ray's end: nothing
    assert physics.surfaces_below(np.array([(36.0, 0.0)]), 0.2, -0.1) == pytest.approx([0.0])
    assert np.isnan(physics.surfaces_below(np.array([(0.0, 0.0)]), 0.5, 0.2)).all()


def test_a_ray_that_starts_inside_a_solid_does_not_report_its_start(physics):
    found = physics.surfaces_below(np.array([(0.0, 0.0), (42.0, 0.0)]), 0.1, -0.1)
    assert not np.any(np.isclose(found, 0.1, atol=1e-3)), found    # the floor box, the wall


def test_a_movable_body_is_passed_through_unless_asked_for(physics):
    body = cube(physics, (3.0, 3.0, 0.1), 0.1)
    try:
        point = np.array([(3.0, 3.0)])
        assert physics.surfaces_below(point, 0.5, -0.1) == pytest.approx([0.0], abs=1e-6)
        assert physics.surfaces_below(point, 0.5, -0.1, static_only=False) == pytest.approx(
            [0.2], abs=1e-6)
    finally:
        pybullet.removeBody(body, physicsClientId=physics.client)


def test_overlaps_name_the_collider_its_depth_and_top(physics):
    body = cube(physics, (42.0, 0.1, 0.5), 0.1)     # 5 cm into the wall (y -0.05..0.05)
    try:
        (uid, link, depth, top), = physics.overlaps(body, 0.01)
        assert depth == pytest.approx(0.05, abs=0.002) and top == pytest.approx(1.0, abs=0.01)
        assert physics.overlaps(body, 0.06) == []
        pybullet.resetBasePositionAndOrientation(body, (3.0, 3.0, 0.1), (0, 0, 0, 1),
                                                 physicsClientId=physics.client)
        assert physics.overlaps(body, 0.01) == []           # resting on the ground
    finally:
        pybullet.removeBody(body, physicsClientId=physics.client)


def test_the_ground_plane_is_a_half_space_without_end(physics):
    """Far beyond its drawn 100 m: a cube sunk 5 cm into the ground overlaps it with its top
    at 0 (not its unbounded box's), a point 3 m under it is in it, one above it is not."""
    body = cube(physics, (500.0, -400.0, 0.05), 0.1)
    try:
        (uid, link, depth, top), = physics.overlaps(body, 0.01)
        assert depth == pytest.approx(0.05, abs=0.002) and top == pytest.approx(0.0, abs=1e-6)
        under, above = physics.solids_at(np.array([(500.0, -400.0, -3.0), (800.0, 0.0, 0.01)]))
        assert under == {(uid, link)} and above == frozenset()
    finally:
        pybullet.removeBody(body, physicsClientId=physics.client)


def test_a_tilted_plane_s_top_is_its_highest_point_over_what_overlaps_it(tmp_path):
    """A plane rising 0.2 m per m along +x (<normal> -0.2 0 1), through (0, 0, 0.5): a cube
    of half side 0.1 sunk 5 cm into it at x 50 overlaps it, its top at the cube box's uphill
    edge (x 50.1)."""
    geometry = "<geometry><plane><normal>-0.2 0 1</normal></plane></geometry>"
    path = tmp_path / "slope.world"
    path.write_text('<sdf version="1.6"><world name="w"><model name="slope"><static>true'
                    '</static><pose>0 0 0.5 0 0 0</pose><link name="l"><collision name="c">%s'
                    '</collision></link></model></world></sdf>' % geometry)
    slope = WorldPhysics(load_world(str(path)), 0.0025)
    try:
        surface = 0.5 + 0.2 * 50.0
        body = cube(slope, (50.0, 0.0, surface + 0.1 * np.hypot(1.0, 0.2) - 0.05), 0.1)
        (_, _, depth, top), = slope.overlaps(body, 0.01)
        uphill = pybullet.getAABB(body, physicsClientId=slope.client)[1][0]
        assert top == pytest.approx(0.5 + 0.2 * uphill, abs=1e-4) and depth > 0.03
    finally:
        slope.close()


def test_solids_at_finds_the_static_solid_holding_each_point(physics):
    body = cube(physics, (3.0, 3.0, 0.1), 0.1)
    try:
        inside = physics.solids_at(np.array([
            (0.0, 0.0, 0.1), (0.7, 0.0, 0.001), (24.0, 0.0, 0.05), (30.0, 0.0, 0.03),
            (36.0, 0.0, 0.3), (42.0, 0.0, 0.5), (3.0, 3.0, -0.02)]))
        # the floor box (to 1 mm of its bottom), cylinder, polyline, table top, wall, ground
        assert all(len(holders) == 1 for holders in inside), inside
        assert len(set(inside)) == 6 and inside[0] == inside[1]      # the floor box twice
        assert physics.solids_at(np.array([(0.0, 0.0, 0.19)])) == [inside[0]]   # on its face
        # 1 mm above the box, the closed slab mesh, under the table, the movable cube
        assert physics.solids_at(np.array([
            (0.0, 0.0, 0.191), (6.0, 0.0, 0.001), (36.0, 0.0, 0.1),
            (3.0, 3.0, 0.1)])) == [frozenset()] * 4
    finally:
        pybullet.removeBody(body, physicsClientId=physics.client)
