"""STL and Wavefront OBJ files read as Gazebo 11 reads them, through trimesh. No ROS and no
pybullet here.

- STL (binary or ASCII): metres as written, no colour. A binary file with bytes after its last
  triangle is read as Gazebo reads it (they are left out); an ASCII file that is not UTF-8 is
  read as trimesh guesses its text (charset-normalizer).
- OBJ: each ``usemtl`` material's colour is its ``.mtl`` ``Kd`` (alpha from ``d``), also where
  it has a texture (``map_Kd``, found by texture_images.find_texture, with the ``vt``
  coordinates); faces without material have None.
"""
import io
import os
import struct
from typing import Dict, List, Optional, Tuple

import numpy as np

from .mesh_side_files import IMAGE_SUFFIXES, SideFiles
from .mesh_types import MeshPart, Rgba
from .texture_images import find_texture


def read_stl_obj(data: bytes, file_type: str,
                 side_files: SideFiles) -> Tuple[np.ndarray, List[MeshPart]]:
    """(vertices, [MeshPart]) of an STL (``file_type`` "stl") or OBJ ("obj") file, as written.
    trimesh's errors propagate."""
    import trimesh    # only for worlds with STL or OBJ meshes
    if file_type == "stl":
        data = _binary_stl_as_gazebo_reads_it(data)
    scene = trimesh.load(io.BytesIO(data), file_type=file_type, force="scene", process=False,
                         resolver=_resolver(side_files))
    chunks, parts, count = [], [], 0
    maps = _mtl_maps(side_files.texts.values()) if file_type == "obj" else {}
    textures: Dict[str, Tuple[Optional[str], Optional[str]]] = {}   # map_Kd -> found
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
                textures[name] = find_texture(side_files.mesh_path, name)
            texture, problem = textures[name]
            uv = getattr(visual, "uv", None)
            if texture is not None and uv is not None and len(uv) == len(vertices):
                uvs = np.asarray(uv, dtype=np.float64)[:, :2][faces]
        parts.append(MeshPart(faces + count, rgba, uvs, texture, problem))
        count += len(vertices)
    return (np.concatenate(chunks) if chunks else np.zeros((0, 3))), parts


def _resolver(side_files: SideFiles):
    """A trimesh Resolver reading through ``side_files`` (images: left to find_texture)."""
    from trimesh.resolvers import Resolver

    class _Resolver(Resolver):
        def __init__(self):
            pass

        def get(self, key):
            if os.path.splitext(key.strip())[1].lower() in IMAGE_SUFFIXES:
                raise FileNotFoundError(key)   # textures: find_texture reads them
            return side_files.read(key)

        def write(self, name, data):
            raise OSError("meshes are only read here")

        def namespaced(self, namespace):
            return self

        def keys(self):
            return iter(())
    return _Resolver()


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
