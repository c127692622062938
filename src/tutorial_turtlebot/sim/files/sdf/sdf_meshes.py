"""A ``<mesh>`` geometry for the world loader (world_sdf): its file found (asset_uri, Fuel URLs
from the Fuel cache: fuel_uri), its ``<scale>``, its ``<submesh>`` (meshes.submeshes) and the
warnings of what is left out. No ROS and no pybullet here. Units: metres, in the mesh frame.

Left out with one warning line each, the link loading without that geometry as in Gazebo: a
file found nowhere, an unreadable Collada file, a scale with a factor 0. Fuel files not in the
cache are one warning each, or one line for them all beyond MAX_FUEL_LINES of them (a world
Gazebo saved names every mesh by its Fuel URL: one had 143). A ``<submesh>`` the file does not
have is one warning, and the whole mesh is taken, as Gazebo's physics takes it.
"""
import os
from typing import Optional, Tuple

from ....errors import UserError
from .. import limits
from ..asset_uri import AssetNotFound, FuelNotCached, resolve_uri
from ..file_read import not_regular
from ..fuel_uri import parse_fuel
from .sdf_elements import one_line
from ..xml_reader import Element

MAX_FUEL_LINES = 5      # Fuel files not cached said one a line up to this many, else in one line


class MeshReader:
    """The loader's reading of meshes, mixed into world_sdf's loader (an xml_reader.XmlReader
    with ``path``, ``base_dir``, ``read_meshes``, ``warnings``, ``warn_short``,
    ``warn_searched``, ``elements`` and ``fuel_missing``: [(file, line, URI, searched)])."""

    def mesh(self, geo: Element, name: str,
             static: bool) -> Optional[Tuple[Tuple[float, ...], str]]:
        """(scale, absolute file) of a <mesh>, its file read once here (unless ``read_meshes``
        is False) so that a bad one is refused with this line; the file of its <submesh>
        alone where it names one. None, with a warning, for what is left out (see above)."""
        from ..meshes.mesh_file import SUFFIXES, MeshUnreadable, load_mesh
        uri_node = geo.child("uri")
        if uri_node is None or not uri_node.value:
            self.fail_bare(geo, "<mesh> of %s needs a <uri>" % name)
        scale = (1.0, 1.0, 1.0)
        scale_node = geo.child("scale")
        if scale_node is not None:
            scale = self.floats(scale_node, 3, finite=False)
            problem = limits.scale_problem(scale, "<scale>")
            if problem and 0 in scale and not limits.scale_problem(
                    [v or 1.0 for v in scale], "<scale>"):
                self.warn_short(scale_node, "%s left out: its <scale> %s has a factor 0, so it "
                                            "has no extent (Gazebo draws and hits nothing "
                                            "there either)" % (name, scale_node.value))
                return None
            if problem:
                self.fail_bare(scale_node, problem)
        try:
            path = resolve_uri(uri_node.value, self.base_dir)
            if self.read_meshes:
                path = self.submesh(geo, path)
                load_mesh(path, scale)
            else:               # what load_mesh refuses without reading the file
                why = not_regular(path)
                if why is not None:
                    self.fail_bare(uri_node, "%s: %s (a mesh file is needed)" % (path, why))
                suffix = os.path.splitext(path)[1].lower()
                if suffix not in SUFFIXES:
                    self.fail_bare(uri_node, "%s: unknown mesh format %r; the formats read "
                                             "are %s" % (path, suffix, ", ".join(SUFFIXES)))
        except FuelNotCached as err:
            uri = uri_node.value.strip()
            if not any(uri == each for _, _, each, _ in self.fuel_missing):
                self.fuel_missing.append((self.path, uri_node.line, uri, err.searched))
            return None
        except (AssetNotFound, MeshUnreadable) as err:
            short = getattr(err, "short", str(err))    # the folders searched: said once
            if not any(short in w for w in self.warnings):   # once per file
                self.warn_short(uri_node, "%s left out: %s" % (name, short))
                self.warn_searched(err)
            return None
        except UserError as err:
            self.fail_bare(uri_node, str(err))
        return scale, path

    def submesh(self, geo: Element, path: str) -> str:
        """The file of the <mesh>'s <submesh> (submeshes.submesh_file), else ``path``; one
        named that the file lacks is a warning, and the whole file is taken."""
        from ..meshes.submeshes import SubmeshMissing, submesh_file
        node = geo.child("submesh")
        name_node = node.child("name") if node is not None else None
        name = name_node.value.strip() if name_node is not None else ""
        if not name or name == "__default__":
            return path
        try:
            return submesh_file(path, name, self.flag(node, "center", False))
        except SubmeshMissing as err:
            self.warn_short(name_node, "%s; the whole mesh is taken, as Gazebo's physics "
                                       "takes it" % err)
            return path

    def fuel_warnings(self) -> None:
        """The warnings of the Fuel files not cached: one a file, or one line for them all
        beyond MAX_FUEL_LINES; then where they were searched, once."""
        missing = self.fuel_missing
        if not missing:
            return
        if len(missing) <= MAX_FUEL_LINES:
            for source, line, uri, _ in missing:
                self.warnings.append(one_line(source, line, "%s not cached: its mesh is left out "
                                                            "(as in Gazebo)" % uri))
        else:
            source, line = missing[0][:2]
            names = ", ".join(_brief(uri) for _, _, uri, _ in missing[:3])
            self.warnings.append(one_line(source, line, "%d Fuel files not cached, their "
                                                        "meshes left out: %s ..."
                                          % (len(missing), names)))
        if missing[0][3] not in self.warnings:
            self.warnings.append(missing[0][3])

    def texture_warnings(self, geo: Element, path: str, scale, own: bool = True) -> None:
        """A warning (once per line, at most 200 characters) for each texture of the visual
        mesh ``path`` that is not drawn: one the mesh reader could not use (its part is drawn
        in its colour), or, without ``own`` (the visual has an SDF <material>, which colours
        the whole mesh), every texture it found."""
        from ..meshes.mesh_file import load_mesh
        for part in load_mesh(path, scale).parts:
            problem = part.texture_problem
            if part.texture is not None and not own:
                problem = ("%s: texture %s not drawn: the visual's <material> colours the mesh"
                           % (os.path.basename(path), os.path.basename(part.texture)))
            if problem and not any(problem[:120] in w for w in self.warnings):   # once
                self.warn_short(geo.child("uri"), problem)


def _brief(uri: str) -> str:
    """A Fuel URL as "NAME/PATH" (its model's name and file), for a line of many."""
    parsed = parse_fuel(uri)
    return "%s/%s" % (parsed[2], parsed[4]) if parsed and parsed[4] else uri
