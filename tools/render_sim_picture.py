#!/usr/bin/env python3
"""Make doc/sim_turtlebot3_world.png: the README's picture of the simulation.

A Waffle Pi stands at its spawn in turtlebot3_world (the simulator's own world, robot and
camera renderer, no ROS master); a camera behind and above it looks over it into the arena.
The PNG is written with zlib and struct only (no image library needed).

    source catkin_ws/devel/setup.bash
    python3 tools/render_sim_picture.py                 # writes doc/sim_turtlebot3_world.png
    python3 tools/render_sim_picture.py --model burger --output /tmp/burger.png
"""
import argparse
import math
import os
import struct
import sys
import zlib

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "src"))

from tutorial_turtlebot.sim.devices.camera import CameraRenderer  # noqa: E402
from tutorial_turtlebot.sim.files.plugins.robot_plugin_types import CameraSpec  # noqa: E402
from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation  # noqa: E402

WIDTH, HEIGHT = 960, 540
HFOV = math.radians(60.0)
# Camera position and the point it looks at (world frame, m): above the arena's far side,
# looking over the pillars at the robot, which faces +x from its spawn (-2.0, -0.5).
EYE = (1.3, 1.8, 3.3)
TARGET = (-1.4, -0.4, 0.0)


def look_at(eye, target):
    """World rotation (columns: x right, y down, z forward) of an optical frame at ``eye``
    looking at ``target`` with the world's +z up."""
    forward = np.subtract(target, eye).astype(float)
    forward /= np.linalg.norm(forward)
    right = np.cross(forward, (0.0, 0.0, 1.0))
    right /= np.linalg.norm(right)
    down = np.cross(forward, right)
    return np.column_stack((right, down, forward))


def png_bytes(rgb: np.ndarray) -> bytes:
    """An 8-bit RGB PNG of ``rgb`` (height x width x 3, uint8)."""
    height, width, _ = rgb.shape
    raw = b"".join(b"\x00" + rgb[row].tobytes() for row in range(height))

    def chunk(kind: bytes, data: bytes) -> bytes:
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body))

    header = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header)
            + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--model", default="waffle_pi", help="burger, waffle or waffle_pi")
    parser.add_argument("--world", default="turtlebot3_world")
    parser.add_argument("--output", default=os.path.join(HERE, "..", "doc",
                                                         "sim_turtlebot3_world.png"))
    args = parser.parse_args(argv)
    # camera=False: the robot's own camera is not needed; the picture's camera is made here.
    sim = Simulation(SimConfig(model=args.model, world=args.world, camera=False))
    try:
        for _ in range(40):          # 0.1 s of sim time: the robot settles on its wheels
            sim.step()
        spec = CameraSpec(width=WIDTH, height=HEIGHT, hfov=HFOV, rate=1.0, near=0.05, far=50.0)
        renderer = CameraRenderer(sim.physics.client, spec, use_egl=sim.physics.egl)
        rgb, _ = renderer.render(EYE, look_at(EYE, TARGET))
    finally:
        sim.close()
    with open(args.output, "wb") as out:
        out.write(png_bytes(rgb))
    print("%s: %dx%d, %s, rendered by %s" % (os.path.normpath(args.output), WIDTH, HEIGHT,
                                             args.model, renderer.renderer_name))
    return 0


if __name__ == "__main__":
    sys.exit(main())
