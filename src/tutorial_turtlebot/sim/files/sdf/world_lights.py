"""The lights of a world as plain data (get_light_properties / set_light_properties).

No ROS and no pybullet: the lights light nothing here (the camera renders with its own fixed
lighting), they are kept so that what a client sets is what it reads back. The world loader
(world_sdf) reads them once, with the rest of the world, into ``World.lights``: the world's
``<light>`` elements and those of its ``<include>``s of a light model (``model://sun``), each
made a ``Light`` by ``light_of`` with SDF's defaults for what it leaves out. A value that cannot
be read keeps SDF's default and is one line in ``World.warnings``. ``lights_by_name`` gives the
world API its own copies. Colours (r, g, b, a) in 0..1; directions and positions in m, world
frame.
"""
from dataclasses import dataclass, field, replace
from typing import Callable, Dict, Iterable, Optional, Tuple

from .. import xml_reader
from ...kinematics import IDENTITY, Pose, Vector3, pose_from_xyz_rpy
from ..xml_reader import Element

Rgba = Tuple[float, float, float, float]
Warn = Callable[[Element, str], None]     # notes one line about an element (world_sdf's warn)


@dataclass
class Light:
    """One light, with SDF's defaults."""

    name: str
    kind: str = "point"                   # point, directional or spot
    cast_shadows: bool = False
    diffuse: Rgba = (1.0, 1.0, 1.0, 1.0)
    specular: Rgba = (0.1, 0.1, 0.1, 1.0)
    attenuation_range: float = 10.0
    attenuation_constant: float = 1.0
    attenuation_linear: float = 1.0
    attenuation_quadratic: float = 0.0
    direction: Vector3 = (0.0, 0.0, -1.0)
    pose: Pose = field(default=IDENTITY)


def _numbers(elem: Optional[Element], count: int, default, warn: Warn):
    """``count`` numbers of ``elem``'s text; ``default`` if there is no ``elem``, and, with a
    warning, if it has not exactly those (a light value that cannot be read keeps SDF's
    default)."""
    if elem is None:
        return default
    values = xml_reader.numbers(elem.value, count, finite=False)
    if values is None:
        warn(elem, "light: <%s> must be %s, got %r: SDF's default is used"
             % (elem.tag, "a number" if count == 1 else "%d numbers" % count, elem.value))
        return default
    return values


def light_pose(elem: Optional[Element], warn: Warn, default: Pose = IDENTITY) -> Pose:
    """The pose "x y z roll pitch yaw" of ``elem`` (a light's or an include's ``<pose>``);
    ``default`` if there is none or, with a warning, if it cannot be read."""
    values = _numbers(elem, 6, None, warn)
    return default if values is None else pose_from_xyz_rpy(values)


def light_of(elem: Element, warn: Warn, name: Optional[str] = None,
             pose: Optional[Pose] = None) -> Light:
    """The Light of a ``<light>`` element (``name``/``pose``: an include's overrides); each
    value that cannot be read keeps SDF's default, with one line to ``warn``."""
    light = Light(name or elem.get("name", ""), elem.get("type", "point"))
    shadows = elem.find("cast_shadows")
    if shadows is not None and shadows.text:
        try:
            light.cast_shadows = xml_reader.boolean(shadows.text)
        except ValueError:
            warn(shadows, "light: <cast_shadows> must be true or false, got %r: SDF's default "
                          "is used" % shadows.text.strip())
    light.diffuse = _numbers(elem.find("diffuse"), 4, light.diffuse, warn)
    light.specular = _numbers(elem.find("specular"), 4, light.specular, warn)
    attenuation = elem.find("attenuation")
    if attenuation is not None:
        for key in ("range", "constant", "linear", "quadratic"):
            value = _numbers(attenuation.find(key), 1, None, warn)
            if value is not None:
                setattr(light, "attenuation_" + key, value[0])
    light.direction = _numbers(elem.find("direction"), 3, light.direction, warn)
    light.pose = pose if pose is not None else light_pose(elem.find("pose"), warn)
    return light


def lights_by_name(lights: Iterable[Light]) -> Dict[str, Light]:
    """``lights`` (a World's) by name, in file order, each a copy of its own: the first of a
    name wins, a light without a name is left out."""
    out: Dict[str, Light] = {}
    for light in lights:
        if light.name and light.name not in out:
            out[light.name] = replace(light)
    return out
