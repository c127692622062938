"""What the launch files put on the parameter server, and how the sim reads its command line:
roslaunch --dump-params (no master) and the sim node's argument helpers."""
import glob
import os
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

import pytest
import yaml

from tutorial_turtlebot.sim.files.sdf.world_catalogue import WORLD_DIR, world_from_command_line
from tutorial_turtlebot.gazebo.single_instance import running_simulator
import unit_paths

ROOT = unit_paths.ROOT


LAUNCH_FILES = sorted(f for f in os.listdir(os.path.join(ROOT, "launch")) if f.endswith(".launch"))


def roslaunch(option, launch, *args):
    """roslaunch's output for ``roslaunch OPTION launch/<launch> args``, with no master."""
    if shutil.which("roslaunch") is None:
        pytest.skip("'roslaunch' not found: install ROS 1 (tools/setup.sh) or source its setup")
    env = dict(os.environ, ROS_MASTER_URI="http://localhost:9")
    env["ROS_PACKAGE_PATH"] = os.pathsep.join(p for p in (ROOT, env.get("ROS_PACKAGE_PATH")) if p)
    env["PYTHONPATH"] = os.pathsep.join(p for p in (os.path.join(ROOT, "src"),
                                                    env.get("PYTHONPATH")) if p)
    env["PATH"] = os.path.dirname(sys.executable) + os.pathsep + env.get("PATH", "")
    env.pop("TURTLEBOT3_MODEL", None)
    run = subprocess.run(["roslaunch", option, os.path.join(ROOT, "launch", launch)]
                         + list(args), capture_output=True, text=True, timeout=60, env=env)
    assert run.returncode == 0, run.stdout + run.stderr
    return run.stdout


def dump_params(launch, *args):
    """The parameters roslaunch would set for ``launch/<launch> args``, with no master."""
    return yaml.safe_load(roslaunch("--dump-params", launch, *args)) or {}


@pytest.mark.parametrize("launch", LAUNCH_FILES)
def test_ros_args_lists_no_optional_argument_as_required(launch):
    """roslaunch --ros-args calls an argument required when its default is empty: every
    argument here has a default that says what it means (auto, /, ...)."""
    listing = roslaunch("--ros-args", launch)
    assert "Required Arguments" not in listing, listing
    assert "Optional Arguments" in listing or "No arguments" in listing
    assert "undocumented" not in listing, listing


def undocumented_args(path):
    """The <arg>s of a launch file that roslaunch --ros-args lists with no doc= (an arg with a
    fixed value= and no default= is not listed)."""
    return [arg.get("name") for arg in ET.parse(path).iter("arg")
            if arg.get("doc") is None and not (arg.get("value") is not None
                                               and arg.get("default") is None)]


@pytest.mark.parametrize("path", [os.path.join("launch", f) for f in LAUNCH_FILES] + sorted(
    os.path.relpath(p, ROOT) for pattern in ("test/**/*.launch", "test/**/*.test")
    for p in glob.glob(os.path.join(ROOT, pattern), recursive=True)))
def test_every_launch_argument_has_a_doc(path):
    missing = undocumented_args(os.path.join(ROOT, path))
    assert not missing, "%s: <arg> without doc=: %s" % (path, ", ".join(missing))


def test_an_argument_without_doc_is_found(tmp_path):
    path = tmp_path / "x.launch"
    path.write_text('<launch><arg name="a" default="1" doc="m"/><arg name="b" default="2"/>'
                    '<arg name="c" value="3"/><arg name="d"/></launch>')
    assert undocumented_args(str(path)) == ["b", "d"]


def test_auto_means_what_empty_meant():
    """x_pos:=auto (the default) sets no spawn, as x_pos:= did; a value is passed on."""
    plain = dump_params("sim.launch")
    assert "/gazebo/x_pos" not in plain and "/gazebo/camera" not in plain
    assert "/gazebo/lidar_samples" not in plain and "/gazebo/robot_name" not in plain
    assert dump_params("sim.launch", "x_pos:=") == plain
    given = dump_params("sim.launch", "x_pos:=1.5", "camera:=false", "lidar_samples:=24")
    assert given["/gazebo/x_pos"] == 1.5 and given["/gazebo/camera"] is False
    assert given["/gazebo/lidar_samples"] == 24


def test_teleop_launch_leaves_the_global_model_alone():
    """teleop_key.launch without model:= sets no /model (the sim's, e.g. waffle, stays); with
    model:= it is the teleop's own parameter."""
    plain = dump_params("teleop_key.launch")
    assert "/model" not in plain
    assert "/turtlebot3_teleop_keyboard/model" not in plain
    given = dump_params("teleop_key.launch", "model:=waffle")
    assert "/model" not in given
    assert given["/turtlebot3_teleop_keyboard/model"] == "waffle"


def test_sim_teleop_launch_sets_one_model_for_both():
    params = dump_params("sim_teleop.launch", "model:=waffle")
    assert params["/model"] == "waffle"
    assert params["/turtlebot3_teleop_keyboard/model"] == "waffle"


def test_sim_launch_sets_no_empty_spawn_params():
    """Unset spawn args leave no ``x_pos: ''`` on the server; given ones are numbers."""
    plain = dump_params("sim.launch")
    for name in ("x_pos", "y_pos", "yaw", "robot_name"):
        assert "/gazebo/" + name not in plain
    given = dump_params("sim.launch", "x_pos:=1.5", "yaw:=0.3")
    assert given["/gazebo/x_pos"] == 1.5 and given["/gazebo/yaw"] == 0.3


def test_relative_world_files_resolve_where_the_command_was_typed():
    environ = {"PWD": "/home/student/lab"}
    assert world_from_command_line("my.world", environ) == "/home/student/lab/my.world"
    assert (world_from_command_line("worlds/arena.sdf", environ)
            == "/home/student/lab/worlds/arena.sdf")
    assert world_from_command_line("/tmp/my.world", environ) == "/tmp/my.world"
    assert world_from_command_line("turtlebot3_house", environ) == "turtlebot3_house"
    assert world_from_command_line("~/my.world", environ) == "~/my.world"  # the loader expands
    assert world_from_command_line("my.world", {}) == os.path.join(os.getcwd(), "my.world")


def test_a_world_not_where_the_command_was_typed_is_looked_for_as_gzserver_does(tmp_path):
    environ = {"PWD": str(tmp_path / "elsewhere")}
    # gazebo_ros's empty_world.launch names worlds/empty.world: Gazebo's own, here the package's
    assert world_from_command_line("worlds/empty.world", environ) == os.path.join(
        WORLD_DIR, "empty.world")
    (tmp_path / "res" / "worlds").mkdir(parents=True)
    (tmp_path / "res" / "worlds" / "arena.world").write_text("<sdf/>")
    environ["GAZEBO_RESOURCE_PATH"] = "/nowhere:%s" % (tmp_path / "res")
    assert world_from_command_line("worlds/arena.world", environ) == str(
        tmp_path / "res" / "worlds" / "arena.world")
    # found nowhere: the path from where the command was typed, for the error to name
    assert world_from_command_line("worlds/nothing.world", environ) == str(
        tmp_path / "elsewhere" / "worlds" / "nothing.world")


def test_no_master_means_no_running_simulator():
    assert running_simulator(master_uri="http://localhost:9") is None


# The lab nodes per robot namespace (several robots: /tb3_1/cmd_vel, /tb3_2/scan, ...).

def launch_nodes(launch, *args):
    """The node names roslaunch would start for ``launch/<launch> args`` (--nodes, no master)."""
    if shutil.which("roslaunch") is None:
        pytest.skip("'roslaunch' not found: install ROS 1 (tools/setup.sh) or source its setup")
    env = dict(os.environ, ROS_MASTER_URI="http://localhost:9")
    env["ROS_PACKAGE_PATH"] = os.pathsep.join(p for p in (ROOT, env.get("ROS_PACKAGE_PATH")) if p)
    env["PATH"] = os.path.dirname(sys.executable) + os.pathsep + env.get("PATH", "")
    run = subprocess.run(["roslaunch", "--nodes", os.path.join(ROOT, "launch", launch)]
                         + list(args), capture_output=True, text=True, timeout=60, env=env)
    assert run.returncode == 0, run.stdout + run.stderr
    return run.stdout.split()


@pytest.mark.parametrize("launch, node", [("wander.launch", "wander"),
                                          ("stop_at_obstacle.launch", "stop_at_obstacle"),
                                          ("teleop_key.launch", "turtlebot3_teleop_keyboard")])
def test_lab_launch_ns_puts_the_node_in_that_namespace(launch, node):
    """ns:=tb3_2 starts /tb3_2/<node> (its relative topics: /tb3_2/scan, /tb3_2/cmd_vel);
    without ns it is /<node>, as before."""
    assert launch_nodes(launch, "ns:=tb3_2") == ["/tb3_2/" + node]
    assert launch_nodes(launch) == ["/" + node]


def test_wander_launch_ns_moves_every_param_with_the_node():
    plain = dump_params("wander.launch")
    spaced = dump_params("wander.launch", "ns:=tb3_2", "model:=waffle", "speed:=0.1")
    assert spaced == dict({key.replace("/wander/", "/tb3_2/wander/"): value
                           for key, value in plain.items()},
                          **{"/tb3_2/wander/model": "waffle", "/tb3_2/wander/speed": 0.1})
    assert sorted(plain) == ["/wander/" + name for name in (
        "clear_margin", "scan_timeout", "sector_deg", "speed", "stop_distance", "turn_speed")]


def test_stop_at_obstacle_and_teleop_launch_ns_move_their_params():
    plain = dump_params("stop_at_obstacle.launch")
    spaced = dump_params("stop_at_obstacle.launch", "ns:=tb3_1", "stop_distance:=0.4")
    assert spaced == dict({key.replace("/stop_at_obstacle/", "/tb3_1/stop_at_obstacle/"): value
                           for key, value in plain.items()},
                          **{"/tb3_1/stop_at_obstacle/stop_distance": 0.4})
    teleop = dump_params("teleop_key.launch", "ns:=tb3_1", "model:=waffle")
    assert teleop == {"/tb3_1/turtlebot3_teleop_keyboard/model": "waffle"}
    assert dump_params("teleop_key.launch", "ns:=tb3_1") == {}


@pytest.mark.parametrize("node", ["wander", "stop_at_obstacle", "laser_data", "teleop_key"])
@pytest.mark.parametrize("namespace", ["tb 3", "tb3-1", "tb3_1/x.y"])
def test_lab_node_in_an_illegal_namespace_says_so_in_one_line(node, namespace):
    """ROS_NAMESPACE (or a launch file's ns) with characters the master refuses: one line naming
    it and exit status 2, before any master is contacted (there is none here); without the
    check the node ran on, every topic refused by the master. teleop_key first needs a
    terminal; without one it says that instead, also in one line."""
    env = dict(os.environ, ROS_MASTER_URI="http://localhost:9", ROS_NAMESPACE=namespace)
    env["PYTHONPATH"] = os.pathsep.join(p for p in (os.path.join(ROOT, "src"),
                                                    env.get("PYTHONPATH")) if p)
    module = "tutorial_turtlebot.lab.%s_node" % node
    run = subprocess.run([sys.executable, "-c", "import %s as m; m.main()" % module],
                         stdin=subprocess.DEVNULL, capture_output=True, text=True, timeout=60,
                         env=env)
    assert run.returncode == 2, run.stdout + run.stderr
    assert len(run.stderr.splitlines()) == 1, run.stderr
    if node == "teleop_key":
        assert "no terminal" in run.stderr
    else:
        assert run.stderr.startswith("%s: namespace '/%s/' is not a legal ROS name"
                                     % (node, namespace)), run.stderr


def test_teleop_banner_names_its_topic_when_it_is_not_cmd_vel():
    """Three terminals, three robots: the banner's first line says which one each drives."""
    from tutorial_turtlebot.lab.teleop_keys import Teleop
    plain = Teleop(0.22, 2.84, "burger").banner()
    assert "driving" not in plain
    spaced = Teleop(0.26, 1.82, "waffle", topic="/tb3_1/cmd_vel").banner()
    first = spaced.strip().splitlines()[0]
    assert first == "Control Your TurtleBot3! (driving /tb3_1/cmd_vel)"
    assert spaced.replace(" (driving /tb3_1/cmd_vel)", "") == Teleop(0.26, 1.82, "waffle").banner()
