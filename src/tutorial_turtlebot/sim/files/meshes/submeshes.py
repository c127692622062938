"""One named submesh of a mesh file, as an SDF ``<mesh><submesh><name>`` takes it, written as a
Wavefront file of its own that every reader of meshes then reads as any other (load_mesh). No
ROS and no pybullet here.

Gazebo 11 names submeshes as its loaders make them, and ``Mesh::GetSubMesh(name)`` takes the
first of that name:

- Collada: one submesh a primitive (``<triangles>``, ``<polylist>`` ...), named after its
  ``<node>`` (collada_reader.submesh_names), node transforms and unit applied;
- OBJ: one submesh an object or group (``o`` / ``g``: the last such line before the faces)
  and material (``usemtl``) in it, named after the object or group;
- STL: no names (no submesh is found).

With ``<center>`` true the submesh's vertices are moved so that the centre of its bounding box
is the mesh frame's origin (``SubMesh::Center``), before the ``<scale>``; its visual and its
collision both take the submesh alone (MeshShape, Visual::AttachMesh). Units: metres, in the
mesh frame. The files are kept in ``submeshes`` beside the mesh cache's folder, one folder a
(file, its mtime and size, name, centring), so that a later start reads them again at once.
"""
import atexit
import hashlib
import os
import shutil
import tempfile
import warnings
from typing import List, Optional, Tuple

import numpy as np

from ..file_read import MAX_MESH_FILE_BYTES
from . import mesh_cache
from .collada_reader import read_collada
from .mesh_side_files import SideFiles, read_file
from .mesh_types import MeshError, MeshPart, MeshUnreadable
from .stl_obj_reader import read_stl_obj

_fallback: List[str] = []           # a temporary folder, where the cache's cannot be made


class SubmeshMissing(MeshError):
    """The mesh file has no submesh of the name asked (one line naming those it has)."""


def submesh_file(path: str, name: str, center: bool) -> str:
    """The Wavefront file of the submesh ``name`` of the mesh file ``path`` (centred if
    ``center``); SubmeshMissing if the file has none of that name, MeshError (MeshUnreadable)
    if it cannot be read."""
    stat = os.stat(path)
    key = (os.path.realpath(path), stat.st_mtime_ns, stat.st_size, name, bool(center))
    folder = os.path.join(_base_folder(), hashlib.sha256(repr(key).encode()).hexdigest()[:24])
    target = os.path.join(folder, "%s__submesh.obj" % os.path.splitext(
        os.path.basename(path))[0])
    if not os.path.isfile(target):      # written by an earlier start (the same file, mtime)
        suffix = os.path.splitext(path)[1].lower()
        data = read_file(path, MAX_MESH_FILE_BYTES, "this mesh file", MeshError)
        vertices, part, names = _named_part(path, suffix, data, name)
        if part is None:
            known = ", ".join(sorted(set(n for n in names if n))[:8]) or "none"
            raise SubmeshMissing("%s: no submesh named %r (its submeshes: %s)"
                                 % (path, name, known))
        _write(target, path, name, vertices, part, center)
    return target


def _named_part(path: str, suffix: str, data: bytes, name: str
                ) -> Tuple[np.ndarray, Optional[MeshPart], List[str]]:
    """(vertices, the first part named ``name`` or None, every part's name) of the file."""
    side_files = SideFiles(path)
    names: List[str] = []
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            if suffix == ".dae":
                vertices, parts = read_collada(data, side_files, names)
            elif suffix == ".obj":
                text, names = _obj_object(data.decode("utf-8", "replace"), name)
                if text is None:
                    return np.zeros((0, 3)), None, names
                vertices, parts = read_stl_obj(text.encode("utf-8"), "obj", side_files)
                names = [name] * len(parts)
            else:
                return np.zeros((0, 3)), None, []
    except Exception as err:   # the same file's load_mesh names it; here one line
        text = " ".join(str(err).split()) or type(err).__name__
        raise MeshUnreadable("%s: cannot read its submesh %r: %s" % (path, name, text[:200]))
    chosen = next((p for p, n in zip(parts, names) if n == name), None)
    return np.asarray(vertices, dtype=np.float64).reshape(-1, 3), chosen, names


def _obj_object(text: str, name: str) -> Tuple[Optional[str], List[str]]:
    """(the OBJ ``text`` with only the faces of the first submesh ``name``, or None; the names
    of its objects and groups). Gazebo's loader makes a submesh of each object (or group) and
    material in it: the faces kept are those of the object's first material."""
    kept, names, current, material, taken = [], [], "", None, None
    for line in text.splitlines():
        words = line.split()
        key = words[0] if words else ""
        if key in ("o", "g"):
            current = " ".join(words[1:])
            names.append(current)
        elif key == "usemtl":
            material = " ".join(words[1:])
        if key == "f":
            if current != name:
                continue
            if taken is None:
                taken = (len(names), material)
            elif taken != (len(names), material):
                continue
        kept.append(line)
    return ("\n".join(kept) + "\n" if taken is not None else None), names


def _write(target: str, path: str, name: str, vertices: np.ndarray, part: MeshPart,
           center: bool) -> None:
    """The Wavefront file ``target`` (and its .mtl) of ``part``'s triangles, in its colour and
    texture; each written to a temporary name and renamed (another process may write it)."""
    faces = np.asarray(part.faces, dtype=np.int64).reshape(-1, 3)
    used, local = np.unique(faces, return_inverse=True)
    points = vertices[used]
    if center and len(points):
        points = points - (points.min(axis=0) + points.max(axis=0)) / 2.0
    stem = os.path.splitext(os.path.basename(target))[0]
    lines = ["# submesh %r of %s, metres" % (name, path), "mtllib %s.mtl" % stem, "usemtl part"]
    lines += ["v %.17g %.17g %.17g" % tuple(v) for v in points]
    corners = local.reshape(-1, 3) + 1
    uvs = part.uvs if part.texture is not None and part.uvs is not None else None
    if uvs is None:
        lines += ["f %d %d %d" % tuple(f) for f in corners]
    else:
        lines += ["vt %.9g %.9g" % tuple(uv) for uv in np.asarray(uvs).reshape(-1, 2)]
        lines += ["f %d/%d %d/%d %d/%d" % (a, 3 * k + 1, b, 3 * k + 2, c, 3 * k + 3)
                  for k, (a, b, c) in enumerate(corners)]
    material = ["newmtl part"]
    if part.rgba is not None:
        material += ["Kd %.9g %.9g %.9g" % tuple(part.rgba[:3]), "d %.9g" % part.rgba[3]]
    elif part.texture is not None:
        material += ["Kd 1 1 1"]
    if part.texture is not None and uvs is not None:
        material += ["map_Kd %s" % part.texture]
    os.makedirs(os.path.dirname(target), exist_ok=True)
    _replace(os.path.join(os.path.dirname(target), stem + ".mtl"), material)
    _replace(target, lines)


def _replace(path: str, lines: List[str]) -> None:
    """Write ``lines`` to ``path`` through a temporary file renamed onto it."""
    fd, temporary = tempfile.mkstemp(dir=os.path.dirname(path), suffix=".part")
    with os.fdopen(fd, "w") as f:
        f.write("\n".join(lines) + "\n")
    os.replace(temporary, path)


def _base_folder() -> str:
    """Where submesh files are kept: ``submeshes`` beside the mesh cache (mesh_cache), so that
    a later start finds them (and the mesh cache their conversion); a temporary folder of this
    process, removed at its exit, where that cannot be made."""
    beside = os.path.join(os.path.dirname(mesh_cache.cache_dir()), "submeshes")
    try:
        os.makedirs(beside, exist_ok=True)
        if os.access(beside, os.W_OK):
            return beside
    except OSError:
        pass
    if not _fallback:
        _fallback.append(tempfile.mkdtemp(prefix="tutorial_turtlebot_submeshes_"))
        atexit.register(shutil.rmtree, _fallback[0], True)
    return _fallback[0]
