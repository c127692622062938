"""A world's meshes read ahead in parallel into the disk cache (mesh_prefetch): the same meshes
and the same warnings or refusals as without it. conftest gives every test an empty cache
under a ROS_HOME of its own. The meshes are bench/mesh_world.py's textured Collada models."""
import os


from tutorial_turtlebot.errors import WorldError
from tutorial_turtlebot.sim.files.meshes import mesh_cache, mesh_file, mesh_prefetch
from tutorial_turtlebot.sim.files.meshes.mesh_file import load_mesh
from tutorial_turtlebot.sim.files.sdf.world_sdf import load_world
import unit_paths

from mesh_cache_helpers import assert_same, dae, entries, mesh_world
HERE = unit_paths.UNIT


def test_parallel_conversion_gives_the_serial_meshes(models, reads, monkeypatch, tmp_path):
    paths = [dae(models, n) for n in range(6)]
    serial = [load_mesh(p) for p in paths]
    assert len(reads) == 6
    monkeypatch.setenv("ROS_HOME", str(tmp_path / "parallel_home"))
    mesh_file.cache_clear()
    mesh_cache.forget_state()
    assert mesh_prefetch.convert_ahead(paths, workers=2) == {}
    here = len(reads) - 6                   # this process reads a share, a worker the rest
    assert len(entries()) == 6 and 0 < here < 6
    for path, mesh in zip(paths, serial):
        assert_same(load_mesh(path), mesh)
    assert len(reads) == 6 + here


def _world(tmp_path, models, bad_body):
    """A world of five generated models and one whose mesh file is ``bad_body``."""
    bad = os.path.join(models, "bad", "meshes")
    os.makedirs(bad)
    name = "bad.dae" if isinstance(bad_body, bytes) else bad_body[0]
    with open(os.path.join(bad, name), "wb") as f:
        f.write(bad_body if isinstance(bad_body, bytes) else bad_body[1])
    includes = "".join("<include><uri>model://%s</uri><pose>%d 3 0 0 0 0</pose></include>"
                       % (mesh_world.model_name(n), n) for n in range(5))
    world = tmp_path / "w.world"
    world.write_text(
        '<?xml version="1.0"?>\n<sdf version="1.6"><world name="w">%s\n<model name="bad">'
        '<static>true</static><link name="l"><collision name="c"><geometry><mesh><uri>'
        'file://%s</uri></mesh></geometry></collision></link></model></world></sdf>\n'
        % (includes, os.path.join(bad, name)))
    return str(world)


def _serial_and_parallel(monkeypatch, tmp_path, world, models):
    """(what loading ``world`` gives serially, the same with the pool, where a worker reads
    every file): a World's warnings or a WorldError's line."""
    monkeypatch.setenv("GAZEBO_MODEL_PATH", models)
    monkeypatch.setattr(mesh_prefetch, "_shares", lambda paths, count: [[], list(paths)])
    spawned = []
    real = mesh_prefetch.convert_ahead
    monkeypatch.setattr(mesh_prefetch, "convert_ahead", lambda paths, **kw: spawned.append(
        real(paths, workers=2, **kw)) or spawned[-1])
    out = []
    for pool in (False, True):
        monkeypatch.setenv("ROS_HOME", str(tmp_path / ("home_%s" % pool)))
        monkeypatch.setattr(mesh_prefetch, "MIN_POOL_FILES", 1 if pool else 10 ** 6)
        mesh_file.cache_clear()
        mesh_cache.forget_state()
        try:
            out.append(load_world(world).warnings)
        except WorldError as err:
            out.append(str(err))
    return out, spawned


def test_a_file_that_fails_in_the_pool_warns_as_it_does_serially(models, monkeypatch,
                                                                 tmp_path, reads):
    world = _world(tmp_path, models, b"this is no XML, so no Collada")
    (serial, parallel), spawned = _serial_and_parallel(monkeypatch, tmp_path, world, models)
    assert len(serial) == 1 and "bad.dae" in serial[0] and "left out" in serial[0]
    assert parallel == serial
    assert list(spawned[-1]) == [os.path.join(models, "bad", "meshes", "bad.dae")]
    # read by the serial run and by the worker, not again here after the worker's failure
    assert reads.count(os.path.join(models, "bad", "meshes", "bad.dae")) == 1


def test_a_file_refused_in_the_pool_is_refused_as_serially(models, monkeypatch, tmp_path):
    world = _world(tmp_path, models, ("bad.stl", b"solid x\nfacet normal\nnot an stl\n"))
    (serial, parallel), spawned = _serial_and_parallel(monkeypatch, tmp_path, world, models)
    assert isinstance(serial, str) and "bad.stl" in serial
    assert parallel == serial
    assert spawned[-1]


def test_a_world_of_few_meshes_starts_no_pool(models, monkeypatch):
    monkeypatch.setattr("subprocess.Popen", None)      # would fail if called
    assert mesh_prefetch.convert_ahead([dae(models, 0), dae(models, 1)]) == {}


def test_the_pool_writes_the_obj_files_a_textured_visual_needs(models, monkeypatch):
    paths = [dae(models, n) for n in range(4)]
    mesh_prefetch.convert_ahead(paths, workers=2, scales={paths[0]: [[0.9, 0.9, 1.1]]})
    monkeypatch.setattr(mesh_cache, "write_obj_parts", None)    # would fail if called here
    mesh = load_mesh(paths[0], (0.9, 0.9, 1.1))
    full = {p.texture: 0 for p in mesh.parts if p.texture is not None}
    assert full
    parts = mesh_cache.visual_obj_parts(mesh, "/nonexistent", full)
    assert parts and all(os.path.isfile(p) for p, _ in parts)
