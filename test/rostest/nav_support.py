"""Helpers for the SLAM and Navigation rostests (test_slam.py, test_navigation.py): the
navigation extra's workspace (catkin_ws/nav, tools/install_extra.sh nav), a roslaunch run in it,
the world's shapes in plan (the sim's own world reader), a map written from them, and the
robot's true pose from /gazebo/model_states.

The tests' own rostest process knows only the package's workspace; gmapping, amcl, map_server
and move_base are found by the roslaunch these helpers start, in a shell where the extra's
setup.bash was sourced. Without the extra every test is skipped, in one line saying how to
install it."""
import ctypes
import math
import os
import signal
import subprocess
import sys

import numpy as np
import rospkg
import rospy
from gazebo_msgs.msg import ModelStates

from sim_test_support import stop_process, wait_for, yaw_of

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "src"))
from tutorial_turtlebot.sim.files.sdf.world_catalogue import resolve_world  # noqa: E402
from tutorial_turtlebot.sim.files.sdf.world_sdf import load_world  # noqa: E402
from tutorial_turtlebot.sim.world.spawn_check import plan_distance  # noqa: E402
from tutorial_turtlebot.sim.world.world_models import robot_model_name  # noqa: E402

NAV_SETUP = os.path.join(ROOT, "catkin_ws", "nav", "devel", "setup.bash")
NOETIC_SETUP = "/opt/ros/noetic/setup.bash"
NOT_INSTALLED = ("the navigation extra is not installed: bash tools/install_extra.sh nav "
                 "(builds gmapping, amcl, map_server, move_base)")
BAND = (0.01, 0.2)   # m above the floor: what the robot can run into (spawn_check's band)


def log_dir() -> str:
    """The ROS log folder (where the tests' maps and roslaunch logs go)."""
    path = rospkg.get_log_dir()
    os.makedirs(path, exist_ok=True)
    return path


def nav_env():
    """The environment of a shell where rosrun finds this package and the extra's packages
    (the ROS master of this test kept), or None where the extra is not installed."""
    if os.path.isfile(NOETIC_SETUP):
        done = subprocess.run(["rospack", "find", "gmapping"], capture_output=True)
        return dict(os.environ) if done.returncode == 0 else None
    if not os.path.isfile(NAV_SETUP):
        return None
    done = subprocess.run(["bash", "-c", 'source "$0" >/dev/null && env -0', NAV_SETUP],
                          capture_output=True, check=True)
    env = dict(line.split("=", 1) for line in done.stdout.decode().split("\0") if "=" in line)
    for key in ("ROS_MASTER_URI", "ROS_IP", "ROS_HOSTNAME", "ROS_LOG_DIR", "ROS_HOME"):
        if key in os.environ:
            env[key] = os.environ[key]
    return env


def _die_with_parent():
    """preexec_fn: the child gets SIGTERM when this test node dies, even by SIGKILL."""
    ctypes.CDLL("libc.so.6", use_errno=True).prctl(1, signal.SIGTERM)  # PR_SET_PDEATHSIG


class Launch:
    """``roslaunch tutorial_turtlebot FILE ARGS`` in the extra's environment, its output in a
    log file (``self.log``) that a failing test prints the end of."""

    def __init__(self, env, launch_file: str, *args: str):
        self.log = os.path.join(log_dir(), "%s-%d.log" % (os.path.splitext(launch_file)[0],
                                                          os.getpid()))
        with open(self.log, "wb") as out:
            self.proc = subprocess.Popen(
                ["roslaunch", "tutorial_turtlebot", launch_file] + list(args), env=env,
                stdin=subprocess.DEVNULL, stdout=out, stderr=subprocess.STDOUT,
                start_new_session=True, preexec_fn=_die_with_parent)

    def tail(self, lines: int = 30) -> str:
        with open(self.log, "r", errors="replace") as f:
            return "".join(f.readlines()[-lines:])

    def stop(self) -> None:
        stop_process(self.proc, timeout=20.0)


def run(env, *command: str, timeout: float = 60.0):
    """A command run to its end in ``env``: (exit status, its output)."""
    done = subprocess.run(list(command), env=env, capture_output=True, text=True,
                          timeout=timeout)
    return done.returncode, done.stdout + done.stderr


class TruePose:
    """The robot's true pose (x, y, yaw in the world frame: m, rad) from /gazebo/model_states:
    the robot sim.launch spawns with ``model`` in ``world`` (its name as turtlebot3_gazebo's)."""

    def __init__(self, world: str, model: str, on_pose=None):
        self.robot = robot_model_name(world, model)
        self.pose = None
        self.on_pose = on_pose       # called with each (x, y, yaw), in the subscriber's thread
        self.sub = rospy.Subscriber("/gazebo/model_states", ModelStates, self._on, queue_size=1)

    def _on(self, msg):
        for name, p in zip(msg.name, msg.pose):
            if name == self.robot:
                self.pose = (p.position.x, p.position.y, yaw_of(p.orientation))
                if self.on_pose is not None:
                    self.on_pose(self.pose)
                return

    def wait(self, timeout: float = 60.0):
        return wait_for(lambda: self.pose, timeout)


def angle_diff(a: float, b: float) -> float:
    """a - b wrapped to [-pi, pi) (rad)."""
    return (a - b + math.pi) % (2.0 * math.pi) - math.pi


def world_shapes(world: str):
    """The collision shapes of a shipped world (or SDF path) that stand in the robot's height
    band, as the sim reads them."""
    loaded = load_world(resolve_world(world)[0])
    return [s for s in loaded.collisions
            if s.kind != "plane" and plan_distance(s, s.pose[0], s.pose[1], BAND) is not None]


def distance_field(shapes, xs: np.ndarray, ys: np.ndarray) -> np.ndarray:
    """The plan distance (m) from each point (xs[i], ys[i]) to the nearest of ``shapes``
    (negative inside one), by spawn_check.plan_distance, for points within 1 m of a shape's
    bounding circle (farther ones get 1.0)."""
    best = np.full(len(xs), 1.0)
    for shape in shapes:
        reach = _reach(shape) + 1.0
        near = np.flatnonzero(np.hypot(xs - shape.pose[0], ys - shape.pose[1]) < reach)
        for i in near:
            d = plan_distance(shape, float(xs[i]), float(ys[i]), BAND)
            if d is not None and d < best[i]:
                best[i] = d
    return best


def _reach(shape) -> float:
    """A radius (m) about the shape's frame origin that holds it in plan."""
    if shape.kind == "box":
        return math.hypot(shape.size[0], shape.size[1]) / 2
    if shape.kind in ("cylinder", "sphere"):
        return shape.size[0]
    if shape.kind == "polyline":
        return max(math.hypot(x, y) for x, y in shape.points)
    return 50.0


def write_world_map(world: str, stem: str, box, resolution: float = 0.05) -> str:
    """A map_server map (``stem``.pgm and ``stem``.yaml, returned) of ``world``'s shapes in plan,
    in the world frame: cells within half a cell of a shape occupied, the rest free. ``box`` is
    (xmin, ymin, xmax, ymax) in m."""
    xmin, ymin, xmax, ymax = box
    width = int(round((xmax - xmin) / resolution))
    height = int(round((ymax - ymin) / resolution))
    cols, rows = np.meshgrid(np.arange(width), np.arange(height))
    xs = xmin + (cols.ravel() + 0.5) * resolution
    ys = ymin + (rows.ravel() + 0.5) * resolution
    field = distance_field(world_shapes(world), xs, ys)
    occupied = (field < resolution / 2).reshape(height, width)
    image = np.where(occupied, 0, 254).astype(np.uint8)[::-1]   # the PGM's first row is the top
    with open(stem + ".pgm", "wb") as f:
        f.write(b"P5\n%d %d\n255\n" % (width, height))
        f.write(image.tobytes())
    with open(stem + ".yaml", "w") as f:
        f.write("image: %s.pgm\nresolution: %g\norigin: [%g, %g, 0.0]\nnegate: 0\n"
                "occupied_thresh: 0.65\nfree_thresh: 0.196\n"
                % (os.path.basename(stem), resolution, xmin, ymin))
    return stem + ".yaml"


def read_map(yaml_path: str):
    """A map_saver map: (occupied cells' centres as an (N, 2) array in the map frame (m), the
    number of free cells)."""
    meta = {}
    with open(yaml_path) as f:
        for line in f:
            if ":" in line:
                key, value = line.split(":", 1)
                meta[key.strip()] = value.strip()
    resolution = float(meta["resolution"])
    origin = [float(v) for v in meta["origin"].strip("[]").split(",")]
    image_path = os.path.join(os.path.dirname(yaml_path), meta["image"])
    with open(image_path, "rb") as f:
        data = f.read()
    header, at = [], 0                       # P5, width, height, maxval; "# ..." comments
    while len(header) < 4:
        while data[at:at + 1].isspace():
            at += 1
        if data[at:at + 1] == b"#":
            at = data.index(b"\n", at)
            continue
        end = at
        while not data[end:end + 1].isspace():
            end += 1
        header.append(data[at:end])
        at = end
    width, height = int(header[1]), int(header[2])
    start = at + 1                           # one whitespace byte after maxval
    pixels = np.frombuffer(data[start:start + width * height], np.uint8).reshape(
        height, width)[::-1]
    rows, cols = np.nonzero(pixels == 0)     # map_saver: 0 occupied, 254 free, 205 unknown
    centres = np.column_stack((origin[0] + (cols + 0.5) * resolution,
                               origin[1] + (rows + 0.5) * resolution))
    return centres, int((pixels == 254).sum())
