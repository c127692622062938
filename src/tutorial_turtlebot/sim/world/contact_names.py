"""Which collision of which model a body's link is, as Gazebo names it in a contact
("model::link::collision"): what a contact sensor (world_sensors.BumperRunner) reports of the
colliders it touches, and where its own collisions are in the engine. Knows nothing of ROS.

A static SDF collision is a fixed body of its own (engine.world_bullet); a movable SDF link is
one body or one link of a multibody (LinkPart), named by its first collision; a URDF model's
link by the first of its geoms (Gazebo's names, world_models.urdf_model) that starts with the
link's name, else "<link>_collision" (sdformat's parser_urdf). A robot's bumper names the
collisions of its link as Gazebo names them (RobotDescription.collision_names): all of them are
that link's one body link in the engine.
"""
from typing import Dict, Optional, Tuple

from ..engine.bodies import Body

Key = Tuple[int, int]          # (body id, link index; -1 the base or a rigid body)


def static_bodies(model) -> Dict[str, Body]:
    """Scoped collision name -> its fixed body, for the static collisions of an SdfModel:
    they are its parts that are not movable, in the order of its document's shapes that
    world_bullet gives a body of their own (a static collision, a static visual without one);
    empty when the counts differ (a model built otherwise)."""
    world = getattr(model, "world", None)
    if world is None:
        return {}
    own = [s for s in world.model_shapes(model.name)
           if s.static and (s.collision or s.twin is None)]
    fixed = [part.body for part in model.parts if not part.movable]
    if len(own) != len(fixed):
        return {}
    return {shape.name: body for shape, body in zip(own, fixed) if shape.collision}


def link_collision(model, link) -> str:
    """The collision a LinkPart of ``model`` is known by in a contact."""
    scoped = "%s::%s" % (model.name, link.name)
    world = getattr(model, "world", None)
    if world is not None:
        first = next((s.name for s in world.model_shapes(model.name)
                      if s.collision and s.link == scoped), None)
        return first or scoped + "::collision"
    prefix = link.name + "_"
    geom = next((g for g in model.geoms if g.startswith(prefix)), link.name + "_collision")
    return "%s::%s" % (scoped, geom)


class ContactNames:
    """(body id, link index) -> "model::link::collision" of every model in ``registry`` (a
    ModelRegistry), made again when the registry's layout changes."""

    def __init__(self, registry):
        self.registry = registry
        self._layout = None
        self._names: Dict[Key, str] = {}

    def current(self) -> Dict[Key, str]:
        """The names now, for ``name_in``."""
        layout = self.registry.layout()
        if layout != self._layout:
            self._names = self._made()
            self._layout = layout
        return self._names

    def _made(self) -> Dict[Key, str]:
        names: Dict[Key, str] = {}
        for model in self.registry.models():
            for name, body in static_bodies(model).items():
                names[(body.uid, -2)] = name      # every link of it (a polyline's pieces)
            for link in model.links:
                if link.body is not None:
                    names.setdefault((link.body.uid, link.index), link_collision(model, link))
        return names


def name_in(names: Dict[Key, str], body: int, link: int) -> str:
    """The collision at ``body``'s ``link`` in ContactNames.current(); "" for one of no
    model."""
    return names.get((body, link), names.get((body, -2), ""))


def collision_link(model, collision: str) -> Optional[Tuple[str, Optional[Body], int]]:
    """Where the scoped ``collision`` of ``model`` is in the engine: (its link's scoped name,
    body, link index); None if the model has no such collision."""
    world = getattr(model, "world", None)
    if world is None and getattr(model, "robot_body", None) is not None:
        return _robot_collision_link(model, collision)
    shape = next((s for s in (world.model_shapes(model.name) if world is not None else ())
                  if s.collision and s.name == collision), None)
    if shape is None:
        return None
    if shape.static:
        body = static_bodies(model).get(collision)
        return (shape.link, body, -1) if body is not None else None
    for link in model.links:
        if "%s::%s" % (model.name, link.name) == shape.link and link.body is not None:
            return shape.link, link.body, link.index
    return None


def _robot_collision_link(model, collision: str) -> Optional[Tuple[str, Optional[Body], int]]:
    """collision_link of a robot's (world_models.RobotModel) "model::link::collision"."""
    prefix = model.name + "::"
    link, sep, geom = collision[len(prefix):].partition("::")
    names = model.robot_body.description.collision_names()
    if not collision.startswith(prefix) or not sep or geom not in names.get(link, ()):
        return None
    for part in model.links:
        if part.name == link and part.body is not None:
            return prefix + link, part.body, part.index
    return None
