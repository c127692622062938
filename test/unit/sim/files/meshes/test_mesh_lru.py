"""The meshes kept in memory (mesh_lru, as mesh_file.load_mesh uses it). No ROS master."""
import numpy as np

from tutorial_turtlebot.sim.files.meshes import mesh_file
from tutorial_turtlebot.sim.files.meshes.mesh_lru import MeshLru
from tutorial_turtlebot.sim.files.meshes.mesh_types import Mesh, MeshPart


def mesh(n_vertices):
    return Mesh("m", np.zeros((n_vertices, 3)), (MeshPart(np.zeros((1, 3), dtype=np.int64), None),))


def test_the_newest_is_kept_and_the_oldest_go_past_the_bound():
    small, big = mesh(1), mesh(100)
    lru = MeshLru(max_bytes=small.nbytes * 3)
    lru.keep("a", small)
    lru.keep("b", small)
    assert lru.get("a") is small                   # a is now newer than b
    lru.keep("c", small)
    lru.keep("d", small)                           # past the bound: b, the oldest, goes
    assert lru.get("b") is None and lru.get("a") is small and lru.bytes == 3 * small.nbytes
    lru.keep("e", big)                             # larger than the bound: kept alone
    assert lru.get("e") is big and lru.get("a") is None and lru.bytes == big.nbytes
    lru.clear()
    assert lru.get("e") is None and lru.bytes == 0


def test_the_meshes_read_are_kept_up_to_a_size_least_recently_used_first(tmp_path, monkeypatch):
    mesh_file.cache_clear()
    paths = []
    for k in range(3):
        path = tmp_path / ("t%d.obj" % k)
        path.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 %d\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n"
                        % (k + 1))
        paths.append(str(path))
    one = mesh_file.load_mesh(paths[0])
    size = mesh_file.MESHES.bytes          # one file: its mesh, and the same at scale 1
    monkeypatch.setattr(mesh_file.MESHES, "max_bytes", 2 * size)
    assert mesh_file.load_mesh(paths[0]) is one               # kept
    mesh_file.load_mesh(paths[1])
    assert mesh_file.MESHES.bytes <= 2 * size
    assert mesh_file.load_mesh(paths[1]) is mesh_file.load_mesh(paths[1])
    mesh_file.load_mesh(paths[2])
    assert mesh_file.load_mesh(paths[0]) is not one           # forgotten, read again
    mesh_file.cache_clear()
