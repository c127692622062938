"""What the launch files put on the parameter server, and how the sim reads its command line:
roslaunch --dump-params (no master) and the sim node's argument helpers."""
import os
import shutil
import subprocess
import sys

import pytest
import yaml

from tutorial_turtlebot.sim.world_sdf import world_from_command_line
from tutorial_turtlebot.gazebo.single_instance import running_simulator

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def dump_params(launch, *args):
    """The parameters roslaunch would set for ``launch/<launch> args``, with no master."""
    if shutil.which("roslaunch") is None:
        pytest.skip("'roslaunch' not found: install ROS 1 (tools/setup.sh) or source its setup")
    env = dict(os.environ, ROS_MASTER_URI="http://localhost:9")
    env["ROS_PACKAGE_PATH"] = os.pathsep.join(p for p in (ROOT, env.get("ROS_PACKAGE_PATH")) if p)
    env["PYTHONPATH"] = os.pathsep.join(p for p in (os.path.join(ROOT, "src"),
                                                    env.get("PYTHONPATH")) if p)
    env["PATH"] = os.path.dirname(sys.executable) + os.pathsep + env.get("PATH", "")
    env.pop("TURTLEBOT3_MODEL", None)
    run = subprocess.run(["roslaunch", "--dump-params", os.path.join(ROOT, "launch", launch)]
                         + list(args), capture_output=True, text=True, timeout=60, env=env)
    assert run.returncode == 0, run.stdout + run.stderr
    return yaml.safe_load(run.stdout) or {}


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


def test_no_master_means_no_running_simulator():
    assert running_simulator(master_uri="http://localhost:9") is None
