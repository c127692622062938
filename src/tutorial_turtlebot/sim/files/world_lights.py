"""The lights of a world file as plain data (get_light_properties / set_light_properties).

No ROS and no pybullet: the lights light nothing here (the camera renders with its own fixed
lighting), they are kept so that what a client sets is what it reads back. Read from the
world's ``<light>`` elements and from ``<include>``s of a light model (``model://sun``, found as
world_sdf finds models), with SDF's defaults for what a light leaves out.
Colours (r, g, b, a) in 0..1; directions and positions in m, world frame.
"""
import os
from dataclasses import dataclass, field
from typing import Dict, List, Optional, Tuple

from ...errors import UserError
from . import xml_reader
from ..kinematics import IDENTITY, Pose, Vector3, pose_from_xyz_rpy
from .xml_reader import Element

Rgba = Tuple[float, float, float, float]


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


def _numbers(elem: Optional[Element], count: int, default):
    """``count`` numbers of ``elem``'s text; ``default`` if it has not exactly those (a light
    that cannot be read keeps SDF's defaults)."""
    values = xml_reader.numbers(elem.value, count, finite=False) if elem is not None else None
    return default if values is None else values


def _pose(elem: Optional[Element], default: Pose) -> Pose:
    values = _numbers(elem, 6, None)
    return default if values is None else pose_from_xyz_rpy(values)


def light_of(elem: Element, name: Optional[str] = None,
             pose: Optional[Element] = None) -> Light:
    """The Light of a ``<light>`` element (``name``/``pose``: an include's overrides)."""
    light = Light(name or elem.get("name", ""), elem.get("type", "point"))
    shadows = elem.find("cast_shadows")
    if shadows is not None and shadows.text:
        light.cast_shadows = shadows.text.strip().lower() in ("1", "true")
    light.diffuse = _numbers(elem.find("diffuse"), 4, light.diffuse)
    light.specular = _numbers(elem.find("specular"), 4, light.specular)
    attenuation = elem.find("attenuation")
    if attenuation is not None:
        for key in ("range", "constant", "linear", "quadratic"):
            value = _numbers(attenuation.find(key), 1, None)
            if value is not None:
                setattr(light, "attenuation_" + key, value[0])
    light.direction = _numbers(elem.find("direction"), 3, light.direction)
    light.pose = _pose(pose if pose is not None else elem.find("pose"), light.pose)
    return light


def _included_lights(include: Element, base_dir: str) -> List[Light]:
    """The lights of an ``<include>`` of a light model; [] for anything else or unreadable."""
    uri = (include.findtext("uri") or "").strip()
    if not uri:
        return []
    try:
        from .asset_uri import model_sdf_file, resolve_uri
        from .world_sdf import parse_xml
        found = resolve_uri(uri, base_dir)
        sdf = model_sdf_file(found, parse_xml) if os.path.isdir(found) else found
        root = xml_reader.parse_file(sdf, "light model")
    except Exception:  # noqa: BLE001 - a light that cannot be read is not there
        return []
    if root.find(".//model") is not None:
        return []
    lights = root.findall(".//light")
    name = (include.findtext("name") or "").strip() or None
    return [light_of(elem, name if len(lights) == 1 else None, include.find("pose"))
            for elem in lights]


def read_lights(path: str) -> Dict[str, Light]:
    """The lights of the world file at ``path`` by name, in file order; {} if there are none or
    the file cannot be read."""
    try:
        root = xml_reader.parse_file(path, "world file")
    except UserError:
        return {}
    world = root if root.tag == "world" else root.find("world")
    if world is None:
        return {}
    base_dir = os.path.dirname(os.path.abspath(path))
    lights: Dict[str, Light] = {}
    for elem in world:
        if elem.tag == "light":
            found = [light_of(elem)]
        elif elem.tag == "include":
            found = _included_lights(elem, base_dir)
        else:
            continue
        for light in found:
            if light.name and light.name not in lights:
                lights[light.name] = light
    return lights
