"""The disk cache of converted meshes (mesh_cache, through mesh_file.load_mesh) and the parallel
conversion of a world's meshes. conftest gives every test an empty cache under a ROS_HOME of its
own. The meshes are bench/mesh_world.py's textured Collada models."""
import os
import shutil
import sys

import numpy as np
import pytest

from tutorial_turtlebot.errors import WorldError
from tutorial_turtlebot.sim.files import mesh_cache, mesh_file
from tutorial_turtlebot.sim.files.mesh_file import MeshError, load_mesh
from tutorial_turtlebot.sim.files.world_sdf import load_world
import unit_paths

HERE = unit_paths.UNIT
sys.path.insert(0, os.path.join(HERE, os.pardir, os.pardir, "bench"))
import mesh_world  # noqa: E402

CAP = os.path.join(HERE, os.pardir, "fixtures", "gazebo_models", "mesh_pillar", "meshes")


@pytest.fixture
def models(tmp_path):
    """A folder of six generated model folders (0..5): gen_box_000, gen_drum_001, ..."""
    folder = str(tmp_path / "models")
    for number in range(6):
        mesh_world.write_model(folder, number)
    return folder


def dae(models, number):
    name = mesh_world.model_name(number)
    return os.path.join(models, name, "meshes", name + ".dae")


@pytest.fixture
def reads(monkeypatch):
    """The files mesh_file really reads (its reader, not the cache), in order."""
    seen = []
    real = mesh_file._read
    monkeypatch.setattr(mesh_file, "_read", lambda path, *rest: seen.append(path)
                        or real(path, *rest))
    return seen


def assert_same(a, b):
    assert a.path == b.path
    assert np.array_equal(a.vertices, b.vertices) and len(a.parts) == len(b.parts)
    for p, q in zip(a.parts, b.parts):
        assert np.array_equal(p.faces, q.faces) and p.rgba == q.rgba
        for field in ("uvs", "texture", "texture_problem"):
            x, y = getattr(p, field, None), getattr(q, field, None)
            assert (x is None and y is None) or (
                np.array_equal(x, y) if isinstance(x, np.ndarray) else x == y)


def entries():
    folder = mesh_cache.cache_dir()
    return sorted(f for f in os.listdir(folder) if f.endswith(".npz")) if os.path.isdir(
        folder) else []


def test_the_cache_is_under_ros_home_else_the_xdg_cache():
    assert mesh_cache.cache_dir({"ROS_HOME": "/r", "XDG_CACHE_HOME": "/x"}) == \
        "/r/tutorial_turtlebot/mesh_cache"
    assert mesh_cache.cache_dir({"XDG_CACHE_HOME": "/x"}) == "/x/tutorial_turtlebot/mesh_cache"
    assert mesh_cache.cache_dir({}) == os.path.join(
        os.path.expanduser("~"), ".cache", "tutorial_turtlebot", "mesh_cache")


def test_a_hit_gives_the_same_mesh_without_reading_the_file(models, reads):
    first = load_mesh(dae(models, 1), (0.9, 0.9, 1.1))
    assert reads == [dae(models, 1)] and len(entries()) == 1
    assert first.parts[0].uvs is not None       # a textured part: its new fields are carried
    mesh_file.cache_clear()                     # a new start: memory empty, disk cache full
    again = load_mesh(dae(models, 1), (0.9, 0.9, 1.1))
    assert reads == [dae(models, 1)]
    assert again is not first
    assert_same(again, first)
    assert not again.vertices.flags.writeable


def test_a_changed_mesh_file_is_read_again(models, reads):
    load_mesh(dae(models, 0))
    mesh_file.cache_clear()
    with open(dae(models, 0), "a") as f:
        f.write("<!-- changed -->\n")
    load_mesh(dae(models, 0))
    assert len(reads) == 2


def test_a_changed_texture_is_read_again(models, reads):
    load_mesh(dae(models, 2))
    mesh_file.cache_clear()
    png = os.path.join(os.path.dirname(dae(models, 2)), "skin.png")
    with open(png, "wb") as f:
        f.write(mesh_world.png_bytes(16, 16, lambda x, y: (x * 8, y * 8, 0)))
    load_mesh(dae(models, 2))
    assert len(reads) == 2


def test_a_changed_material_file_is_read_again(tmp_path, reads):
    for name in ("cap.obj", "cap.mtl"):
        shutil.copy(os.path.join(CAP, name), str(tmp_path / name))
    obj = str(tmp_path / "cap.obj")
    before = load_mesh(obj)
    mesh_file.cache_clear()
    assert_same(load_mesh(obj), before)
    assert len(reads) == 1
    mesh_file.cache_clear()
    mtl = (tmp_path / "cap.mtl").read_text().replace("0.8 0.1 0.1", "0.1 0.1 0.8")
    (tmp_path / "cap.mtl").write_text(mtl)
    after = load_mesh(obj)
    assert len(reads) == 2
    assert (0.1, 0.1, 0.8, 1.0) in [p.rgba for p in after.parts]


def test_a_file_added_beside_the_mesh_is_a_miss(tmp_path, reads):
    """A missing .mtl (or texture) put in place later: the mesh is read again, with it."""
    shutil.copy(os.path.join(CAP, "cap.obj"), str(tmp_path / "cap.obj"))
    obj = str(tmp_path / "cap.obj")
    assert all(p.rgba is None for p in load_mesh(obj).parts)
    mesh_file.cache_clear()
    shutil.copy(os.path.join(CAP, "cap.mtl"), str(tmp_path / "cap.mtl"))
    assert (0.8, 0.1, 0.1, 1.0) in [p.rgba for p in load_mesh(obj).parts]
    assert len(reads) == 2


def test_a_changed_converter_misses(models, reads, monkeypatch):
    load_mesh(dae(models, 3))
    mesh_file.cache_clear()
    monkeypatch.setattr(mesh_cache, "_converter", "another version of the code")
    load_mesh(dae(models, 3))
    assert len(reads) == 2


def test_the_converter_digest_is_of_mesh_file_and_mesh_cache_sources(monkeypatch, tmp_path):
    digest = mesh_cache.converter_digest()
    changed = tmp_path / "mesh_file.py"
    changed.write_text(open(mesh_file.__file__).read() + "\n# changed\n")
    monkeypatch.setattr(mesh_file, "__file__", str(changed))
    monkeypatch.setattr(mesh_cache, "_converter", None)
    assert mesh_cache.converter_digest() != digest


@pytest.mark.parametrize("damage", ["truncated", "garbage", "foreign"])
def test_a_damaged_entry_is_ignored_and_replaced(models, reads, capsys, damage):
    first = load_mesh(dae(models, 4))
    (entry,) = entries()
    path = os.path.join(mesh_cache.cache_dir(), entry)
    data = open(path, "rb").read()
    with open(path, "wb") as f:
        if damage == "truncated":
            f.write(data[:len(data) // 2])
        elif damage == "garbage":
            f.write(b"\0not a zip file" * 100)
        else:   # another program's npz: arrays, but no header
            np.savez(f, other=np.arange(3))
    mesh_file.cache_clear()
    assert_same(load_mesh(dae(models, 4)), first)
    assert len(reads) == 2
    warning = capsys.readouterr().err
    assert len(warning.splitlines()) == 1 and "mesh cache" in warning
    mesh_file.cache_clear()
    assert_same(load_mesh(dae(models, 4)), first)     # the entry was written anew: a hit
    assert len(reads) == 2


def test_an_unwritable_cache_loads_with_one_warning(models, reads, capsys, monkeypatch,
                                                    tmp_path):
    blocker = tmp_path / "not_a_folder"
    blocker.write_text("a file where the cache's folder would be")
    monkeypatch.setenv("ROS_HOME", str(blocker))
    meshes = [load_mesh(dae(models, n)) for n in range(3)]
    assert [len(m.faces) for m in meshes] == [len(m.faces) for m in meshes if len(m.faces)]
    warning = capsys.readouterr().err
    assert len(warning.splitlines()) == 1 and "mesh cache" in warning
    assert len(reads) == 3


def test_the_size_bound_removes_the_least_recently_used(models, monkeypatch, tmp_path):
    home = os.environ["ROS_HOME"]
    monkeypatch.setenv("ROS_HOME", str(tmp_path / "elsewhere"))
    load_mesh(dae(models, 3))                  # the size of the entry that comes last
    fourth = sum(os.path.getsize(os.path.join(mesh_cache.cache_dir(), e)) for e in entries())
    monkeypatch.setenv("ROS_HOME", home)
    mesh_file.cache_clear()
    sizes = []
    for n in range(3):
        load_mesh(dae(models, n))
        sizes.append(sum(os.path.getsize(os.path.join(mesh_cache.cache_dir(), e))
                         for e in entries()))
    names = entries()
    order = [mesh_cache._entry_name(dae(models, n), mesh_cache.file_digest(dae(models, n)))
             + ".npz" for n in range(3)]
    assert sorted(order) == names
    for age, name in zip((300, 200, 100), order):     # 0 oldest, then 1, 2
        t = 1e9 - age
        os.utime(os.path.join(mesh_cache.cache_dir(), name), (t, t))
    mesh_file.cache_clear()
    load_mesh(dae(models, 0))                         # a hit: 0 is now the newest
    lru = os.path.getsize(os.path.join(mesh_cache.cache_dir(), order[1]))
    # room for all but the least recently used one, beside the new one
    monkeypatch.setattr(mesh_cache, "MAX_CACHE_BYTES", sizes[-1] - lru + fourth)
    mesh_cache.forget_state()
    load_mesh(dae(models, 3))                         # one more: the oldest (1) goes
    left = entries()
    assert order[1] not in left
    assert order[0] in left and order[2] in left and len(left) == 3


def test_obj_parts_are_written_once_for_the_same_content(models, tmp_path):
    mesh = load_mesh(dae(models, 1))
    calls = []

    def write(m, folder):
        calls.append(folder)
        return mesh_file.write_obj_parts(m, folder)
    first = mesh_cache.obj_parts(mesh, str(tmp_path), write)
    second = mesh_cache.obj_parts(mesh, str(tmp_path), write)
    assert first == second and len(calls) == 1
    assert all(p.startswith(mesh_cache.cache_dir()) and os.path.isfile(p) for p, _ in first)
    other = mesh_cache.obj_parts(mesh_file._scaled(mesh, (2.0, 2.0, 2.0)), str(tmp_path), write)
    assert len(calls) == 2 and other[0][0] != first[0][0]


def test_parallel_conversion_gives_the_serial_meshes(models, reads, monkeypatch, tmp_path):
    paths = [dae(models, n) for n in range(6)]
    serial = [load_mesh(p) for p in paths]
    assert len(reads) == 6
    monkeypatch.setenv("ROS_HOME", str(tmp_path / "parallel_home"))
    mesh_file.cache_clear()
    mesh_cache.forget_state()
    assert mesh_cache.convert_ahead(paths, workers=2) == {}
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
    monkeypatch.setattr(mesh_cache, "_shares", lambda paths, count: [[], list(paths)])
    spawned = []
    real = mesh_cache.convert_ahead
    monkeypatch.setattr(mesh_cache, "convert_ahead", lambda paths, **kw: spawned.append(
        real(paths, workers=2, **kw)) or spawned[-1])
    out = []
    for pool in (False, True):
        monkeypatch.setenv("ROS_HOME", str(tmp_path / ("home_%s" % pool)))
        monkeypatch.setattr(mesh_cache, "MIN_POOL_FILES", 1 if pool else 10 ** 6)
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
    assert mesh_cache.convert_ahead([dae(models, 0), dae(models, 1)]) == {}


def test_the_pool_writes_the_obj_files_a_textured_visual_needs(models, monkeypatch):
    paths = [dae(models, n) for n in range(4)]
    mesh_cache.convert_ahead(paths, workers=2, scales={paths[0]: [[0.9, 0.9, 1.1]]})
    monkeypatch.setattr(mesh_file, "write_obj_parts", None)    # would fail if called here
    mesh = load_mesh(paths[0], (0.9, 0.9, 1.1))
    parts = mesh_cache.visual_obj_parts(mesh, "/nonexistent", True)
    assert parts and all(os.path.isfile(p) for p, _ in parts)
