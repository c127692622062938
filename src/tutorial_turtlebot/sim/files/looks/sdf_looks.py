"""What a world's visuals look like, for the world loader (world_sdf): a visual's ``<material>``
as a colour and a texture image, and each collision paired with the visual of the same geometry
(whose colour it takes: the laser's and contacts' bodies are drawn). No ROS, no pybullet.

Colours are (r, g, b, a) in 0..1: an explicit ``<diffuse>``, else ``<ambient>``, else Gazebo's
own ``Gazebo/<Name>`` colour (gazebo_materials), else the colour and texture of the model's own
material scripts (material_scripts), else grey (world_types.DEFAULT_RGBA).
"""
from dataclasses import replace
from typing import Dict, List, Optional, Tuple

from ..asset_uri import AssetError, resolve_uri
from .gazebo_materials import GAZEBO_MATERIALS
from ..world_types import DEFAULT_RGBA, Rgba, Shape
from ..xml_reader import Element


class LookReader:
    """The loader's reading of looks, mixed into world_sdf's loader (an xml_reader.XmlReader
    with ``warn``, ``warnings``, ``material_scripts`` and ``base_dir``)."""

    def colour(self, material: Optional[Element]) -> Rgba:
        """Explicit <diffuse>, else <ambient>, else a known Gazebo script name, else the
        colour of the script's own material (material_scripts), else grey."""
        return self.look(material)[0]

    def look(self, material: Optional[Element]) -> Tuple[Rgba, Optional[str]]:
        """(colour, texture image or None) of a visual's <material>: ``colour``'s, and the
        image of a script's own material where it has one. A bad script is a warning (its
        file and line), never an error: the visual is drawn grey."""
        if material is None:
            return DEFAULT_RGBA, None
        for tag in ("diffuse", "ambient"):
            node = material.child(tag)
            if node is not None:
                values = node.value.split()
                rgba = self.floats(node, 4 if len(values) == 4 else 3)
                if not all(0.0 <= v <= 1.0 for v in rgba):
                    self.fail_bare(node, "<%s> values must lie in 0..1, got %r" % (tag, node.value))
                return tuple(rgba) + (1.0,) * (4 - len(rgba)), None
        script = material.child("script")
        script_name = script.child("name") if script is not None else None
        if script_name is None:
            return DEFAULT_RGBA, None
        if script_name.value in GAZEBO_MATERIALS:
            return GAZEBO_MATERIALS[script_name.value], None
        return self.script_look(script, script_name)

    def script_look(self, script: Element, name: Element) -> Tuple[Rgba, Optional[str]]:
        """(colour, texture or None) of a material the <script>'s own <uri> folders define;
        (grey, None) where none does. A <uri> found nowhere is passed over, as Gazebo does
        (its error line is not a warning here); each problem of the scripts is one warning."""
        places = []
        for uri in script.all("uri"):
            try:
                places.append(resolve_uri(uri.value, self.base_dir))
            except AssetError:
                continue
        found, problems = self.material_scripts.material(name.value, places)
        for problem in problems:
            if not any(w.endswith(problem) for w in self.warnings):   # once per world
                self.warn(name, problem)
        if found is None:
            return DEFAULT_RGBA, None
        return found.rgba or DEFAULT_RGBA, found.texture

    def pair_twins(self, shapes: List[Shape]) -> List[Shape]:
        """Link each collision to the visual with the same geometry and pose, and colour it:
        by its twin, else by the link's first visual."""
        visuals = [s for s in shapes if not s.collision]
        taken = set()
        twins: Dict[str, str] = {}
        for c in (s for s in shapes if s.collision):
            for v in visuals:
                if v.name not in taken and _same_geometry(c, v):
                    twins[c.name], twins[v.name] = v.name, c.name
                    taken.add(v.name)
                    break
        by_name = {v.name: v for v in visuals}
        out = []
        for s in shapes:
            twin = twins.get(s.name)
            if s.collision:
                source = by_name.get(twin) if twin else (visuals[0] if visuals else None)
                rgba = source.rgba if source else DEFAULT_RGBA
                own = bool(source and source.mesh_colours and source.mesh == s.mesh)
                texture = source.texture if twin else None     # the same face to draw it on
                s = replace(s, rgba=rgba, twin=twin, mesh_colours=own, texture=texture)
            elif twin:
                s = replace(s, twin=twin)
            out.append(s)
        return out


def _same_geometry(a: Shape, b: Shape, tol: float = 1e-9) -> bool:
    return (a.kind == b.kind and a.mesh == b.mesh and len(a.points) == len(b.points)
            and all(abs(u - v) <= tol for u, v in zip(a.size + a.pose, b.size + b.pose))
            and all(abs(u - v) <= tol for p, q in zip(a.points, b.points) for u, v in zip(p, q)))
