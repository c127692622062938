"""``robot_description MODEL [CAMERA]``: what sim.launch loads as /robot_description."""
import os
import subprocess
import sys
from pathlib import Path

import pytest

from tutorial_turtlebot.gazebo import robot_description
import unit_paths

ROOT = Path(unit_paths.ROOT)
URDF = ROOT / "urdf"


def urdf_text(name):
    return (URDF / name).read_text(encoding="utf-8")


def run_main(capsys, *args):
    """(exit status, stdout, stderr) of main(args); status 0 when it returns normally."""
    try:
        robot_description.main(list(args))
        status = 0
    except SystemExit as done:
        status = done.code
    out, err = capsys.readouterr()
    return status, out, err


@pytest.mark.parametrize("model", ["burger", "waffle", "waffle_pi"])
def test_prints_the_model_urdf(capsys, model):
    """A model name alone prints urdf/turtlebot3_<model>.urdf as it is, nothing on stderr."""
    status, out, err = run_main(capsys, model)
    assert status == 0
    assert out == urdf_text("turtlebot3_%s.urdf" % model)
    assert err == ""


@pytest.mark.parametrize("camera", ["false", "False", "FALSE"])
def test_camera_false_is_the_plain_model(capsys, camera):
    """camera false (any case) changes nothing."""
    assert run_main(capsys, "burger", camera)[1] == urdf_text("turtlebot3_burger.urdf")


@pytest.mark.parametrize("camera", ["true", "True"])
def test_burger_with_camera_is_the_autorace_burger(capsys, camera):
    """burger + camera true gives the AutoRace burger (with its camera frames)."""
    status, out, _ = run_main(capsys, "burger", camera)
    assert status == 0
    assert out == urdf_text("turtlebot3_burger_for_autorace.urdf")
    assert out != urdf_text("turtlebot3_burger.urdf")


@pytest.mark.parametrize("model", ["waffle", "waffle_pi"])
def test_waffles_carry_their_camera_anyway(capsys, model):
    """camera true on a model that has a camera: its own URDF."""
    assert run_main(capsys, model, "true")[1] == urdf_text("turtlebot3_%s.urdf" % model)


def one_error_line(err):
    lines = err.splitlines()
    assert len(lines) == 1, err
    assert "Traceback" not in err
    return lines[0]


def test_bad_model_exits_2_naming_the_valid_ones(capsys):
    """An unknown model: status 2, one stderr line listing burger, waffle, waffle_pi."""
    status, out, err = run_main(capsys, "nonsense")
    assert status == 2 and out == ""
    line = one_error_line(err)
    assert "nonsense" in line
    assert all(name in line for name in ("burger", "waffle", "waffle_pi"))


def test_bad_camera_exits_2(capsys):
    """A camera flag that is not true/false: status 2, one stderr line saying so."""
    status, out, err = run_main(capsys, "burger", "maybe")
    assert status == 2 and out == ""
    line = one_error_line(err)
    assert "maybe" in line and "true" in line and "false" in line


@pytest.mark.parametrize("args", [(), ("burger", "true", "extra")])
def test_wrong_argument_count_prints_usage(capsys, args):
    """No argument or too many: the usage line, status 2."""
    status, out, err = run_main(capsys, *args)
    assert status == 2 and out == ""
    assert one_error_line(err).startswith("usage: robot_description MODEL")


def test_script_answers_bad_model_without_traceback():
    """The installed script, run for real: status 2, one line, no traceback."""
    env = dict(os.environ, PYTHONPATH=str(ROOT / "src"))
    done = subprocess.run([sys.executable, str(ROOT / "scripts" / "robot_description"),
                           "nonsense"], capture_output=True, text=True, env=env, timeout=60,
                          check=False)
    assert done.returncode == 2
    assert done.stdout == ""
    assert "Traceback" not in done.stderr
    assert len(done.stderr.splitlines()) == 1
    assert "burger" in done.stderr


def test_script_prints_the_urdf():
    """The script with a good model prints the URDF and exits 0."""
    env = dict(os.environ, PYTHONPATH=str(ROOT / "src"))
    done = subprocess.run([sys.executable, str(ROOT / "scripts" / "robot_description"),
                           "waffle"], capture_output=True, text=True, env=env, timeout=60,
                          check=False)
    assert done.returncode == 0, done.stderr
    assert done.stdout == urdf_text("turtlebot3_waffle.urdf")


def test_a_file_that_is_not_xml_is_named_in_one_line(capsys, monkeypatch, tmp_path):
    """A model's URDF that is not XML: status 2, one line naming the file and its line."""
    broken = tmp_path / "turtlebot3_burger.urdf"
    broken.write_text('<robot name="b">\n<link name="x">\n</robot>\n', encoding="utf-8")
    monkeypatch.setattr(robot_description, "urdf_path", lambda model, camera=False: str(broken))
    status, out, err = run_main(capsys, "burger")
    assert status == 2 and out == ""
    line = one_error_line(err)
    assert str(broken) in line and ":3" in line


def test_the_script_imports_no_numpy():
    """sim.launch runs it before roslaunch starts the master: every start-up waits for it, and
    numpy alone took 0.1 s of it."""
    env = dict(os.environ, PYTHONPATH=str(ROOT / "src"))
    done = subprocess.run(
        [sys.executable, "-c", "import sys; import tutorial_turtlebot.gazebo.robot_description;"
         " print('numpy' in sys.modules)"], capture_output=True, text=True, env=env, timeout=60,
        check=False)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "False"
