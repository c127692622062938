"""The SDF world loader: a world file (or a spawn request's model) read into plain data
(world_types: ``World``, ``Shape``, ``Link``, ``Model``, ``Actor``) that engine.world_bullet
turns into bodies. No ROS and no pybullet here.

What is read follows Gazebo 11 (sdformat 9) element by element, as sdf_elements' table says
(doc/worlds.md shows it): models, nested models, links, their collisions and visuals (box,
cylinder, sphere, plane, one extruded polyline, a Collada, STL or OBJ mesh: mesh_file), poses
relative to the parent or to a named frame (sdf_frames), colours and textures (sdf_looks),
meshes and their submeshes (sdf_meshes),
``<include>``s of model folders found as Gazebo finds them (asset_uri) nested to
MAX_INCLUDE_DEPTH, actors (world_actors), the first ``<state>``'s model poses (sdf_saved_state)
and the world's lights (world_lights). A movable link keeps its ``<inertial>`` (SDF's defaults
where absent) and each collision its ``<surface><friction><ode><mu>``.

Nothing Gazebo reads refuses a world. An element not simulated (a heightmap, a road, a plugin
...) is left out with one warning line per kind and world (sdf_elements.ElementNotes); so are,
one warning line each, an ``<include>`` whose model is found nowhere or names no file (the
model is left out), a ``<mesh>`` whose file is found nowhere or is an unreadable Collada file
(its link loads without it), a material script or texture that cannot be used, a light's value
that cannot be read; a link's ``<sensor>``s are world_sensor_reading's. Refused with one line
(file, line, fault) is what Gazebo refuses or what would poison the physics: malformed XML, a
NaN pose, numbers beyond ``limits``, a movable link's mass or inertia that is not positive, an
include loop, a file that is not regular. A static model's ``<inertial>`` is not checked.

``load_world`` reads a world in three passes over the same parsed XML: its structure alone (no
mesh read: a refusal comes at once, whatever meshes come before it), then with the mesh files
noted and converted in parallel into the disk cache (mesh_cache), then for real.

Units: metres, radians. Poses are in the world frame (z up), kept as SDF writes them
(kinematics.XyzRpy). Errors are xml_reader's one line: file, line, what is wrong.
"""
import math
import os
from dataclasses import replace
from typing import Dict, List, Optional, Tuple

from ....errors import WorldError
from .. import limits
from .. import xml_reader
from ..asset_uri import AssetError, AssetNotFound, model_sdf_file, resolve_uri
from ..file_read import not_regular
from ..looks.material_scripts import MaterialScripts
from ..plugins.world_model_plugins import ModelPluginReading, with_plugins
from ..plugins.world_sensor_reading import WorldSensorReading
from .sdf_elements import ElementNotes, one_line
from .sdf_frames import MODEL_FRAME, WORLD_FRAME, Frames
from .sdf_geometry import box_size, clean_polygon, normal_pose, plane_size
from .sdf_inertia import InertiaReader
from .sdf_meshes import MeshReader
from .sdf_joints import JointNode, simulated_joints
from ..looks.sdf_looks import LookReader, sets_nothing
from .sdf_saved_state import saved_poses, with_saved_pose
from .sdf_versions import upgraded, with_version_warnings
from .world_actors import MAX_WAYPOINTS, read_actor
from .world_lights import Light, light_of, light_pose
from ..world_types import DEFAULT_RGBA, KINDS, Actor, Link, Model, Shape, World
from ...kinematics import ZERO_XYZ_RPY, XyzRpy, compose_xyz_rpy
from ..xml_reader import Element, XmlReader

MAX_INCLUDE_DEPTH = 16    # <include>s nested deeper are refused (a model including itself)
# What one document may expand to, includes and all (a 155-character request of three local
# models once fanned out to 10,000 boxes): reading stops with one line beyond these.
MAX_WORLD_SHAPES = 100_000   # collisions and visuals
MAX_INCLUDES = 10_000


def _parse_xml(path: str) -> Element:
    """The root element of the SDF file at ``path``; WorldError (file, line) if it cannot."""
    return upgraded(xml_reader.parse_file(path, "world file", WorldError), path)


def parse_xml(data, source: str) -> Element:
    """The root element of the XML text ``data`` (str or bytes); WorldError if it cannot."""
    return upgraded(xml_reader.parse(data, source, WorldError), source)


# --- the loader ---------------------------------------------------------------------------------

class _Loader(InertiaReader, LookReader, MeshReader, XmlReader):
    """Walks one SDF document; every error names the file and the line of the element at fault."""

    def __init__(self, path: str, base_dir: Optional[str] = None, depth: int = 0,
                 read_meshes: bool = True, parsed: Optional[Dict[str, Element]] = None,
                 material_scripts: Optional[MaterialScripts] = None):
        """``path`` names the document in errors; relative URIs are read from ``base_dir``
        (default: the document's folder); ``depth`` counts the includes around it;
        ``read_meshes`` False reads no mesh file (the structure alone); ``parsed`` (included
        files already parsed, by path) and ``material_scripts`` are shared by the passes of
        one load_world, so that each file is read once."""
        super().__init__(path, WorldError)
        self.path = path
        self.base_dir = base_dir if base_dir is not None else os.path.dirname(path)
        self.depth = depth
        self.read_meshes = read_meshes
        self.parsed = parsed if parsed is not None else {}
        self.shapes: List[Shape] = []
        self._links: List[Link] = []
        self._joints: List[Tuple[str, str]] = []    # (name, type)
        self._joint_nodes: List[JointNode] = []     # the same, to be placed (sdf_joints)
        # shared with the loaders of includes:
        self.warnings: List[str] = []
        self.budget = {"shapes": MAX_WORLD_SHAPES, "includes": MAX_INCLUDES,
                       "waypoints": MAX_WAYPOINTS}
        self.material_scripts = material_scripts or MaterialScripts()   # each file read once
        self.elements = ElementNotes(self.warnings)
        self.lights: List[Light] = []               # the world's, in file order
        self.actors: List[Tuple[Actor, Model]] = []   # the world's, in file order
        self.sensors = WorldSensorReading()         # the links' <sensor>s (world_sensor_reading)
        self.model_plugins = ModelPluginReading()   # the models' <plugin>s (world_model_plugins)
        self.fuel_missing: List[tuple] = []         # Fuel files not cached (sdf_meshes)

    def inner(self, path: str) -> "_Loader":
        """A loader of the included file ``path`` that adds to what this one has read."""
        inner = _Loader(path, depth=self.depth + 1, read_meshes=self.read_meshes,
                        parsed=self.parsed)
        for shared in ("shapes", "warnings", "budget", "material_scripts", "elements", "lights",
                       "actors", "sensors", "model_plugins", "fuel_missing"):
            setattr(inner, shared, getattr(self, shared))
        return inner

    def warn(self, node: Element, message: str) -> None:
        """Note ``message`` about ``node`` ("file:line: message"), once."""
        line = "%s:%d: %s" % (self.path, node.line, message)
        if line not in self.warnings:
            self.warnings.append(line)

    def warn_short(self, node: Element, message: str) -> None:
        """``warn``, in at most sdf_elements.MAX_WARNING_CHARS characters (one_line)."""
        line = one_line(self.path, node.line, message)
        if line not in self.warnings:
            self.warnings.append(line)

    def warn_searched(self, err: Exception) -> None:
        """The folders a missing file was searched in (AssetNotFound.searched), once per
        world: the warnings of each missing file name it alone."""
        searched = getattr(err, "searched", "")
        if searched and searched not in self.warnings:
            self.warnings.append(searched)

    # numbers

    def positive(self, parent: Element, tag: str, count: int, default: Tuple[float, ...]):
        node = parent.child(tag)
        if node is None:
            return default
        values = self.floats(node, count, finite=False)
        problem = limits.size_problem("<%s>" % tag, values)
        if problem:
            self.fail_bare(node, problem)
        return values

    def pose(self, parent: Element) -> XyzRpy:
        """The numbers of ``parent``'s <pose> (relative to the frame it names: sdf_frames)."""
        node = parent.child("pose")
        if node is None or not node.value:
            return ZERO_XYZ_RPY
        if node.attrib.get("rotation_format", "euler_rpy") != "euler_rpy":
            self.fail_bare(node, "<pose rotation_format=...> is SDF 1.9, which Gazebo 11 does "
                                 "not read: use euler_rpy")
        x, y, z, roll, pitch, yaw = self.floats(node, 6)
        if node.attrib.get("degrees", "false").lower() in ("true", "1"):
            roll, pitch, yaw = (math.radians(a) for a in (roll, pitch, yaw))
        problem = (limits.position_problem("<pose>", (x, y, z))
                   or limits.angles_problem("<pose>", (roll, pitch, yaw)))
        if problem:
            self.fail_bare(node, problem)
        return (x, y, z, roll, pitch, yaw)

    def frames(self, scope_pose: XyzRpy, scope_frame: str, nodes) -> Frames:
        return Frames(scope_pose, scope_frame, nodes, self.pose, self.fail_bare)

    def model_frames(self, node: Element, pose: XyzRpy) -> Frames:
        """The named frames of the model (or actor) ``node`` standing at world ``pose``."""
        return self.frames(pose, MODEL_FRAME, [c for c in node.children
                                               if c.tag in ("link", "model", "frame")])

    # structure

    def document(self, root: Element) -> World:
        if root.tag != "sdf":
            self.fail_bare(root, "not an SDF file: the root element is <%s>, not <sdf>" % root.tag)
        world = root.child("world")
        if world is None:
            if not root.all("model"):
                self.fail_bare(root, "no <world> or <model> in this file")
            world, name = root, os.path.splitext(os.path.basename(self.path))[0]
        else:
            name = world.attrib.get("name", "default")
        return with_version_warnings(self.models_of(world, name), [root, *self.parsed.values()])

    def models_of(self, world: Element, name: str, parent: XyzRpy = ZERO_XYZ_RPY) -> World:
        """The World made of ``world``'s top-level models, includes and actors, placed in
        ``parent``: the models in file order, then the actors (Gazebo's World::LoadEntities)."""
        models: List[Model] = []
        gravity = World.gravity
        saved = saved_poses(world, self.warn)
        nodes = [with_saved_pose(n, saved) if n.tag in ("model", "include", "actor") else n
                 for n in world.children]
        frames = self.frames(parent, WORLD_FRAME, [n for n in nodes if n.tag in (
            "model", "include", "actor", "frame")])
        is_world = world.tag == "world"
        for node in nodes:
            before = len(self.shapes)
            if node.tag == "model":
                self._unless_taken(models, node, [self.top_model(node, frames.place(node,
                                                                                    parent))],
                                   before)
            elif node.tag == "include":
                self._unless_taken(models, node,
                                   self.include(node, parent, "", frames=frames), before)
            elif node.tag == "actor" and is_world:
                self.actor(node, frames.place(node, parent))
            elif node.tag == "light" and is_world:
                self.lights.append(light_of(node, self.warn))
            elif node.tag == "gravity" and is_world:
                gravity = self.floats(node, 3)
                problem = limits.symmetric("<gravity>", gravity, limits.MAX_GRAVITY, "m/s^2")
                if problem:
                    self.fail_bare(node, problem)
            elif is_world:
                self.elements.check("world", node, self.path)
        models.extend(model for _, model in self.actors)
        self.elements.finish()
        self.fuel_warnings()
        return World(name, self.path, tuple(m.name for m in models), tuple(self.shapes),
                     tuple(models), tuple(self.warnings), tuple(self.lights),
                     tuple(actor for actor, _ in self.actors), sensors=self.sensors.of(models),
                     gravity=gravity, model_plugins=self.model_plugins.of(models))

    def _unless_taken(self, models: List[Model], node: Element, new: List[Model],
                      shapes_before: int) -> None:
        """Append the top-level ``new`` models read from ``node`` to ``models``; but a model
        whose name an earlier one has is left out, with the shapes it added (those after
        ``shapes_before``) and one warning: Gazebo 11's World::LoadModel does not insert it
        ("already exists"), so its services and /gazebo/model_states know the first alone."""
        for model in new:
            if any(m.name == model.name for m in models):
                del self.shapes[shapes_before:]
                self.warn_short(node, "a second model named %s is left out, as Gazebo leaves "
                                      "it out (\"already exists\")" % model.name)
            else:
                models.append(model)

    def begin_model(self) -> None:
        """Start collecting the links and joints of a new top-level model or actor."""
        self._links = []
        self._joints = []
        self._joint_nodes = []
        self.model_plugins.nodes = []

    def links_so_far(self) -> List[Link]:
        return self._links

    def add_link(self, link: Link) -> None:
        self._links.append(link)

    def add_shape(self, shape: Shape) -> None:
        """Append ``shape``, held to the world's budget of shapes."""
        self.shapes.append(shape)
        if len(self.shapes) > self.budget["shapes"]:
            raise WorldError("%s: more than %d collisions and visuals in all (do includes fan "
                             "out?)" % (self.path, self.budget["shapes"]))

    def top_model(self, node: Element, pose: XyzRpy) -> Model:
        """The top-level model ``node`` standing at world ``pose``."""
        self.begin_model()
        name = self.model(node, pose, "", False)
        static = self.flag(node, "static", False)
        return self.model_plugins.read(self, Model(
            name, pose, static, tuple(self._links), tuple(n for n, _ in self._joints),
            tuple(t for _, t in self._joints),
            () if static else simulated_joints(self, self._joint_nodes, self._links)))

    def actor(self, node: Element, pose: XyzRpy) -> None:
        """The actor ``node`` standing at world ``pose``, kept in ``self.actors``."""
        self.actors.append(read_actor(self, node, pose))

    def include(self, node: Element, parent: XyzRpy, scope: str, parent_static: bool = False,
                frames: Optional[Frames] = None) -> List[Model]:
        """The model an <include> adds, read from the folder or file its <uri> names, with the
        include's <name>, <pose> (in ``frames``, the includer's) and <static> in place of the
        model's own. At the top level it is a Model of the world; inside a model (``scope``) its
        links join that model. A file of an <actor> adds that actor (at the top level); one of
        lights only (model://sun) adds no model, and at the top level its lights join the
        world's."""
        uri_node = node.child("uri")
        uri = uri_node.value if uri_node is not None else ""
        if not uri:
            self.fail_bare(node, "<include> needs a <uri>")
        if self.depth >= MAX_INCLUDE_DEPTH:
            self.fail_bare(node, "<include> of %s: includes nested more than %d deep (does a "
                                 "model include itself?)" % (uri, MAX_INCLUDE_DEPTH))
        self.budget["includes"] -= 1
        if self.budget["includes"] < 0:
            self.fail_bare(node, "<include> of %s: more than %d includes in all (do includes "
                                 "fan out?)" % (uri, MAX_INCLUDES))
        try:
            found = resolve_uri(uri, self.base_dir)
            sdf = model_sdf_file(found) if os.path.isdir(found) else found
        except AssetNotFound as err:     # Gazebo (sdformat) skips it: "Unable to find uri"
            self.warn_short(node, "<include> left out: %s" % err.short)
            self.warn_searched(err)
            return []
        except AssetError as err:
            self.fail_bare(node, "<include>: %s" % err)
        why = not_regular(sdf)     # /dev/stdin or a FIFO would wait for ever, /dev/zero fill
        if why is not None:        # the memory (file_read)
            self.fail_bare(node, "<include> of %s: %s: %s" % (uri, sdf, why))
        root = self.parsed.get(sdf)
        if root is None:
            root = self.parsed[sdf] = _parse_xml(sdf)
        models = root.all("model")
        if len(models) != 1:
            if not models and root.all("actor") and not scope:
                actor = _overridden(root.all("actor")[0], node, ("pose",))
                self.inner(sdf).actor(actor, self._placed(node, actor, parent, frames))
                return []
            if not models and root.all("light"):
                if not scope:
                    self.light_model(node, sdf, root)
                return []
            self.fail_bare(node, "<include> of %s: %s must hold one <model>, it holds %d"
                           % (uri, sdf, len(models)))
        model = _overridden(models[0], node, ("pose", "static"))
        model = with_plugins(model, [p for p in node.all("plugin")   # sdformat 9 adds them
                                     if not self.elements.check("model", p, self.path)])
        inner = self.inner(sdf)
        pose = self._placed(node, model, parent, frames)
        if not scope:
            return [inner.top_model(model, pose)]
        inner._links, inner._joints = self._links, self._joints
        inner._joint_nodes = self._joint_nodes
        inner.model(model, pose, scope, parent_static)
        return []

    def _placed(self, include: Element, model: Element, parent: XyzRpy,
                frames: Optional[Frames]) -> XyzRpy:
        """World pose of an included ``model``: the include's <pose> in the includer's frames,
        else the model's own <pose> relative to ``parent``."""
        if include.child("pose") is not None and frames is not None:
            return frames.place(include, parent)
        return compose_xyz_rpy(parent, self.pose(model))

    def light_model(self, include: Element, sdf: str, root: Element) -> None:
        """Keep the lights of the light model ``root`` (read from ``sdf``) that ``include``
        adds to the world, with the include's <name> (a model of one light) and <pose> in
        place of their own."""
        lights = root.all("light")
        name_node = include.child("name")
        name = name_node.value if name_node is not None and len(lights) == 1 else None
        override = include.child("pose")
        pose = light_pose(override, self.warn) if override is not None else None
        inner = _Loader(sdf, depth=self.depth + 1)   # its warnings name the light's file
        inner.warnings = self.warnings
        self.lights.extend(light_of(elem, inner.warn, name, pose) for elem in lights)

    def model(self, node: Element, pose: XyzRpy, scope: str, parent_static: bool) -> str:
        """Read the model ``node`` standing at world ``pose`` inside ``scope`` (the names of
        the models around it, each with "::"); its name."""
        name = self.name(node)
        static = parent_static or self.flag(node, "static", False)
        scope += name + "::"
        frames = self.model_frames(node, pose)
        for child in node.children:
            if child.tag == "link":
                self.link(child, frames.place(child, pose), scope, static, frames)
            elif child.tag == "model":
                self.model(child, frames.place(child, pose), scope, static)
            elif child.tag == "include":
                self.include(child, pose, scope, static, frames)
            else:
                if child.tag == "joint":
                    self._joints.append((self.name(child), child.attrib.get("type", "")))
                    self._joint_nodes.append(JointNode(child, scope, pose, frames))
                self.model_plugins.kept(child, self.elements.check("model", child, self.path,
                                                                   static))
        return name

    def name(self, node: Element) -> str:
        name = node.attrib.get("name", "")
        if not name:
            self.fail_bare(node, "<%s> needs a name attribute" % node.tag)
        problem = limits.name_problem("<%s> name" % node.tag, name)
        if problem:
            self.fail_bare(node, problem)
        return name

    def link(self, node: Element, pose: XyzRpy, scope: str, static: bool,
             frames: Frames) -> None:
        """Read the link ``node`` standing at world ``pose``; ``frames``: its model's."""
        own = self.name(node)
        link = scope + own
        scope = link + "::"
        shapes = []
        for child in node.children:
            if child.tag in ("collision", "visual"):
                shape = self.element(child, frames.place(child, pose), scope, static)
                if shape is not None:
                    shapes.append(replace(shape, link=link))
            elif child.tag == "sensor":
                self.sensors.read(self, child, link, self._links)
            elif child.tag not in ("inertial", "pose"):
                self.elements.check("link", child, self.path, static)
        self.shapes.extend(self.pair_twins(shapes))
        if len(self.shapes) > self.budget["shapes"]:
            self.fail_bare(node, "more than %d collisions and visuals in all (do includes fan "
                                 "out?)" % self.budget["shapes"])
        self._links.append(Link(own, link, pose,
                                self.inertial(node.child("inertial"), static)))

    def element(self, node: Element, pose: XyzRpy, scope: str, static: bool) -> Optional[Shape]:
        """A collision or visual standing at world ``pose`` as a Shape; None for an empty
        geometry or one left out (sdf_elements: a heightmap, an image ...)."""
        name = scope + self.name(node)
        for child in node.children:
            if child.tag not in ("geometry", "pose", "material"):
                self.elements.check(node.tag, child, self.path, static)
        geometry = node.child("geometry")
        if geometry is None or not geometry.children or geometry.children[0].tag == "empty":
            return None
        if len(geometry.children) > 1:
            self.fail_bare(geometry.children[1], "<geometry> of %s holds more than one shape "
                                                 "(one <polyline> at most)" % name)
        geo = geometry.children[0]
        if self.elements.check("geometry", geo, self.path, static):
            return None
        points: Tuple[Tuple[float, float], ...] = ()
        if geo.tag == "box":
            size = box_size(self, geo)
        elif geo.tag == "cylinder":
            size = (self.positive(geo, "radius", 1, (1.0,))[0],
                    self.positive(geo, "length", 1, (1.0,))[0])
        elif geo.tag == "sphere":
            size = self.positive(geo, "radius", 1, (1.0,))
        elif geo.tag == "plane":
            size = plane_size(self, geo)
            normal_node = geo.child("normal")
            normal = self.floats(normal_node, 3) if normal_node is not None else (0.0, 0.0, 1.0)
            length = math.hypot(*normal)     # no overflow for 1e200
            if length == 0:
                self.fail_bare(normal_node, "<normal> must not be zero")
            pose = compose_xyz_rpy(pose, normal_pose([v / length for v in normal]))
        elif geo.tag == "polyline":
            size = self.positive(geo, "height", 1, (1.0,))
            points = self.polygon(geo)
        elif geo.tag == "mesh":
            found = self.mesh(geo, name, static)
            if found is None:
                return None
            size, mesh = found
        else:
            self.fail_bare(geo, "unsupported geometry <%s> in %s (Gazebo 11 reads %s, "
                                "heightmap, image)" % (geo.tag, name, ", ".join(KINDS)))
        collision = node.tag == "collision"
        rgba, texture = (DEFAULT_RGBA, None) if collision else self.look(node.child("material"))
        mu = self.friction(node) if collision else 1.0
        mesh_colours = geo.tag == "mesh" and not collision and sets_nothing(node.child("material"))
        if geo.tag == "mesh" and not collision and self.read_meshes:
            self.texture_warnings(geo, mesh, size, own=mesh_colours)
        return Shape(name, geo.tag, pose, tuple(size), points, rgba, static, collision, mu=mu,
                     mesh=mesh if geo.tag == "mesh" else "", mesh_colours=mesh_colours,
                     texture=texture)

    def polygon(self, polyline: Element) -> Tuple[Tuple[float, float], ...]:
        points = [self.floats(p, 2) for p in polyline.all("point")]
        for node, point in zip(polyline.all("point"), points):
            problem = limits.position_problem("<point>", point)
            if problem:
                self.fail_bare(node, problem)
        cleaned = clean_polygon([(x, y) for x, y in points])
        if cleaned is None:
            self.fail_bare(polyline, "<polyline> must be a simple polygon of at least 3 corners "
                                     "(not crossing itself)")
        return cleaned


def _unique_names(world: World) -> World:
    """``world`` with a second collision or visual of a name already taken in its link (not
    its twin) renamed ``NAME~2`` (~3 ...), with one warning each: Gazebo loads such a file,
    and the simulator keys each shape by its scoped name."""
    seen: Dict[str, Shape] = {}
    shapes, warnings = [], list(world.warnings)
    for s in world.shapes:
        other = seen.get(s.name)
        if other is not None and other.twin != s.name:
            count = 2
            while "%s~%d" % (s.name, count) in seen:
                count += 1
            kind = "collision" if s.collision else "visual"
            renamed = "%s~%d" % (s.name, count)
            warnings.append("%s: two elements are named %s (the second a %s): the second is %s "
                            "here" % (world.path, s.name, kind, renamed))
            s = replace(s, name=renamed)
        seen[s.name] = s
        shapes.append(s)
    if len(warnings) == len(world.warnings):
        return world
    return replace(world, shapes=tuple(shapes), warnings=tuple(warnings))


def _overridden(model: Element, include: Element, tags: Tuple[str, ...]) -> Element:
    """The included ``model`` (or actor) with the include's <name> and each of its ``tags``
    (<pose>, <static>) in place of the model's own."""
    children = list(model.children)
    for tag in tags:
        override = include.child(tag)
        if override is not None:
            children = [c for c in children if c.tag != tag] + [override]
    attrib = dict(model.attrib)
    name_node = include.child("name")
    if name_node is not None and name_node.value:
        attrib["name"] = name_node.value
    return xml_reader.element(model.tag, attrib, model.line, children)


def load_world(path: str) -> World:
    """Parse the SDF file at ``path``; WorldError (one line: file, line, fault) if it cannot.

    First its structure alone, reading no mesh: a refusal that needs no mesh content comes at
    once. Then its mesh files are converted in parallel into the disk cache (mesh_cache), and
    the world is read with them."""
    from ..meshes.mesh_prefetch import convert_world
    root = _parse_xml(path)
    shared = {"parsed": {}, "material_scripts": MaterialScripts()}
    _Loader(path, read_meshes=False, **shared).document(root)   # refusals, before the meshes
    convert_world(lambda: _Loader(path, **shared).document(root), path)
    return _unique_names(_Loader(path, **shared).document(root))


def load_model_xml(root, source: str, name: str, pose: XyzRpy = ZERO_XYZ_RPY,
                   max_shapes: int = None) -> World:
    """The one ``<model>`` of an SDF document (a spawn request's model_xml): ``root`` is its
    root element as xml_reader parsed it (changed here), or its text, parsed here. The model is
    renamed ``name`` and placed with its own <pose> composed onto ``pose``; WorldError (one
    line with the line number) if it is not that, or if it holds more than ``max_shapes``
    (default MAX_WORLD_SHAPES) collisions and visuals: reading stops there."""
    root = upgraded(root, source) if isinstance(root, Element) else parse_xml(root, source)
    loader = _Loader(source, base_dir=os.getcwd())
    if max_shapes is not None:
        loader.budget["shapes"] = max_shapes
    if root.tag not in ("sdf", "gazebo"):
        loader.fail_bare(root, "the root element is <%s>: an SDF model starts with <sdf>"
                         % root.tag)
    models = root.all("model")
    if len(models) != 1:
        loader.fail_bare(root, "<sdf> must hold exactly one <model>, it holds %d" % len(models))
    models[0].set("name", name)
    world = loader.models_of(xml_reader.element(root.tag, {}, root.line, models), name, pose)
    return with_version_warnings(_unique_names(world), [root])
