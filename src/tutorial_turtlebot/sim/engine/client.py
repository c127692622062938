"""One pybullet client as one object: the only place that hands pybullet a client id.

``Client`` owns the id pybullet gave a connection. Its methods are pybullet's functions bound to
that id: ``client.stepSimulation()``, ``client.rayTestBatch(starts, ends, ...)``,
``client.getBasePositionAndOrientation(uid)`` (pybullet's own arguments, less
``physicsClientId``). Each is bound once, on first use (a ``functools.partial`` kept on the
object), so a call in the stepping loop costs what the plain call with the id does. pybullet's
constants stay pybullet's (``pybullet.GEOM_BOX``); its functions that need no client (the
transforms, the camera matrices) are called on pybullet itself.

The client also holds the engine's state of that connection, each module's own, made here at
construction (none of it is keyed by the id: a new connection that gets an old id starts
afresh):
- ``filters``: collision_filters' collider -> (group, mask), once tracked (else None);
- ``shapes``: bullet_shapes' shared collision shapes, once tracked (else None);
- ``egl_plugin``, ``textured``: rendering's EGL plugin id (None: not loaded) and whether a
  textured visual was built (note_textures);
- ``texture_plan``: texture_budget's halvings of the client's texture images (None: none yet);
- ``view_noted``: view_culling's bodies, body id -> what the builder said of it;
- ``joints_set``: bodies' joints changed since they were built (set_joint_properties),
  (body id, joint index) -> what was set (bodies.Body);
- ``built_joints``: body id -> a bodies.BuiltJoint per joint of a body built from SDF
  (movable_bodies): its name, child link and properties as built, which pybullet's
  getJointInfo does not give for a createMultiBody's joints.

``int(client)`` (``__index__``) is the id, for a test or tool that calls pybullet itself.
"""
import functools
import types
from collections import OrderedDict
from typing import Any, Dict, Optional, Tuple

from .bullet import pybullet


class Client:
    """pybullet client ``client_id`` (already connected): pybullet's functions bound to it."""

    def __init__(self, client_id: int):
        self.id = client_id
        self.filters: Optional[OrderedDict] = None     # collision_filters (tracked clients)
        self.shapes: Any = None                        # bullet_shapes (tracked clients)
        self.egl_plugin: Optional[int] = None          # rendering: the EGL plugin's id
        self.textured = False                          # rendering.note_textures
        self.texture_plan: Any = None                  # texture_budget
        self.view_noted: Dict[int, Any] = {}           # view_culling: body id -> noted
        self.joints_set: Dict[Tuple[int, int], Dict[str, Any]] = {}   # bodies: what was set
        self.built_joints: Dict[int, Tuple[Any, ...]] = {}   # bodies.BuiltJoint per joint

    @classmethod
    def connect(cls, method: Optional[int] = None, **options) -> Optional["Client"]:
        """A new pybullet connection (``method``: pybullet.DIRECT unless given; ``options``:
        pybullet.connect's), or None when pybullet could not make it (a window that cannot
        open)."""
        client_id = pybullet.connect(pybullet.DIRECT if method is None else method, **options)
        return cls(client_id) if client_id >= 0 else None

    def __getattr__(self, name: str):
        """pybullet's function ``name`` bound to this client, made on first use and kept."""
        if name.startswith("_") or name == "connect":
            raise AttributeError(name)
        function = getattr(pybullet, name)
        if not isinstance(function, types.BuiltinFunctionType):
            raise AttributeError("pybullet.%s is no function: use it from pybullet" % name)
        bound = functools.partial(function, physicsClientId=self.id)
        setattr(self, name, bound)
        return bound

    def __index__(self) -> int:
        return self.id

    def __repr__(self) -> str:
        return "Client(%d)" % self.id
