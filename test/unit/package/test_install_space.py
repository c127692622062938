"""The package as `catkin_make install` installs it, used with only install/setup.bash sourced.

A copy of the workspace (links to this repository, its msgs/ and ros_shims/ packages) is
configured as tools/setup.sh and doc/development.md configure one, except that the venv is a link in
the test's folder (<tmp>/venv -> catkin_ws/venv), and installed into <tmp>/ws/install. Then,
each time in a fresh `env -i bash` that sources nothing but the install space's setup.bash:

1. with the recorded venv: roscore, `roslaunch tutorial_turtlebot sim.launch`,
   `dynparam get/set /gazebo` and `graph --output x.dot`;
2. the link removed and the install space copied elsewhere: `source setup.bash` still works,
   and `rosrun tutorial_turtlebot sim` says in one line what is missing (no traceback);
3. that copy with a venv/ inside it: the sim, dynparam and graph work again.

The real catkin_ws/venv is never moved: only the test's links to it are. About a minute.
"""
import os
import shutil
import subprocess
import sys
import tempfile
import textwrap

import pytest

from unit_helpers import free_port
import unit_paths

ROOT = unit_paths.ROOT
VENV = os.path.join(ROOT, "catkin_ws", "venv")
CLEAN_PATH = "/usr/local/bin:/usr/bin:/bin"

pytestmark = pytest.mark.skipif(
    os.path.realpath(sys.prefix) != os.path.realpath(VENV),
    reason="runs once, under catkin_ws/venv's Python (not again under Python 3.8)")

# Run in `env -i bash SCRIPT INSTALL PORT HOME`: the sim, dynparam and graph on a master of its own.
SESSION = textwrap.dedent(r"""
    source "$1/setup.bash" || exit 90
    export ROS_MASTER_URI=http://localhost:$2 ROS_HOME=$3 ROS_LOG_DIR=$3/log
    echo "python3: $(command -v python3)"
    roscore -p "$2" >"$3/roscore.log" 2>&1 &
    core=$!
    sim=
    finish() {
      [ -n "$sim" ] && kill -INT "$sim" 2>/dev/null && wait "$sim"
      kill -INT "$core" 2>/dev/null; wait "$core"
    }
    trap finish EXIT
    for _ in $(seq 100); do rosnode list >/dev/null 2>&1 && break; sleep 0.2; done
    roslaunch -p "$2" tutorial_turtlebot sim.launch >"$3/sim.log" 2>&1 &
    sim=$!
    for _ in $(seq 300); do
      rosservice list 2>/dev/null | grep -qx /gazebo/set_parameters && break
      kill -0 "$sim" 2>/dev/null || { echo "sim.launch ended"; tail -n 20 "$3/sim.log"; exit 91; }
      sleep 0.2
    done
    echo "get: $(rosrun dynamic_reconfigure dynparam get /gazebo)" || exit 92
    rosrun dynamic_reconfigure dynparam set /gazebo max_update_rate 250 || exit 93
    echo "after set: $(rosrun dynamic_reconfigure dynparam get /gazebo)"
    rosrun tutorial_turtlebot graph --output "$3/graph.dot" || exit 94
    grep -c n___gazebo "$3/graph.dot"
""")


def clean_bash(script, *args, timeout=180):
    """bash SCRIPT ARGS with an empty environment but HOME and a PATH without any venv."""
    env = {"HOME": os.environ.get("HOME", "/tmp"), "PATH": CLEAN_PATH, "LANG": "C.UTF-8"}
    return subprocess.run(["bash", "-c", script, "bash"] + [str(a) for a in args], env=env,
                          stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                          universal_newlines=True, timeout=timeout)


@pytest.fixture(scope="module")
def tmp():
    folder = tempfile.mkdtemp(prefix="tutorial_turtlebot_install_")
    try:
        yield folder
    finally:
        shutil.rmtree(folder, ignore_errors=True)


@pytest.fixture(scope="module")
def install(tmp):
    """<tmp>/ws/install, built from links to this repository, venv recorded as <tmp>/venv."""
    venv_link = os.path.join(tmp, "venv")
    os.symlink(VENV, venv_link)
    src = os.path.join(tmp, "ws", "src")
    pkg = os.path.join(src, "tutorial_turtlebot")
    os.makedirs(pkg)
    for entry in os.listdir(ROOT):   # as tools/setup.sh: every entry but the hidden ones
        if not entry.startswith("."):
            os.symlink(os.path.join(ROOT, entry), os.path.join(pkg, entry))
    for parent in ("msgs", "ros_shims"):
        for name in sorted(os.listdir(os.path.join(ROOT, parent))):
            os.symlink(os.path.join(ROOT, parent, name), os.path.join(src, name))
    prefix = os.path.join(tmp, "ws", "install")
    build = clean_bash(
        'catkin_make -C "$1" -DPYTHON_EXECUTABLE="$2/bin/python3" '
        '-DPython_EXECUTABLE="$2/bin/python3" '
        '-DTUTORIAL_TURTLEBOT_VENV="$2" '
        '-DCATKIN_ENABLE_TESTING=OFF -DCMAKE_INSTALL_PREFIX="$3" install',
        os.path.join(tmp, "ws"), venv_link, prefix, timeout=600)
    assert build.returncode == 0, (build.stdout + build.stderr)[-3000:]
    return prefix


def session(install, home):
    os.makedirs(home, exist_ok=True)
    run = clean_bash(SESSION, install, free_port(), home)
    out = run.stdout + run.stderr
    assert run.returncode == 0, "%s\n--- sim.log\n%s" % (out[-3000:], _read(home, "sim.log"))
    return run.stdout


def _read(folder, name):
    try:
        with open(os.path.join(folder, name)) as f:
            return f.read()[-3000:]
    except OSError:
        return ""


def test_install_space_runs_sim_dynparam_and_graph_with_the_recorded_venv(install, tmp):
    with open(os.path.join(install, "_setup_util.py")) as f:
        assert f.readline().strip() == "#!/usr/bin/env python3"   # not the venv's python
    for name in ("lib/dynamic_reconfigure/dynparam", "lib/xacro/xacro",
                 "lib/tutorial_turtlebot/sim", "lib/tutorial_turtlebot/graph"):
        assert os.access(os.path.join(install, name), os.X_OK), name
    out = session(install, os.path.join(tmp, "home1"))
    assert "python3: %s/venv/bin/python3" % tmp in out
    assert "'max_update_rate': 400.0" in out.split("after set:")[0]
    assert "'max_update_rate': 250.0" in out.split("after set:")[1]
    assert int(out.rstrip().splitlines()[-1]) >= 1   # the graph holds /gazebo


@pytest.fixture(scope="module")
def moved(install, tmp):
    """The recorded venv gone (its link removed), the install space copied to <tmp>/moved."""
    link = os.path.join(tmp, "venv")
    if os.path.islink(link):
        os.unlink(link)
    copy = os.path.join(tmp, "moved", "install")
    shutil.copytree(install, copy, symlinks=True)
    return copy


def test_without_a_venv_sim_says_in_one_line_what_is_missing(moved):
    run = clean_bash('source "$1/setup.bash" || exit 90; echo "python3: $(command -v python3)"; '
                     'rosrun tutorial_turtlebot sim', moved, timeout=60)
    assert run.returncode not in (0, 90), run.stdout + run.stderr
    (python,) = [line[len("python3: "):] for line in run.stdout.splitlines()
                 if line.startswith("python3: ")]
    assert "venv" not in python
    probe = subprocess.run([python, "-c", "import pybullet"],
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    if probe.returncode == 0:
        pytest.skip("the system python3 imports pybullet: nothing is missing here")
    lines = run.stderr.strip().splitlines()
    assert len(lines) == 1, run.stderr
    assert "Traceback" not in run.stderr
    assert lines[0].startswith("sim: pybullet is not importable from %s" % python)
    assert "tools/setup.sh --deps-only" in lines[0] and "pip install" in lines[0]


def test_a_copied_install_space_with_its_own_venv_works(moved, tmp):
    carried = os.path.join(moved, "venv")
    os.symlink(VENV, carried)
    try:
        out = session(moved, os.path.join(tmp, "home2"))
    finally:
        os.unlink(carried)
    assert "python3: %s/bin/python3" % carried in out
    assert "'max_update_rate': 250.0" in out.split("after set:")[1]
