"""move_turtlebot's command line: the parser, and the script itself on bad arguments (which must
fail before any contact with ROS, so no master is needed). Units: m/s, rad/s."""
import os
import subprocess
import sys

import pytest

from tutorial_turtlebot.errors import UserError
from tutorial_turtlebot.lab.move_args import (USAGE, command_line_settings, parse, user_args,
                                              wants_help)
import unit_paths

ROOT = unit_paths.ROOT


@pytest.mark.parametrize("args, expected", [
    (["0.2", "0.5"], (0.2, 0.5)),
    (["-0.1", "-1"], (-0.1, -1.0)),
    (["0", "0"], (0.0, 0.0)),
    (["1e-1", ".5"], (0.1, 0.5)),
    ([" 0.2", "+0.5 "], (0.2, 0.5))])
def test_parse_good(args, expected):
    assert parse(args) == pytest.approx(expected)


@pytest.mark.parametrize("args, message", [
    ([], "expected 2 arguments, LINEAR and ANGULAR, got 0"),
    (["0.2"], "got 1"),
    (["0.2", "0.5", "1"], "got 3"),
    (["abc", "0.5"], "LINEAR must be a number, got 'abc'"),
    (["0.2", "fast"], "ANGULAR must be a number, got 'fast'"),
    (["nan", "0"], "LINEAR must be a finite number, got 'nan'"),
    (["0", "inf"], "ANGULAR must be a finite number"),
    (["-inf", "0"], "LINEAR must be a finite number"),
    (["1e999", "0"], "LINEAR must be a finite number"),
    (["", "0"], "LINEAR must be a number")])
def test_parse_bad(args, message):
    with pytest.raises(UserError, match=message.replace("(", r"\(")):
        parse(args)


def test_ros_arguments_are_not_ours():
    argv = ["0.2", "cmd_vel:=/robot/cmd_vel", "__name:=mover", "_rate:=5", "-0.5",
            "__log:=/tmp/x.log", "__ns:=/a"]
    assert user_args(argv) == ["0.2", "-0.5"]
    assert parse(user_args(argv)) == (0.2, -0.5)


def test_help():
    assert wants_help(["-h"]) and wants_help(["0.2", "--help"])
    assert not wants_help(["-0.2", "0.5"])


def run_script(*args):
    env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "src"),
               ROS_MASTER_URI="http://127.0.0.1:1")  # nothing there: it must not try
    return subprocess.run([sys.executable, os.path.join(ROOT, "scripts", "move_turtlebot")]
                          + list(args), env=env, capture_output=True, text=True, timeout=30)


@pytest.mark.parametrize("args", [["abc"], [], ["0.2"], ["0.2", "0.5", "0.1"], ["abc", "1"],
                                  ["nan", "0"], ["0", "inf"], ["0.2", "x", "cmd_vel:=y"]])
def test_script_bad_arguments(args):
    done = run_script(*args)
    assert done.returncode == 2
    lines = done.stderr.splitlines()
    assert lines[0] == USAGE
    assert lines[1].startswith("move_turtlebot: error: ")
    assert len(lines) == 2
    assert "Traceback" not in done.stderr
    assert done.stdout == ""


def test_script_help():
    done = run_script("--help")
    assert done.returncode == 0
    assert done.stdout.strip() == USAGE


def test_command_line_settings_are_taken_out_of_what_rospy_sees():
    """``_name:=value`` arguments become this run's settings (YAML values, as rospy reads them)
    and are left out of the arguments given to rospy, which would store them on the parameter
    server for every later run; remappings and special names stay."""
    settings, rest = command_line_settings(
        ["move_turtlebot", "0.2", "0.5", "_duration:=3", "_rate:=2.5", "cmd_vel:=/x",
         "__name:=mover", "_note:=hello"])
    assert settings == {"duration": 3, "rate": 2.5, "note": "hello"}
    assert rest == ["move_turtlebot", "0.2", "0.5", "cmd_vel:=/x", "__name:=mover"]


def test_usage_names_the_settings():
    assert "_duration:=S" in USAGE and "_rate:=HZ" in USAGE
