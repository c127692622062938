"""spawn_model's command line (gazebo_ros's options), the roll/pitch/yaw quaternion and the
checks done before any contact with ROS: no master needed."""
import io
import math
import os
import subprocess
import sys

import numpy as np
import pytest
import unit_paths

sys.path.insert(0, os.path.join(unit_paths.ROOT, "src"))

from tutorial_turtlebot.errors import UserError  # noqa: E402
from tutorial_turtlebot.gazebo import spawn_model_cli as cli  # noqa: E402
from tutorial_turtlebot.gazebo.spawn_model_cli import (  # noqa: E402
    UsageError, check_xml, param_xml, parse_args, pre_ros, quaternion_from_rpy, service_name)

BOX = ('<sdf version="1.6"><model name="box"><link name="link"><collision name="c"><geometry>'
       '<box><size>0.1 0.1 0.1</size></box></geometry></collision></link></model></sdf>')
SCRIPT = os.path.join(unit_paths.ROOT, "scripts", "spawn_model")


# --- the options ---------------------------------------------------------------------------

def test_defaults():
    args = parse_args(["-sdf", "-file", "box.sdf", "-model", "box"], "/tb3_0/")
    assert args.sdf and not args.urdf
    assert (args.file, args.param, args.stdin, args.database) == ("box.sdf", None, False, None)
    assert args.model == "box"
    assert (args.x, args.y, args.z, args.R, args.P, args.Y) == (0.0,) * 6
    assert args.reference_frame == ""
    assert args.gazebo_namespace == "/gazebo"
    assert args.robot_namespace == "/tb3_0/"  # the node's namespace
    assert not args.unpause and args.wait is None and args.joints == []
    assert not args.package_to_model and not args.bond


def test_every_option():
    args = parse_args(["-urdf", "-param", "robot_description", "-model", "tb3_1",
                       "-x", "-1.5", "-y", "2", "-z", "0.25", "-R", "0.1", "-P", "-0.2",
                       "-Y", "3.14", "-reference_frame", "crate::link",
                       "-gazebo_namespace", "/sim", "-robot_namespace", "tb3_1", "-unpause",
                       "-wait", "ground_plane", "-J", "wheel_left_joint", "0.5",
                       "-J", "wheel_right_joint", "-1", "-package_to_model", "-b"])
    assert args.urdf and not args.sdf and args.param == "robot_description"
    assert (args.x, args.y, args.z, args.R, args.P, args.Y) == (-1.5, 2.0, 0.25, 0.1, -0.2, 3.14)
    assert args.reference_frame == "crate::link"
    assert args.gazebo_namespace == "/sim" and args.robot_namespace == "tb3_1"
    assert args.unpause and args.wait == "ground_plane"
    assert args.joints == [("wheel_left_joint", 0.5), ("wheel_right_joint", -1.0)]
    assert args.package_to_model and args.bond


def test_stdin_and_equals_form():
    args = parse_args(["-sdf", "-stdin", "-model", "m", "-x=-1e-3"])
    assert args.stdin and args.file is None and args.x == -0.001


@pytest.mark.parametrize("argv, words", [
    ([], "required"),
    (["-file", "f", "-model", "m"], "one of the arguments -urdf -sdf is required"),
    (["-sdf", "-model", "m"], "one of the arguments -file -param -database -stdin is required"),
    (["-sdf", "-file", "f"], "the following arguments are required: -model"),
    (["-sdf", "-urdf", "-file", "f", "-model", "m"], "not allowed with"),
    (["-sdf", "-file", "f", "-stdin", "-model", "m"], "not allowed with"),
    (["-sdf", "-file", "f", "-model", ""], "must not be empty"),
    (["-sdf", "-file", "f", "-model", "m", "-x", "one"], "argument -x: must be a number"),
    (["-sdf", "-file", "f", "-model", "m", "-Y", "nan"], "argument -Y: must be a finite"),
    (["-sdf", "-file", "f", "-model", "m", "-z", "inf"], "argument -z: must be a finite"),
    (["-sdf", "-file", "f", "-model", "m", "-x"], "argument -x: expected one argument"),
    (["-sdf", "-file", "f", "-model", "m", "-J", "j"], "argument -J: expected 2 arguments"),
    (["-sdf", "-file", "f", "-model", "m", "-J", "j", "up"], "joint 'j' must be a number"),
    (["-sdf", "-file", "f", "-model", "m", "extra"], "unrecognized arguments: extra"),
])
def test_bad_command_lines(argv, words):
    with pytest.raises(UsageError) as err:
        parse_args(argv)
    assert words in str(err.value)
    assert "\n" not in str(err.value)


def test_database_is_refused_but_not_as_usage():
    with pytest.raises(UserError) as err:
        parse_args(["-sdf", "-database", "coke_can", "-model", "can"])
    assert not isinstance(err.value, UsageError)
    assert "not supported here: there is no Gazebo model database; use -file" in str(err.value)


def test_service_names():
    assert service_name("/gazebo", "spawn_urdf_model") == "/gazebo/spawn_urdf_model"
    assert service_name("/gazebo/", "delete_model") == "/gazebo/delete_model"
    assert service_name("gazebo", "model_states") == "gazebo/model_states"


# --- roll, pitch, yaw ----------------------------------------------------------------------

def _rot(axis, angle):
    c, s = math.cos(angle), math.sin(angle)
    i, j = [(1, 2), (2, 0), (0, 1)][axis]
    m = np.eye(3)
    m[i, i], m[i, j], m[j, i], m[j, j] = c, -s, s, c
    return m


def _matrix(q):
    x, y, z, w = q
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


@pytest.mark.parametrize("rpy", [(0, 0, 0), (0, 0, math.pi / 2), (0.3, 0, 0), (0, -0.7, 0),
                                 (0.1, -0.2, 3.0), (-2.5, 1.2, -0.4), (math.pi, 0.5, 1.0)])
def test_quaternion_is_fixed_axes_roll_then_pitch_then_yaw(rpy):
    q = quaternion_from_rpy(*rpy)
    assert math.isclose(sum(c * c for c in q), 1.0, rel_tol=1e-12)
    expected = _rot(2, rpy[2]) @ _rot(1, rpy[1]) @ _rot(0, rpy[0])  # Rz Ry Rx, as URDF's rpy
    np.testing.assert_allclose(_matrix(q), expected, atol=1e-12)


def test_quaternion_known_values():
    np.testing.assert_allclose(quaternion_from_rpy(0, 0, 0), (0, 0, 0, 1))
    h = math.sqrt(0.5)
    np.testing.assert_allclose(quaternion_from_rpy(0, 0, math.pi / 2), (0, 0, h, h))
    np.testing.assert_allclose(quaternion_from_rpy(math.pi / 2, 0, 0), (h, 0, 0, h))
    np.testing.assert_allclose(quaternion_from_rpy(0, math.pi / 2, 0), (0, h, 0, h))


# --- the XML, before ROS -------------------------------------------------------------------

def test_xml_checks():
    assert check_xml(BOX, "file b") == BOX  # sent as written
    for text, words in (("", "file b is empty"), ("  \n", "file b is empty"),
                        ("<sdf><model>", "file b:1: malformed XML: no element found"),
                        ("<sdf></model>", "file b:1: malformed XML: mismatched tag")):
        with pytest.raises(UserError) as err:
            check_xml(text, "file b")
        assert words in str(err.value)


def test_param_values():
    assert param_xml(BOX, "robot_description", "/tb3_0/robot_description") == BOX
    for value, words in ((None, "parameter robot_description (/tb3_0/robot_description) does "
                                "not exist"),
                         (3, "is a int, not model XML"),
                         ("", "parameter /tb3_0/robot_description is empty")):
        with pytest.raises(UserError) as err:
            param_xml(value, "robot_description", "/tb3_0/robot_description")
        assert words in str(err.value)


def test_pre_ros_reads_file_and_stdin(tmp_path):
    path = tmp_path / "box.sdf"
    path.write_text(BOX)
    args, xml = pre_ros(["spawn_model", "-sdf", "-file", str(path), "-model", "b"], "/")
    assert xml == BOX and args.robot_namespace == "/"
    args, xml = pre_ros(["spawn_model", "-sdf", "-stdin", "-model", "b"], "/", io.StringIO(BOX))
    assert xml == BOX
    args, xml = pre_ros(["spawn_model", "-urdf", "-param", "d", "-model", "b"], "/")
    assert xml is None  # read from the master later


def test_pre_ros_file_errors(tmp_path):
    missing = tmp_path / "nope.sdf"
    for target, words in ((missing, "specified file %s does not exist" % missing),
                          (tmp_path, "specified file %s is not a file" % tmp_path)):
        with pytest.raises(UserError) as err:
            pre_ros(["spawn_model", "-sdf", "-file", str(target), "-model", "b"], "/")
        assert words in str(err.value)
    binary = tmp_path / "bin.sdf"
    binary.write_bytes(b"\xff\xfe<sdf/>")
    with pytest.raises(UserError) as err:
        pre_ros(["spawn_model", "-sdf", "-file", str(binary), "-model", "b"], "/")
    assert "cannot read" in str(err.value)


# --- main's exits before ROS (the real script, no master) -----------------------------------

def _run(args, stdin=""):
    src = os.path.join(unit_paths.ROOT, "src")
    env = dict(os.environ, ROS_MASTER_URI="http://localhost:1",  # nothing there
               PYTHONPATH=os.pathsep.join([src] + [os.environ.get("PYTHONPATH", "")]))
    return subprocess.run([sys.executable, SCRIPT] + args, input=stdin, capture_output=True,
                          text=True, timeout=60, env=env,
                          cwd=unit_paths.ROOT)


@pytest.mark.parametrize("args, status, words", [
    (["-sdf", "-model", "m"], 2, "spawn_model: error: one of the arguments -file"),
    (["-sdf", "-file", "f", "-model", "m", "-R", "x", "__name:=s", "__log:=/tmp/l"], 2,
     "argument -R: must be a number, got 'x'"),
    (["-sdf", "-file", "/nonexistent/box.sdf", "-model", "m", "__name:=s"], 1,
     "spawn_model: error: specified file /nonexistent/box.sdf does not exist"),
    (["-sdf", "-database", "coke_can", "-model", "m"], 1, "no Gazebo model database"),
    (["-urdf", "-stdin", "-model", "m"], 1, "stdin:1: malformed XML: mismatched tag"),
])
def test_script_exits_with_one_line(args, status, words):
    done = _run(args, stdin="<robot></link>")
    assert done.returncode == status, done.stderr
    assert done.stdout == ""
    lines = done.stderr.splitlines()
    assert len(lines) == 1, done.stderr
    assert words in lines[0]
    if status == 2:
        assert "usage: spawn_model -urdf|-sdf" in lines[0]


def test_help_lists_every_option():
    done = _run(["-h"])
    assert done.returncode == 0
    for option in ("-urdf", "-sdf", "-file", "-param", "-database", "-stdin", "-model",
                   "-reference_frame", "-gazebo_namespace", "-robot_namespace", "-unpause",
                   "-wait", "-x", "-Y", "-J", "-package_to_model", "-b"):
        assert option in done.stdout


def test_roslaunch_arguments_are_not_options():
    argv = cli.rospy.myargv(["spawn_model", "-sdf", "-file", "f", "-model", "m",
                             "__name:=spawner", "__log:=/tmp/x.log", "a:=b"])
    assert parse_args(argv[1:]).model == "m"
