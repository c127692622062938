"""Helpers for the rostest nodes: wait on wall time (a stalled /clock must fail a test, never
hang it), collect messages, read and make poses, call /gazebo's services, run the package's
nodes as a user does (on a pipe or on a pseudo-terminal). Imported by the test_*.py nodes
beside it (rostest runs them from this folder, so it is first on their sys.path). The process
helpers (free_port, stop_process, cpu_seconds, rss_kb) come from test/process_helpers.py, shared
with the unit tests and the bench, and are imported from here."""
import functools
import math
import os
import signal
import subprocess
import sys
import termios
import threading
import time
import unittest

import rosgraph
import roslib.packages
import rospy
from gazebo_msgs.msg import ModelStates
from gazebo_msgs.srv import (DeleteModel, GetLinkState, GetModelProperties, GetModelState,
                             GetPhysicsProperties, GetWorldProperties, SetLinkState,
                             SetModelState, SetPhysicsProperties, SpawnModel)
from geometry_msgs.msg import Point, Pose, Quaternion, Twist, Vector3
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock
from std_srvs.srv import Empty

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir))
import process_helpers  # noqa: E402
from process_helpers import cpu_seconds, free_port, rss_kb, stop_process  # noqa: E402

REEXPORTED = (cpu_seconds, free_port, rss_kb, stop_process)  # imported from here by the tests


def yaw_of(q) -> float:
    """Heading (rad) of a geometry_msgs/Quaternion."""
    return math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))


def pose(x: float, y: float, z: float = 0.0, yaw: float = 0.0) -> Pose:
    """A geometry_msgs/Pose at (x, y, z), turned ``yaw`` rad about z."""
    return Pose(position=Point(x, y, z),
                orientation=Quaternion(0, 0, math.sin(yaw / 2), math.cos(yaw / 2)))


WAIT = 60.0            # s: how long a test waits for the sim to answer or publish
SHORT_WAIT = 30.0      # s: the same, for the tests that give up sooner
ROBOT = "turtlebot3_burger"  # the model name of the robot sim.launch spawns (model burger)
ARENA_APOTHEM = 2.540  # m: turtlebot3_world's inner walls from the centre (doc/turtlebot3.md 4.2)


def arena_wall_distance(origin, bearing_deg: float) -> float:
    """Distance from ``origin`` (x, y) to turtlebot3_world's hexagonal inner wall (flats at
    ARENA_APOTHEM, corners on +-x) along a bearing (degrees counter-clockwise from +x)."""
    ox, oy = origin
    dx, dy = math.cos(math.radians(bearing_deg)), math.sin(math.radians(bearing_deg))
    best = math.inf
    for k in range(6):
        nx, ny = math.cos(math.radians(30 + 60 * k)), math.sin(math.radians(30 + 60 * k))
        along = nx * dx + ny * dy
        if along > 1e-9:
            best = min(best, (ARENA_APOTHEM - (nx * ox + ny * oy)) / along)
    return best


# The Burger's collision box in base_footprint: x -0.102..0.038, y +-0.070.
BURGER_BOX_CORNERS = ((-0.102, -0.070), (-0.102, 0.070), (0.038, -0.070), (0.038, 0.070))


def box_outside_arena(x: float, y: float, yaw: float) -> float:
    """How far (m) the Burger's collision box at (x, y, yaw) reaches beyond turtlebot3_world's
    inner wall (negative: that far inside)."""
    def outside_by(px, py):
        return max(math.cos(math.radians(30 + 60 * k)) * px
                   + math.sin(math.radians(30 + 60 * k)) * py - ARENA_APOTHEM for k in range(6))
    return max(outside_by(x + cx * math.cos(yaw) - cy * math.sin(yaw),
                          y + cx * math.sin(yaw) + cy * math.cos(yaw))
               for cx, cy in BURGER_BOX_CORNERS)


# wait_for(predicate, timeout wall s, step s): also gives up once the node is shut down (e.g.
# because rostest is tearing down after the sim died)
wait_for = functools.partial(process_helpers.wait_for, give_up=rospy.is_shutdown)


def publishers(topic: str):
    """The nodes publishing ``topic``, as the master lists them."""
    state = rosgraph.Master("/test").getSystemState()
    return next((nodes for name, nodes in state[0] if name == topic), [])


class Recorder:
    """Keeps every message of a topic (with its arrival) for later questions."""

    def __init__(self, topic, msg_type):
        self.msgs = []
        self.received = []  # ROS time at which each message of self.msgs arrived
        self._lock = threading.Lock()
        self.sub = rospy.Subscriber(topic, msg_type, self._on_msg, queue_size=100)

    def _on_msg(self, msg):
        with self._lock:
            header = getattr(msg, "header", None)
            if header is not None and self.msgs and header.stamp < self.msgs[-1].header.stamp:
                # sim time went back (reset_simulation): older stamps would mislead
                self.msgs, self.received = [], []
            self.msgs.append(msg)
            self.received.append(rospy.Time.now())

    def clear(self):
        """Forget what was received (e.g. after the sim's time was reset)."""
        with self._lock:
            self.msgs = []
            self.received = []

    def snapshot(self):
        """A copy of (messages, their arrival ROS times), for messages without a header."""
        with self._lock:
            return list(self.msgs), list(self.received)

    def between(self, start: rospy.Time, end: rospy.Time):
        """Messages stamped within [start, end], in arrival order."""
        with self._lock:
            return [m for m in self.msgs if start <= m.header.stamp <= end]

    def latest(self, timeout: float = 10.0):
        """The newest message, waiting up to ``timeout`` wall s for a first one (None if none)."""
        wait_for(lambda: self.msgs, timeout)
        with self._lock:
            return self.msgs[-1] if self.msgs else None

    def after(self, stamp: rospy.Time, timeout: float):
        """The first message stamped at or after ``stamp`` (None if none within ``timeout``)."""
        def find():
            with self._lock:
                return next((m for m in self.msgs if m.header.stamp >= stamp), None)
        wait_for(lambda: find() is not None, timeout)
        return find()


def one_message(topic, msg_type, timeout: float = WAIT):
    """The first message on ``topic`` (None if none within ``timeout`` wall s); unsubscribes,
    so that the sim stops making it (cameras and the IMU work only while subscribed)."""
    recorder = Recorder(topic, msg_type)
    try:
        return recorder.latest(timeout)
    finally:
        recorder.sub.unregister()


def later(recorder: Recorder, msg, seconds: float, timeout: float = WAIT):
    """The odometry message of ``recorder`` ``seconds`` of sim time after ``msg``; fails the
    test if none comes within ``timeout`` wall s."""
    result = recorder.after(msg.header.stamp + rospy.Duration(seconds), timeout)
    if result is None:
        raise AssertionError("no odometry %g s of sim time later" % seconds)
    return result


class Driver:
    """Publishes cmd_vel and calls the /gazebo services."""

    def __init__(self):
        self.pub = rospy.Publisher("cmd_vel", Twist, queue_size=1)
        self.odom = Recorder("odom", Odometry)
        wait_for(lambda: self.pub.get_num_connections() > 0, 20.0)

    def send(self, linear: float, angular: float) -> None:
        """Publish one Twist (the sim keeps it until the next)."""
        self.pub.publish(Twist(linear=Vector3(linear, 0, 0), angular=Vector3(0, 0, angular)))

    @staticmethod
    def call(service: str) -> None:
        """Call a std_srvs/Empty service such as /gazebo/reset_world."""
        rospy.wait_for_service(service, timeout=20.0)
        rospy.ServiceProxy(service, Empty)()


SERVICES = {"get_model_state": GetModelState, "set_model_state": SetModelState,
            "get_link_state": GetLinkState, "set_link_state": SetLinkState,
            "get_world_properties": GetWorldProperties,
            "get_model_properties": GetModelProperties, "spawn_sdf_model": SpawnModel,
            "spawn_urdf_model": SpawnModel, "delete_model": DeleteModel,
            "get_physics_properties": GetPhysicsProperties,
            "set_physics_properties": SetPhysicsProperties, "reset_world": Empty,
            "reset_simulation": Empty, "pause_physics": Empty, "unpause_physics": Empty}


class Gazebo:
    """Proxies of /gazebo's services (``gz.get_model_state(...)``) and a model_states recorder."""

    def __init__(self):
        for name, srv in SERVICES.items():
            rospy.wait_for_service("/gazebo/" + name, timeout=30.0)
            setattr(self, name, rospy.ServiceProxy("/gazebo/" + name, srv))
        self.states = Recorder("/gazebo/model_states", ModelStates)
        self.clock = Recorder("/clock", Clock)

    def latest_states(self, timeout=10.0):
        return self.states.latest(timeout)

    def names(self, timeout=10.0):
        msg = self.latest_states(timeout)
        return list(msg.name) if msg else None

    def wait_names(self, predicate, timeout=20.0):
        """Wait (wall s) until the latest model_states names satisfy ``predicate``."""
        return wait_for(lambda: self.names() is not None and predicate(self.names()), timeout)

    def position(self, name):
        resp = self.get_model_state(model_name=name)
        assert resp.success, resp.status_message
        p = resp.pose.position
        return p.x, p.y, p.z

    def factor(self, wall_seconds=3.0):
        """Sim seconds per wall second over ``wall_seconds`` of /clock."""
        start = self.clock.latest(10.0).clock.to_sec()
        t0 = time.monotonic()
        time.sleep(wall_seconds)
        end = self.clock.latest(10.0).clock.to_sec()
        return (end - start) / (time.monotonic() - t0)


class SimTestCase(unittest.TestCase):
    """Base of the test nodes that use /gazebo's services: setUpClass starts the node (named
    ``node_name``, by default the test file's name) and waits for the services (``cls.gz``).
    A subclass's own setUpClass calls super().setUpClass() first."""

    node_name = None   # the test node's name; None: the name of the file the class is in

    @classmethod
    def setUpClass(cls):
        name = cls.node_name or os.path.splitext(
            os.path.basename(sys.modules[cls.__module__].__file__))[0]
        rospy.init_node(name)
        cls.gz = Gazebo()


def spawn_model(*args: str):
    """``rosrun tutorial_turtlebot spawn_model ARGS`` (gazebo_ros's command line) run to its
    end, within WAIT wall s: (exit status, what it printed)."""
    done = subprocess.run(["rosrun", "tutorial_turtlebot", "spawn_model"] + list(args),
                          capture_output=True, text=True, timeout=WAIT)
    return done.returncode, done.stdout + done.stderr


def executable(name: str, package: str = "tutorial_turtlebot") -> str:
    """Path of a node executable as roslaunch (and rosrun) find it: the devel or install space
    relay first."""
    found = roslib.packages.find_node(package, name)
    if not found:
        raise RuntimeError("no executable %r in package %s" % (name, package))
    return found[0]


class NodeProcess:
    """A package node started as ``rosrun PACKAGE NAME ARGS`` would start it, with stdin from
    /dev/null and stdout and stderr collected; stopped with a signal as Ctrl-C stops it."""

    def __init__(self, name: str, *args: str, env=None):
        env = dict(os.environ if env is None else env)
        env.pop("PYTHONUNBUFFERED", None)   # as on a user's machine: output is the node's to flush
        self.proc = subprocess.Popen([executable(name)] + list(args),
                                     stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                                     stderr=subprocess.PIPE, env=env)
        self._out = {"stdout": [], "stderr": []}
        self._threads = [threading.Thread(target=self._drain, args=(stream, key), daemon=True)
                         for stream, key in ((self.proc.stdout, "stdout"),
                                             (self.proc.stderr, "stderr"))]
        for t in self._threads:
            t.start()

    def _drain(self, stream, key):
        for line in iter(stream.readline, b""):
            self._out[key].append(line.decode("utf-8", "replace"))

    @property
    def stdout(self) -> str:
        return "".join(self._out["stdout"])

    @property
    def stderr(self) -> str:
        return "".join(self._out["stderr"])

    def interrupt(self, timeout: float = 20.0):
        """SIGINT (what Ctrl-C sends), then wait up to ``timeout`` wall s; the exit status, or
        None if it is still running."""
        if self.proc.poll() is None:
            self.proc.send_signal(signal.SIGINT)
        return self.wait(timeout)

    def wait(self, timeout: float):
        """The exit status within ``timeout`` wall s, or None if still running."""
        try:
            status = self.proc.wait(timeout)
        except subprocess.TimeoutExpired:
            return None
        for t in self._threads:
            t.join(2.0)
        return status

    def kill(self) -> None:
        """Make sure it is gone (for tearDown)."""
        if self.proc.poll() is None:
            self.proc.kill()
            self.proc.wait(10.0)


class PtyProcess:
    """A package node run in a pseudo-terminal as in a user's terminal window: the pty's slave
    side is its stdin, stdout, stderr and controlling terminal (``setsid -c``), so keys written
    to the master side arrive as typed keys and Ctrl-C (``\\x03``) sends SIGINT."""

    def __init__(self, name: str, *args: str):
        self.master, self.slave = os.openpty()
        attrs = termios.tcgetattr(self.slave)  # a terminal as a shell leaves it: cooked, echo
        attrs[3] |= termios.ICANON | termios.ECHO | termios.ISIG
        termios.tcsetattr(self.slave, termios.TCSANOW, attrs)
        self.modes_before = termios.tcgetattr(self.slave)
        self.proc = subprocess.Popen(["setsid", "-c", executable(name)] + list(args),
                                     stdin=self.slave, stdout=self.slave, stderr=self.slave,
                                     close_fds=True)
        self._chunks = []
        self._lock = threading.Lock()
        self._reader = threading.Thread(target=self._drain, daemon=True)
        self._reader.start()

    def _drain(self):
        while True:
            try:
                data = os.read(self.master, 4096)
            except OSError:  # EIO once no process holds the slave side (we keep it: not here)
                return
            if not data:
                return
            with self._lock:
                self._chunks.append(data)

    @property
    def output(self) -> str:
        """Everything the program wrote to its terminal so far (CR LF as LF)."""
        with self._lock:
            return b"".join(self._chunks).decode("utf-8", "replace").replace("\r\n", "\n")

    def send(self, keys: str) -> None:
        """Type ``keys``."""
        os.write(self.master, keys.encode("latin-1"))

    def modes(self):
        """The terminal's current settings (termios.tcgetattr of the slave side)."""
        return termios.tcgetattr(self.slave)

    def wait(self, timeout: float):
        """The exit status within ``timeout`` wall s, or None if still running."""
        try:
            return self.proc.wait(timeout)
        except subprocess.TimeoutExpired:
            return None

    def quit(self) -> None:
        """Ctrl-C, a moment to exit, then close (for tearDown)."""
        self.send("\x03")
        self.wait(10.0)
        self.close()

    def close(self) -> None:
        """Make sure the program is gone, then close the terminal."""
        if self.proc.poll() is None:
            self.proc.kill()
            self.proc.wait(10.0)
        for fd in (self.slave, self.master):
            try:
                os.close(fd)
            except OSError:
                pass
