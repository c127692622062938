"""Wavefront OBJ files of a Mesh, one per part, for pybullet to draw (and to collide with). No
ROS and no pybullet here. Units: metres, in the mesh frame.
"""
import os
import tempfile
from typing import Callable, Dict, List, Optional, Tuple

import numpy as np

from ..file_read import MAX_MESH_SIDE_FILE_BYTES
from .mesh_side_files import read_file
from .mesh_types import Mesh, MeshError, Rgba
from .texture_images import fit_halvings, halved_image, image_problem, image_size

# texture path -> the file name, in the folder written to, of the image to draw it with (or
# None: drawn without it)
ImageFiles = Callable[[str], Optional[str]]


def write_obj_parts(mesh: Mesh, directory: str, textures: bool = True,
                    images: Optional[ImageFiles] = None) -> List[Tuple[str, Optional[Rgba]]]:
    """One Wavefront file per part in ``directory``: (path, the colour to draw it in or None).
    Flat shaded: one normal per face (``vn``), so that pybullet's EGL and TinyRenderer renderers
    both light it. Only the part's own vertices are written, in metres.

    With ``textures``, a part with a texture also gets its corners' ``vt`` and the ``.mtl`` of
    its image (``mtl_name``), whose ``map_Kd`` names the image file in ``directory`` that
    ``images`` gives (by default a copy of the texture, read again through file_read and
    checked: what pybullet loads is what was checked). pybullet's loader textures such a file
    in both renderers and multiplies the texture by the shape's rgbaColor, so its colour is the
    part's rgba (an OBJ's Kd tints as in Gazebo) or else white. A texture without an image file
    now leaves the part untextured in its rgba.
    """
    stem = os.path.splitext(os.path.basename(mesh.path))[0] or "mesh"
    if images is None:
        copies: Dict[str, Optional[str]] = {}    # texture -> its copy's file name

        def images(texture):
            if texture not in copies:
                copies[texture] = texture_copy(texture, directory)
            return copies[texture]
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
        image = None
        if textures and part.texture is not None and part.uvs is not None:
            image = images(part.texture)
        lines = ["# %s part %d, metres, flat shaded" % (os.path.basename(mesh.path), number)]
        if image is not None:
            lines += ["mtllib %s" % write_mtl(image, directory), "usemtl texture"]
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


def mtl_name(image: str) -> str:
    """The file name of the .mtl that ``write_mtl`` writes for the image file ``image``."""
    return os.path.splitext(image)[0] + ".mtl"


def write_mtl(image: str, directory: str) -> str:
    """The file name (in ``directory``) of the .mtl of one material "texture": white, the image
    file ``image`` (in ``directory``) as its diffuse map. Written once (to a temporary name,
    then renamed: a reader never sees half of it)."""
    name = mtl_name(image)
    path = os.path.join(directory, name)
    if not os.path.isfile(path):
        fd, temp = tempfile.mkstemp(suffix=".tmp", prefix=".mtl-", dir=directory)
        with os.fdopen(fd, "w") as f:
            f.write("newmtl texture\nKa 0 0 0\nKd 1 1 1\nKs 0 0 0\nmap_Kd %s\n" % image)
        os.replace(temp, path)
    return name


def texture_copy(texture: str, directory: str, halvings: int = 0) -> Optional[str]:
    """The file name (in ``directory``) of a checked copy of the image ``texture``, halved
    ``halvings`` times more than it is to fit MAX_TEXTURE_SIDE (texture_images.halved_image,
    fit_halvings; the whole image if it cannot be halved); None if it is no longer a usable
    texture (changed since the mesh was read)."""
    try:
        data = read_file(texture, MAX_MESH_SIDE_FILE_BYTES, "a texture", MeshError)
    except MeshError:
        return None
    if image_problem(data) is not None:
        return None
    halvings += fit_halvings(*image_size(data))
    try:
        data, suffix = halved_image(data, halvings)
    except ValueError:
        suffix = ".png" if data[:4] == b"\x89PNG" else ".jpg"
    fd, path = tempfile.mkstemp(suffix=suffix, prefix="texture_", dir=directory)
    with os.fdopen(fd, "wb") as f:
        f.write(data)
    return os.path.basename(path)
