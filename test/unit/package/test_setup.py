"""tools/setup.sh as a user meets it: tab completion finds the package, a second run builds
nothing, and a broken venv is made anew with one line saying why.

The venv tests set up a venv of their own (TUTORIAL_TURTLEBOT_WS=<tmp>, `--deps-only`), break it
as an interrupted `make clean` or a stray system Python would, and run the set-up again: about
two minutes, from pip's cache. They run once, under catkin_ws/venv's Python.
"""
import importlib.util
import os
import shutil
import subprocess
import sys

import pytest
import unit_paths

ROOT = unit_paths.ROOT
WS = os.path.join(ROOT, "catkin_ws")
VENV = os.path.join(WS, "venv")
SETUP = os.path.join(ROOT, "tools", "setup.sh")
COMPLETION = "/usr/share/bash-completion/completions/rosbash"

once = pytest.mark.skipif(
    os.path.realpath(sys.prefix) != os.path.realpath(VENV),
    reason="runs once, under catkin_ws/venv's Python (not again under Python 3.8)")


def run(args, env=None, timeout=900):
    full = dict(os.environ)
    full.update(env or {})
    return subprocess.run(args, cwd=ROOT, env=full, stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT, universal_newlines=True, timeout=timeout)


def complete(line_words):
    """What rosbash's own completion offers after ``line_words`` (command, package, ""), in a
    shell that sourced the workspace's devel/setup.bash as the README says."""
    command = line_words[0]
    function = {"rosrun": "_roscomplete_exe", "roslaunch": "_roscomplete_launch"}[command]
    script = ('source "%s/devel/setup.bash" && source "%s" && COMP_WORDS=(%s) && '
              'COMP_CWORD=%d && %s && printf "%%s\\n" "${COMPREPLY[@]}"'
              % (WS, COMPLETION, " ".join('"%s"' % w for w in line_words),
                 len(line_words) - 1, function))
    out = run(["bash", "-c", script], timeout=120)
    assert out.returncode == 0, out.stdout
    return set(out.stdout.split())


@pytest.mark.skipif(not os.path.isfile(COMPLETION), reason="rosbash's completion not installed")
def test_rosrun_completes_the_packages_scripts():
    offered = complete(["rosrun", "tutorial_turtlebot", ""])
    assert {"sim", "move_turtlebot", "laser_data", "teleop_key", "stop_at_obstacle",
            "wander", "spawn_model"} <= offered, sorted(offered)


@pytest.mark.skipif(not os.path.isfile(COMPLETION), reason="rosbash's completion not installed")
def test_roslaunch_completes_the_packages_launch_files():
    offered = complete(["roslaunch", "tutorial_turtlebot", ""])
    assert {"sim.launch", "sim_teleop.launch", "turtlebot3_world.launch",
            "multi_turtlebot3.launch"} <= offered, sorted(offered)


def test_the_workspace_path_has_no_hidden_folder():
    """rosbash's _roscomplete_find drops every path matching .*/[.][^./].*: a workspace in a
    hidden folder completes nothing (the clone's own path is the user's to choose)."""
    relative = os.path.relpath(WS, ROOT)
    assert not any(part.startswith(".") for part in relative.split(os.sep)), relative
    with open(SETUP) as handle:
        assert 'WS="${TUTORIAL_TURTLEBOT_WS:-$ROOT/catkin_ws}"' in handle.read()


@once
def test_a_second_run_builds_nothing():
    first = run(["bash", SETUP])
    assert first.returncode == 0, first.stdout
    second = run(["bash", SETUP])
    assert second.returncode == 0, second.stdout
    assert "catkin workspace: built, nothing changed" in second.stdout, second.stdout
    assert "building catkin workspace" not in second.stdout


def workspace_digest(ws):
    """tools/setup.sh's workspace_inputs for the workspace ``ws`` (the function alone, run)."""
    script = ('eval "$(sed -n \'/^workspace_inputs() {/,/^}/p\' "$SETUP")"; '
              'workspace_inputs "-DX=1"')
    out = subprocess.run(["bash", "-c", script], capture_output=True, text=True, check=True,
                         env=dict(os.environ, SETUP=SETUP, WS=str(ws), ROOT=ROOT))
    return out.stdout.strip()


def test_the_set_up_byte_compiles_the_package_and_the_generated_messages(tmp_path):
    """compile_python: a Python that writes no bytecode itself (PYTHONDONTWRITEBYTECODE) would
    compile every module at every start of the sim; the set-up leaves the .pyc beside them."""
    module = tmp_path / "src" / "tutorial_turtlebot" / "gazebo" / "node.py"
    message = tmp_path / "ws" / "devel" / "lib" / "python3" / "dist-packages" / "m" / "_M.py"
    for path in (module, message):
        path.parent.mkdir(parents=True)
        path.write_text("VALUE = 1\n")
    script = ('say() { :; }; eval "$(sed -n \'/^compile_python() {/,/^}/p\' "$SETUP")"; '
              'compile_python')
    subprocess.run(["bash", "-c", script], check=True, env=dict(
        os.environ, SETUP=SETUP, ROOT=str(tmp_path), WS=str(tmp_path / "ws"), VENV=sys.prefix))
    for path in (module, message):
        assert os.path.isfile(importlib.util.cache_from_source(str(path))), path
    with open(SETUP) as handle:
        assert handle.read().count("build_workspace; compile_python") == 2   # make and --test


def test_the_build_stamp_ignores_the_cmakelists_catkin_make_writes(tmp_path):
    """A fresh workspace's first build makes the source folder's CMakeLists.txt: the digest
    taken before it must equal the next run's, or the next run builds once more. A new package
    in src/ still changes it."""
    (tmp_path / "src").mkdir()
    (tmp_path / "src" / "tutorial_turtlebot").symlink_to(ROOT)
    before = workspace_digest(tmp_path)
    (tmp_path / "src" / "CMakeLists.txt").symlink_to("/usr/share/catkin/cmake/toplevel.cmake")
    assert workspace_digest(tmp_path) == before
    (tmp_path / "src" / "other_package").mkdir()
    assert workspace_digest(tmp_path) != before


@once
def test_a_changed_build_file_builds_again(tmp_path):
    """The stamp covers what catkin_make reads: a new rostest file (globbed by CMakeLists.txt)."""
    assert run(["bash", SETUP]).returncode == 0
    extra = os.path.join(ROOT, "test", "rostest", "zz_stamp_probe.test")
    with open(extra, "w") as handle:
        handle.write("<launch/>\n")
    try:
        out = run(["bash", SETUP])
    finally:
        os.remove(extra)
    assert out.returncode == 0, out.stdout
    assert "building catkin workspace" in out.stdout
    assert run(["bash", SETUP]).returncode == 0   # and back, for the tests after this one


def break_no_pyvenv_cfg(venv):
    os.remove(os.path.join(venv, "pyvenv.cfg"))


def break_foreign_python(venv):
    """bin/python3 replaced by something that runs the system's Python (prefix /usr)."""
    python = os.path.join(venv, "bin", "python3")
    os.remove(python)
    with open(python, "w") as handle:
        handle.write('#!/bin/sh\nexec /usr/bin/python3 "$@"\n')
    os.chmod(python, 0o755)


def break_packages(venv):
    site = subprocess.run([os.path.join(venv, "bin", "python3"), "-c",
                           "import pybullet, os; print(os.path.dirname(pybullet.__file__))"],
                          stdout=subprocess.PIPE, universal_newlines=True, check=True).stdout
    for name in os.listdir(site.strip()):
        if name.startswith("pybullet"):
            path = os.path.join(site.strip(), name)
            (shutil.rmtree if os.path.isdir(path) else os.remove)(path)


@once
def test_a_broken_venv_is_made_anew_with_one_line(tmp_path):
    env = {"TUTORIAL_TURTLEBOT_WS": str(tmp_path / "ws")}
    venv = str(tmp_path / "ws" / "venv")
    first = run(["bash", SETUP, "--deps-only"], env)
    assert first.returncode == 0, first.stdout
    check = [os.path.join(venv, "bin", "python3"), "-c", "import pybullet, rospy, xacro"]
    for breaking, why in ((break_no_pyvenv_cfg, "it has no pyvenv.cfg"),
                          (break_foreign_python, "its bin/python3 is not the venv's"),
                          (break_packages, "it is stamped ready but cannot import its packages")):
        breaking(venv)
        out = run(["bash", SETUP, "--deps-only"], env)
        assert out.returncode == 0, "%s: %s" % (breaking.__name__, out.stdout)
        lines = [line for line in out.stdout.splitlines() if "is broken" in line]
        assert len(lines) == 1 and lines[0].startswith(
            "[setup] python venv %s is broken (%s" % (venv, why)), (breaking.__name__, out.stdout)
        assert lines[0].endswith("): making it anew")
        assert subprocess.run(check).returncode == 0, breaking.__name__
        prefix = subprocess.run(check[:2] + ["import sys; print(sys.prefix)"],
                                stdout=subprocess.PIPE, universal_newlines=True).stdout.strip()
        assert os.path.realpath(prefix) == os.path.realpath(venv), breaking.__name__
