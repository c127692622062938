"""pytest fixtures shared by the unit tests (plain helpers: unit_helpers.py, unit_paths.py and
texture_fixtures.py beside this file). The test tree mirrors src/tutorial_turtlebot/ (sim/files/,
sim/engine/, ..., gazebo/, lab/) and package/ tests the package as a whole (docs, set-up, launch
files); every test file imports the helpers by name, as this folder is put first on sys.path
here. The package is imported inside the fixtures: a module of it that fails to import fails the
tests that use it, not the collection of every test here."""
import os
import sys

import pytest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))


@pytest.fixture
def empty():
    """A Burger at the origin of the empty world, and the world API over it: (sim, wc)."""
    from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
    from tutorial_turtlebot.sim.world.world_control import WorldControl

    sim = Simulation(SimConfig(model="burger", world="empty"))
    yield sim, WorldControl(sim)
    sim.close()


@pytest.fixture
def client():
    """A pybullet client of its own (DIRECT: no window), disconnected afterwards: an
    engine.client.Client (``int(client)`` is its id, for pybullet's own functions)."""
    from tutorial_turtlebot.sim.engine.client import Client

    connected = Client.connect()
    yield connected
    connected.disconnect()


@pytest.fixture(autouse=True)
def mesh_cache_home(tmp_path_factory, monkeypatch):
    """Every test has an empty disk mesh cache of its own (mesh_cache), under a ROS_HOME of its
    own: no test reads what another wrote, none writes into the user's cache."""
    from tutorial_turtlebot.sim.files.meshes import mesh_cache

    home = tmp_path_factory.mktemp("ros_home")
    monkeypatch.setenv("ROS_HOME", str(home))
    mesh_cache.forget_state()
    yield home
    mesh_cache.forget_state()
