"""The files pybullet draws a visual from, shared by the static and the movable builders.

Mesh visuals are drawn part by part, each in its SDF ``<material>`` colour, or where the visual
has none, in the mesh file's own colour of that part, and with its texture where it has one
(obj_writer.write_obj_parts, each image halved as texture_budget says). A box or plane whose
``<material>`` script has a texture image is drawn with it (``box_visual_file``). Boxes and
prisms are Wavefront files too (``obj_file``): pybullet's EGL renderer draws no mesh given as
vertex lists and flattens thin GEOM_BOX visuals. ``unseen_visual`` draws nothing, for a link
whose collisions alone are not to be drawn. Units: metres, in the shape's frame.
"""
import os
import tempfile
from typing import Dict, Sequence, Tuple

import numpy as np

from . import texture_budget
from ..files.meshes import mesh_cache
from .bullet import pybullet
from .client import Client
from .rendering import egl_enabled, note_textures
from ..files.meshes.mesh_types import Mesh, MeshPart
from ..files.meshes.texture_images import texture_info
from ..files.world_types import Shape

Point = Tuple[float, float]


def mesh_part_files(shape: Shape, mesh: Mesh, client: Client, mesh_dir: str):
    """write_obj_parts of a visual mesh: with its textures where the file's own colours are
    drawn (no SDF <material>), or where it is a box or plane of a script's texture
    (``box_mesh``), each image halved as the client's texture budget says (texture_budget);
    tells the camera when the client gets a texture."""
    own = shape.mesh_colours or shape.kind in ("box", "plane")
    halvings: Dict[str, int] = {}    # texture file -> times halved
    for texture in {p.texture for p in mesh.parts if p.texture is not None} if own else ():
        info = texture_info(texture)
        if info is not None:
            use = texture_budget.TextureUse(texture, info.width, info.height)
            halvings[texture] = texture_budget.halvings(client, info.digest, use,
                                                        per_visual=not egl_enabled(client))
    if halvings:
        note_textures(client)
    # written once for this content, kept in the mesh cache (mesh_cache.obj_parts)
    return mesh_cache.visual_obj_parts(mesh, mesh_dir, halvings or None)


def part_colour(shape: Shape, rgba) -> Tuple[float, float, float, float]:
    """The colour a mesh part is drawn in: the SDF material's, else the file's, else grey."""
    return tuple(rgba) if shape.mesh_colours and rgba is not None else shape.rgba


def unseen_visual(client: Client, mesh_dir: str) -> int:
    """A visual shape that draws nothing (one triangle of no area, a file in ``mesh_dir``). A
    body or link without a visual shape is drawn by pybullet's renderers as its collision shape
    (white, or EGL's link colours); Gazebo's cameras never see collisions."""
    path = os.path.join(mesh_dir, "unseen.obj")
    if not os.path.isfile(path):
        with open(path, "w") as f:
            f.write("# one triangle of no area: nothing drawn\nv 0 0 0\nv 0 0 0\nv 0 0 0\n"
                    "f 1 2 3\n")
    return client.createVisualShape(pybullet.GEOM_MESH, fileName=path)


def mesh_visual(polygon: Sequence[Point], z0: float, z1: float, rgba, client: Client,
                mesh_dir: str) -> int:
    """Visual shape of a convex counter-clockwise polygon extruded from ``z0`` to ``z1``,
    flat-shaded, written as a Wavefront file in ``mesh_dir`` (read when its body is created).

    A file, because pybullet's EGL renderer draws no mesh given as vertex lists, and flattens
    thin boxes; both renderers draw a file as it is.
    """
    return client.createVisualShape(pybullet.GEOM_MESH, rgbaColor=rgba,
                                    fileName=obj_file(polygon, z0, z1, mesh_dir))


def obj_file(polygon: Sequence[Point], z0: float, z1: float, mesh_dir: str) -> str:
    """Path of a Wavefront file in ``mesh_dir`` of the convex counter-clockwise polygon extruded
    from ``z0`` to ``z1``, flat-shaded."""
    n = len(polygon)
    normals = [(0.0, 0.0, 1.0), (0.0, 0.0, -1.0)]
    for i in range(n):
        (x0, y0), (x1, y1) = polygon[i], polygon[(i + 1) % n]
        length = ((x1 - x0) ** 2 + (y1 - y0) ** 2) ** 0.5
        normals.append(((y1 - y0) / length, (x0 - x1) / length, 0.0))
    # .obj indices count from 1: bottom corners 1..n, top corners n+1..2n; normal 1 up, 2 down,
    # 3+i the side from corner i to corner i+1. Faces are counter-clockwise seen from outside.
    faces = [[(n + 1 + i, 1) for i in range(n)], [(1 + i, 2) for i in reversed(range(n))]]
    for i in range(n):
        j = (i + 1) % n
        faces.append([(1 + i, 3 + i), (1 + j, 3 + i), (n + 1 + j, 3 + i), (n + 1 + i, 3 + i)])
    lines = ["v %.9g %.9g %.9g" % (x, y, z) for z in (z0, z1) for x, y in polygon]
    lines += ["vn %.9g %.9g %.9g" % v for v in normals]
    lines += ["f " + " ".join("%d//%d" % corner for corner in face) for face in faces]
    fd, path = tempfile.mkstemp(suffix=".obj", prefix="visual_", dir=mesh_dir)
    with os.fdopen(fd, "w") as f:
        f.write("\n".join(lines) + "\n")
    return path


def box_mesh(shape: Shape, hx: float, hy: float, z0: float, z1: float) -> Mesh:
    """A box or plane visual of a script's texture as a Mesh of one textured part (tinted by
    ``shape.rgba``): x in -hx..hx, y in -hy..hy, z in z0..z1 (m, the shape's frame). Its top
    and bottom faces map the image by x and y (u = 0..1 along +x, v = 0..1 along +y: upright
    seen from above with +x to the right); a box's side faces each show the whole image upright
    (v along +z) seen from outside, a plane's sides the image's edge beside them."""
    corners = [(-hx, -hy), (hx, -hy), (hx, hy), (-hx, hy)]          # counter-clockwise
    vertices = np.array([(x, y, z) for z in (z0, z1) for x, y in corners], dtype=np.float64)

    def above(i):
        x, y = corners[i % 4]
        return ((x + hx) / (2 * hx), (y + hy) / (2 * hy))

    faces = [(4, 5, 6), (4, 6, 7), (0, 2, 1), (0, 3, 2)]           # top, bottom
    for i in range(4):
        j = (i + 1) % 4
        faces += [(i, j, 4 + j), (i, 4 + j, 4 + i)]                 # a side, from outside
    uvs = [[above(v) for v in face] for face in faces[:4]]
    upright = (((0.0, 0.0), (1.0, 0.0), (1.0, 1.0)), ((0.0, 0.0), (1.0, 1.0), (0.0, 1.0)))
    for k, face in enumerate(faces[4:]):
        uvs.append(upright[k % 2] if shape.kind == "box" else [above(v) for v in face])
    part = MeshPart(np.array(faces, dtype=np.int64), tuple(shape.rgba),
                    np.array(uvs, dtype=np.float64), shape.texture)
    return Mesh(shape.kind, vertices, (part,))


def box_visual_file(shape: Shape, hx: float, hy: float, z0: float, z1: float, client: Client,
                    mesh_dir: str) -> Tuple[str, Tuple[float, float, float, float]]:
    """(Wavefront file, colour to draw it in) of ``box_mesh``: textured as ``mesh_part_files``
    allows, else in ``shape.rgba``."""
    [(path, rgba)] = mesh_part_files(shape, box_mesh(shape, hx, hy, z0, z1), client, mesh_dir)
    return path, tuple(rgba) if rgba is not None else shape.rgba
