"""Leave out of one camera image the static world bodies that cannot show in it (CameraRenderer).

pybullet's EGL renderer draws a client with a textured visual through its shadow-map shader: a
4096 x 4096 depth pass of every opaque visual as seen from the light, then the image. On Mesa's
llvmpipe that pass is most of a frame in a world of many models (measured, the Waffle Pi's
640 x 480 camera in bench/mesh_world.py's world: 106 ms of CPU an image, 66 ms with the bodies
out of view left out). A visual whose colour has alpha below 1 is drawn after the opaque ones
and casts no shadow; with alpha 0 its pixels are discarded. ``ViewCulling.hidden_outside``
gives alpha 0, for one image, to the static bodies that lie wholly outside the camera's view
frustum (its field of view between its near and far clip planes) together with their shadows,
and gives their colours back afterwards. The image is the same, depth too, but for a few
pixels where two surfaces lie at one depth and are drawn in another order (measured: 4 pixels of
14.7 million over 48 views of that world).

The builder of the world's bodies (world_bullet) says what it built (``note_static_body``,
``note_drawn_groups``); nothing else is ever left out (robots, URDF models, movable models).
Two rules keep the image whole:
- pybullet's EGL renderer draws every visual of one mesh file (at the same place in its body)
  as one shape, and marks the whole shape transparent when one of them is: a body is left out
  only when every body of its group (``visual_group``: the same mesh file name, whatever the
  folder) is out of view, and no movable body and no visual drawn with alpha below 1 is of it;
- a shadow falls along the light onto surfaces at or above the lowest bottom of the static
  bodies in view: a body counts as out of view only with that shadow.
A body id that pybullet gives to a new body is known by the user data each noted body carries.

Units: metres, radians; poses in the world frame.
"""
import contextlib
import math
import os
from typing import Hashable, Iterable, Iterator, List, Optional, Sequence, Tuple

import numpy as np

from ...errors import UserError
from ..files.meshes.mesh_file import load_mesh
from ..files.world_types import Shape
from .bullet import pybullet
from .client import Client

Bounds = Tuple[np.ndarray, np.ndarray]   # (lowest corner, highest corner), 3 floats each
USER_DATA_KEY = "tutorial_turtlebot.view_culling"
PLANE_THICKNESS = 0.05   # m: world_bullet.PLANE_THICKNESS, a plane's drawn thickness


class _Noted:
    """What the builder said of one body."""

    __slots__ = ("body", "tag", "bounds", "groups", "rgba")

    def __init__(self, body: int, tag: int, bounds: Optional[Bounds], groups: Tuple,
                 rgba: Tuple):
        self.body, self.tag = body, tag
        self.bounds = bounds        # in the body's base frame; None: never left out
        self.groups = groups        # the visual_group of each of its visuals
        self.rgba = rgba            # (link, colour) of each link, as built


def visual_group(shape: Shape) -> Hashable:
    """Which bodies may share one drawing of ``shape``'s visual with another: a mesh by its
    file's name (world_bullet draws it from a file of the mesh cache named after it), a box or
    plane of a script's texture by its kind (the same way); any other shape is drawn from a
    file of its own."""
    if shape.kind == "mesh":
        return ("mesh", os.path.basename(shape.mesh))
    if shape.kind in ("box", "plane") and shape.texture is not None:
        return ("mesh", shape.kind)
    return ("own", shape.name)


def shape_bounds(shape: Shape) -> Optional[Bounds]:
    """Bounds of what world_bullet draws of ``shape``, in the shape's frame; None if unknown."""
    size = shape.size
    if shape.kind == "box":
        half = np.abs(np.asarray(size[:3], float)) / 2.0
        return -half, half
    if shape.kind == "plane":
        half = np.abs(np.asarray(size[:2], float)) / 2.0
        return np.array([-half[0], -half[1], -PLANE_THICKNESS]), np.array([half[0], half[1], 0.0])
    if shape.kind == "cylinder":
        radius, half_length = abs(size[0]), abs(size[1]) / 2.0
        return (np.array([-radius, -radius, -half_length]),
                np.array([radius, radius, half_length]))
    if shape.kind == "sphere":
        radius = np.full(3, abs(size[0]))
        return -radius, radius
    if shape.kind == "polyline" and shape.points:
        points = np.asarray(shape.points, float)
        low_z, high_z = sorted((0.0, float(size[0])))
        return (np.append(points.min(axis=0), low_z), np.append(points.max(axis=0), high_z))
    if shape.kind == "mesh":
        try:
            vertices = np.asarray(load_mesh(shape.mesh, shape.size).vertices, float)
        except UserError:
            return None
        if len(vertices):
            return vertices.min(axis=0), vertices.max(axis=0)
    return None


def note_static_body(client: Client, body: int, shape: Shape) -> None:
    """``body`` (fixed, its base frame the shape's frame) draws ``shape``: it may be left out
    of an image that cannot show it. A shape drawn with alpha below 1 never is."""
    links = _link_colours(client, body)
    bounds = shape_bounds(shape) if all(rgba[3] >= 1.0 for _, rgba in links) else None
    if bounds is not None and not all(np.all(np.isfinite(b)) for b in bounds):
        bounds = None
    _note(client, body, bounds, (visual_group(shape),), links)


def note_drawn_groups(client: Client, body: int, shapes: Iterable[Shape]) -> None:
    """``body`` (a movable one) draws ``shapes``: never left out, nor is any body of their
    visual groups."""
    _note(client, body, None, tuple(visual_group(s) for s in shapes),
          _link_colours(client, body))


def forget(client: Client) -> None:
    """Forget what was noted of ``client`` (before it is disconnected)."""
    client.view_noted = {}


def _link_colours(client: Client, body: int) -> Tuple:
    """(link, rgba) of each link's first visual (pybullet gives colours right even for the
    visuals it draws from another's shape)."""
    colours = {}
    for visual in client.getVisualShapeData(body):
        colours.setdefault(visual[1], tuple(visual[7]))
    return tuple(colours.items())


def _note(client: Client, body: int, bounds, groups, links) -> None:
    tag = client.addUserData(body, USER_DATA_KEY, "1")
    client.view_noted[body] = _Noted(body, tag, bounds, groups, links)


def _tag(client: Client, body: int) -> int:
    """The id of ``body``'s view_culling user data; -1 if it has none or is gone."""
    try:
        return client.getUserDataId(body, USER_DATA_KEY)
    except pybullet.error:
        return -1


def box_in_frame(bounds: Bounds, position, orientation) -> Bounds:
    """Axis-aligned bounds, in the parent frame, of ``bounds`` placed at ``position`` with
    quaternion ``orientation`` (x, y, z, w)."""
    rotation = np.array(pybullet.getMatrixFromQuaternion(orientation)).reshape(3, 3)
    centre, half = (bounds[0] + bounds[1]) / 2.0, (bounds[1] - bounds[0]) / 2.0
    middle = rotation @ centre + np.asarray(position, float)
    reach = np.abs(rotation) @ half
    return middle - reach, middle + reach


def outside_frustum(lows: np.ndarray, highs: np.ndarray, position, rotation, hfov: float,
                    aspect: float, near: float, far: float) -> np.ndarray:
    """Which boxes (rows of ``lows``, ``highs``: N x 3, world frame) lie wholly outside the view
    frustum of a camera at ``position`` whose 3x3 ``rotation`` has columns x right, y down,
    z forward (the optical frame); ``aspect`` = height / width. True means surely outside; a
    box that only touches the frustum counts as inside."""
    rot = np.asarray(rotation, float).reshape(3, 3)
    tan_x = math.tan(hfov / 2.0)
    tan_y = tan_x * aspect
    # Outward normals in the optical frame, and each plane's offset along it from the camera.
    normals = np.array([[1.0, 0.0, -tan_x], [-1.0, 0.0, -tan_x],
                        [0.0, 1.0, -tan_y], [0.0, -1.0, -tan_y],
                        [0.0, 0.0, -1.0], [0.0, 0.0, 1.0]])
    offsets = np.array([0.0, 0.0, 0.0, 0.0, -near, far])
    world = normals @ rot.T                                   # 6 x 3, world frame
    limits = offsets + world @ np.asarray(position, float)    # n . p > limit: outside
    # Along each normal, the corner of each box that reaches least far (N x 6).
    least = sum(np.where(world[:, k] > 0, lows[:, k:k + 1], highs[:, k:k + 1]) * world[:, k]
                for k in range(3))
    return np.any(least > limits, axis=1)


def with_shadows(lows: np.ndarray, highs: np.ndarray, towards_light: Sequence[float],
                 floor: float) -> Tuple[np.ndarray, np.ndarray]:
    """Boxes grown to hold the shadows they cast down to height ``floor`` (m) under a light
    that lies along ``towards_light`` (its z above 0) from every point."""
    light = np.asarray(towards_light, float)
    light = light / np.linalg.norm(light)
    run = np.maximum(highs[:, 2] - floor, 0.0) / light[2]        # along the light, per box
    shifted_lows = lows - run[:, None] * light
    shifted_highs = highs - run[:, None] * light
    return np.minimum(lows, shifted_lows), np.maximum(highs, shifted_highs)


class ViewCulling:
    """Hides, for one image at a time, the noted static bodies of ``client`` that a camera
    (``hfov`` rad, ``aspect`` height / width, clip ``near``..``far`` m) cannot see."""

    def __init__(self, client: Client, hfov: float, aspect: float, near: float, far: float,
                 towards_light: Sequence[float]):
        self.client = client
        self.hfov, self.aspect, self.near, self.far = hfov, aspect, near, far
        self.towards_light = tuple(towards_light)
        self.hidden_bodies = frozenset()   # the body ids left out of the last image

    @contextlib.contextmanager
    def hidden_outside(self, position, rotation) -> Iterator[int]:
        """Within the context, the bodies that a camera at ``position`` with ``rotation``
        (optical frame, as outside_frustum) cannot see have alpha 0; their colours come back
        when it ends, whatever happens. The context's value: how many bodies are hidden."""
        hidden = self._hide(position, rotation)
        try:
            yield len(hidden)
        finally:
            self._paint(hidden, restore=True)

    def _hide(self, position, rotation) -> List[_Noted]:
        noted = self._current()
        candidates = [n for n in noted if n.bounds is not None]
        self.hidden_bodies = frozenset()
        if not candidates:
            return []
        lows, highs = self._world_boxes(candidates)
        frustum = (position, rotation, self.hfov, self.aspect, self.near, self.far)
        in_view = ~outside_frustum(lows, highs, *frustum)
        # shadows fall onto surfaces down to the lowest bottom of the bodies in view (a body
        # parked far below the world is not one)
        floor = float((lows[in_view] if in_view.any() else lows)[:, 2].min())
        out = outside_frustum(*with_shadows(lows, highs, self.towards_light, floor), *frustum)
        seen = {g for n in noted if n.bounds is None for g in n.groups}
        seen.update(g for n, gone in zip(candidates, out) if not gone for g in n.groups)
        hidden = [n for n, gone in zip(candidates, out) if gone and seen.isdisjoint(n.groups)]
        self._paint(hidden, restore=False)
        self.hidden_bodies = frozenset(n.body for n in hidden)
        return hidden

    def _paint(self, bodies: Sequence[_Noted], restore: bool) -> None:
        client = self.client
        for n in bodies:
            for link, rgba in n.rgba:
                client.changeVisualShape(n.body, link,
                                         rgbaColor=rgba if restore else rgba[:3] + (0.0,))

    def _current(self) -> List[_Noted]:
        """The noted bodies still there (a removed one's id may be a new body's: it has not
        the user data)."""
        client = self.client
        bodies = client.view_noted
        gone = [body for body, n in bodies.items() if _tag(client, body) != n.tag]
        for body in gone:
            del bodies[body]
        return list(bodies.values())

    def _world_boxes(self, noted: Sequence[_Noted]) -> Tuple[np.ndarray, np.ndarray]:
        """(lows, highs): N x 3 world bounds of the ``noted`` bodies where they stand now."""
        client = self.client
        lows, highs = np.empty((len(noted), 3)), np.empty((len(noted), 3))
        for k, n in enumerate(noted):
            position, orientation = client.getBasePositionAndOrientation(n.body)
            lows[k], highs[k] = box_in_frame(n.bounds, position, orientation)
        return lows, highs
