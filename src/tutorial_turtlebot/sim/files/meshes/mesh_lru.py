"""The meshes read in this process, least recently used first, up to a number of bytes of their
arrays (mesh_file.load_mesh's memory: a world's meshes are read once, a spawned one's again
if it comes back after many others). No ROS and no pybullet here."""
from collections import OrderedDict
from typing import Hashable, Optional

from .mesh_types import Mesh


class MeshLru:
    """Meshes by key; at most ``max_bytes`` of their arrays (``Mesh.nbytes``) are kept, the
    newest always."""

    def __init__(self, max_bytes: int):
        self.max_bytes = max_bytes
        self.bytes = 0                  # of the meshes kept
        self._meshes: "OrderedDict[Hashable, Mesh]" = OrderedDict()

    def get(self, key: Hashable) -> Optional[Mesh]:
        """The mesh kept under ``key`` (now the newest), or None."""
        mesh = self._meshes.get(key)
        if mesh is not None:
            self._meshes.move_to_end(key)
        return mesh

    def keep(self, key: Hashable, mesh: Mesh) -> Mesh:
        """Keep ``mesh`` as the newest; forget the oldest beyond ``max_bytes`` (not this one)."""
        self._meshes[key] = mesh
        self.bytes += mesh.nbytes
        while self.bytes > self.max_bytes and len(self._meshes) > 1:
            _, gone = self._meshes.popitem(last=False)
            self.bytes -= gone.nbytes
        return mesh

    def clear(self) -> None:
        self._meshes.clear()
        self.bytes = 0
