"""pybullet's own window (gui:=true), in a virtual display: it opens looking at the robot,
and pybullet's start-up and shut-down chatter stays out of the terminal."""
import json
import os
import shutil
import subprocess
import sys

import pytest
import unit_paths

ROOT = unit_paths.ROOT
SCRIPT = """
import json
from tutorial_turtlebot.sim.engine.bullet import pybullet
from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
sim = Simulation(SimConfig(model="burger", world="turtlebot3_world", gui=True))
import time
deadline = time.monotonic() + 10.0
while True:  # the window's own thread takes the new view in a moment
    sim.step()
    camera = pybullet.getDebugVisualizerCamera(physicsClientId=sim.physics.client)
    if camera[11][0] != 0.0 or time.monotonic() > deadline:
        break
    time.sleep(0.01)
sim.close()
print(json.dumps({"yaw": camera[8], "pitch": camera[9], "distance": camera[10],
                  "target": camera[11]}))
"""


def test_window_opens_on_the_robot_quietly():
    if shutil.which("xvfb-run") is None:
        pytest.skip("xvfb-run not found (Debian: xvfb, which tools/setup.sh installs)")
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(
        p for p in (os.path.join(ROOT, "src"), os.environ.get("PYTHONPATH")) if p))
    run = subprocess.run(["xvfb-run", "-a", "-s", "-screen 0 1280x1024x24", sys.executable,
                          "-c", SCRIPT], capture_output=True, text=True, timeout=120, env=env)
    assert run.returncode == 0, run.stdout + run.stderr
    lines = run.stdout.splitlines()
    assert len(lines) == 1, "pybullet printed to the terminal:\n" + run.stdout
    assert run.stderr == "", "pybullet printed to the terminal:\n" + run.stderr
    camera = json.loads(lines[0])
    assert camera["target"][:2] == pytest.approx([-2.0, -0.5], abs=1e-3)  # the spawn
    assert camera["yaw"] == pytest.approx(-90.0)      # from behind a robot facing +x
    assert camera["pitch"] < -45.0                     # looking down, over the walls
    assert camera["distance"] < 5.0
