"""A URDF's ``<mesh>`` geometry turned into the Wavefront files pybullet loads. No ROS, no pybullet.

pybullet's own URDF loader would read STL and OBJ itself, and Collada with its up axis applied
(Gazebo does not apply it). So every mesh is read by ``mesh_file.load_mesh`` (Collada's unit
applied, its up axis not; the URDF ``scale`` applied) and the URDF that pybullet loads names
Wavefront files instead, in metres:

- a mesh ``<visual>`` becomes one ``<visual>`` per colour part of the mesh, each in the URDF
  ``<material>``'s colour where the visual has one (it overrides the mesh's own colours and
  textures), else in the part's colour from the file (none: pybullet's default) and with its
  texture where it has one (obj_writer.write_obj_parts; a texture that cannot be used leaves
  the part in its colour). ``textured_urdf`` tells whether a URDF text names such a file;
- a mesh ``<collision>`` becomes one file of the mesh's convex hull: pybullet collides a moving
  body's mesh as its convex hull (Gazebo's ODE collides with the triangles themselves).
This is a robot's URDF; a plain URDF spawned is converted to SDF (urdf_to_sdf) instead.

The files are written once per process for each (mesh file, scale) into one folder of the
system's temporary directory, which is removed when the process ends (the folder of a process
that was killed is removed by the next process that makes one). The MAX_CONVERTED (mesh file,
scale) pairs used last are kept; an older one's files are removed (pybullet has read them) and
written again if it comes back.
"""
import atexit
import copy
import os
import shutil
import tempfile
from collections import OrderedDict
from typing import Dict, List, Optional, Sequence, Tuple
from xml.etree import ElementTree

import numpy as np

from ..asset_uri import resolve_uri
from ..meshes.convex_hull import convex_hull_vertices
from ..meshes.mesh_file import load_mesh
from ..meshes.mesh_types import Mesh, MeshPart
from ..meshes.obj_writer import write_obj_parts
from .urdf_file import mesh_scale
from ....errors import UserError

Rgba = Tuple[float, float, float, float]
CACHE_PREFIX = "tutorial_turtlebot_urdf_meshes_"

MAX_CONVERTED = 256   # (mesh file, scale) pairs whose files are kept, of each kind

_cache_dir: Optional[str] = None
_visual_parts: "OrderedDict[tuple, List[Tuple[str, Optional[Rgba]]]]" = OrderedDict()
_hulls: "OrderedDict[tuple, str]" = OrderedDict()
_textured: set = set()    # the files of _visual_parts that are textured


def _kept(cache: OrderedDict, key: tuple, value, files: Sequence[str]) -> None:
    """Put ``value`` (whose files are ``files``) in ``cache`` as the newest; remove the files
    of the oldest beyond MAX_CONVERTED."""
    cache[key] = value
    while len(cache) > MAX_CONVERTED:
        _, old = cache.popitem(last=False)
        for path in ([p for p, _ in old] if isinstance(old, list) else [old]):
            _textured.discard(path)
            try:
                os.unlink(path)
            except OSError:
                pass


def _folder() -> str:
    """This process's folder of converted meshes, made on first use."""
    global _cache_dir
    if _cache_dir is None or not os.path.isdir(_cache_dir):
        _sweep_dead()
        _cache_dir = tempfile.mkdtemp(prefix="%s%d_" % (CACHE_PREFIX, os.getpid()))
        _visual_parts.clear()
        _hulls.clear()
        _textured.clear()
        atexit.register(shutil.rmtree, _cache_dir, True)
    return _cache_dir


def _sweep_dead() -> None:
    """Remove the folders left by processes that no longer run (killed before their atexit)."""
    root = tempfile.gettempdir()
    try:
        names = os.listdir(root)
    except OSError:
        return
    for name in names:
        if not name.startswith(CACHE_PREFIX):
            continue
        pid = name[len(CACHE_PREFIX):].split("_", 1)[0]
        if not pid.isdigit() or int(pid) == os.getpid():
            continue
        try:
            os.kill(int(pid), 0)
        except ProcessLookupError:
            shutil.rmtree(os.path.join(root, name), ignore_errors=True)
        except OSError:
            pass                              # alive, another user's


def _key(path: str, scale: Sequence[float]) -> tuple:
    stat = os.stat(path)
    return (os.path.realpath(path), stat.st_mtime_ns, stat.st_size, tuple(scale))


def visual_parts(path: str, scale: Sequence[float] = (1.0, 1.0, 1.0), textures: bool = True
                 ) -> List[Tuple[str, Optional[Rgba]]]:
    """[(Wavefront file, the part's rgba or None)] of the mesh file ``path`` times ``scale``:
    one file per colour part, in metres, textured where the part has a usable texture and
    ``textures`` is true. MeshError (one line) for a bad file."""
    mesh = load_mesh(path, scale)
    key = _key(path, scale) + (bool(textures),)
    folder = _folder()
    if key in _visual_parts:
        _visual_parts.move_to_end(key)
    else:
        parts = write_obj_parts(mesh, folder, textures=textures)
        if textures:
            _textured.update(obj for (obj, _), part in zip(parts, mesh.parts)
                             if part.texture is not None)
        _kept(_visual_parts, key, parts, [path for path, _ in parts])
    return _visual_parts[key]


def textured_urdf(urdf: str) -> bool:
    """Whether the URDF text ``urdf`` (of bullet_urdf_text) names a textured file of
    visual_parts: its client's camera must then draw textures (rendering.note_textures)."""
    return any(path in urdf for path in _textured)


def hull_file(path: str, scale: Sequence[float] = (1.0, 1.0, 1.0)) -> str:
    """A Wavefront file of the convex hull's corners of the mesh file ``path`` times ``scale``
    (its triangles are a fan over the corners: pybullet builds its hull from the points)."""
    mesh = load_mesh(path, scale)
    key = _key(path, scale)
    folder = _folder()
    if key in _hulls:
        _hulls.move_to_end(key)
    else:
        corners = convex_hull_vertices(mesh)
        if len(corners) < 3:                 # a line or a point: still a file pybullet reads
            corners = np.concatenate([corners, corners[:1], corners[-1:]])[:max(3, len(corners))]
        fan = np.array([(0, k, k + 1) for k in range(1, len(corners) - 1)], dtype=np.int64)
        hull = Mesh(mesh.path, np.asarray(corners, dtype=np.float64), (MeshPart(fan, None),))
        path = write_obj_parts(hull, folder)[0][0]
        _kept(_hulls, key, path, [path])
    return _hulls[key]


def _mesh_element(element: ElementTree.Element) -> Optional[ElementTree.Element]:
    geometry = element.find("geometry")
    return geometry.find("mesh") if geometry is not None else None


def _scale(mesh: ElementTree.Element) -> Tuple[float, float, float]:
    scale = mesh_scale(mesh.get("scale"))
    if scale is None:
        raise UserError("scale=%r is not three non-zero numbers" % mesh.get("scale"))
    return scale


def _has_colour(material: Optional[ElementTree.Element], colours: Dict[str, bool]) -> bool:
    """Whether a visual's ``<material>`` gives it a colour (its own, or a robot-level one's)."""
    if material is None:
        return False
    if material.find("color") is not None:
        return True
    return colours.get(material.get("name", ""), False)


def bullet_meshes(robot: ElementTree.Element, base_dir: str) -> None:
    """Rewrite, in place, every ``<mesh>`` visual and collision of the URDF ``<robot>`` into
    the Wavefront files of this module (filenames relative to ``base_dir``), the collisions as
    hulls. UserError (one line) for a mesh that cannot be found or read."""
    colours = {m.get("name", ""): m.find("color") is not None for m in robot.findall("material")}
    for link in robot.findall("link"):
        try:
            _link_meshes(link, colours, base_dir)
        except UserError as err:
            raise UserError("link %r <mesh>: %s" % (link.get("name", ""), err)) from None


def _link_meshes(link: ElementTree.Element, colours: Dict[str, bool], base_dir: str) -> None:
    """bullet_meshes of one link."""
    for number, visual in enumerate(list(link.findall("visual"))):
        mesh = _mesh_element(visual)
        if mesh is None:
            continue
        path = resolve_uri(mesh.get("filename", ""), base_dir)
        override = _has_colour(visual.find("material"), colours)
        parts = visual_parts(path, _scale(mesh), textures=not override)
        index = list(link).index(visual)
        link.remove(visual)
        for part, (obj, rgba) in enumerate(parts):
            piece = copy.deepcopy(visual)
            if len(parts) > 1 and piece.get("name"):
                piece.set("name", "%s_part%d" % (piece.get("name"), part))
            piece_mesh = _mesh_element(piece)
            piece_mesh.set("filename", obj)
            piece_mesh.attrib.pop("scale", None)
            if not override:
                for material in piece.findall("material"):
                    piece.remove(material)
                if rgba is not None:
                    material = ElementTree.SubElement(
                        piece, "material",
                        name="%s_mesh%d_part%d" % (link.get("name", ""), number, part))
                    ElementTree.SubElement(material, "color",
                                           rgba=" ".join("%.6g" % c for c in rgba))
            link.insert(index + part, piece)
    for collision in link.findall("collision"):
        mesh = _mesh_element(collision)
        if mesh is None:
            continue
        path = resolve_uri(mesh.get("filename", ""), base_dir)
        mesh.set("filename", hull_file(path, _scale(mesh)))
        mesh.attrib.pop("scale", None)


def indent(element: ElementTree.Element, level: int = 0) -> None:
    """Put each element on a line of its own, in place (ElementTree.indent, which Python 3.8
    lacks). Only white space between elements changes: a text or tail that holds anything
    else is left as it is."""
    children = list(element)
    if not children:
        return
    inner = "\n" + "  " * (level + 1)
    if not (element.text or "").strip():
        element.text = inner
    for child in children:
        indent(child, level + 1)
        if not (child.tail or "").strip():
            child.tail = inner
    if not (children[-1].tail or "").strip():
        children[-1].tail = "\n" + "  " * level


def urdf_text(robot: ElementTree.Element) -> str:
    """The URDF text of ``robot`` for pybullet: one element a line. pybullet's URDF importer
    reads a file through a line buffer of a few KB and joins the pieces with line breaks, so
    a long line (a URDF of ~40 links written on one line) is cut inside a name or a number
    and the file does not load ("Cannot load URDF file")."""
    indent(robot)
    return ElementTree.tostring(robot, encoding="unicode")


# What a link without <inertial> weighs in the URDF pybullet loads (kg; kg m^2 about each axis).
BARE_LINK_MASS = 1e-6
BARE_LINK_INERTIA = 1e-12


def bullet_urdf_text(robot: ElementTree.Element, base_dir: str) -> str:
    """The URDF text pybullet loads (engine/urdf_loader) of a copy of the parsed ``<robot>``:
    its meshes rewritten by ``bullet_meshes`` (relative to ``base_dir``), each link without an
    ``<inertial>`` (a bare frame: base_footprint, base_scan, ...) given next to no mass, joint
    damping left out (not simulated: pybullet's adds energy), one element a line
    (``urdf_text``). Gazebo drops a bare frame's link or merges it with no mass; pybullet would
    give it 1 kg, which merged into a Burger's chassis would triple it."""
    robot = copy.deepcopy(robot)
    if next(robot.iter("mesh"), None) is not None:
        bullet_meshes(robot, base_dir)
    for dynamics in robot.iter("dynamics"):   # pybullet's joint damping adds energy (a joint
        dynamics.set("damping", "0")          # of damping 0.02 spun up to its velocity limit)
    for link in robot.iter("link"):
        if link.find("inertial") is None:
            inertial = ElementTree.SubElement(link, "inertial")
            ElementTree.SubElement(inertial, "mass", value=repr(BARE_LINK_MASS))
            ElementTree.SubElement(inertial, "inertia", ixx=repr(BARE_LINK_INERTIA),
                                   iyy=repr(BARE_LINK_INERTIA), izz=repr(BARE_LINK_INERTIA),
                                   ixy="0", ixz="0", iyz="0")
    return urdf_text(robot)


def mesh_triangles(description) -> Tuple[int, int]:
    """(triangles of every mesh a ``urdf_file.RobotDescription`` uses, the most vertices of
    one of its collision meshes, which collide as hulls), its files read (and kept, as
    load_mesh keeps them)."""
    triangles = hull_vertices = 0
    for link in description.links.values():
        for shapes, collide in ((link.visuals, False), (link.collisions, True)):
            for shape in shapes:
                geometry = shape.geometry
                if geometry.shape != "mesh":
                    continue
                mesh = load_mesh(geometry.filename, geometry.size)
                triangles += sum(len(part.faces) for part in mesh.parts)
                if collide:
                    hull_vertices = max(hull_vertices, len(mesh.vertices))
    return triangles, hull_vertices


def texture_warnings(description) -> List[str]:
    """One line for each texture of a ``urdf_file.RobotDescription``'s visual meshes that is
    not drawn (mesh_file's ``texture_problem``: its part is drawn in its colour)."""
    lines: List[str] = []
    for link in description.links.values():
        for shape in link.visuals:
            geometry = shape.geometry
            if geometry.shape != "mesh":
                continue
            try:
                parts = load_mesh(geometry.filename, geometry.size).parts
            except UserError:
                continue                   # refused where the mesh is converted
            lines += [p.texture_problem for p in parts
                      if p.texture_problem and p.texture_problem not in lines]
    return lines


def absolute_meshes(robot: ElementTree.Element, known: Dict[str, str]) -> ElementTree.Element:
    """A copy of the parsed URDF ``<robot>`` whose every ``<mesh filename>`` is the absolute
    path ``known`` gives it (``mesh_paths`` of its description), for a copy written
    elsewhere."""
    robot = copy.deepcopy(robot)
    for mesh in robot.iter("mesh"):
        uri = mesh.get("filename", "").strip()
        mesh.set("filename", known.get(uri, uri))
    return robot


def mesh_paths(description) -> Dict[str, str]:
    """{mesh filename as written: its absolute path} of a ``urdf_file.RobotDescription``."""
    return {shape.geometry.uri: shape.geometry.filename
            for link in description.links.values()
            for shape in link.visuals + link.collisions if shape.geometry.shape == "mesh"}


def cache_clear() -> None:
    """Forget and remove every converted file (for tests)."""
    global _cache_dir
    if _cache_dir is not None:
        shutil.rmtree(_cache_dir, ignore_errors=True)
    _cache_dir = None
    _visual_parts.clear()
    _hulls.clear()
    _textured.clear()
