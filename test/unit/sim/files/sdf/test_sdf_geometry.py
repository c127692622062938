"""SDF geometry as the world loader reads it (sdf_geometry): a plane's <size> beyond the abuse
limit is drawn limits.MAX_SIZE a side with one warning, and the plane still collides as an
infinite plane, as Gazebo's; a Waffle Pi stands on the 40 km plane of
test/fixtures/worlds/big_plane.world (ours). No ROS."""
import math
import os

import pybullet
import pytest

from tutorial_turtlebot.errors import WorldError
from tutorial_turtlebot.sim.engine.world_bullet import build_world
from tutorial_turtlebot.sim.files import limits
from tutorial_turtlebot.sim.files.sdf.world_sdf import load_world
from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation

import unit_paths

BIG_PLANE = os.path.join(unit_paths.FIXTURES, "worlds", "big_plane.world")


def plane_world(tmp_path, size):
    path = tmp_path / "plane.world"
    path.write_text('<sdf version="1.6"><world name="w"><model name="p"><static>true</static>'
                    '<link name="l"><collision name="c"><geometry><plane><size>%s</size>'
                    '</plane></geometry></collision></link></model></world></sdf>' % size)
    return str(path)


def test_a_40_km_plane_is_drawn_at_the_limit_with_one_warning_and_collides_everywhere(client):
    world = load_world(BIG_PLANE)
    assert [s.size for s in world.shapes] == [(limits.MAX_SIZE, limits.MAX_SIZE)] * 2
    [warning] = world.warnings
    assert "plane <size> 40000 40000 drawn 10000 x 10000 m" in warning
    assert "only its drawing is clamped" in warning and "infinite plane" in warning
    assert "\n" not in warning and len(warning) <= 200
    ground = build_world(world, client)["ground_plane::link::collision"]
    # within the drawn 10 km, beyond it, and beyond the 40 km written
    for x, y in ((0.0, 0.0), (4000.0, -4900.0), (15000.0, 15000.0), (-30000.0, 25000.0)):
        hit = pybullet.rayTestBatch([(x, y, 1.0)], [(x, y, -1.0)], physicsClientId=client)[0]
        assert hit[0] == ground and hit[3][2] == pytest.approx(0.0, abs=1e-3), (x, y)


def test_a_plane_within_the_limit_is_as_written_and_a_bad_size_refused(tmp_path):
    world = load_world(plane_world(tmp_path, "20000 30"))
    assert world.shapes[0].size == (limits.MAX_SIZE, 30.0) and len(world.warnings) == 1
    assert load_world(plane_world(tmp_path, "30 40")).shapes[0].size == (30.0, 40.0)
    for bad in ("-1 5", "nan 5", "0 5", "inf 5"):
        with pytest.raises(WorldError, match="<size>"):
            load_world(plane_world(tmp_path, bad))


def standing(world):
    """(x, y, z, roll, pitch, yaw) of a Waffle Pi spawned at (3, -2) facing 0.5 rad in
    ``world``, after 1 s without a command."""
    sim = Simulation(SimConfig(model="waffle_pi", world=world, x=3.0, y=-2.0, yaw=0.5,
                               camera=False))
    try:
        for _ in range(round(1.0 / sim.config.time_step)):
            sim.robot.before_step(sim.time_ns)
            sim.physics.step()
            sim.time_ns += sim.step_ns
        position, orn = sim.robot.ground_truth()
        return tuple(position) + tuple(sim.physics.client.getEulerFromQuaternion(orn))
    finally:
        sim.close()


def test_a_waffle_pi_stands_on_the_40_km_plane_as_on_the_empty_worlds():
    """Where it was spawned, on z 0, as level as on the empty world's 100 m ground plane."""
    on_big, on_empty = standing(BIG_PLANE), standing("empty")
    x, y, z, roll, pitch, yaw = on_big
    assert math.hypot(x - 3.0, y + 2.0) < 1e-3 and abs(z) < 0.005
    assert yaw == pytest.approx(0.5, abs=1e-5)    # it lands from 1 mm: a few microradians
    assert abs(roll) < 0.01 and abs(pitch) < 0.01
    assert on_big == pytest.approx(on_empty, abs=1e-5)
