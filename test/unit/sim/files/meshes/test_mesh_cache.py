"""The disk cache of converted meshes (mesh_cache, through mesh_file.load_mesh). conftest gives
every test an empty cache under a ROS_HOME of its own. The meshes are bench/mesh_world.py's
textured Collada models; test_mesh_prefetch.py reads them ahead in parallel."""
import os
import shutil

import numpy as np
import pytest

from tutorial_turtlebot.sim.files.meshes import mesh_cache, mesh_file
from tutorial_turtlebot.sim.files.meshes.mesh_file import load_mesh
from tutorial_turtlebot.sim.files.meshes.obj_writer import write_obj_parts
import unit_paths

from mesh_cache_helpers import assert_same, dae, entries, mesh_world
HERE = unit_paths.UNIT

CAP = os.path.join(HERE, os.pardir, "fixtures", "gazebo_models", "mesh_pillar", "meshes")


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


def test_the_converter_digest_is_of_the_converters_sources(monkeypatch, tmp_path):
    """Every module the reading of a mesh imports, of this package, is one of the sources
    (a change in one of them is a new cache); a changed source changes the digest."""
    import ast
    here = os.path.dirname(mesh_cache.__file__)
    todo, seen = ["mesh_file.py", "obj_writer.py"], set()
    while todo:
        name = todo.pop()
        seen.add(name)
        tree = ast.parse(open(os.path.join(here, name)).read())
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom) and node.level == 1:
                for module in [node.module] if node.module else [a.name for a in node.names]:
                    if module + ".py" not in seen and os.path.isfile(
                            os.path.join(here, module + ".py")):
                        todo.append(module + ".py")
    assert seen - {"file_read.py", "limits.py"} == set(mesh_cache.CONVERTER_SOURCES)
    digest = mesh_cache.converter_digest()
    copy = tmp_path / "files"
    shutil.copytree(here, str(copy))
    with open(str(copy / "collada_reader.py"), "a") as f:
        f.write("\n# changed\n")
    monkeypatch.setattr(mesh_cache, "__file__", str(copy / "mesh_cache.py"))
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


def test_the_warning_is_one_line_of_at_most_200_characters_to_the_sink(monkeypatch, capsys):
    """The /gazebo node sends it to rospy's log (warning_sink); stderr is left alone then."""
    said = []
    monkeypatch.setattr(mesh_cache, "warning_sink", said.append)
    mesh_cache.warn_once("a very long reason " * 40 + "\nover two lines")
    mesh_cache.warn_once("a second one is not said")
    [line] = said
    assert len(line) <= 200 and "\n" not in line and line.startswith("mesh cache ")
    assert line.endswith("...; meshes are read from their files")
    assert capsys.readouterr().err == ""


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
        return write_obj_parts(m, folder)
    first = mesh_cache.obj_parts(mesh, str(tmp_path), write)
    second = mesh_cache.obj_parts(mesh, str(tmp_path), write)
    assert first == second and len(calls) == 1
    assert all(p.startswith(mesh_cache.cache_dir()) and os.path.isfile(p) for p, _ in first)
    other = mesh_cache.obj_parts(mesh_file._scaled(mesh, (2.0, 2.0, 2.0)), str(tmp_path), write)
    assert len(calls) == 2 and other[0][0] != first[0][0]
