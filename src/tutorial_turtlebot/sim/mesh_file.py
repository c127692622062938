"""Mesh files as Gazebo reads them: Collada (.dae), STL (binary or ASCII) and Wavefront OBJ.

No ROS and no pybullet here. A file becomes a ``Mesh``: float64 vertices in metres in the mesh
frame (the frame the SDF ``<mesh>``'s visual or collision pose places) and one ``MeshPart`` of
triangles per material colour.

- Collada: the ``<asset><unit meter="...">`` (0.0254 for inches) and every ``<node>`` transform
  (matrix, translate, rotate, scale) down to each ``<instance_geometry>`` of the visual scene are
  applied. ``<up_axis>`` is NOT: Gazebo uses the vertex data as written (a Y_UP file is rotated
  by its user in SDF). A part's colour is its material's ``<diffuse><color>``; a textured
  diffuse gives None. A file without ``<scene>`` gives its geometries as written. pycollada,
  which reads it, applies neither unit nor up axis by itself (trimesh's Collada loader, not
  used here, neither: it only records the unit).
- STL (binary or ASCII, read by trimesh): metres as written, no colour.
- OBJ (read by trimesh): each ``usemtl`` material's colour is its ``.mtl`` ``Kd`` (alpha from
  ``d``), also where it has a texture; faces without material have None.
- STL: a binary file with bytes after its last triangle is read as Gazebo reads it (they are
  left out); an ASCII file that is not UTF-8 is read as trimesh guesses its text
  (charset-normalizer).
Points shared by several triangles become one vertex. Then every vertex is multiplied by
``scale`` (per axis; a mirroring scale keeps the faces counter-clockwise seen from outside), and
every vertex a triangle uses must then lie within +-limits.MAX_POSITION m of the mesh frame.

Files are read through file_read: the mesh and every file it names (an OBJ's ``mtllib`` and
textures, a Collada's images, looked for beside it) only if they are regular files, the mesh
of at most file_read.MAX_MESH_FILE_BYTES, the others MAX_MESH_SIDE_FILE_BYTES. A Collada file
that is a zip archive (.zae) is refused, as Gazebo refuses it.

trimesh and pycollada are imported on first use, so worlds without meshes do not pay for them.
A file is read once for the same (real path, mtime, size), whatever the scale, while its mesh
is among the last MAX_CACHED_BYTES of meshes used.
"""
import io
import math
import os
import struct
import tempfile
import warnings
from collections import OrderedDict
from dataclasses import dataclass
from typing import Dict, List, Optional, Sequence, Tuple

import numpy as np

from ..errors import UserError
from . import limits
from .file_read import MAX_MESH_FILE_BYTES, MAX_MESH_SIDE_FILE_BYTES, not_regular, read_file

Rgba = Tuple[float, float, float, float]
_FORMATS = {".dae": "Collada", ".stl": "STL", ".obj": "Wavefront OBJ"}
SUFFIXES = tuple(_FORMATS)   # the file name endings read (any letter case)


class MeshError(UserError):
    """A mesh file that cannot be used; ``str(err)`` is one line naming the file and the problem."""


class MeshUnreadable(MeshError):
    """A Collada file whose content cannot be read (not XML, not Collada, or no triangles in
    it). Gazebo then loads the link without that geometry; world_sdf does the same, with this
    line as a warning. Files that are refused (not regular, too big, non-finite or far vertices)
    stay MeshError."""


@dataclass(frozen=True, eq=False)
class MeshPart:
    """The triangles of one material."""

    faces: np.ndarray        # (K, 3) int indices into Mesh.vertices, counter-clockwise from outside
    rgba: Optional[Rgba]     # the material's diffuse colour (0..1); None if the file gives none


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


# The meshes read, least recently used first: (real path, mtime, size) -> the file's mesh,
# unscaled, and the same + (scale,) -> the mesh load_mesh returns. At most MAX_CACHED_BYTES of
# their arrays are kept: a world's meshes are read once, a spawned one's again if it comes back
# after many others.
MAX_CACHED_BYTES = 256 * 1024 * 1024
_meshes: "OrderedDict[tuple, Mesh]" = OrderedDict()
_cached_bytes = 0


def _nbytes(mesh: Mesh) -> int:
    return mesh.vertices.nbytes + sum(part.faces.nbytes for part in mesh.parts)


def _cached(key: tuple) -> Optional[Mesh]:
    mesh = _meshes.get(key)
    if mesh is not None:
        _meshes.move_to_end(key)
    return mesh


def _keep(key: tuple, mesh: Mesh) -> Mesh:
    """Keep ``mesh`` as the newest; forget the oldest beyond MAX_CACHED_BYTES (not this one)."""
    global _cached_bytes
    _meshes[key] = mesh
    _cached_bytes += _nbytes(mesh)
    while _cached_bytes > MAX_CACHED_BYTES and len(_meshes) > 1:
        _, gone = _meshes.popitem(last=False)
        _cached_bytes -= _nbytes(gone)
    return mesh


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
    scaled = _cached(file_key + (factors,))
    if scaled is not None:
        return scaled
    unscaled = _cached(file_key) or _keep(file_key, _read(path, suffix))
    return _keep(file_key + (factors,), _scaled(unscaled, factors))


def cache_clear() -> None:
    """Forget every mesh read (for tests)."""
    global _cached_bytes
    _meshes.clear()
    _cached_bytes = 0


def _read(path: str, suffix: str) -> Mesh:
    """The file's mesh, unscaled, checked: finite vertices, triangles with indices in range."""
    data = read_file(path, MAX_MESH_FILE_BYTES, "this %s file" % _FORMATS[suffix], MeshError)
    side_files = _SideFiles(path)
    unreadable = MeshUnreadable if suffix == ".dae" else MeshError   # its content, not the file
    try:
        with warnings.catch_warnings():   # pycollada's numpy.matrix, trimesh's notes
            warnings.simplefilter("ignore")
            if suffix == ".dae":
                vertices, parts = _read_collada(data, side_files)
            else:
                vertices, parts = _read_trimesh(data, suffix[1:], side_files)
    except Exception as err:   # trimesh, pycollada, lxml, numpy: any failure is a bad file
        if side_files.refused is not None:
            raise MeshError(side_files.refused) from None
        text = " ".join(str(err).split()) or type(err).__name__
        raise unreadable("%s: cannot read this %s file: %s"
                         % (path, _FORMATS[suffix], text[:200])) from None
    if side_files.refused is not None:
        raise MeshError(side_files.refused)
    parts = [(np.asarray(f, dtype=np.int64).reshape(-1, 3), rgba) for f, rgba in parts]
    parts = [(f, rgba) for f, rgba in parts if len(f)]
    if not parts:
        raise unreadable(
            "%s: the file holds no triangles" % path)
    vertices = np.asarray(vertices, dtype=np.float64).reshape(-1, 3)
    if not np.all(np.isfinite(vertices)):
        raise MeshError("%s: the file has vertex coordinates that are not numbers" % path)
    if any(f.min() < 0 or f.max() >= len(vertices) for f, _ in parts):
        raise MeshError("%s: a triangle names a vertex the file does not have" % path)
    # One vertex per distinct point (STL and Collada repeat them); no triangle repeats one.
    vertices, inverse = np.unique(vertices, axis=0, return_inverse=True)
    inverse = inverse.reshape(-1)
    parts = [(inverse[f], rgba) for f, rgba in parts]
    parts = [(f[(f[:, 0] != f[:, 1]) & (f[:, 1] != f[:, 2]) & (f[:, 2] != f[:, 0])], rgba)
             for f, rgba in parts]
    parts = [(f, rgba) for f, rgba in parts if len(f)]
    if not parts:
        raise unreadable(
            "%s: the file holds no triangles (only degenerate ones)" % path)
    return Mesh(path, vertices, tuple(MeshPart(f, rgba) for f, rgba in _merge_colours(parts)))


def _merge_colours(parts):
    """One (faces, rgba) per distinct colour, in order of first appearance."""
    merged: Dict[Optional[Rgba], List[np.ndarray]] = {}
    for faces, rgba in parts:
        merged.setdefault(rgba, []).append(faces)
    return [(np.concatenate(f), rgba) for rgba, f in merged.items()]


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
        parts.append(MeshPart(faces, part.rgba))
    return Mesh(mesh.path, vertices, tuple(parts))


class _SideFiles:
    """The files a mesh names (an OBJ's mtllib and textures, a Collada's images), read beside
    it (the name as written, else its last part, as trimesh looks) through file_read. One
    that is missing is left out (a mesh without its colours, as in Gazebo); the first one
    refused is kept in ``refused`` (trimesh swallows what a resolver raises)."""

    def __init__(self, mesh_path: str):
        self.folder = os.path.dirname(mesh_path)
        self.refused: Optional[str] = None

    def read(self, name: str) -> bytes:
        for candidate in (name.strip(), os.path.basename(name.strip())):
            path = os.path.normpath(os.path.join(self.folder, candidate))
            if candidate and os.path.lexists(path):
                try:
                    return read_file(path, MAX_MESH_SIDE_FILE_BYTES, "a file the mesh names",
                                     MeshError)
                except MeshError as err:
                    self.refused = self.refused or str(err)
                    raise
        raise FileNotFoundError(name)

    def trimesh_resolver(self):
        """A trimesh Resolver reading through ``read``."""
        from trimesh.resolvers import Resolver
        side_files = self

        class _Resolver(Resolver):
            def __init__(self):
                pass

            def get(self, key):
                return side_files.read(key)

            def write(self, name, data):
                raise OSError("meshes are only read here")

            def namespaced(self, namespace):
                return self

            def keys(self):
                return iter(())
        return _Resolver()


def _read_collada(data: bytes, side_files: _SideFiles):
    """(vertices, [(faces, rgba)]) of a Collada file: unit and node transforms applied, not the
    up axis."""
    import collada
    if data[:4] == b"PK\x03\x04":
        raise ValueError("it is a zip archive (a .zae); Gazebo reads .dae files of plain XML")
    doc = collada.Collada(io.BytesIO(_without_comments(data)), aux_file_loader=side_files.read,
                          ignore=[collada.common.DaeUnsupportedError,
                                  collada.common.DaeBrokenRefError])
    if doc.scene is not None:
        geometries = list(doc.scene.objects("geometry"))
    else:   # no visual scene: every geometry as written
        geometries = [g.bind(np.identity(4), {}) for g in doc.geometries]
    unit = doc.assetInfo.unitmeter or 1.0
    chunks, parts, count = [], [], 0
    for geometry in geometries:
        for primitive in geometry.primitives():
            if hasattr(primitive, "triangleset"):       # polylist, polygons
                primitive = primitive.triangleset()
            if not hasattr(primitive, "vertex_index") or primitive.vertex is None \
                    or primitive.vertex_index is None or not hasattr(primitive, "ntriangles"):
                continue                                # lines, or no data
            chunks.append(np.asarray(primitive.vertex, dtype=np.float64).reshape(-1, 3))
            parts.append((np.asarray(primitive.vertex_index) + count,
                          _collada_colour(primitive.material)))
            count += len(chunks[-1])
    vertices = np.concatenate(chunks) * unit if chunks else np.zeros((0, 3))
    return vertices, parts


def _without_comments(data: bytes) -> bytes:
    """The XML document ``data`` without its comments and processing instructions, whose text
    pieces join up again. pycollada reads only an element's text before the first comment (a
    comment in a <float_array> cuts the numbers short) and takes a comment in a <mesh> for a
    primitive it cannot read (the mesh then has no triangles); Gazebo's TinyXML reader skips
    them. A document with a DOCTYPE (entities) or one that does not parse is returned as it
    is, for pycollada to read or to name its fault."""
    if (b"<!--" not in data and b"<?" not in data[1:]) or b"<!DOCTYPE" in data:
        return data
    from xml.etree import ElementTree
    parser = ElementTree.XMLParser(
        target=ElementTree.TreeBuilder(insert_comments=False, insert_pis=False))
    try:
        parser.feed(data)
        return ElementTree.tostring(parser.close())
    except ElementTree.ParseError:
        return data


def _collada_colour(material) -> Optional[Rgba]:
    """A Collada material's diffuse colour; None without material or with a texture."""
    diffuse = getattr(getattr(material, "effect", None), "diffuse", None)
    if not isinstance(diffuse, tuple) or len(diffuse) not in (3, 4):
        return None
    return tuple(float(v) for v in diffuse) + ((1.0,) if len(diffuse) == 3 else ())


def _read_trimesh(data: bytes, file_type: str, side_files: _SideFiles):
    """(vertices, [(faces, rgba)]) of an STL or OBJ file read by trimesh, as written."""
    import trimesh
    if file_type == "stl":
        data = _binary_stl_as_gazebo_reads_it(data)
    scene = trimesh.load(io.BytesIO(data), file_type=file_type, force="scene", process=False,
                         resolver=side_files.trimesh_resolver())
    chunks, parts, count = [], [], 0
    for node in scene.graph.nodes_geometry:
        transform, name = scene.graph[node]
        geometry = scene.geometry[name]
        if not hasattr(geometry, "faces") or len(geometry.faces) == 0:
            continue
        vertices = np.asarray(geometry.vertices, dtype=np.float64)
        chunks.append(vertices @ transform[:3, :3].T + transform[:3, 3])
        rgba = _obj_colour(geometry) if file_type == "obj" else None
        parts.append((np.asarray(geometry.faces) + count, rgba))
        count += len(vertices)
    return (np.concatenate(chunks) if chunks else np.zeros((0, 3))), parts


def _binary_stl_as_gazebo_reads_it(data: bytes) -> bytes:
    """A binary STL (80 bytes of header, the triangle count, 50 bytes a triangle) without the
    bytes after its last triangle, which Gazebo leaves unread and trimesh would take for the
    sign of an ASCII file. Anything else as it is: an ASCII file's count would be the text's
    bytes, so at least 0x09090909 triangles, far more than any file of it holds."""
    if len(data) < 84:
        return data
    end = 84 + 50 * struct.unpack("<I", data[80:84])[0]
    return data[:end] if end < len(data) else data


def _obj_colour(geometry) -> Optional[Rgba]:
    """The ``Kd`` (and ``d``) of an OBJ part's .mtl material, exactly as written; None if none."""
    material = getattr(getattr(geometry, "visual", None), "material", None)
    kwargs = getattr(material, "kwargs", None) or {}
    kd = kwargs.get("kd")
    if kd is None:
        return None
    kd = [float(kd)] * 3 if np.isscalar(kd) else [float(v) for v in kd][:3]
    if len(kd) != 3:
        return None
    try:
        alpha = float(np.ravel(kwargs.get("d", [1.0]))[0])
    except (TypeError, ValueError, IndexError):
        alpha = 1.0
    return (kd[0], kd[1], kd[2], alpha)


def convex_hull_vertices(mesh: Mesh) -> np.ndarray:
    """(H, 3) the corner points of the convex hull of the vertices the faces use, m (a flat mesh:
    the corners of its outline; a line: its two ends)."""
    points = np.unique(mesh.vertices[np.unique(mesh.faces)], axis=0)
    centre = points.mean(axis=0)
    _, sizes, axes = np.linalg.svd(points - centre, full_matrices=False)
    rank = int(np.sum(sizes > 1e-9 * sizes[0])) if len(sizes) and sizes[0] > 0 else 0
    if rank == 3 and len(points) >= 4:
        return _hull_3d(points)
    if rank == 2:
        flat = (points - centre) @ axes[:2].T
        return points[_hull_2d(flat)]
    if rank == 1:
        along = (points - centre) @ axes[0]
        return points[[int(np.argmin(along)), int(np.argmax(along))]]
    return points[:1]


def _hull_2d(points: np.ndarray) -> List[int]:
    """Indices of the corners of the convex hull of 2-D points (monotone chain, collinear points
    dropped), counter-clockwise."""
    order = sorted(range(len(points)), key=lambda i: (points[i][0], points[i][1]))

    def cross(o, a, b):
        return ((points[a][0] - points[o][0]) * (points[b][1] - points[o][1])
                - (points[a][1] - points[o][1]) * (points[b][0] - points[o][0]))

    def chain(indices):
        out: List[int] = []
        for i in indices:
            while len(out) >= 2 and cross(out[-2], out[-1], i) <= 0:
                out.pop()
            out.append(i)
        return out

    lower, upper = chain(order), chain(reversed(order))
    return lower[:-1] + upper[:-1]


def _hull_3d(points: np.ndarray) -> np.ndarray:
    """Corners of the convex hull of points that span 3-D (quickhull with conflict lists), then
    only the hull vertices whose face normals span 3-D: a point on an edge or a face is no corner.
    """
    eps = 1e-9 * float(np.ptp(points, axis=0).max())
    faces: Dict[int, Tuple[int, int, int]] = {}
    planes: Dict[int, Tuple[np.ndarray, float]] = {}   # face -> (unit outward normal, offset)
    edges: Dict[Tuple[int, int], int] = {}             # directed edge -> its face
    conflicts: Dict[int, np.ndarray] = {}              # face -> the points outside it

    def add_faces(corners):
        """Add faces (i, j, k), counter-clockwise from outside; returns their keys."""
        p, q, r = (points[[f[i] for f in corners]] for i in range(3))
        normals = np.cross(q - p, r - p)
        normals /= np.linalg.norm(normals, axis=1)[:, None]
        keys = list(range(len(planes), len(planes) + len(corners)))
        for key, corner, normal, origin in zip(keys, corners, normals, p):
            faces[key], planes[key] = corner, (normal, float(normal @ origin))
            for i in range(3):
                edges[corner[i], corner[(i + 1) % 3]] = key
        return keys

    def assign(candidates, keys):
        if not len(candidates) or not keys:
            return
        normals = np.array([planes[k][0] for k in keys])
        offsets = np.array([planes[k][1] for k in keys])
        distance = points[candidates] @ normals.T - offsets
        best = np.argmax(distance, axis=1)
        outside = distance[np.arange(len(candidates)), best] > eps
        for j, key in enumerate(keys):
            conflicts[key] = candidates[outside & (best == j)]

    # The start: a tetrahedron of far-apart points, counter-clockwise from outside.
    a = int(np.argmax(points @ np.array([1.0, 0.318309886, 0.141421356])))
    b = int(np.argmax(np.linalg.norm(points - points[a], axis=1)))
    c = int(np.argmax(np.linalg.norm(np.cross(points - points[a], points[b] - points[a]), axis=1)))
    normal = np.cross(points[b] - points[a], points[c] - points[a])
    d = int(np.argmax(np.abs((points - points[a]) @ normal)))
    if (points[d] - points[a]) @ normal > 0:
        b, c = c, b
    start = add_faces([(a, b, c), (a, d, b), (b, d, c), (c, d, a)])
    assign(np.arange(len(points)), start)
    todo = list(start)
    while todo:
        key = todo.pop()
        if key not in faces or not len(conflicts.get(key, ())):
            continue
        eye = int(conflicts[key][np.argmax(points[conflicts[key]] @ planes[key][0])])
        visible, queue = {key}, [key]
        while queue:                      # the faces the eye sees: a connected cap
            corner = faces[queue.pop()]
            for i in range(3):
                other = edges[corner[(i + 1) % 3], corner[i]]
                if other not in visible and points[eye] @ planes[other][0] - planes[other][1] > eps:
                    visible.add(other)
                    queue.append(other)
        horizon = [(f[i], f[(i + 1) % 3]) for k in visible for f in [faces[k]] for i in range(3)
                   if edges[f[(i + 1) % 3], f[i]] not in visible]
        orphans = np.concatenate([conflicts.pop(k, np.zeros(0, dtype=np.int64)) for k in visible])
        for k in visible:
            corner = faces.pop(k)
            for i in range(3):
                del edges[corner[i], corner[(i + 1) % 3]]
        new = add_faces([(p, q, eye) for p, q in horizon])
        assign(orphans[orphans != eye], new)
        todo.extend(new)
    around: Dict[int, List[np.ndarray]] = {}
    for key, corner in faces.items():
        for vertex in corner:
            around.setdefault(vertex, []).append(planes[key][0])
    return points[[v for v in sorted(around)
                   if np.linalg.matrix_rank(np.array(around[v]), tol=1e-7) == 3]]


def write_obj_parts(mesh: Mesh, directory: str) -> List[Tuple[str, Optional[Rgba]]]:
    """One Wavefront file per part in ``directory``: (path, the part's rgba). Flat shaded: one
    normal per face (``vn`` and ``f a//n b//n c//n``), so that pybullet's EGL and TinyRenderer
    renderers both light it. Only the part's own vertices are written, in metres."""
    stem = os.path.splitext(os.path.basename(mesh.path))[0] or "mesh"
    written = []
    for number, part in enumerate(mesh.parts):
        used, faces = np.unique(part.faces, return_inverse=True)
        faces = faces.reshape(-1, 3)
        vertices = mesh.vertices[used]
        corners = vertices[faces]
        normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
        lengths = np.linalg.norm(normals, axis=1)
        normals = np.where(lengths[:, None] > 0, normals / np.maximum(lengths, 1e-300)[:, None],
                           np.array([0.0, 0.0, 1.0]))
        lines = ["# %s part %d, metres, flat shaded" % (os.path.basename(mesh.path), number)]
        lines += ["v %.9g %.9g %.9g" % tuple(v) for v in vertices]
        lines += ["vn %.6g %.6g %.6g" % tuple(n) for n in normals]
        lines += ["f %d//%d %d//%d %d//%d" % (a + 1, k + 1, b + 1, k + 1, c + 1, k + 1)
                  for k, (a, b, c) in enumerate(faces)]
        fd, path = tempfile.mkstemp(suffix=".obj", prefix="%s_part%d_" % (stem, number),
                                    dir=directory)
        with os.fdopen(fd, "w") as f:
            f.write("\n".join(lines) + "\n")
        written.append((path, part.rgba))
    return written
