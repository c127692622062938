"""A world's ``<actor>``s, read as Gazebo 11 reads them (gazebo/physics/Actor.cc): plain data for
sim/world/actors.py to move. No ROS, no pybullet.

- ``<script>``: ``loop`` (default true), ``delay_start`` (s, default 0), ``auto_start`` (default
  true) and its ``<trajectory id type tension>``s, kept in id order (equal ids in file order),
  each with its ``<waypoint><time><pose>``s in time order, one per time (the last written
  wins), the first moved to time 0 (Actor::LoadScript). A waypoint without ``<time>`` or
  ``<pose>`` takes sdformat's default (0, the zero pose). Refused: a time that is not a finite
  number from 0 to MAX_SCRIPT_TIME s, a pose that is NaN or beyond the bounds (limits), more
  than MAX_WAYPOINTS waypoints in the world.
- ``<skin>``: its Collada file, found as a mesh is (asset_uri) and then in each
  GAZEBO_RESOURCE_PATH folder's ``media/models`` (where Gazebo keeps walk.dae and the other
  stock people), scaled by its ``<scale>``, is drawn as it is written (no skinning: what the
  file's triangles are without its skeleton's animation). A skin that is not found or has no
  triangles to draw (a file of skinned geometry only, ``<instance_controller>``) is drawn as a
  box of a person's size, SKIN_BOX, standing on the actor's frame, with one warning.
- The actor's own ``<link>``s (and ``<include>``s) are read as a model's; their visuals move
  with it, their collisions are left out: Gazebo 11 never enables an actor's collisions
  (Actor::Init does not initialise its links; ActorCollisionsPlugin's README says a plugin must
  call Link::Init for them), so its CPU ray sensor and its contacts pass through an actor.

Units: metres, seconds, radians; poses kinematics.XyzRpy in the world frame.
"""
import os
from dataclasses import replace
from typing import Dict, List, Tuple

from .. import limits
from ..asset_uri import AssetError, AssetNotFound, resolve_uri
from ..file_read import not_regular
from ...kinematics import XyzRpy, compose_xyz_rpy
from ..world_types import Actor, Link, Model, Shape, Trajectory, Waypoint
from ..xml_reader import Element, numbers

MAX_SCRIPT_TIME = 1e6          # s: a waypoint's time, an actor's delay_start
MAX_WAYPOINTS = 100_000        # in one world, all actors together
SKIN_BOX = (0.5, 0.5, 1.8)     # m: the box standing in for a skin that cannot be drawn
SKIN_BOX_RGBA = (0.55, 0.45, 0.40, 1.0)


def skin_names(actor: str) -> Tuple[str, str]:
    """(link, visual) scoped names of an actor's skin, as Gazebo names them
    ("a::a_pose", "a::a_pose::a_visual")."""
    link = "%s::%s_pose" % (actor, actor)
    return link, "%s::%s_visual" % (link, actor)


def read_actor(loader, node: Element, pose: XyzRpy) -> Tuple[Actor, Model]:
    """The Actor and the Model (its links) of the ``<actor>`` ``node`` standing at world ``pose``;
    its visuals are appended to ``loader.shapes``. ``loader`` is world_sdf's loader: its
    readers of names, numbers, poses, links and includes, its warnings and element notes."""
    name = loader.name(node)
    loader.begin_model()
    start = len(loader.shapes)
    skin = _skin(loader, node, name, pose)
    frames = loader.model_frames(node, pose)
    for child in node.children:
        if child.tag == "link":
            loader.link(child, frames.place(child, pose), name + "::", True, frames)
        elif child.tag == "include":
            loader.include(child, pose, name + "::", True, frames)
        elif child.tag not in ("skin", "script", "pose"):
            loader.elements.check("actor", child, loader.path, True)
    # Gazebo enables no collision of an actor: its visuals only, each drawn by itself.
    loader.shapes[start:] = [replace(s, twin=None) for s in loader.shapes[start:]
                             if not s.collision]
    script = node.child("script")
    actor = Actor(name, pose, _trajectories(loader, script),
                  loop=loader.flag(script, "loop", True),
                  delay_start=_seconds(loader, script, "delay_start", allow_negative=True),
                  auto_start=loader.flag(script, "auto_start", True), skin=skin)
    links = tuple(loader.links_so_far())
    return actor, Model(name, pose, True, links)


def _seconds(loader, parent, tag: str, allow_negative: bool = False) -> float:
    """The finite number of seconds of ``parent``'s optional child ``tag`` (0 without one)."""
    node = parent.child(tag) if parent is not None else None
    if node is None or not node.value:
        return 0.0
    value = loader.floats(node, 1, finite=False)[0]
    low = -MAX_SCRIPT_TIME if allow_negative else 0.0
    problem = limits.outside("<%s>" % tag, value, low, MAX_SCRIPT_TIME, "s")
    if problem:
        loader.fail_bare(node, problem)
    return value


def _trajectories(loader, script) -> Tuple[Trajectory, ...]:
    """The script's trajectories as Gazebo keeps them, in id order."""
    if script is None:
        return ()
    out: List[Trajectory] = []
    for node in script.all("trajectory"):
        ident = _integer(loader, node, "id", 0)
        tension = _attribute_number(loader, node, "tension", 0.0)
        points: Dict[float, XyzRpy] = {}
        for waypoint in node.all("waypoint"):
            loader.budget["waypoints"] -= 1
            if loader.budget["waypoints"] < 0:
                loader.fail_bare(waypoint, "more than %d waypoints in all" % MAX_WAYPOINTS)
            points[_seconds(loader, waypoint, "time")] = loader.pose(waypoint)
        times = sorted(points)
        waypoints = tuple(Waypoint(0.0 if i == 0 else t, points[t])
                          for i, t in enumerate(times))
        trajectory = Trajectory(ident, node.attrib.get("type", "__default__"),
                                min(max(tension, 0.0), 1.0), waypoints)
        at = len(out)
        while at > 0 and out[at - 1].id > ident:
            at -= 1
        out.insert(at, trajectory)
    return tuple(out)


def _integer(loader, node: Element, key: str, default: int) -> int:
    text = node.attrib.get(key, "").strip()
    if not text:
        return default
    try:
        value = int(text)
    except ValueError:
        loader.fail_bare(node, "<%s %s=%r>: must be an integer" % (node.tag, key, text))
    if abs(value) > 2 ** 31 - 1:
        loader.fail_bare(node, "<%s %s=%r>: beyond a 32-bit integer" % (node.tag, key, text))
    return value


def _attribute_number(loader, node: Element, key: str, default: float) -> float:
    text = node.attrib.get(key, "").strip()
    if not text:
        return default
    value = numbers(text, 1)
    if value is None:
        loader.fail_bare(node, "<%s %s=%r>: must be a number" % (node.tag, key, text))
    return value[0]


def _skin(loader, actor: Element, name: str, pose: XyzRpy) -> str:
    """Append the skin's visual (its mesh, or SKIN_BOX) and its link; the mesh file drawn, or
    "" (no skin, or a box stands in for it)."""
    node = actor.child("skin")
    if node is None:
        return ""
    link, visual = skin_names(name)
    loader.add_link(Link(link.split("::", 1)[1], link, pose))
    filename = node.child("filename")
    scale_node = node.child("scale")
    scale = 1.0
    if scale_node is not None and scale_node.value:
        scale = loader.floats(scale_node, 1, finite=False)[0]
        problem = limits.scale_problem((scale,) * 3, "<scale>")
        if problem or scale <= 0:
            loader.fail_bare(scale_node, problem or "<scale> %g must be positive" % scale)
    text = filename.value if filename is not None else ""
    path, why = _skin_file(loader, text, filename if filename is not None else node)
    if path and loader.read_meshes:
        why = _unreadable(loader, filename, path, scale)
    if path and not why:
        loader.add_shape(Shape(visual, "mesh", pose, (scale,) * 3, static=True,
                               collision=False, link=link, mesh=path, mesh_colours=True))
        return path
    loader.warn_short(filename if filename is not None else node,
                      "actor %s: skin %s drawn as a %g x %g x %g m box: %s"
                      % ((name, text or "(no <filename>)") + SKIN_BOX + (why,)))
    box_pose = compose_xyz_rpy(pose, (0.0, 0.0, SKIN_BOX[2] / 2, 0.0, 0.0, 0.0))
    loader.add_shape(Shape(visual, "box", box_pose, SKIN_BOX, rgba=SKIN_BOX_RGBA, static=True,
                           collision=False, link=link))
    return ""


def _skin_file(loader, text: str, at: Element) -> Tuple[str, str]:
    """(the skin file's absolute path, "") or ("", why it is not found); a file that is not
    regular is refused at ``at``."""
    if not text or text == "__default__":
        return "", "no skin file named"
    try:
        path = resolve_uri(text, loader.base_dir)
    except AssetNotFound:
        for folder in os.environ.get("GAZEBO_RESOURCE_PATH", "").split(":"):
            candidate = os.path.join(folder, "media", "models", text)
            if folder and not os.path.isabs(text) and os.path.isfile(candidate):
                return candidate, ""
        return "", ("found nowhere (looked for as a mesh is, then in GAZEBO_RESOURCE_PATH's "
                    "media/models, where Gazebo keeps its stock skins)")
    except AssetError as err:
        return "", _short(str(err))
    why = not_regular(path)
    if why is not None:     # a FIFO would wait for ever: refused, as a mesh is
        loader.fail_bare(at, "%s: %s (a mesh file is needed)" % (path, why))
    return path, ""


def _unreadable(loader, filename: Element, path: str, scale: float) -> str:
    """"" if the skin's file has triangles to draw (its texture problems warned), else why."""
    from ..meshes.mesh_file import MeshError, load_mesh
    try:
        mesh = load_mesh(path, (scale,) * 3)
    except MeshError as err:       # its line names the file: the warning does already
        return _short(str(err).replace(path + ": ", "", 1))
    for part in mesh.parts:
        if part.texture_problem:
            loader.warn(filename, part.texture_problem)
    return ""


def _short(text: str, limit: int = 90) -> str:
    """``text`` cut to ``limit`` characters (a warning line stays readable)."""
    return text if len(text) <= limit else text[:limit - 3] + "..."
