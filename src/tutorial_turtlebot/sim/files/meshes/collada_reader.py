"""Collada (.dae) files read as Gazebo 11 reads them, through pycollada. No ROS and no pybullet.

``read_collada`` gives the vertices and one MeshPart per ``<triangles>``/``<polylist>``/
``<polygons>`` of the visual scene: every ``<node>`` transform (matrix, translate, rotate,
scale) down to each ``<instance_geometry>`` applied, and the ``<asset><unit meter="...">``
(0.0254 for inches). ``<up_axis>`` is NOT: Gazebo uses the vertex data as written (a Y_UP file
is rotated by its user in SDF). A file without ``<scene>`` gives its geometries as written.
pycollada applies neither unit nor up axis by itself.

A part's colour is its material's ``<diffuse><color>``; a textured diffuse gives None and the
texture, found by texture_images.find_texture, with the primitive's first set of texture
coordinates (Gazebo's Collada loader reads only the first ``TEXCOORD`` input); each part's
submesh name is Gazebo's (``submesh_names``: a node's name). The texture may
be named through the ``<newparam>`` surface -> sampler2D chain or, as 3ds Max's exporter
writes it, straight by the image's id (``<texture texture="Map #N-image">``). What Gazebo does
not read is left out before pycollada sees it: XML comments and processing instructions
(pycollada would cut an element's text at a comment) and the ``<extra>`` elements of effects
(3ds Max's bump maps there name images without a sampler, which pycollada refuses).
"""
import io
from typing import Dict, List, Optional, Tuple

import numpy as np

from .mesh_side_files import SideFiles
from .mesh_types import MeshPart, Rgba
from .texture_images import find_texture


def read_collada(data: bytes, side_files: SideFiles,
                 names: Optional[List[str]] = None) -> Tuple[np.ndarray, List[MeshPart]]:
    """(vertices, [MeshPart]) of a Collada file: unit and node transforms applied, not the up
    axis. Faces and uvs not yet checked. pycollada's errors propagate. ``names``: a list that
    gets each part's submesh name, as Gazebo names it (``submesh_names``)."""
    import collada    # pycollada only for worlds with Collada meshes
    if data[:4] == b"PK\x03\x04":
        raise ValueError("it is a zip archive (a .zae); Gazebo reads .dae files of plain XML")
    doc = collada.Collada(io.BytesIO(as_gazebo_reads_it(data)), aux_file_loader=side_files.read,
                          ignore=[collada.common.DaeUnsupportedError,
                                  collada.common.DaeBrokenRefError])
    if doc.scene is not None:
        geometries = list(doc.scene.objects("geometry"))
    else:   # no visual scene: every geometry as written
        geometries = [g.bind(np.identity(4), {}) for g in doc.geometries]
    geometry_names = submesh_names(doc.scene) if doc.scene is not None else []
    unit = doc.assetInfo.unitmeter or 1.0
    chunks, parts, count = [], [], 0
    textures: Dict[str, Tuple[Optional[str], Optional[str]]] = {}   # image path -> found
    for number, geometry in enumerate(geometries):
        for primitive in geometry.primitives():
            if hasattr(primitive, "triangleset"):       # polylist, polygons
                primitive = primitive.triangleset()
            if not hasattr(primitive, "vertex_index") or primitive.vertex is None \
                    or primitive.vertex_index is None or not hasattr(primitive, "ntriangles"):
                continue                                # lines, or no data
            chunks.append(np.asarray(primitive.vertex, dtype=np.float64).reshape(-1, 3))
            texture, problem = _texture(primitive.material, side_files, textures)
            uvs = _uvs(primitive) if texture is not None else None
            parts.append(MeshPart(np.asarray(primitive.vertex_index) + count,
                                  _colour(primitive.material), uvs, texture, problem))
            if names is not None:
                names.append(geometry_names[number] if number < len(geometry_names) else "")
            count += len(chunks[-1])
    vertices = np.concatenate(chunks) * unit if chunks else np.zeros((0, 3))
    return vertices, parts


def submesh_names(scene) -> List[str]:
    """The submesh name of each geometry ``scene.objects("geometry")`` gives, in its order, as
    Gazebo 11's ColladaLoader names them: reading a ``<node>``, its ``name`` (where it has one)
    becomes the current name; its child nodes are read next, then its own geometries, which
    take the current name then (a nameless node's geometries: the last name met before)."""
    from collada import scene as collada_scene
    current = [""]

    def walk(node) -> List[str]:
        """The names of ``node``'s geometries in document order (pycollada's)."""
        node = getattr(node, "node", node)         # an <instance_node>: the node it names
        xml = getattr(node, "xmlnode", None)
        if xml is not None and xml.get("name"):
            current[0] = xml.get("name")
        entries: List[Optional[List[str]]] = []    # None: one own geometry, named at the end
        for child in getattr(node, "children", ()):
            if isinstance(child, collada_scene.GeometryNode):
                entries.append(None)
            elif isinstance(child, (collada_scene.Node, collada_scene.NodeNode)):
                entries.append(walk(child))
        own = current[0]
        return [n for entry in entries for n in (entry if entry is not None else [own])]

    return [n for node in scene.nodes for n in walk(node)]


def as_gazebo_reads_it(data: bytes) -> bytes:
    """The XML document ``data`` without its comments and processing instructions, whose text
    pieces join up again, and without the ``<extra>`` elements inside its ``<effect>``s.
    pycollada reads only an element's text before the first comment (a comment in a
    <float_array> cuts the numbers short), takes a comment in a <mesh> for a primitive it cannot
    read (the mesh then has no triangles), and refuses the whole file for an effect's <extra>
    <texture> that names an image without a sampler (3ds Max's bump maps); Gazebo's TinyXML
    reader skips comments and Gazebo reads no <extra>. A document with none of these is
    returned as it is; so is one with a DOCTYPE (entities) or one that does not parse, for
    pycollada to read or to name its fault."""
    commented = b"<!--" in data or b"<?" in data[1:]
    extras = b"<extra" in data and b"<texture" in data
    if not (commented or extras) or b"<!DOCTYPE" in data:
        return data
    from xml.etree import ElementTree
    parser = ElementTree.XMLParser(
        target=ElementTree.TreeBuilder(insert_comments=False, insert_pis=False))
    try:
        parser.feed(data)
        root = parser.close()
    except ElementTree.ParseError:
        return data
    for effect in root.iter():
        if _local(effect.tag) == "effect":
            for parent in list(effect.iter()):
                for child in [c for c in parent if _local(c.tag) == "extra"]:
                    parent.remove(child)
    return ElementTree.tostring(root)


def _local(tag) -> str:
    """An element's tag without its namespace."""
    return tag.rsplit("}", 1)[-1] if isinstance(tag, str) else ""


def _texture(material, side_files: SideFiles, textures: dict
             ) -> Tuple[Optional[str], Optional[str]]:
    """(image path, None), (None, why not) or (None, None) without a texture: a Collada
    material's diffuse texture (effect -> sampler2D -> surface -> image; pycollada makes the
    sampler of a texture that names an image straight)."""
    diffuse = getattr(getattr(material, "effect", None), "diffuse", None)
    image = getattr(getattr(getattr(diffuse, "sampler", None), "surface", None), "image", None)
    name = getattr(image, "path", None)
    if not isinstance(name, str):
        return None, None
    if name not in textures:
        textures[name] = find_texture(side_files.mesh_path, name)
    return textures[name]


def _uvs(primitive) -> Optional[np.ndarray]:
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


def _colour(material) -> Optional[Rgba]:
    """A Collada material's diffuse colour; None without material or with a texture."""
    diffuse = getattr(getattr(material, "effect", None), "diffuse", None)
    if not isinstance(diffuse, tuple) or len(diffuse) not in (3, 4):
        return None
    return tuple(float(v) for v in diffuse) + ((1.0,) if len(diffuse) == 3 else ())
