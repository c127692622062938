"""Worlds written for Gazebo, with model:// includes and meshes (world_sdf, world_bullet,
spawn_check), in pybullet with no ROS master. The fixture world test/fixtures/worlds/
turtlebot3_world_meshes.world is turtlebot3_gazebo's turtlebot3_world as Gazebo users have it:
its walls and hexagons are Collada meshes in inches, found through GAZEBO_MODEL_PATH."""
import os

import numpy as np
import pybullet
import pytest

from tutorial_turtlebot.errors import RequestError, WorldError
from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
from tutorial_turtlebot.sim.world.spawn_check import find_obstacle
from tutorial_turtlebot.sim.engine.world_bullet import WORLD_COLLISION_GROUP, build_world

from unit_helpers import ROBOT
from tutorial_turtlebot.sim.files.sdf.world_sdf import load_world
from tutorial_turtlebot.sim.files.world_types import DEFAULT_RGBA
import unit_paths

FIXTURES = unit_paths.FIXTURES
MODELS = os.path.join(FIXTURES, "gazebo_models")
MESH_WORLD = os.path.join(FIXTURES, "worlds", "turtlebot3_world_meshes.world")
SYMBOL = "turtlebot3_world::ros_symbol::symbol::"
SPAWN = (-2.0, -0.5)


@pytest.fixture(autouse=True)
def model_path(monkeypatch):
    monkeypatch.setenv("GAZEBO_MODEL_PATH", MODELS)


def world_with(tmp_path, body):
    path = tmp_path / "test.world"
    path.write_text('<?xml version="1.0"?>\n<sdf version="1.6">\n<world name="w">\n'
                    '<include><uri>model://ground_plane</uri></include>\n%s\n</world>\n</sdf>\n'
                    % body)
    return str(path)


def test_the_mesh_world_is_read_as_gazebo_reads_it():
    world = load_world(MESH_WORLD)
    assert world.models == ("ground_plane", "turtlebot3_world")
    wall = world.shape(SYMBOL + "body")
    assert wall.kind == "mesh" and wall.static and wall.size == (0.25, 0.25, 0.25)
    assert wall.mesh.endswith(os.path.join("turtlebot3_world", "meshes", "wall.dae"))
    assert wall.pose[:3] == (0.0, 0.0, -0.3) and wall.pose[5] == pytest.approx(-1.5708)
    assert world.shape(SYMBOL + "one_one").kind == "cylinder"


def test_its_scan_matches_the_built_in_primitive_copy_ray_by_ray():
    """The same spawn, the same seed: the mesh walls stand where the primitive ones do."""
    scans = []
    for world in (MESH_WORLD, "turtlebot3_world"):
        sim = Simulation(SimConfig(world=world, x=SPAWN[0], y=SPAWN[1]))
        try:
            for _ in range(200):
                sim.step()
            scans.append(np.array(sim.robot.scan(), dtype=float))
        finally:
            sim.close()
    mesh, primitive = scans
    assert np.array_equal(np.isfinite(mesh), np.isfinite(primitive))
    both = np.isfinite(mesh)
    assert both.sum() > 300
    error = np.abs(mesh[both] - primitive[both])
    assert np.median(error) < 0.002 and error.max() < 0.03


@pytest.mark.parametrize("x, y", [
    (0.0, 2.58),                  # across the wall ring's inner face
    (1.8, 2.7),                   # in a hexagon, and across the ring's inner face
])
def test_a_spawn_in_a_mesh_is_taken_with_one_warning(x, y):
    """No refusal (spawn_check): the robot's body cuts the wall ring's triangles, and one
    warning names the model and the ring's top (1.27 m high, from z -0.3) as z_pos."""
    sim = Simulation(SimConfig(world=MESH_WORLD, x=x, y=y))
    try:
        assert sim.spawn[2] == 0.0            # the meshes' bottoms are no floor above z 0
        (warning,) = sim.robot.warnings
        assert " overlaps turtlebot3_world by " in warning and "z_pos 0.970" in warning
    finally:
        sim.close()


@pytest.mark.parametrize("x, y", [SPAWN, (0.0, 3.2), (0.55, 0.55)])
def test_a_spawn_clear_of_the_meshes_is_taken(x, y):
    """In the arena (the ring's hollow is no obstacle), outside the ring, between pillars."""
    assert find_obstacle(load_world(MESH_WORLD), x, y, 0.105) is None


def test_stl_collides_as_triangles_and_obj_draws_its_own_colours(tmp_path, client):
    world = load_world(world_with(tmp_path, '<include><uri>model://mesh_pillar</uri></include>'))
    bodies = build_world(world, client)
    # the pillar spans x 0.8..1.2, y 1.9..2.1, z 0..1.5 in the world
    for start, end, axis, expected in (((0.0, 2.0, 0.5), (2.0, 2.0, 0.5), 0, 0.8),
                                       ((1.0, 0.0, 1.4), (1.0, 4.0, 1.4), 1, 1.9),
                                       ((1.0, 2.0, 3.0), (1.0, 2.0, 0.5), 2, 1.5)):
        hit = pybullet.rayTest(start, end, physicsClientId=client)[0]
        assert hit[0] == bodies["mesh_pillar::pillar::pillar"]
        assert hit[3][axis] == pytest.approx(expected, abs=2e-3)
    cap = bodies["mesh_pillar::pillar::cap"]
    colours = sorted(tuple(round(c, 2) for c in v[7])
                     for v in pybullet.getVisualShapeData(cap, physicsClientId=client))
    assert colours == [(0.8, 0.1, 0.1, 1.0), (0.9, 0.9, 0.9, 1.0)]
    pillar = pybullet.getVisualShapeData(bodies["mesh_pillar::pillar::pillar"],
                                         physicsClientId=client)
    assert [tuple(v[7]) for v in pillar] == [pytest.approx(DEFAULT_RGBA)]   # STL: no colour
    assert pybullet.rayTest((1.0, 1.6, 1.55), (1.0, 2.4, 1.55), physicsClientId=client)[0][0] \
        == -1                                               # a visual the laser passes through


def test_a_material_in_the_sdf_paints_the_whole_mesh(tmp_path, client):
    world = load_world(world_with(tmp_path, '''
      <model name="m"><static>true</static><link name="l"><visual name="v"><geometry><mesh>
        <uri>model://mesh_pillar/meshes/cap.obj</uri></mesh></geometry>
        <material><diffuse>0 0 1 1</diffuse></material></visual></link></model>'''))
    body = build_world(world, client)["m::l::v"]
    assert {tuple(v[7]) for v in pybullet.getVisualShapeData(body, physicsClientId=client)} \
        == {(0.0, 0.0, 1.0, 1.0)}


def test_a_movable_mesh_falls_and_rests_on_its_convex_hull(tmp_path):
    path = world_with(tmp_path, '''
      <model name="crate"><pose>0 0 1 0 0 0</pose><link name="l">
        <inertial><mass>2</mass></inertial>
        <collision name="c"><geometry><mesh><uri>model://mesh_pillar/meshes/pillar.stl</uri>
          <scale>1 1 0.3</scale></mesh></geometry></collision>
        <visual name="v"><geometry><mesh><uri>model://mesh_pillar/meshes/pillar.stl</uri>
          <scale>1 1 0.3</scale></mesh></geometry></visual></link></model>''')
    sim = Simulation(SimConfig(world=path, spawn_robot=False))
    try:
        for _ in range(800):       # 2 s
            sim.step()
        (x, y, z), _ = sim.models.get("crate").pose()
        assert (x, y) == pytest.approx((0.0, 0.0), abs=1e-3)
        assert z == pytest.approx(0.0, abs=5e-3)           # the mesh's z 0 is its bottom face
        hit = pybullet.rayTest((-1.0, 0.0, 0.15), (1.0, 0.0, 0.15),
                               collisionFilterMask=WORLD_COLLISION_GROUP,
                               physicsClientId=sim.physics.client)[0]
        assert hit[3][0] == pytest.approx(-0.2, abs=3e-3)   # the 0.4 m box's hull
    finally:
        sim.close()


def test_a_broken_mesh_is_one_line_naming_the_file_and_the_line(tmp_path):
    (tmp_path / "bad.stl").write_bytes(b"solid nothing\nendsolid\n")
    path = world_with(tmp_path, '''<model name="m"><static>true</static><link name="l">
      <collision name="c"><geometry><mesh><uri>bad.stl</uri></mesh></geometry></collision>
      </link></model>''')
    with pytest.raises(WorldError) as err:
        load_world(path)
    message = str(err.value)
    assert "\n" not in message and "test.world:6:" in message and "bad.stl" in message


@pytest.mark.parametrize("static, coordinate, scale, words", [
    ("true", "1e308", "10 10 10", "vertex coordinate inf is outside [-1e+06, 1e+06] m (the "
                                  "file's 1e+308 scaled by 10)"),
    ("false", "1e12", "1 1 1", "vertex coordinate 1e+12 is outside [-1e+06, 1e+06] m"),
    ("false", "1e308", "1 1 1", "vertex coordinate 1e+308 is outside"),
])
def test_a_spawned_mesh_beyond_the_world_is_refused(tmp_path, empty, monkeypatch, static,
                                                    coordinate, scale, words):
    """These were once taken, the static one blinding the laser (0 hits of 360), the
    movable ones falling through the floor."""
    sim, wc = empty
    (tmp_path / "far.obj").write_text("v 0 0 0\nv %s 0 0\nv 0 1 0\nv 0 0 1\n"
                                      "f 1 2 3\nf 1 3 4\nf 1 4 2\nf 2 4 3\n" % coordinate)
    monkeypatch.chdir(tmp_path)
    sdf = ("<sdf version='1.6'><model name='x'><static>%s</static><link name='l'>"
           "<collision name='c'><geometry><mesh><uri>far.obj</uri><scale>%s</scale></mesh>"
           "</geometry></collision></link></model></sdf>" % (static, scale))
    with pytest.raises(RequestError) as err:
        wc.spawn("far", sdf, ((1.0, 1.0, 0.5), (0, 0, 0, 1)))
    assert words in str(err.value) and "far.obj" in str(err.value)
    assert "\n" not in str(err.value) and "far" not in sim.models
    assert sim.models.names() == ["ground_plane", ROBOT]


def test_the_camera_draws_the_meshes_as_the_primitive_copy_looks():
    """A Waffle Pi's camera at the same pose: the Collada walls and hexagons, drawn in their
    SDF materials' colours, give the picture of the built-in world (mean difference < 1 level,
    while a turn of 0.05 rad changes it by far more)."""
    images = []
    for world, yaw in ((MESH_WORLD, 0.3), ("turtlebot3_world", 0.3), ("turtlebot3_world", 0.35)):
        sim = Simulation(SimConfig(world=world, model="waffle_pi", x=SPAWN[0], y=SPAWN[1],
                                   yaw=yaw))
        try:
            for _ in range(100):
                sim.step()
            images.append(sim.robot.camera_image()[0].astype(float))
        finally:
            sim.close()
    mesh, primitive, turned = images
    assert np.abs(mesh - primitive).mean() < 1.0
    assert np.abs(turned - primitive).mean() > 5.0
