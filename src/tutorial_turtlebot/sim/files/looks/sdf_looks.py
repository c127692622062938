"""What a world's visuals look like, for the world loader (world_sdf): a visual's ``<material>``
as a colour and a texture image, and each collision paired with the visual of the same geometry
(whose colour it takes: the laser's and contacts' bodies are drawn). No ROS, no pybullet.

Colours are (r, g, b, a) in 0..1, in Gazebo 11's precedence (``LookReader.look``): an explicit
``<diffuse>``, else the ``<script>``'s material (Gazebo's own ``Gazebo/<Name>`` colours:
gazebo_materials; a model's own material scripts: material_scripts), else ``<ambient>``, else
grey (world_types.DEFAULT_RGBA). A script's texture stays beside a ``<diffuse>``, tinted by it
(a textured Gazebo/<Name>, drawn in its texture's mean colour: that colour times the diffuse).
"""
from dataclasses import replace
from typing import Dict, List, Optional, Tuple

from ..asset_uri import AssetError, resolve_uri
from .gazebo_materials import GAZEBO_MATERIALS, GAZEBO_TEXTURED
from ..world_types import DEFAULT_RGBA, Rgba, Shape
from ..xml_reader import Element


NO_MATERIAL = "__default__"    # a script of this name: Gazebo's Visual::SetMaterial does nothing


def sets_nothing(material: Optional[Element]) -> bool:
    """Whether a visual's ``material`` changes nothing Gazebo draws: absent, or only a
    ``<script>`` naming ``__default__`` (a mesh then keeps its file's colours and textures)."""
    if material is None:
        return True
    script = material.child("script")
    name = script.child("name") if script is not None else None
    return (name is not None and name.value.strip() == NO_MATERIAL
            and all(child.tag == "script" for child in material.children))


class LookReader:
    """The loader's reading of looks, mixed into world_sdf's loader (an xml_reader.XmlReader
    with ``warn``, ``warnings``, ``material_scripts`` and ``base_dir``)."""

    def colour(self, material: Optional[Element]) -> Rgba:
        """The colour ``look`` draws ``material`` in."""
        return self.look(material)[0]

    def look(self, material: Optional[Element]) -> Tuple[Rgba, Optional[str]]:
        """(colour, texture image or None) of a visual's <material>, in Gazebo 11's precedence
        (rendering::Visual::Load): the <script>'s material first (a Gazebo/<Name> colour, or
        the colour and texture of the model's own scripts), then an explicit <diffuse> sets
        the colour of that material's passes, so it replaces the script's colour and tints its
        texture (a white one leaves the texture as it is). Without <diffuse>: the script's
        colour, else <ambient>, else grey. A bad script is a warning (its file and line), never
        an error."""
        if sets_nothing(material):
            return DEFAULT_RGBA, None
        given = {}
        for tag in ("diffuse", "ambient"):
            node = material.child(tag)
            if node is not None:
                values = node.value.split()
                rgba = self.floats(node, 4 if len(values) == 4 else 3)
                if not all(0.0 <= v <= 1.0 for v in rgba):
                    self.fail_bare(node, "<%s> values must lie in 0..1, got %r" % (tag, node.value))
                given[tag] = tuple(rgba) + (1.0,) * (4 - len(rgba))
        scripted, texture = None, None
        script = material.child("script")
        script_name = script.child("name") if script is not None else None
        if script_name is not None:
            if script_name.value in GAZEBO_MATERIALS:
                scripted = GAZEBO_MATERIALS[script_name.value]
                if script_name.value in GAZEBO_TEXTURED and "diffuse" in given:
                    # its texture (drawn as its mean colour) tinted by the <diffuse>
                    return tuple(m * d for m, d in zip(scripted[:3], given["diffuse"])) + (
                        given["diffuse"][3],), None
            else:
                scripted, texture = self.script_look(script, script_name)
        rgba = given.get("diffuse") or scripted or given.get("ambient") or DEFAULT_RGBA
        return rgba, texture

    def script_look(self, script: Element, name: Element
                    ) -> Tuple[Optional[Rgba], Optional[str]]:
        """(colour, texture or None) of a material the <script>'s own <uri> folders define;
        (None, None) where none does. A <uri> found nowhere is passed over, as Gazebo does
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
            return None, None
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
