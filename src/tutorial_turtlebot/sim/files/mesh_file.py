"""Mesh files as Gazebo reads them: Collada (.dae), STL (binary or ASCII) and Wavefront OBJ.

No ROS and no pybullet here. A file becomes a ``Mesh``: float64 vertices in metres in the mesh
frame (the frame the SDF ``<mesh>``'s visual or collision pose places) and one ``MeshPart`` of
triangles per material colour.

- Collada: the ``<asset><unit meter="...">`` (0.0254 for inches) and every ``<node>`` transform
  (matrix, translate, rotate, scale) down to each ``<instance_geometry>`` of the visual scene are
  applied. ``<up_axis>`` is NOT: Gazebo uses the vertex data as written (a Y_UP file is rotated
  by its user in SDF). A part's colour is its material's ``<diffuse><color>``; a textured
  diffuse gives None and the texture (effect -> sampler2D -> surface -> ``<image>``), with the
  first set of texture coordinates. A file without ``<scene>`` gives its geometries as
  written. pycollada, which reads it, applies neither unit nor up axis by itself (trimesh's
  Collada loader, not used here, neither: it only records the unit).
- STL (binary or ASCII, read by trimesh): metres as written, no colour.
- OBJ (read by trimesh): each ``usemtl`` material's colour is its ``.mtl`` ``Kd`` (alpha from
  ``d``), also where it has a texture (``map_Kd``, with the ``vt`` coordinates); faces without
  material have None.
- Textures: an image named by the mesh is looked for as written (relative: beside the mesh),
  then by its last part beside the mesh and in ``../materials/textures`` (a Gazebo model
  folder's place for them). It is used only if it is a regular PNG or JPEG file of at most
  MAX_MESH_SIDE_FILE_BYTES and MAX_TEXTURE_SIDE px a side: what pybullet's image loader reads.
  Otherwise the part keeps its colour and ``texture_problem`` says why in one line.
- STL: a binary file with bytes after its last triangle is read as Gazebo reads it (they are
  left out); an ASCII file that is not UTF-8 is read as trimesh guesses its text
  (charset-normalizer).
Points shared by several triangles become one vertex (texture coordinates are per triangle
corner, so nothing of them is lost). Then every vertex is multiplied by ``scale`` (per axis; a
mirroring scale keeps the faces counter-clockwise seen from outside, corners and their texture
coordinates reversed together), and
every vertex a triangle uses must then lie within +-limits.MAX_POSITION m of the mesh frame.

Files are read through file_read: the mesh and every file it names (an OBJ's ``mtllib`` and
textures, a Collada's images) only if they are regular files, the mesh
of at most file_read.MAX_MESH_FILE_BYTES, the others MAX_MESH_SIDE_FILE_BYTES. A Collada file
that is a zip archive (.zae) is refused, as Gazebo refuses it.

trimesh and pycollada are imported on first use, so worlds without meshes do not pay for them.
A file is read once for the same (real path, mtime, size), whatever the scale, while its mesh
is among the last MAX_CACHED_BYTES of meshes used; and once for the same content across
starts, while mesh_cache keeps it on disk.
"""
import hashlib
import io
import math
import os
import struct
import tempfile
import threading
import urllib.parse
import warnings
from collections import OrderedDict
from dataclasses import dataclass, replace
from typing import Dict, List, Optional, Sequence, Tuple

import numpy as np

from ...errors import UserError
from . import limits
from . import file_read, mesh_cache
from ..kinematics import cross_2d
from .file_read import MAX_MESH_FILE_BYTES, MAX_MESH_SIDE_FILE_BYTES, not_regular

Rgba = Tuple[float, float, float, float]
_FORMATS = {".dae": "Collada", ".stl": "STL", ".obj": "Wavefront OBJ"}
SUFFIXES = tuple(_FORMATS)   # the file name endings read (any letter case)
MAX_TEXTURE_SIDE = 4096      # px: a larger texture image is not drawn (its part keeps its colour)
# File name endings of images: an OBJ's map_Kd is read here, not by trimesh (see _texture).
_IMAGE_SUFFIXES = (".png", ".jpg", ".jpeg", ".tga", ".bmp", ".gif", ".tif", ".tiff", ".dds",
                   ".psd", ".hdr", ".exr", ".webp")


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
    #                                    JPEG file checked as _texture says; None if none usable
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
    noted = mesh_cache.noted_paths()
    if noted is not None:       # a world read ahead of its meshes (mesh_cache.convert_world)
        noted.append((path, factors))
        return _placeholder(path)
    unscaled = _cached(file_key) or _keep(file_key, _read_cached(path, suffix, file_key))
    return _keep(file_key + (factors,), _scaled(unscaled, factors))


def _read_cached(path: str, suffix: str, file_key: tuple) -> Mesh:
    """``_read``'s mesh, from the disk cache (mesh_cache) when it holds this content."""
    failure = mesh_cache.failure(file_key)    # met by a pool worker: raised as it would be
    if failure is not None and failure[0] in ("MeshError", "MeshUnreadable"):
        raise {"MeshError": MeshError, "MeshUnreadable": MeshUnreadable}[failure[0]](failure[1])
    data = read_file(path, MAX_MESH_FILE_BYTES, "this %s file" % _FORMATS[suffix], MeshError)
    digest = mesh_cache.file_digest(path, data)
    mesh = mesh_cache.load(path, digest)
    if mesh is None:
        _reads.log = log = []
        try:
            mesh = _read(path, suffix, data)
        finally:
            _reads.log = None
        mesh_cache.store(path, digest, mesh, log)
    return mesh


_reads = threading.local()   # .log: [(path, sha256)] of the files read while a mesh is read


def read_file(path: str, limit: int, what: str, error=UserError) -> bytes:
    """file_read.read_file, noting each file read while ``_read_cached`` reads a mesh (the
    disk cache checks them again before it gives that mesh back)."""
    data = file_read.read_file(path, limit, what, error)
    log = getattr(_reads, "log", None)
    if log is not None:
        log.append((os.path.realpath(path), hashlib.sha256(data).hexdigest()))
    return data


def _placeholder(path: str) -> Mesh:
    """A one-triangle mesh for a file only noted, not read."""
    return Mesh(path, np.identity(3), (MeshPart(np.array([[0, 1, 2]]), None),))


def cache_clear() -> None:
    """Forget every mesh read (for tests); the disk cache stays (mesh_cache.clear)."""
    global _cached_bytes
    _meshes.clear()
    _cached_bytes = 0


def _read(path: str, suffix: str, data: Optional[bytes] = None) -> Mesh:
    """The file's mesh, unscaled, checked: finite vertices, triangles with indices in range.
    ``data``: the file's bytes, if the caller has read them already."""
    if data is None:
        data = read_file(path, MAX_MESH_FILE_BYTES, "this %s file" % _FORMATS[suffix],
                         MeshError)
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
                       texture_problem=_texture_line(path, part.texture, why))
    return replace(part, uvs=uvs)


def _texture_line(mesh_path: str, name: str, why: str) -> str:
    """The one line of a texture that is not drawn."""
    return "%s: texture %s not drawn (%s); its part is drawn in its colour" % (
        mesh_path, " ".join(name.split()), why)


def _texture(side_files: "_SideFiles", name: str) -> Tuple[Optional[str], Optional[str]]:
    """(absolute path, None) of the usable image file a mesh names ``name`` (a path or
    ``file://`` URI, %-escapes allowed), or (None, the one line why not)."""
    written = urllib.parse.unquote(name.strip())
    if written.startswith("file://"):
        written = written[len("file://"):]
    if not written:
        return None, _texture_line(side_files.mesh_path, repr(name), "no file name")
    base = os.path.basename(written.replace("\\", "/"))
    folder = side_files.folder
    candidates = [os.path.join(folder, written), os.path.join(folder, base),
                  os.path.join(folder, os.pardir, "materials", "textures", base)]
    found = next((os.path.abspath(c) for c in candidates if os.path.lexists(c)), None)
    if found is None:
        where = ", ".join(sorted(set(os.path.abspath(os.path.dirname(c)) for c in candidates)))
        return None, _texture_line(side_files.mesh_path, written, "found nowhere; looked in "
                                   + where)
    try:
        data = read_file(found, MAX_MESH_SIDE_FILE_BYTES, "a texture", MeshError)
    except MeshError as err:
        return None, _texture_line(side_files.mesh_path, written, str(err))
    why = image_problem(data)
    if why is not None:
        return None, _texture_line(side_files.mesh_path, written, "%s: %s" % (found, why))
    return found, None


_texture_sizes: Dict[tuple, int] = {}   # (real path, mtime, size) -> pixels, of textures seen


def texture_pixels(path: str) -> int:
    """Width x height px of the texture file ``path`` (0 if it is no usable texture now)."""
    try:
        stat = os.stat(path)
    except OSError:
        return 0
    key = (os.path.realpath(path), stat.st_mtime_ns, stat.st_size)
    if key not in _texture_sizes:
        try:
            data = read_file(path, MAX_MESH_SIDE_FILE_BYTES, "a texture", MeshError)
        except MeshError:
            return 0
        size = _image_size(data) if image_problem(data) is None else None
        if len(_texture_sizes) > 4096:
            _texture_sizes.clear()
        _texture_sizes[key] = size[0] * size[1] if size else 0
    return _texture_sizes[key]


def _image_size(data: bytes) -> Optional[Tuple[int, int]]:
    """(width, height) px of PNG or JPEG bytes; None if not found."""
    if data[:8] == b"\x89PNG\r\n\x1a\n":
        if len(data) >= 24 and data[12:16] == b"IHDR":
            return struct.unpack(">II", data[16:24])
        return None
    if data[:3] == b"\xff\xd8\xff":
        return _jpeg_size(data)
    return None


def image_problem(data: bytes) -> Optional[str]:
    """Why the bytes of an image file are no texture drawn here: not PNG or baseline/progressive
    JPEG (what pybullet's stb_image reads), or wider or taller than MAX_TEXTURE_SIDE px; None if
    they are one."""
    if data[:8] != b"\x89PNG\r\n\x1a\n" and data[:3] != b"\xff\xd8\xff":
        return "neither a PNG nor a JPEG file"
    size = _image_size(data)
    if size is None and data[:1] == b"\xff":
        return "a JPEG file without a frame size this reader takes"
    if size is None or 0 in size:
        return "a broken image file"
    if max(size) > MAX_TEXTURE_SIDE:
        return "%d x %d px, more than %d px a side" % (size[0], size[1], MAX_TEXTURE_SIDE)
    return None


def _jpeg_size(data: bytes) -> Optional[Tuple[int, int]]:
    """(width, height) px of a baseline or progressive Huffman JPEG (SOF0..SOF2); None for
    others (arithmetic coding, lossless) and broken files."""
    at = 2
    while at + 4 <= len(data):
        if data[at] != 0xFF:
            return None
        marker = data[at + 1]
        if marker == 0xFF:            # fill byte
            at += 1
            continue
        if 0xD0 <= marker <= 0xD9 or marker == 0x01:   # markers without a length
            at += 2
            continue
        length = struct.unpack(">H", data[at + 2:at + 4])[0]
        if marker in (0xC0, 0xC1, 0xC2):
            if at + 9 > len(data):
                return None
            height, width = struct.unpack(">HH", data[at + 5:at + 9])
            return width, height
        if 0xC3 <= marker <= 0xCF and marker not in (0xC4, 0xC8, 0xCC):
            return None               # lossless or arithmetic coded: stb_image reads neither
        at += 2 + length
    return None


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


class _SideFiles:
    """The files a mesh names (an OBJ's mtllib and textures, a Collada's images), read beside
    it (the name as written, else its last part, as trimesh looks) through file_read. One
    that is missing is left out (a mesh without its colours, as in Gazebo); the first one
    refused is kept in ``refused`` (trimesh swallows what a resolver raises)."""

    def __init__(self, mesh_path: str):
        self.mesh_path = mesh_path
        self.folder = os.path.dirname(mesh_path)
        self.refused: Optional[str] = None
        self.texts: Dict[str, bytes] = {}   # name as asked -> bytes, of the files read

    def read(self, name: str) -> bytes:
        for candidate in (name.strip(), os.path.basename(name.strip())):
            path = os.path.normpath(os.path.join(self.folder, candidate))
            if candidate and os.path.lexists(path):
                try:
                    data = read_file(path, MAX_MESH_SIDE_FILE_BYTES, "a file the mesh names",
                                     MeshError)
                    self.texts[name] = data
                    return data
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
                if os.path.splitext(key.strip())[1].lower() in _IMAGE_SUFFIXES:
                    raise FileNotFoundError(key)   # textures: _texture reads them
                return side_files.read(key)

            def write(self, name, data):
                raise OSError("meshes are only read here")

            def namespaced(self, namespace):
                return self

            def keys(self):
                return iter(())
        return _Resolver()


def _read_collada(data: bytes, side_files: _SideFiles):
    """(vertices, [MeshPart]) of a Collada file: unit and node transforms applied, not the up
    axis. Faces and uvs not yet checked."""
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
    textures: Dict[str, Tuple[Optional[str], Optional[str]]] = {}   # image path -> _texture
    for geometry in geometries:
        for primitive in geometry.primitives():
            if hasattr(primitive, "triangleset"):       # polylist, polygons
                primitive = primitive.triangleset()
            if not hasattr(primitive, "vertex_index") or primitive.vertex is None \
                    or primitive.vertex_index is None or not hasattr(primitive, "ntriangles"):
                continue                                # lines, or no data
            chunks.append(np.asarray(primitive.vertex, dtype=np.float64).reshape(-1, 3))
            texture, problem = _collada_texture(primitive.material, side_files, textures)
            uvs = None
            if texture is not None:
                uvs = _collada_uvs(primitive)
            parts.append(MeshPart(np.asarray(primitive.vertex_index) + count,
                                  _collada_colour(primitive.material), uvs, texture, problem))
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


def _collada_texture(material, side_files: _SideFiles, textures: dict
                     ) -> Tuple[Optional[str], Optional[str]]:
    """(image path, None), (None, why not) or (None, None) without a texture: a Collada
    material's diffuse texture (effect -> sampler2D -> surface -> image)."""
    diffuse = getattr(getattr(material, "effect", None), "diffuse", None)
    image = getattr(getattr(getattr(diffuse, "sampler", None), "surface", None), "image", None)
    name = getattr(image, "path", None)
    if not isinstance(name, str):
        return None, None
    if name not in textures:
        textures[name] = _texture(side_files, name)
    return textures[name]


def _collada_uvs(primitive) -> Optional[np.ndarray]:
    """(K, 3, 2) the first texture coordinate set at each triangle corner, or None."""
    sets = getattr(primitive, "texcoordset", None)
    indices = getattr(primitive, "texcoord_indexset", None)
    if not sets or not indices or sets[0] is None or indices[0] is None:
        return None
    coords = np.asarray(sets[0], dtype=np.float64)
    index = np.asarray(indices[0])
    if coords.ndim != 2 or coords.shape[1] < 2 or index.size == 0 or index.max() >= len(coords) \
            or index.min() < 0:
        return None
    return coords[index.reshape(-1, 3)][:, :, :2]


def _collada_colour(material) -> Optional[Rgba]:
    """A Collada material's diffuse colour; None without material or with a texture."""
    diffuse = getattr(getattr(material, "effect", None), "diffuse", None)
    if not isinstance(diffuse, tuple) or len(diffuse) not in (3, 4):
        return None
    return tuple(float(v) for v in diffuse) + ((1.0,) if len(diffuse) == 3 else ())


def _read_trimesh(data: bytes, file_type: str, side_files: _SideFiles):
    """(vertices, [MeshPart]) of an STL or OBJ file read by trimesh, as written."""
    import trimesh
    if file_type == "stl":
        data = _binary_stl_as_gazebo_reads_it(data)
    scene = trimesh.load(io.BytesIO(data), file_type=file_type, force="scene", process=False,
                         resolver=side_files.trimesh_resolver())
    chunks, parts, count = [], [], 0
    maps = _mtl_maps(side_files.texts.values()) if file_type == "obj" else {}
    textures: Dict[str, Tuple[Optional[str], Optional[str]]] = {}   # map_Kd -> _texture
    for node in scene.graph.nodes_geometry:
        transform, name = scene.graph[node]
        geometry = scene.geometry[name]
        if not hasattr(geometry, "faces") or len(geometry.faces) == 0:
            continue
        vertices = np.asarray(geometry.vertices, dtype=np.float64)
        chunks.append(vertices @ transform[:3, :3].T + transform[:3, 3])
        rgba = _obj_colour(geometry) if file_type == "obj" else None
        faces = np.asarray(geometry.faces)
        visual = getattr(geometry, "visual", None)
        name = maps.get(getattr(getattr(visual, "material", None), "name", None))
        texture = problem = uvs = None
        if name is not None:
            if name not in textures:
                textures[name] = _texture(side_files, name)
            texture, problem = textures[name]
            uv = getattr(visual, "uv", None)
            if texture is not None and uv is not None and len(uv) == len(vertices):
                uvs = np.asarray(uv, dtype=np.float64)[:, :2][faces]
        parts.append(MeshPart(faces + count, rgba, uvs, texture, problem))
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


_MTL_OPTIONS = {"-blendu": 1, "-blendv": 1, "-bm": 1, "-boost": 1, "-cc": 1, "-clamp": 1,
                "-imfchan": 1, "-texres": 1, "-mm": 2, "-o": 3, "-s": 3, "-t": 3}


def _mtl_maps(texts) -> Dict[str, str]:
    """{material name: its ``map_Kd`` image file name} of the .mtl files' ``texts`` (options
    such as ``-s 1 1`` before the name are skipped; -o, -s and -t take 1 to 3 numbers)."""
    maps: Dict[str, str] = {}
    for data in texts:
        material = None
        for line in data.decode("utf-8", "replace").splitlines():
            words = line.split()
            if len(words) < 2:
                continue
            key = words[0].lower()
            if key == "newmtl":
                material = " ".join(words[1:])
            elif key == "map_kd" and material is not None:
                rest, at = words[1:], 0
                while at < len(rest) - 1 and rest[at].lower() in _MTL_OPTIONS:
                    most = _MTL_OPTIONS[rest[at].lower()]
                    at += 1
                    taken = 0
                    while taken < most and at < len(rest) - 1:
                        if most == 3 and taken > 0 and not _is_number(rest[at]):
                            break
                        at += 1
                        taken += 1
                maps[material] = " ".join(rest[at:])
    return maps


def _is_number(text: str) -> bool:
    try:
        float(text)
        return True
    except ValueError:
        return False


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

    def chain(indices):
        out: List[int] = []
        for i in indices:
            while len(out) >= 2 and cross_2d(points[out[-2]], points[out[-1]], points[i]) <= 0:
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


def write_obj_parts(mesh: Mesh, directory: str, textures: bool = True
                    ) -> List[Tuple[str, Optional[Rgba]]]:
    """One Wavefront file per part in ``directory``: (path, the colour to draw it in or None).
    Flat shaded: one normal per face (``vn``), so that pybullet's EGL and TinyRenderer renderers
    both light it. Only the part's own vertices are written, in metres.

    With ``textures``, a part with a texture also gets its corners' ``vt`` and a ``.mtl`` whose
    ``map_Kd`` names a copy of the image in ``directory`` (read again through file_read and
    checked: what pybullet loads is what was checked). pybullet's loader textures such a file
    in both renderers and multiplies the texture by the shape's rgbaColor, so its colour is
    the part's rgba (an OBJ's Kd tints as in Gazebo) or else white. A texture that cannot be
    copied now leaves the part untextured in its rgba.
    """
    stem = os.path.splitext(os.path.basename(mesh.path))[0] or "mesh"
    written = []
    copies: Dict[str, Optional[str]] = {}    # texture -> its copy's file name in directory
    for number, part in enumerate(mesh.parts):
        used, faces = np.unique(part.faces, return_inverse=True)
        faces = faces.reshape(-1, 3)
        vertices = mesh.vertices[used]
        corners = vertices[faces]
        normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
        lengths = np.linalg.norm(normals, axis=1)
        normals = np.where(lengths[:, None] > 0, normals / np.maximum(lengths, 1e-300)[:, None],
                           np.array([0.0, 0.0, 1.0]))
        image = None
        if textures and part.texture is not None and part.uvs is not None:
            if part.texture not in copies:
                copies[part.texture] = _texture_copy(part.texture, directory)
            image = copies[part.texture]
        lines = ["# %s part %d, metres, flat shaded" % (os.path.basename(mesh.path), number)]
        if image is not None:
            material = _write_mtl(image, directory)
            lines += ["mtllib %s" % material, "usemtl texture"]
        lines += ["v %.9g %.9g %.9g" % tuple(v) for v in vertices]
        lines += ["vn %.6g %.6g %.6g" % tuple(n) for n in normals]
        if image is None:
            lines += ["f %d//%d %d//%d %d//%d" % (a + 1, k + 1, b + 1, k + 1, c + 1, k + 1)
                      for k, (a, b, c) in enumerate(faces)]
            rgba = part.rgba
        else:    # texture coordinate 3k + i is corner i of face k
            lines += ["vt %.7g %.7g" % tuple(uv) for uv in part.uvs.reshape(-1, 2)]
            lines += ["f %d/%d/%d %d/%d/%d %d/%d/%d" % (a + 1, 3 * k + 1, k + 1, b + 1, 3 * k + 2,
                                                        k + 1, c + 1, 3 * k + 3, k + 1)
                      for k, (a, b, c) in enumerate(faces)]
            rgba = part.rgba if part.rgba is not None else (1.0, 1.0, 1.0, 1.0)
        fd, path = tempfile.mkstemp(suffix=".obj", prefix="%s_part%d_" % (stem, number),
                                    dir=directory)
        with os.fdopen(fd, "w") as f:
            f.write("\n".join(lines) + "\n")
        written.append((path, rgba))
    return written


def _texture_copy(texture: str, directory: str) -> Optional[str]:
    """The file name (in ``directory``) of a checked copy of the image ``texture``; None if it
    is no longer a usable texture (changed since the mesh was read)."""
    try:
        data = read_file(texture, MAX_MESH_SIDE_FILE_BYTES, "a texture", MeshError)
    except MeshError:
        return None
    if image_problem(data) is not None:
        return None
    suffix = ".png" if data[:4] == b"\x89PNG" else ".jpg"
    fd, path = tempfile.mkstemp(suffix=suffix, prefix="texture_", dir=directory)
    with os.fdopen(fd, "wb") as f:
        f.write(data)
    return os.path.basename(path)


def _write_mtl(image: str, directory: str) -> str:
    """The file name (in ``directory``) of a new .mtl of one material "texture": white, the
    image file ``image`` (in ``directory``) as its diffuse map."""
    fd, path = tempfile.mkstemp(suffix=".mtl", prefix="texture_", dir=directory)
    with os.fdopen(fd, "w") as f:
        f.write("newmtl texture\nKa 0 0 0\nKd 1 1 1\nKs 0 0 0\nmap_Kd %s\n" % image)
    return os.path.basename(path)
