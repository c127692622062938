"""pybullet's own 3D window (``gui:=true``), opened as a user wants it: on the robot, without
pybullet's debug panels and camera previews, and without its start-up chatter in the terminal."""
import math
from typing import Sequence

from .bullet import pybullet, quiet_output

WINDOW = "--width=1024 --height=768"
VIEW_DISTANCE = 2.5   # m from the robot
VIEW_PITCH = -70.0    # degrees: looking down at the robot, over any wall behind it
_PANELS = ("COV_ENABLE_GUI", "COV_ENABLE_RGB_BUFFER_PREVIEW", "COV_ENABLE_DEPTH_BUFFER_PREVIEW",
           "COV_ENABLE_SEGMENTATION_MARK_PREVIEW")


def open_window() -> int:
    """Connect pybullet with its window (the caller checks that a display exists); the client
    id, negative when the window could not open."""
    with quiet_output():
        client = pybullet.connect(pybullet.GUI, options=WINDOW)
        if client >= 0:
            for panel in _PANELS:
                pybullet.configureDebugVisualizer(getattr(pybullet, panel), 0,
                                                  physicsClientId=client)
            # The window's thread says hello ("ven = Mesa/X.org") once its OpenGL is up, after
            # connect returns: a round trip through that thread waits for it.
            pybullet.getDebugVisualizerCamera(physicsClientId=client)
    return client


def look_at(client: int, position: Sequence[float], yaw: float) -> None:
    """Point the window's camera at ``position`` (m, world) from behind a robot heading ``yaw``
    (rad, counter-clockwise from +x)."""
    pybullet.resetDebugVisualizerCamera(
        cameraDistance=VIEW_DISTANCE, cameraYaw=math.degrees(yaw) - 90.0,
        cameraPitch=VIEW_PITCH, cameraTargetPosition=list(position), physicsClientId=client)
