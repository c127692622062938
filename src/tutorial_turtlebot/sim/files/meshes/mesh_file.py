"""Mesh files as Gazebo reads them: Collada (.dae), STL (binary or ASCII) and Wavefront OBJ.

No ROS and no pybullet here. ``load_mesh`` makes a file a ``Mesh`` (mesh_types): float64
vertices in metres in the mesh frame (the frame the SDF ``<mesh>``'s visual or collision pose
places) and one ``MeshPart`` of triangles per material colour. The readers: collada_reader
(unit and node transforms, not the up axis, as Gazebo), stl_obj_reader (trimesh); the images
they name: texture_images; the files they read beside the mesh: mesh_side_files.

Points shared by several triangles become one vertex (texture coordinates are per triangle
corner, so nothing of them is lost). Then every vertex is multiplied by ``scale`` (per axis; a
mirroring scale keeps the faces counter-clockwise seen from outside, corners and their texture
coordinates reversed together), and every vertex a triangle uses must then lie within
+-limits.MAX_POSITION m of the mesh frame.

Files are read through file_read: the mesh and every file it names (an OBJ's ``mtllib`` and
textures, a Collada's images) only if they are regular files, the mesh of at most
file_read.MAX_MESH_FILE_BYTES, the others MAX_MESH_SIDE_FILE_BYTES. A Collada file that is a
zip archive (.zae) is refused, as Gazebo refuses it.

trimesh and pycollada are imported on first use, so worlds without meshes do not pay for them.
A file is read once for the same (real path, mtime, size), whatever the scale, while its mesh
is among the last MESHES.max_bytes of meshes used (mesh_lru); and once for the same content
across starts, while mesh_cache keeps it on disk. While ``noting`` (a world read ahead of its
meshes, mesh_prefetch), load_mesh reads nothing and notes what it is asked for.
"""
import contextlib
import math
import os
import threading
import warnings
from dataclasses import replace
from typing import Dict, Iterator, List, Optional, Sequence, Tuple

import numpy as np

from .. import limits
from . import mesh_cache
from .collada_reader import read_collada
from ..file_read import MAX_MESH_FILE_BYTES, not_regular
from .mesh_lru import MeshLru
from .mesh_side_files import SideFiles, read_file, read_log
from .mesh_types import Mesh, MeshError, MeshPart, MeshUnreadable
from .stl_obj_reader import read_stl_obj
from .texture_images import texture_line

_FORMATS = {".dae": "Collada", ".stl": "STL", ".obj": "Wavefront OBJ"}
SUFFIXES = tuple(_FORMATS)   # the file name endings read (any letter case)

# The meshes read: (real path, mtime, size) -> the file's mesh, unscaled, and the same +
# (scale,) -> the mesh load_mesh returns.
MESHES = MeshLru(256 * 1024 * 1024)


def load_mesh(path: str, scale: Sequence[float] = (1.0, 1.0, 1.0)) -> Mesh:
    """The mesh in file ``path`` multiplied by ``scale`` (x, y, z; finite, non-zero); MeshError
    (one line) if the file is missing, of an unknown kind, malformed or holds no triangles."""
    try:
        factors = tuple(float(v) for v in scale)
    except (TypeError, ValueError):
        factors = ()
    if len(factors) != 3 or not all(math.isfinite(v) and v != 0.0 for v in factors):
        raise MeshError("%s: mesh scale must be three finite non-zero numbers, got %r"
                        % (path, scale))
    if not os.path.exists(path):
        raise MeshError("%s: no such mesh file" % path)
    why = not_regular(path)
    if why is not None:
        raise MeshError("%s: %s (a mesh file is needed)" % (path, why))
    suffix = os.path.splitext(path)[1].lower()
    if suffix not in SUFFIXES:
        raise MeshError("%s: unknown mesh format %r; the formats read are %s"
                        % (path, suffix, ", ".join(SUFFIXES)))
    stat = os.stat(path)
    file_key = (os.path.realpath(path), stat.st_mtime_ns, stat.st_size)
    scaled = MESHES.get(file_key + (factors,))
    if scaled is not None:
        return scaled
    noted = noted_paths()
    if noted is not None:       # a world read ahead of its meshes (mesh_prefetch)
        noted.append((path, factors))
        return _placeholder(path)
    unscaled = MESHES.get(file_key) or MESHES.keep(file_key,
                                                   _read_cached(path, suffix, file_key))
    return MESHES.keep(file_key + (factors,), _scaled(unscaled, factors))


def cache_clear() -> None:
    """Forget every mesh read (for tests); the disk cache stays (mesh_cache.clear)."""
    MESHES.clear()


# --- a world read ahead of its meshes (mesh_prefetch) -----------------------------------------

_noting = threading.local()
_failures: Dict[tuple, Tuple[str, str]] = {}


def noted_paths() -> Optional[List[Tuple[str, Tuple[float, float, float]]]]:
    """While ``noting``: the list load_mesh notes (file, scale) in (and reads nothing); else
    None."""
    return getattr(_noting, "paths", None)


@contextlib.contextmanager
def noting() -> Iterator[List[Tuple[str, Tuple[float, float, float]]]]:
    """While in it, load_mesh of this thread reads nothing: it notes (file, scale) in the list
    it gives and returns a one-triangle placeholder."""
    _noting.paths = paths = []
    try:
        yield paths
    finally:
        _noting.paths = None


def note_failure(file_key: tuple, failure: Tuple[str, str]) -> None:
    """(error class name, line) that a pool worker met reading the file of ``file_key`` ((real
    path, mtime ns, size)): load_mesh raises it once instead of reading the file again."""
    _failures[file_key] = failure


def forget_failures() -> None:
    """Forget what ``note_failure`` noted (for tests)."""
    _failures.clear()


def _placeholder(path: str) -> Mesh:
    """A one-triangle mesh for a file only noted, not read."""
    return Mesh(path, np.identity(3), (MeshPart(np.array([[0, 1, 2]]), None),))


# --- reading --------------------------------------------------------------------------------

def _read_cached(path: str, suffix: str, file_key: tuple) -> Mesh:
    """``_read``'s mesh, from the disk cache (mesh_cache) when it holds this content."""
    failure = _failures.pop(file_key, None)    # met by a pool worker: raised as it would be
    if failure is not None and failure[0] in ("MeshError", "MeshUnreadable"):
        raise {"MeshError": MeshError, "MeshUnreadable": MeshUnreadable}[failure[0]](failure[1])
    data = read_file(path, MAX_MESH_FILE_BYTES, "this %s file" % _FORMATS[suffix], MeshError)
    digest = mesh_cache.file_digest(path, data)
    mesh = mesh_cache.load(path, digest)
    if mesh is None:
        with read_log() as log:
            mesh = _read(path, suffix, data)
        mesh_cache.store(path, digest, mesh, log)
    return mesh


def _read(path: str, suffix: str, data: Optional[bytes] = None) -> Mesh:
    """The file's mesh, unscaled, checked: finite vertices, triangles with indices in range.
    ``data``: the file's bytes, if the caller has read them already."""
    if data is None:
        data = read_file(path, MAX_MESH_FILE_BYTES, "this %s file" % _FORMATS[suffix],
                         MeshError)
    side_files = SideFiles(path)
    unreadable = MeshUnreadable if suffix == ".dae" else MeshError   # its content, not the file
    try:
        with warnings.catch_warnings():   # pycollada's numpy.matrix, trimesh's notes
            warnings.simplefilter("ignore")
            if suffix == ".dae":
                vertices, parts = read_collada(data, side_files)
            else:
                vertices, parts = read_stl_obj(data, suffix[1:], side_files)
    except Exception as err:   # trimesh, pycollada, lxml, numpy: any failure is a bad file
        if side_files.refused is not None:
            raise MeshError(side_files.refused) from None
        text = " ".join(str(err).split()) or type(err).__name__
        raise unreadable("%s: cannot read this %s file: %s"
                         % (path, _FORMATS[suffix], text[:200])) from None
    if side_files.refused is not None:
        raise MeshError(side_files.refused)
    parts = [_checked_uvs(replace(p, faces=np.asarray(p.faces, dtype=np.int64).reshape(-1, 3)),
                          path) for p in parts]
    parts = [p for p in parts if len(p.faces)]
    if not parts:
        raise unreadable(
            "%s: the file holds no triangles" % path)
    vertices = np.asarray(vertices, dtype=np.float64).reshape(-1, 3)
    if not np.all(np.isfinite(vertices)):
        raise MeshError("%s: the file has vertex coordinates that are not numbers" % path)
    if any(p.faces.min() < 0 or p.faces.max() >= len(vertices) for p in parts):
        raise MeshError("%s: a triangle names a vertex the file does not have" % path)
    # One vertex per distinct point (STL and Collada repeat them); no triangle repeats one.
    # Texture coordinates belong to the triangles' corners: they go where their triangle goes.
    vertices, inverse = np.unique(vertices, axis=0, return_inverse=True)
    inverse = inverse.reshape(-1)
    kept = []
    for part in parts:
        f = inverse[part.faces]
        keep = (f[:, 0] != f[:, 1]) & (f[:, 1] != f[:, 2]) & (f[:, 2] != f[:, 0])
        if keep.any():
            kept.append(replace(part, faces=f[keep],
                                uvs=None if part.uvs is None else part.uvs[keep]))
    if not kept:
        raise unreadable(
            "%s: the file holds no triangles (only degenerate ones)" % path)
    return Mesh(path, vertices, tuple(_merge_colours(kept)))


def _checked_uvs(part: MeshPart, path: str) -> MeshPart:
    """``part`` with its uvs as (K, 3, 2) float64, or without texture (and saying why) if they
    do not fit its faces or are not finite numbers."""
    if part.texture is None:
        return replace(part, uvs=None)
    uvs = None if part.uvs is None else np.asarray(part.uvs, dtype=np.float64)
    if uvs is None or uvs.shape != (len(part.faces), 3, 2) or not np.all(np.isfinite(uvs)):
        why = ("its triangles have no texture coordinates" if uvs is None
               else "its texture coordinates do not fit its triangles or are not numbers")
        return replace(part, uvs=None, texture=None,
                       texture_problem=texture_line(path, part.texture, why))
    return replace(part, uvs=uvs)


def _merge_colours(parts: List[MeshPart]) -> List[MeshPart]:
    """One part per distinct (colour, texture), in order of first appearance; an untextured
    part keeps the first texture_problem of its group (they are drawn alike)."""
    merged: Dict[tuple, List[MeshPart]] = {}
    for part in parts:
        merged.setdefault((part.rgba, part.texture), []).append(part)
    out = []
    for group in merged.values():
        first = group[0]
        uvs = None if first.texture is None else np.concatenate([p.uvs for p in group])
        problem = next((p.texture_problem for p in group if p.texture_problem), None)
        out.append(replace(first, faces=np.concatenate([p.faces for p in group]), uvs=uvs,
                           texture_problem=problem))
    return out


def _scaled(mesh: Mesh, factors: Tuple[float, float, float]) -> Mesh:
    """``mesh`` scaled per axis, its arrays read-only; a mirror (odd number of negative factors)
    reverses every triangle so that faces stay counter-clockwise seen from outside. MeshError
    if a vertex a triangle uses lands beyond +-limits.MAX_POSITION (or overflows)."""
    with np.errstate(over="ignore"):
        vertices = mesh.vertices * np.array(factors)
    used = vertices[np.unique(mesh.faces)].ravel()
    worst = int(np.argmax(np.abs(used)))
    problem = limits.outside("vertex coordinate", used[worst], -limits.MAX_POSITION,
                             limits.MAX_POSITION, "m")
    if problem:
        original = mesh.vertices[np.unique(mesh.faces)].ravel()[worst]
        raise MeshError("%s: %s (the file's %g scaled by %g)"
                        % (mesh.path, problem, original, factors[worst % 3]))
    vertices.setflags(write=False)
    mirror = (factors[0] < 0) ^ (factors[1] < 0) ^ (factors[2] < 0)
    parts = []
    for part in mesh.parts:
        faces = np.ascontiguousarray(part.faces[:, ::-1] if mirror else part.faces)
        faces.setflags(write=False)
        uvs = part.uvs
        if uvs is not None:    # a corner keeps its (u, v): the image is mirrored with the mesh
            uvs = np.ascontiguousarray(uvs[:, ::-1] if mirror else uvs)
            uvs.setflags(write=False)
        parts.append(replace(part, faces=faces, uvs=uvs))
    return Mesh(mesh.path, vertices, tuple(parts))
