"""The three TurtleBot3 models: what no URDF holds (doc/turtlebot3.md 2.5).

A robot's drive, laser, IMU and camera come from its URDF's ``<gazebo>`` blocks
(``sim.files.plugins.robot_plugins``); what is here is the firmware's and turtlebot3_teleop_key's
speed limits, the circle each model sweeps turning in place, and which URDF file each model is. The
simulator and the lab's nodes both read these facts here. Units: m, m/s, rad/s.
"""
import re
from dataclasses import dataclass
from pathlib import Path
from typing import Optional, Tuple

from .errors import ModelError
from .package_data import data_dir


@dataclass(frozen=True)
class ModelSpec:
    """One TurtleBot3 model's name, speed limits, and whether its URDF carries a camera."""

    name: str
    max_linear: float           # m/s, firmware / teleop limit
    max_angular: float          # rad/s
    # m: the circle it sweeps turning in place about base_footprint, the farthest corner of its
    # navigation footprint (doc/turtlebot3.md 1.1), rounded up
    turn_radius: float
    carries_camera: bool        # False: camera:=true picks the AutoRace variant's URDF

    @property
    def urdf_name(self) -> str:
        """File name of the model's URDF in ``urdf/``."""
        return "turtlebot3_%s.urdf" % self.name


MODELS = {
    "burger": ModelSpec("burger", 0.22, 2.84, 0.15, carries_camera=False),
    "waffle": ModelSpec("waffle", 0.26, 1.82, 0.26, carries_camera=True),
    "waffle_pi": ModelSpec("waffle_pi", 0.26, 1.82, 0.26, carries_camera=True),
}

MODEL_NAMES: Tuple[str, ...] = tuple(MODELS)
_IN_ROBOT_NAME = re.compile(r"turtlebot3_(waffle_pi|waffle|burger)")


def get_model(name: str) -> ModelSpec:
    """Return the spec of ``name``; an unknown name raises ModelError listing the valid ones."""
    try:
        return MODELS[name]
    except (KeyError, TypeError):
        raise ModelError("unknown TurtleBot3 model %r: valid models are %s"
                         % (name, ", ".join(MODEL_NAMES))) from None


def urdf_path(model_name: str, with_camera: bool = False) -> str:
    """Path of the URDF shipped for a TurtleBot3 model. ``with_camera`` on a model that carries no
    camera (burger) gives its AutoRace variant; an unknown model raises ModelError."""
    spec = get_model(model_name)
    if with_camera and not spec.carries_camera:
        return str(Path(data_dir("urdf")) / ("turtlebot3_%s_for_autorace.urdf" % spec.name))
    return str(Path(data_dir("urdf")) / spec.urdf_name)


def model_limits(name: str) -> Tuple[float, float]:
    """(max linear m/s, max angular rad/s) as turtlebot3_teleop_key picks them: any unknown
    name gets the burger limits."""
    spec = MODELS.get(name, MODELS["burger"])
    return spec.max_linear, spec.max_angular


def turn_radius(name: str) -> float:
    """The turn radius (m) of model ``name``; the largest of them for an unknown name (the
    safe side)."""
    spec = MODELS.get(name)
    return spec.turn_radius if spec else max(m.turn_radius for m in MODELS.values())


def turtlebot3_model_of(robot_name: str) -> Optional[str]:
    """The TurtleBot3 model a URDF's ``<robot name>`` names (turtlebot3_waffle_pi ->
    waffle_pi; turtlebot3_burger_for_autorace -> burger), None for any other robot."""
    match = _IN_ROBOT_NAME.search(robot_name or "")
    return match.group(1) if match else None
