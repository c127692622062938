"""<mesh> in a world (sdf_meshes): Fuel URLs with and without the Fuel cache, their warnings
(one a file, one line for many), and <submesh> (a Collada node's part, an OBJ object's,
centred or not) drawn and colliding alone. Fixtures of our own: test/fixtures/worlds/fuel/
(a world naming three Fuel meshes, a cache holding one) and test/fixtures/worlds/submesh/
(a Collada file of two submeshes). No ROS."""
import os
import shutil

import numpy as np
import pytest

from tutorial_turtlebot.sim.engine.physics import WorldPhysics
from tutorial_turtlebot.sim.files.meshes.mesh_file import cache_clear, load_mesh
from tutorial_turtlebot.sim.files.sdf.world_sdf import load_world

import unit_paths

FUEL = os.path.join(unit_paths.FIXTURES, "worlds", "fuel")
FUEL_WORLD = os.path.join(FUEL, "fuel_meshes.world")
CRATE_TIP = os.path.join(FUEL, "cache", "fuel.ignitionrobotics.org", "openrobotics", "models",
                         "test_crate", "2", "meshes", "crate.obj")
SUBMESH_WORLD = os.path.join(unit_paths.FIXTURES, "worlds", "submesh", "submesh.world")


@pytest.fixture(autouse=True)
def no_fuel_cache(tmp_path, monkeypatch):
    """An empty HOME (no ~/.ignition/fuel) and no cache variables, unless a test sets them."""
    home = tmp_path / "home"
    home.mkdir()
    monkeypatch.setenv("HOME", str(home))
    for name in ("IGN_FUEL_CACHE_PATH", "GZ_FUEL_CACHE_PATH", "GAZEBO_MODEL_PATH"):
        monkeypatch.delenv(name, raising=False)
    cache_clear()
    yield home
    cache_clear()


def bounds(shape):
    low, high = load_mesh(shape.mesh, shape.size).bounds
    return np.round(low, 6).tolist(), np.round(high, 6).tolist()


# --- Fuel URLs ---------------------------------------------------------------------------------

def test_the_fuel_world_with_its_cache_takes_the_cached_mesh(monkeypatch):
    monkeypatch.setenv("IGN_FUEL_CACHE_PATH", os.path.join(FUEL, "cache"))
    world = load_world(FUEL_WORLD)
    crate = world.model_shapes("crate")
    assert len(crate) == 2 and all(s.mesh == CRATE_TIP for s in crate)   # tip: version 2
    assert bounds(crate[0]) == ([-0.25, -0.25, 0.0], [0.25, 0.25, 0.5])
    assert not world.model_shapes("table") and not world.model_shapes("lamp")
    missing = [w for w in world.warnings if "not cached: its mesh is left out" in w]
    assert len(missing) == 2 and all("\n" not in w for w in missing)
    assert any("Test_Table/3/files/meshes/table.obj" in w for w in missing)
    assert sum("Fuel URLs searched the Fuel cache" in w for w in world.warnings) == 1
    assert len(world.warnings) == 3


def test_the_fuel_world_without_a_cache_loads_without_those_meshes():
    world = load_world(FUEL_WORLD)
    assert world.models == ("ground_plane", "crate", "table", "lamp")
    assert not [s for s in world.shapes if s.kind == "mesh"]
    assert sum("not cached: its mesh is left out" in w for w in world.warnings) == 3
    assert len(world.warnings) == 4


def test_the_cache_in_home_is_gazebos_default(no_fuel_cache):
    shutil.copytree(os.path.join(FUEL, "cache"), str(no_fuel_cache / ".ignition" / "fuel"))
    world = load_world(FUEL_WORLD)
    [shape, _] = world.model_shapes("crate")
    assert shape.mesh == str(no_fuel_cache / ".ignition" / "fuel" / os.path.relpath(
        CRATE_TIP, os.path.join(FUEL, "cache")))


def test_an_include_of_a_fuel_model_takes_its_cached_folder(tmp_path, monkeypatch):
    monkeypatch.setenv("IGN_FUEL_CACHE_PATH", os.path.join(FUEL, "cache"))
    path = tmp_path / "include.world"
    path.write_text('<sdf version="1.6"><world name="w"><include><name>crate</name><uri>'
                    'https://fuel.ignitionrobotics.org/1.0/OpenRobotics/models/Test_Crate'
                    '</uri></include><include><uri>https://fuel.gazebosim.org/1.0/o/models/'
                    'Gone</uri></include></world></sdf>')
    world = load_world(str(path))
    assert world.models == ("crate",)
    assert [s.mesh for s in world.shapes] == [CRATE_TIP] * 2
    assert "<include> left out: https://fuel.gazebosim.org/1.0/o/models/Gone not cached" in \
        world.warnings[0]


def test_many_fuel_files_not_cached_are_one_line(tmp_path):
    uri = "https://fuel.ignitionrobotics.org/1.0/o/models/Part%d/1/files/meshes/part%d.obj"
    models = "".join(
        '<model name="m%d"><static>true</static><link name="l"><visual name="v"><geometry>'
        '<mesh><uri>%s</uri></mesh></geometry></visual></link></model>' % (i, uri % (i, i))
        for i in range(8))
    path = tmp_path / "many.world"
    path.write_text('<sdf version="1.6"><world name="w">%s</world></sdf>' % models)
    world = load_world(str(path))
    [line, searched] = world.warnings
    assert "8 Fuel files not cached, their meshes left out: Part0/meshes/part0.obj" in line
    assert "Part2/meshes/part2.obj ..." in line and len(line) <= 200
    assert searched.startswith("Fuel URLs searched the Fuel cache")


# --- <submesh> ---------------------------------------------------------------------------------

def test_each_submesh_alone_is_drawn_the_centred_one_about_its_centre():
    world = load_world(SUBMESH_WORLD)
    assert world.warnings == ()
    trunk, crown = world.shape("tree::link::trunk"), world.shape("tree::link::crown")
    assert bounds(trunk) == ([-0.1, -0.1, 0.0], [0.1, 0.1, 1.0])       # as written
    assert bounds(crown) == ([-0.5, -0.5, -0.3], [0.5, 0.5, 0.3])      # its centre at 0
    assert [p.rgba for p in load_mesh(trunk.mesh).parts] == [(0.4, 0.25, 0.1, 1.0)]
    assert [p.rgba for p in load_mesh(crown.mesh).parts] == [(0.0, 0.6, 0.0, 1.0)]
    collision = world.shape("tree::link::trunk_collision")
    assert collision.mesh == trunk.mesh and collision.twin == trunk.name


def test_only_the_named_submesh_collides():
    """Rays from x 0 towards the tree at x 2: at 0.5 m they hit the trunk (0.1 m from its
    axis); at 1.3 m they pass where the crown would be, had the whole file collided."""
    physics = WorldPhysics(load_world(SUBMESH_WORLD), 0.0025)
    try:
        directions = np.array([(1.0, 0.0, 0.0)])
        at_trunk = physics.ray_distances(np.array([0.0, 0.0, 0.5]), directions, 5.0)
        at_crown = physics.ray_distances(np.array([0.0, 0.0, 1.3]), directions, 5.0)
    finally:
        physics.close()
    assert at_trunk[0] == pytest.approx(1.9, abs=1e-3)
    assert np.isinf(at_crown[0])


def write_obj_world(folder, submesh):
    """An OBJ of two objects ("left": a 0.2 m cube at y 1, "right": a 0.4 m cube at y -1,
    each of one material) and a world of one visual taking ``submesh`` of it."""
    lines = ["mtllib parts.mtl"]
    for number, (name, side, y) in enumerate((("left", 0.2, 1.0), ("right", 0.4, -1.0))):
        h = side / 2
        lines += ["o %s" % name, "usemtl %s" % name]
        lines += ["v %g %g %g" % (x, y + dy, z) for x in (-h, h) for dy in (-h, h)
                  for z in (0.0, side)]
        b = 8 * number
        lines += ["f %d %d %d" % (b + i, b + j, b + k) for i, j, k in (
            (1, 2, 4), (1, 4, 3), (5, 7, 8), (5, 8, 6), (1, 5, 6), (1, 6, 2), (3, 4, 8),
            (3, 8, 7), (1, 3, 7), (1, 7, 5), (2, 6, 8), (2, 8, 4))]
    (folder / "parts.obj").write_text("\n".join(lines) + "\n")
    (folder / "parts.mtl").write_text("newmtl left\nKd 1 0 0\nnewmtl right\nKd 0 0 1\n")
    (folder / "obj.world").write_text(
        '<sdf version="1.6"><world name="w"><model name="m"><static>true</static>'
        '<link name="l"><visual name="v"><geometry><mesh><uri>parts.obj</uri>%s</mesh>'
        '</geometry></visual></link></model></world></sdf>' % submesh)
    return str(folder / "obj.world")


def test_an_obj_object_is_a_submesh(tmp_path):
    world = load_world(write_obj_world(tmp_path, "<submesh><name>right</name></submesh>"))
    assert world.warnings == ()
    [shape] = world.shapes
    assert bounds(shape) == ([-0.2, -1.2, 0.0], [0.2, -0.8, 0.4])
    assert [p.rgba for p in load_mesh(shape.mesh).parts] == [(0.0, 0.0, 1.0, 1.0)]


def test_a_submesh_the_file_lacks_is_one_warning_and_the_whole_mesh(tmp_path):
    world = load_world(write_obj_world(tmp_path, "<submesh><name>middle</name>"
                                                 "<center>true</center></submesh>"))
    [warning] = world.warnings
    assert "no submesh named 'middle' (its submeshes: left, right)" in warning
    assert "the whole mesh is taken" in warning
    [shape] = world.shapes
    assert shape.mesh == str(tmp_path / "parts.obj")
    assert bounds(shape) == ([-0.2, -1.2, 0.0], [0.2, 1.1, 0.4])
