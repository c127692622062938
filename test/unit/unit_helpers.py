"""Plain helpers and constants shared by the unit tests (the pytest fixtures are in conftest.py
beside this file). Tests import it by name, ``from unit_helpers import at, run``: there is no
__init__.py in test/unit, so pytest puts this folder first on sys.path for every test file it
collects here, whether it runs the folder or one file. The package is imported where it is
used: a module of it that fails to import fails only the tests that need it. The process
helpers (free_port, stop_process, cpu_seconds, wait_for) are test/process_helpers.py's, shared
with the rostests and the bench, and are imported from here too."""
import gc
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir))
import process_helpers  # noqa: E402
from process_helpers import cpu_seconds, free_port, stop_process, wait_for  # noqa: E402

REEXPORTED = (cpu_seconds, free_port, stop_process, wait_for)  # imported from here by the tests

ROBOT = "turtlebot3_burger"   # the robot's model name in a Simulation of model burger

# a heavy base on the floor with a disc on a vertical continuous joint: the disc's inertia about
# its axis is 0.02 kg m^2, so an effort of 0.02 N m turns it up at 1 rad/s^2 (the rostests
# spawn the same file)
with open(os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "fixtures",
                       "wheel.urdf")) as _f:
    WHEEL = _f.read().rstrip("\n")


# --- the simulation ----------------------------------------------------------------------------

def at(x, y, z=0.0, yaw=0.0):
    """A world pose ((x, y, z), quaternion x y z w) turned ``yaw`` rad about z."""
    return (x, y, z), (0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2))


def run(sim, seconds, per_robot=True):
    """Step ``seconds`` of sim time; return how often each output was due, keyed by (robot
    name or None, output name), or by the output name alone with ``per_robot=False``."""
    counts = {}
    for _ in range(round(seconds / sim.config.time_step)):
        for robot, name in sim.step():
            key = ((robot.name if robot else None), name) if per_robot else name
            counts[key] = counts.get(key, 0) + 1
    return counts


def box_sdf(size=0.15, mass=0.1, static=False, visual=True):
    """An SDF model ``x``: one link ``link``, a solid cube of side ``size`` (m) and ``mass``
    (kg), with a collision and (``visual``) a visual box."""
    inertia = mass * size * size / 6
    shape = "<geometry><box><size>%g %g %g</size></box></geometry>" % ((size,) * 3)
    return ("<sdf version='1.6'><model name='x'>%s<link name='link'><inertial><mass>%g</mass>"
            "<inertia><ixx>%g</ixx><iyy>%g</iyy><izz>%g</izz></inertia></inertial>"
            "<collision name='c'>%s</collision>%s</link></model></sdf>"
            % ("<static>1</static>" if static else "", mass, inertia, inertia, inertia, shape,
               "<visual name='v'>%s</visual>" % shape if visual else ""))


CUBE = box_sdf(0.15, 2.0, visual=False)   # a 2 kg cube 0.15 m across, no visual


def urdf_text(model):
    """The package's URDF of a TurtleBot3 ``model`` (burger, waffle, waffle_pi), as text."""
    from tutorial_turtlebot.sim.files.urdf.urdf_file import urdf_path

    with open(urdf_path(model)) as f:
        return f.read()


def urdf_body(client, text):
    """The pybullet body id of a robot's URDF ``text`` built as the sim builds a robot's body
    (engine.robot_body: the SDF model of its URDF, built by movable_bodies), its root link at
    the origin."""
    from tutorial_turtlebot.sim.engine.movable_bodies import model_body
    from tutorial_turtlebot.sim.engine.robot_body import robot_model
    from tutorial_turtlebot.sim.files.urdf.urdf_file import read_urdf_text

    return model_body(robot_model(read_urdf_text(text, "test URDF"))[0], client)


def write(folder, name, text):
    """Write ``text`` to the file ``name`` in ``folder``; return its path."""
    path = os.path.join(str(folder), name)
    with open(path, "w") as f:
        f.write(text)
    return path


# --- synthetic laser scans ---------------------------------------------------------------------

INF = math.inf
NAN = math.nan


def f32(value):
    """``value`` as a LaserScan float32 field arrives in Python."""
    return float(np.float32(value))


# name -> (angle_min, angle_increment, ray count)
CONVENTIONS = {
    "gazebo": (0.0, f32(6.28319 / 359), 360),   # Gazebo's TurtleBot3 scan: ray 359 repeats ray 0
    "lds01": (0.0, f32(math.radians(1.0)), 360),  # the real LDS-01: exact degrees
    "hokuyo": (f32(-math.pi), f32(2 * math.pi / 720), 720),  # ray 360 straight ahead
}


def make_scan(convention, world, range_min=0.12, range_max=3.5):
    """A scan whose ray at bearing b (rad, [-pi, pi)) reads ``world(b)``."""
    from tutorial_turtlebot.lab.scan_reading import Scan

    angle_min, inc, count = CONVENTIONS[convention]
    ranges = []
    for i in range(count):
        b = (angle_min + i * inc + math.pi) % (2 * math.pi) - math.pi
        ranges.append(f32(world(b)))
    return Scan(ranges, angle_min, inc, f32(range_min), f32(range_max))


def within(seconds, call, *args):
    """``call(*args)``'s result (or exception, raised here), in a daemon thread; AssertionError
    if it is not done within ``seconds`` (a read that would wait for ever fails the test, not
    the run)."""
    import threading

    out = {}

    def run():
        try:
            out["result"] = call(*args)
        except BaseException as err:   # noqa: BLE001 - handed to the caller
            out["error"] = err
    thread = threading.Thread(target=run, daemon=True)
    thread.start()
    thread.join(seconds)
    assert not thread.is_alive(), "%s did not end within %s s" % (call.__name__, seconds)
    if "error" in out:
        raise out["error"]
    return out["result"]


def world_file(folder, body, name="test.world", version="1.6"):
    """Write the SDF world file ``name`` in ``folder`` (a pathlib.Path) holding ``body`` inside
    <world name="w">, ``body`` starting on line 4; its path."""
    path = folder / name
    path.write_text('<?xml version="1.0"?>\n<sdf version="%s">\n<world name="w">\n%s\n'
                    '</world>\n</sdf>\n' % (version, body))
    return str(path)


def world_fault(path):
    """The one-line WorldError that loading the world file ``path`` raises (it names the
    file)."""
    import pytest
    from tutorial_turtlebot.errors import WorldError
    from tutorial_turtlebot.sim.files.sdf.world_sdf import load_world
    with pytest.raises(WorldError) as err:
        load_world(path)
    message = str(err.value)
    assert "\n" not in message and path in message
    return message


def rss_kb() -> int:
    """This process's resident memory (KB), after a garbage collection."""
    gc.collect()
    return process_helpers.rss_kb()


class RecordingPublisher:
    """A stand-in for a rospy Publisher (or Subscriber) in tests without a master: it records
    what is published (``sent``: messages, packed ones unpacked) and has ``connections``
    subscribers, as the test sets them."""

    def __init__(self, topic, msg_type=None, *args, **kwargs):
        self.topic = self.name = topic
        self.msg_type, self.connections, self.sent = msg_type, 0, []
        self.unregistered = False

    def get_num_connections(self):
        return self.connections

    def publish(self, msg):
        self.sent.append(msg)

    def publish_packed(self, packed):
        self.sent.append(packed.message())

    def unregister(self):
        self.unregistered = True
