"""Shared by the disk mesh cache's tests (test/unit/sim/files/meshes/test_mesh_cache.py and
test_mesh_prefetch.py; their fixtures, in test/unit/sim/files/conftest.py, are made of these):
bench/mesh_world.py's textured Collada models, the reads mesh_file makes, a comparison of two
meshes, the cache's entries. Imported by name, as unit_helpers is."""
import os
import sys

import numpy as np

import unit_paths

sys.path.insert(0, os.path.join(unit_paths.ROOT, "bench"))
import mesh_world  # noqa: E402


def write_models(folder):
    """Six generated model folders (0..5) in ``folder``: gen_box_000, gen_drum_001, ..."""
    for number in range(6):
        mesh_world.write_model(folder, number)
    return folder


def dae(models, number):
    """The Collada file of generated model ``number`` in folder ``models``."""
    name = mesh_world.model_name(number)
    return os.path.join(models, name, "meshes", name + ".dae")


def record_reads(monkeypatch):
    """A list that gets the files mesh_file really reads (its reader, not the cache), in
    order."""
    from tutorial_turtlebot.sim.files.meshes import mesh_file
    seen = []
    real = mesh_file._read
    monkeypatch.setattr(mesh_file, "_read", lambda path, *rest: seen.append(path)
                        or real(path, *rest))
    return seen


def assert_same(a, b):
    """Two meshes are the same: path, vertices, and every part's faces, colour and texture."""
    assert a.path == b.path
    assert np.array_equal(a.vertices, b.vertices) and len(a.parts) == len(b.parts)
    for p, q in zip(a.parts, b.parts):
        assert np.array_equal(p.faces, q.faces) and p.rgba == q.rgba
        for field in ("uvs", "texture", "texture_problem"):
            x, y = getattr(p, field, None), getattr(q, field, None)
            assert (x is None and y is None) or (
                np.array_equal(x, y) if isinstance(x, np.ndarray) else x == y)


def entries():
    """The cache's entry files (sorted names), none when it has no folder yet."""
    from tutorial_turtlebot.sim.files.meshes import mesh_cache
    folder = mesh_cache.cache_dir()
    return sorted(f for f in os.listdir(folder) if f.endswith(".npz")) if os.path.isdir(
        folder) else []
