"""pybullet collision shapes by content: each distinct shape is built once per client and shared
by every body that has it, within a budget of the memory they hold.

pybullet 3.2.7 frees no collision shape it built: ``removeBody`` keeps the body's shape,
``removeCollisionShape`` refuses a shape a body once used ("it is used"), and neither
``resetSimulation`` nor ``disconnect`` gives the memory back (measured here, per shape: about
5 KB for a box, 1.1 MB for the hull of 10,000 vertices, 8.5 MB for a concave mesh of 10,000
triangles made from arrays, 1.7 MB for the same read from a file). So a spawn-and-delete loop
of new shapes would grow the process for good. Built once per content, the memory follows the
distinct shapes a sim has seen, not the spawns; past MAX_SHAPE_BYTES of them (estimated), a
new shape is refused with ShapeBudgetError and the sim goes on with the shapes it has.

A shape is keyed by every argument given to pybullet, mesh files by the digest of their
content (the files written for a mesh are new each time, their content is not). Shapes are
shared in the clients ``track``ed (kept on the client: ``Client.shapes``), from their
connection to ``forget_client`` (WorldPhysics does both); in another client each call builds a
new shape.
"""
import hashlib
import os
from typing import Dict, Tuple

import numpy as np

from ...errors import WorldError
from .bullet import pybullet
from .client import Client

MAX_SHAPE_BYTES = 512 * 1024 * 1024   # estimated memory of the distinct shapes of one client
PRIMITIVE_BYTES = 5 * 1024            # a box, sphere, cylinder or plane
BYTES_PER_HULL_VERTEX = 40            # a convex mesh (pybullet keeps its points)
BYTES_PER_TRIMESH_ELEMENT = 220       # a concave mesh: per vertex and per triangle


class ShapeBudgetError(WorldError):
    """A new collision shape would take the client's shapes past MAX_SHAPE_BYTES."""


class _ClientShapes:
    def __init__(self):
        self.ids: Dict[tuple, int] = {}
        self.bytes = 0


def collision_shape(client: Client, shape_type: int, **kwargs) -> int:
    """``pybullet.createCollisionShape(shape_type, **kwargs)`` in ``client``, or the id of the
    same shape built before."""
    return _shared(client, "one", (shape_type,), kwargs)


def collision_shape_array(client: Client, **kwargs) -> int:
    """``pybullet.createCollisionShapeArray(**kwargs)`` in ``client``, or the id of the same
    compound built before."""
    return _shared(client, "array", (), kwargs)


def track(client: Client) -> None:
    """Share shapes in ``client``, newly connected, from now on (``client.shapes``)."""
    client.shapes = _ClientShapes()


def forget_client(client: Client) -> None:
    """The client was disconnected."""
    client.shapes = None


def shape_bytes(client: Client) -> int:
    """The estimated memory (bytes) of the distinct shapes built in ``client``."""
    shapes = client.shapes
    return shapes.bytes if shapes is not None else 0


def _shared(client: Client, how: str, args: tuple, kwargs: dict) -> int:
    make = client.createCollisionShape if how == "one" else client.createCollisionShapeArray
    shapes = client.shapes
    if shapes is None:   # not tracked: each call builds a new shape
        return make(*args, **kwargs)
    key = (how,) + args + tuple(sorted((name, _content(name, value))
                                       for name, value in kwargs.items()))
    found = shapes.ids.get(key)
    if found is not None:
        return found
    cost = _estimate(args, kwargs)
    if shapes.bytes + cost > MAX_SHAPE_BYTES:
        raise ShapeBudgetError(
            "this simulation holds %d MB of distinct collision shapes, and pybullet frees none "
            "of them: a new one of %.1f MB is refused (at most %d MB; shapes built before can "
            "be spawned again; restart the simulation to start afresh)"
            % (shapes.bytes >> 20, cost / 2 ** 20, MAX_SHAPE_BYTES >> 20))
    shape = make(*args, **kwargs)
    if shape >= 0:
        shapes.ids[key] = shape
        shapes.bytes += cost
    return shape


def _content(name: str, value):
    """A hashable stand-in for one argument: file names by the digest of their content, arrays
    by the digest of their numbers."""
    if name == "fileName":
        return _file_digest(value)
    if name == "fileNames":
        return tuple(_file_digest(path) for path in value)
    if name in ("vertices", "indices"):
        data = np.asarray(value, dtype=np.float64 if name == "vertices" else np.int64)
        return (data.shape, hashlib.sha256(data.tobytes()).hexdigest())
    return _frozen(value)


def _frozen(value):
    if isinstance(value, (list, tuple)):
        return tuple(_frozen(v) for v in value)
    if isinstance(value, np.ndarray):
        return _frozen(value.tolist())
    return value


def _file_digest(path: str) -> Tuple[str, str]:
    if not path:
        return ("", "")
    with open(path, "rb") as f:
        return (os.path.splitext(path)[1].lower(), hashlib.sha256(f.read()).hexdigest())


def _estimate(args: tuple, kwargs: dict) -> int:
    """The memory (bytes) pybullet will hold for the shape, from the per-shape figures above."""
    if "vertices" in kwargs:
        vertices = len(kwargs["vertices"])
        if kwargs.get("flags", 0) & pybullet.GEOM_FORCE_CONCAVE_TRIMESH:
            triangles = len(kwargs.get("indices") or ()) // 3
            return PRIMITIVE_BYTES + BYTES_PER_TRIMESH_ELEMENT * (vertices + triangles)
        return PRIMITIVE_BYTES + BYTES_PER_HULL_VERTEX * vertices
    total = 0
    for path in kwargs.get("fileNames") or ([kwargs["fileName"]] if "fileName" in kwargs else []):
        if path:   # a Wavefront file written here: one "v" line per vertex
            with open(path, "rb") as f:
                vertices = sum(1 for line in f if line.startswith(b"v "))
            total += PRIMITIVE_BYTES + BYTES_PER_HULL_VERTEX * vertices
        else:
            total += PRIMITIVE_BYTES
    return max(total, PRIMITIVE_BYTES)
