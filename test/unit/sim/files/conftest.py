"""Fixtures of the mesh tests in this folder (test_mesh_cache.py, test_mesh_prefetch.py), made
with test/unit/mesh_cache_helpers.py."""
import pytest

from mesh_cache_helpers import record_reads, write_models


@pytest.fixture
def models(tmp_path):
    """A folder of six generated model folders (0..5): gen_box_000, gen_drum_001, ..."""
    return write_models(str(tmp_path / "models"))


@pytest.fixture
def reads(monkeypatch):
    """The files mesh_file really reads (its reader, not the cache), in order."""
    return record_reads(monkeypatch)
