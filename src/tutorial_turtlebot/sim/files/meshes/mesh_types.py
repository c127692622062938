"""What a mesh file becomes (``Mesh``, one ``MeshPart`` per material) and the errors of reading
one. No ROS and no pybullet here; mesh_file.load_mesh makes them.

Units: metres, in the mesh frame (the frame the SDF ``<mesh>``'s visual or collision pose
places); colours 0..1; texture coordinates (u, v) with v up (OBJ's convention: image row 0 at
v = 1).
"""
from dataclasses import dataclass
from typing import Optional, Tuple

import numpy as np

from ....errors import UserError

Rgba = Tuple[float, float, float, float]


class MeshError(UserError):
    """A mesh file that cannot be used; ``str(err)`` is one line naming the file and the problem."""


class MeshUnreadable(MeshError):
    """A Collada file whose content cannot be read (not XML, not Collada, or no triangles in
    it). Gazebo then loads the link without that geometry; world_sdf does the same, with this
    line as a warning. Files that are refused (not regular, too big, non-finite or far vertices)
    stay MeshError."""


@dataclass(frozen=True, eq=False)
class MeshPart:
    """The triangles of one material. Every field is a numpy array, a str or None, or a tuple
    of floats or None (mesh caches store a part field by field)."""

    faces: np.ndarray        # (K, 3) int indices into Mesh.vertices, counter-clockwise from outside
    rgba: Optional[Rgba]     # the material's diffuse colour (0..1); None if the file gives none
    uvs: Optional[np.ndarray] = None   # (K, 3, 2) float64 texture (u, v) of each face's corners
    #                                    (OBJ convention: v up, image row 0 at v = 1); or None
    texture: Optional[str] = None      # absolute path of its diffuse image, a regular PNG or
    #                                    JPEG file (texture_images.find_texture); None if none
    texture_problem: Optional[str] = None   # one line: why a texture the file names is not
    #                                         used (the part is drawn in its colour); else None


@dataclass(frozen=True, eq=False)
class Mesh:
    """A triangle mesh in metres in the mesh frame; loaded meshes are shared: read-only arrays."""

    path: str
    vertices: np.ndarray         # (N, 3) float64, m
    parts: Tuple[MeshPart, ...]  # one per material colour, at least one

    @property
    def faces(self) -> np.ndarray:
        """(K, 3) every part's faces, concatenated in part order."""
        return np.concatenate([p.faces for p in self.parts])

    @property
    def bounds(self) -> Tuple[np.ndarray, np.ndarray]:
        """(min xyz, max xyz) of the vertices the faces use, m."""
        used = self.vertices[np.unique(self.faces)]
        return used.min(axis=0), used.max(axis=0)

    @property
    def nbytes(self) -> int:
        """Bytes of its vertex and face arrays."""
        return self.vertices.nbytes + sum(part.faces.nbytes for part in self.parts)
