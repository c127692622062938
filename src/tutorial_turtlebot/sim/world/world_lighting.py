"""The world's lights in Gazebo's world API: get/set_light_properties and delete_light over
copies of the loaded world's lights (files/world_lights reads them). A deleted light stays
deleted through reset_world and reset_simulation, as in Gazebo. The camera images do not
follow them: the renderer has a light of its own (engine/rendering)."""
from dataclasses import replace
from typing import Dict, Sequence

from ...errors import RequestError
from ..files import limits
from ..files.sdf.world_lights import Light, lights_by_name
from . import reference_frames as rf
from .reference_frames import Pose
from .request_checks import check_names


class LightRequests:
    """The light requests of the world API (its ``_lights``: the copies, made the first time).

    A part of ``WorldControl`` (world_control), which gives it ``sim``, ``models`` and the
    shared look-ups (``_model``, ``_frame``, ``_scoped_link``, ``_joint``)."""

    def lights(self) -> Dict[str, Light]:
        """The world's lights by name (copies of the loaded world's, made the first time)."""
        if self._lights is None:
            self._lights = lights_by_name(self.sim.world.lights)
        return self._lights

    def get_light(self, name: str) -> Light:
        check_names("getLightProperties: ", light_name=name)
        light = self.lights().get(name)
        if light is None:
            raise RequestError("getLightProperties: Requested light %s not found!" % name)
        return replace(light)

    def delete_light(self, name: str) -> str:
        """Take light ``name`` out of the world: get/set_light_properties no longer find it.
        The answer's status message (Gazebo's)."""
        check_names("DeleteLight: ", light_name=name)
        if self.lights().pop(name, None) is None:
            raise RequestError("DeleteLight: Requested light %s not found!" % name)
        return "DeleteLight: %s successfully deleted" % name

    def set_light(self, name: str, cast_shadows: bool, diffuse: Sequence[float],
                  specular: Sequence[float], attenuation: Sequence[float],
                  direction: Sequence[float], pose: Pose) -> None:
        """Keep what set_light_properties gives: ``attenuation`` (constant, linear,
        quadratic); the pose's quaternion normalised (all-zero: identity)."""
        check_names("setLightProperties: ", light_name=name)
        light = self.lights().get(name)
        if light is None:
            raise RequestError("setLightProperties: Requested light %s not found!" % name)
        if not rf.finite(diffuse, specular, attenuation, direction, pose[0], pose[1]):
            raise RequestError("setLightProperties: NaN or infinite value in the request")
        problem = limits.position_problem("pose.position", pose[0])
        if problem:
            raise RequestError("setLightProperties: %s" % problem)
        light.cast_shadows = bool(cast_shadows)
        light.diffuse = tuple(float(v) for v in diffuse)
        light.specular = tuple(float(v) for v in specular)
        light.attenuation_constant, light.attenuation_linear, light.attenuation_quadratic = (
            float(v) for v in attenuation)
        light.direction = tuple(float(v) for v in direction)
        light.pose = (tuple(float(v) for v in pose[0]), limits.unit_quaternion(pose[1]))
