"""catkin_lint -W2 (every problem, notices included) finds nothing in the repository's catkin
packages: tutorial_turtlebot, msgs/gazebo_msgs and ros_shims/*. catkin_lint comes from PyPI
into catkin_ws/venv (tools/setup_plan.py); the package is linted under its own name, as it
sits in a workspace's src/ (a link <tmp>/tutorial_turtlebot -> this repository)."""
import glob
import os
import shutil
import subprocess
import sys

import pytest
import unit_paths

ROOT = unit_paths.ROOT
VENV_LINT = os.path.join(ROOT, "catkin_ws", "venv", "bin", "catkin_lint")


def catkin_lint():
    """The venv's catkin_lint, else one on PATH, else the one beside this Python."""
    for exe in (VENV_LINT, shutil.which("catkin_lint"),
                os.path.join(os.path.dirname(sys.executable), "catkin_lint")):
        if exe and os.access(exe, os.X_OK):
            return exe
    pytest.fail("catkin_lint is not installed: run tools/setup.sh (it pip-installs catkin-lint "
                "into catkin_ws/venv)")


def packages(base):
    nested = sorted(os.path.dirname(p)
                    for p in glob.glob(os.path.join(ROOT, "*", "*", "package.xml")))
    return [base] + [os.path.join(base, os.path.relpath(p, ROOT)) for p in nested]


def test_the_nested_packages_are_found():
    names = sorted(os.path.relpath(p, ROOT) for p in packages(ROOT)[1:])
    assert names == ["msgs/gazebo_msgs", "ros_shims/dynamic_reconfigure", "ros_shims/xacro"]


def test_catkin_lint_W2_reports_nothing(tmp_path):
    base = tmp_path / "tutorial_turtlebot"
    base.symlink_to(ROOT)
    env = dict(os.environ, ROS_PACKAGE_PATH="")   # only the packages given, none installed
    run = subprocess.run([catkin_lint(), "-W2", "--strict", "--color", "never"]
                         + packages(str(base)), stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                         universal_newlines=True, timeout=120, env=env)
    problems = [line for line in (run.stdout + run.stderr).splitlines()
                if ": error:" in line or ": warning:" in line or ": notice:" in line]
    assert not problems and run.returncode == 0, run.stdout + run.stderr
    assert "checked 4 packages and found 0 problems" in run.stderr + run.stdout
