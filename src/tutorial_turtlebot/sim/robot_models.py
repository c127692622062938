"""The three TurtleBot3 models: drive geometry, speed limits and sensors (tb3_facts.md 1, 2).

Units: metres, seconds, radians. Frames follow REP 103/105.
"""
from dataclasses import dataclass
from typing import Optional, Tuple

from ..errors import ModelError


@dataclass(frozen=True)
class CameraSpec:
    """An RGB camera mounted at ``frame`` (the URDF link whose optical frame it renders)."""

    width: int
    height: int
    hfov: float            # horizontal field of view, rad
    rate: float            # Hz, sim time
    near: float = 0.03     # clip planes, m
    far: float = 100.0
    depth: bool = False    # also publishes /camera/depth/* (RealSense R200)
    baseline: float = 0.0  # gazebo_ros hackBaseline, m (P[3] = -f * baseline)


@dataclass(frozen=True)
class ModelSpec:
    """One TurtleBot3 model as the diff-drive plugin and the teleop node see it."""

    name: str
    wheel_separation: float     # m, between wheel centres
    wheel_radius: float         # m
    max_linear: float           # m/s, firmware / teleop limit
    max_angular: float          # rad/s
    camera: Optional[CameraSpec]  # the camera it carries by default, None for burger
    optional_camera: Optional[CameraSpec] = None  # camera:=true on a model without one
    wheel_torque: float = 10.0       # N*m, joint fmax of the Gazebo plugin
    wheel_acceleration: float = 1.0  # m/s^2 at the wheel rim (Gazebo wheelAcceleration)

    @property
    def urdf_name(self) -> str:
        """File name of the model's URDF in ``urdf/``."""
        return "turtlebot3_%s.urdf" % self.name


# The AutoRace burger's Pi camera, pitched 10 degrees down (tb3_facts 4.5).
AUTORACE_CAMERA = CameraSpec(width=320, height=240, hfov=1.085595, rate=30.0)

MODELS = {
    "burger": ModelSpec("burger", 0.160, 0.033, 0.22, 2.84, camera=None,
                        optional_camera=AUTORACE_CAMERA),
    "waffle": ModelSpec("waffle", 0.287, 0.033, 0.26, 1.82,
                        camera=CameraSpec(1920, 1080, 1.3439, 30.0, depth=True, baseline=0.07)),
    "waffle_pi": ModelSpec("waffle_pi", 0.287, 0.033, 0.26, 1.82,
                           camera=CameraSpec(640, 480, 1.085595, 30.0, baseline=0.07)),
}

MODEL_NAMES: Tuple[str, ...] = tuple(MODELS)


def get_model(name: str) -> ModelSpec:
    """Return the spec of ``name``; an unknown name raises ModelError listing the valid ones."""
    try:
        return MODELS[name]
    except (KeyError, TypeError):
        raise ModelError("unknown TurtleBot3 model %r: valid models are %s"
                         % (name, ", ".join(MODEL_NAMES))) from None


def model_limits(name: str) -> Tuple[float, float]:
    """(max linear m/s, max angular rad/s) as turtlebot3_teleop_key picks them: any unknown
    name gets the burger limits."""
    spec = MODELS.get(name, MODELS["burger"])
    return spec.max_linear, spec.max_angular
