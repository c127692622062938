"""pybullet's own 3D window (``gui:=true``), opened as a user wants it: on the robot, without
pybullet's debug panels and camera previews, and without its start-up chatter in the terminal."""
import math
import time
from typing import Optional, Sequence

from .bullet import pybullet, quiet_output
from .client import Client

WINDOW = "--width=1024 --height=768"
HELLO, HELLOS = b"ven = ", 2   # what the window's thread prints, and how often, as it starts
HELLO_WAIT = 5.0               # s: the longest that is waited for it
VIEW_DISTANCE = 2.5   # m from the robot
VIEW_PITCH = -70.0    # degrees: looking down at the robot, over any wall behind it
_PANELS = ("COV_ENABLE_GUI", "COV_ENABLE_RGB_BUFFER_PREVIEW", "COV_ENABLE_DEPTH_BUFFER_PREVIEW",
           "COV_ENABLE_SEGMENTATION_MARK_PREVIEW")


def open_window() -> Optional[Client]:
    """Connect pybullet with its window (the caller checks that a display exists); the client,
    None when the window could not open."""
    with quiet_output() as printed:
        client = Client.connect(pybullet.GUI, options=WINDOW)
        if client is not None:
            for panel in _PANELS:
                client.configureDebugVisualizer(getattr(pybullet, panel), 0)
            # The window's thread says hello ("ven = Mesa/X.org") at each of its first two
            # frames, after connect returns (0.1 to 0.2 s later here, later on a busy machine):
            # its output stays silenced until it has.
            deadline = time.monotonic() + HELLO_WAIT
            while printed().count(HELLO) < HELLOS and time.monotonic() < deadline:
                time.sleep(0.02)
    return client


def look_at(client: Client, position: Sequence[float], yaw: float) -> None:
    """Point the window's camera at ``position`` (m, world) from behind a robot heading ``yaw``
    (rad, counter-clockwise from +x)."""
    client.resetDebugVisualizerCamera(
        cameraDistance=VIEW_DISTANCE, cameraYaw=math.degrees(yaw) - 90.0,
        cameraPitch=VIEW_PITCH, cameraTargetPosition=list(position))
