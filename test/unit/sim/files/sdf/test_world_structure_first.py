"""A world that will be refused is refused before any of its meshes is read or converted
(world_sdf.load_world reads the structure first): the refusal of a fault after a large mesh
comes in well under a second, not after the mesh. No ROS master, no pybullet."""
import os
import struct
import time

import pytest

from tutorial_turtlebot.errors import WorldError
from tutorial_turtlebot.sim.files.meshes import mesh_file, mesh_prefetch
from tutorial_turtlebot.sim.files.sdf.world_sdf import load_world

import unit_paths

FIXTURES = unit_paths.FIXTURES


@pytest.fixture
def mesh_reads(monkeypatch):
    """The mesh files load_mesh is asked for and those given to the parallel conversion."""
    calls = {"load_mesh": [], "convert_ahead": []}
    load_mesh, convert_ahead = mesh_file.load_mesh, mesh_prefetch.convert_ahead

    def counted_load(path, *args, **kwargs):
        calls["load_mesh"].append(path)
        return load_mesh(path, *args, **kwargs)

    def counted_convert(paths, *args, **kwargs):
        paths = list(paths)
        calls["convert_ahead"].extend(paths)
        return convert_ahead(paths, *args, **kwargs)
    monkeypatch.setattr(mesh_file, "load_mesh", counted_load)
    monkeypatch.setattr(mesh_prefetch, "convert_ahead", counted_convert)
    mesh_file.cache_clear()
    return calls


def big_stl(path, triangles=200_000):
    """A binary STL of ``triangles`` thin triangles in a 10 m square (9.6 MB)."""
    with open(path, "wb") as f:
        f.write(b"\0" * 80 + struct.pack("<I", triangles))
        for i in range(triangles):
            x, y = (i % 1000) * 0.01, (i // 1000) * 0.05
            f.write(struct.pack("<12fH", 0, 0, 1, x, y, 0, x + 0.01, y, 0, x, y + 0.01, 0, 0))


def test_the_fixture_world_is_refused_without_reading_its_meshes(monkeypatch, mesh_reads):
    monkeypatch.setenv("GAZEBO_MODEL_PATH", os.path.join(FIXTURES, "gazebo_models"))
    path = os.path.join(FIXTURES, "worlds", "refused_after_meshes.world")
    with pytest.raises(WorldError) as err:
        load_world(path)
    assert str(err.value).startswith(path + ":17: ") and "<pose>" in str(err.value)
    assert mesh_reads == {"load_mesh": [], "convert_ahead": []}


def test_a_refusal_after_a_large_mesh_comes_in_well_under_a_second(tmp_path, mesh_reads):
    big_stl(str(tmp_path / "floor.stl"))
    world = tmp_path / "big.world"
    world.write_text(
        '<sdf version="1.6"><world name="w">\n'
        '<model name="floor"><static>true</static><link name="l"><collision name="c"><geometry>'
        '<mesh><uri>floor.stl</uri></mesh></geometry></collision></link></model>\n'
        '<model name="bad"><static>true</static><pose>0 0 0 0 0 0 0</pose></model>\n'
        '</world></sdf>\n')
    start = time.monotonic()
    with pytest.raises(WorldError, match=":3: <pose>: must be 6 numbers"):
        load_world(str(world))
    assert time.monotonic() - start < 1.0
    assert mesh_reads == {"load_mesh": [], "convert_ahead": []}


def test_a_world_that_loads_still_reads_its_meshes_once_each(monkeypatch, mesh_reads):
    """The structure pass reads no mesh; the conversion pass notes them; the last pass reads
    each file (from the cache the conversion filled)."""
    monkeypatch.setenv("GAZEBO_MODEL_PATH", os.path.join(FIXTURES, "gazebo_models"))
    world = load_world(os.path.join(FIXTURES, "worlds", "turtlebot3_world_meshes.world"))
    assert any(s.kind == "mesh" for s in world.shapes)
    meshes = {s.mesh for s in world.shapes if s.kind == "mesh"}
    assert set(mesh_reads["convert_ahead"]) <= meshes
    assert meshes <= set(mesh_reads["load_mesh"])
