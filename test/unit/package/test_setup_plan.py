"""The set-up's decisions (tools/setup_plan.py) for the platforms where ROS 1 users are, from
faked os-release text, a faked /opt/ros/noetic and faked Python versions; and setup.sh's
refusal before it installs anything."""
import importlib.util
import os
import subprocess
import sys

import pytest
import unit_paths

ROOT = unit_paths.ROOT
SCRIPT = os.path.join(ROOT, "tools", "setup_plan.py")
SETUP_SH = os.path.join(ROOT, "tools", "setup.sh")
MESHES_XACRO = ("trimesh>=4,<6", "pycollada>=0.8", "charset-normalizer>=3,<4", "xacro==1.13.3",
                "catkin-lint==1.6.25", "gymnasium>=1.0,<2", "pycodestyle==2.12.1",
                "pyflakes==3.2.0")
MESHES_XACRO_PY38 = ("trimesh>=4,<5", "pycollada>=0.8,<0.9", "charset-normalizer>=3,<4",
                     "xacro==1.13.3", "catkin-lint==1.6.25", "gymnasium>=1.0,<2",
                     "pycodestyle==2.12.1", "pyflakes==3.2.0")

_spec = importlib.util.spec_from_file_location("setup_plan", SCRIPT)
setup_plan = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(setup_plan)
make_plan, Refusal = setup_plan.make_plan, setup_plan.Refusal

DEBIAN_12 = '''PRETTY_NAME="Debian GNU/Linux 12 (bookworm)"
NAME="Debian GNU/Linux"
VERSION_ID="12"
VERSION="12 (bookworm)"
VERSION_CODENAME=bookworm
ID=debian
HOME_URL="https://www.debian.org/"
'''
DEBIAN_13 = DEBIAN_12.replace("12", "13").replace("bookworm", "trixie")
DEBIAN_11 = DEBIAN_12.replace("12", "11").replace("bookworm", "bullseye")
DEBIAN_SID = '''PRETTY_NAME="Debian GNU/Linux trixie/sid"
NAME="Debian GNU/Linux"
VERSION_CODENAME=trixie
ID=debian
'''
UBUNTU = '''NAME="Ubuntu"
VERSION="{v} LTS ({name})"
ID=ubuntu
ID_LIKE=debian
PRETTY_NAME="Ubuntu {v} LTS"
VERSION_ID="{v}"
VERSION_CODENAME={code}
UBUNTU_CODENAME={code}
'''
UBUNTU_2004 = UBUNTU.format(v="20.04", name="Focal Fossa", code="focal")
UBUNTU_2204 = UBUNTU.format(v="22.04", name="Jammy Jellyfish", code="jammy")
UBUNTU_2404 = UBUNTU.format(v="24.04", name="Noble Numbat", code="noble")
UBUNTU_1804 = UBUNTU.format(v="18.04", name="Bionic Beaver", code="bionic")
MINT_21 = '''NAME="Linux Mint"
VERSION="21.3 (Virginia)"
ID=linuxmint
ID_LIKE="ubuntu debian"
PRETTY_NAME="Linux Mint 21.3"
VERSION_ID="21.3"
UBUNTU_CODENAME=jammy
'''
FEDORA = '''NAME="Fedora Linux"
VERSION="40 (Workstation Edition)"
ID=fedora
VERSION_ID=40
PRETTY_NAME="Fedora Linux 40 (Workstation Edition)"
'''

# What the lab's walk-through (doc/lab.md) and the other tools use, on Debian.
DEBIAN_MUST_HAVE = (
    "ros-std-msgs ros-geometry-msgs ros-sensor-msgs ros-nav-msgs ros-std-srvs ros-rosgraph-msgs "
    "ros-tf2-msgs ros-trajectory-msgs ros-message-generation ros-message-runtime python3-genmsg "
    "python3-genpy graphviz xdot python3-tk python3-pil.imagetk xvfb python3-dynamic-reconfigure "
    "python3-rosbag x11-utils shellcheck python3-rospy python3-roslaunch python3-rostest "
    "ros-robot-state-publisher python3-tf2-ros ros-image-view rviz python3-venv").split()


def refusal(*args, **kwargs):
    with pytest.raises(Refusal) as caught:
        make_plan(*args, **kwargs)
    message = str(caught.value)
    assert message and "\n" not in message  # one line
    return message


# --- the platforms --------------------------------------------------------------------------------

def test_debian_12_uses_debians_ros_and_the_pybullet_wheel():
    plan = make_plan(DEBIAN_12, noetic=False, python=(3, 11))
    assert plan.ros == "distro" and plan.ros_setup == ""
    assert "Debian GNU/Linux 12 (bookworm)" in plan.platform
    missing = [p for p in DEBIAN_MUST_HAVE if p not in plan.apt]
    assert not missing
    assert not [p for p in plan.apt if p.startswith("ros-noetic-")]
    assert "python3-pytest" in plan.apt and plan.pytest == ""
    assert plan.numpy == "numpy>=2" and plan.pybullet_from == "wheel"
    assert plan.pip == ("pybullet==3.2.7", "numpy>=2") + MESHES_XACRO and plan.pip_first == ()
    assert plan.pip_flags == () and "python3-dev" not in plan.apt
    assert plan.gazebo_msgs == "repo"  # Debian has no gazebo_msgs: msgs/gazebo_msgs is built
    assert not plan.apt_update_first and plan.notes == ()
    assert len(set(plan.apt)) == len(plan.apt)


def test_debian_12_installs_message_definitions_and_their_cmake_configs():
    # rosmsg show reads ros-X's .msg files; catkin_make of gazebo_msgs needs libX-dev's CMake.
    apt = make_plan(DEBIAN_12, noetic=False, python=(3, 11)).apt
    for name in ("std-msgs", "geometry-msgs", "sensor-msgs", "std-srvs", "trajectory-msgs"):
        assert "ros-" + name in apt and "lib%s-dev" % name in apt, name


def test_debian_13_builds_pybullet_from_source_with_numpy():
    plan = make_plan(DEBIAN_13, noetic=False, python=(3, 13))
    assert plan.ros == "distro" and plan.gazebo_msgs == "repo"
    assert plan.pybullet_from == "source" and "python3-dev" in plan.apt
    assert plan.pip_first == ("numpy>=2", "setuptools", "wheel")
    assert plan.pip_flags == ("--no-build-isolation",)
    assert plan.pip == ("pybullet==3.2.7", "numpy>=2") + MESHES_XACRO
    (note,) = plan.notes
    assert "from source" in note and "5 minutes" in note


def test_debian_testing_without_version_id_is_newer_than_12():
    plan = make_plan(DEBIAN_SID, noetic=False, python=(3, 12))
    assert plan.ros == "distro" and plan.pybullet_from == "source"
    assert make_plan(DEBIAN_SID.replace("trixie", "sid"), noetic=False,
                     python=(3, 12)).ros == "distro"


def test_ubuntu_2004_with_noetic_uses_noetics_packages_and_python_38_pins():
    plan = make_plan(UBUNTU_2004, noetic=True, python=(3, 8))
    assert plan.ros == "noetic" and plan.ros_setup == "/opt/ros/noetic/setup.bash"
    assert "Ubuntu 20.04 LTS" in plan.platform and "Noetic" in plan.platform
    ros_names = [p for p in plan.apt if p.startswith("ros-") or p.startswith("python3-ros")]
    assert ros_names and all(p.startswith("ros-noetic-") for p in ros_names)
    for pkg in ("ros-noetic-gazebo-msgs", "ros-noetic-rostest", "ros-noetic-nav-msgs",
                "ros-noetic-dynamic-reconfigure", "ros-noetic-rosbag", "graphviz", "xvfb"):
        assert pkg in plan.apt, pkg
    assert not {"python3-rospy", "ros-core", "catkin", "python3-pytest"} & set(plan.apt)
    assert plan.numpy == "numpy>=1.23,<1.25"  # pybullet's cp38 wheel: numpy C API 0x10
    assert plan.pytest == "pytest>=6.2"       # focal's pytest 4.6.9 is too old
    assert plan.pip == ("pybullet==3.2.7", "numpy>=1.23,<1.25") + MESHES_XACRO_PY38 + (
        "pytest>=6.2", "Pillow>=7.1")
    assert plan.pybullet_from == "wheel" and plan.gazebo_msgs == "system"
    assert "ros-noetic-rqt-graph" in plan.apt_optional


def test_ubuntu_2004_without_noetic_is_refused_naming_noetic():
    message = refusal(UBUNTU_2004, noetic=False, python=(3, 8))
    assert "Noetic" in message and "/opt/ros/noetic" in message and "20.04" in message


def test_ubuntu_2204_uses_the_distributions_ros():
    plan = make_plan(UBUNTU_2204, noetic=False, python=(3, 10))
    assert plan.ros == "distro" and plan.ros_setup == ""
    assert plan.numpy == "numpy>=2" and plan.pybullet_from == "wheel"
    assert plan.gazebo_msgs == "repo" and plan.pytest == ""


def test_ubuntu_2404_builds_pybullet_from_source_or_asks_for_universe():
    plan = make_plan(UBUNTU_2404, noetic=False, python=(3, 12))
    assert plan.pybullet_from == "source" and "python3-dev" in plan.apt
    assert plan.pip_flags == ("--no-build-isolation",) and "5 minutes" in plan.notes[0]
    message = refusal(UBUNTU_2404, noetic=False, python=(3, 12), ros1_apt=False)
    assert "ROS 1" in message and "universe" in message


def test_a_derivative_is_taken_for_its_ubuntu_release():
    assert setup_plan.identify(setup_plan.parse_os_release(MINT_21)) == ("ubuntu", (22, 4))
    assert make_plan(MINT_21, noetic=False, python=(3, 10)).ros == "distro"


def test_no_apt_is_refused_before_anything_else():
    message = refusal(FEDORA, noetic=False, python=(3, 12), apt=False)
    assert "apt-get" in message and "Fedora Linux 40" in message
    assert "apt-get" in refusal(FEDORA, noetic=True, python=(3, 8), apt=False)


def test_no_ros1_in_the_apt_sources_is_refused():
    message = refusal(DEBIAN_12, noetic=False, python=(3, 11), ros1_apt=False)
    assert "no ROS 1 packages" in message and "python3-rospy" in message


def test_unknown_ros1_in_apt_asks_for_apt_get_update_first():
    assert make_plan(DEBIAN_12, noetic=False, python=(3, 11), ros1_apt=None).apt_update_first
    assert not make_plan(UBUNTU_2004, noetic=True, python=(3, 8), ros1_apt=None).apt_update_first


@pytest.mark.parametrize("os_release, python", [(DEBIAN_11, (3, 9)), (UBUNTU_1804, (3, 6)),
                                                (UBUNTU_1804, (3, 8)), (DEBIAN_12, (3, 7))])
def test_too_old_is_refused(os_release, python):
    message = refusal(os_release, noetic=False, python=python)
    assert "Debian 12 or newer" in message or "Python 3.8" in message


def test_an_unknown_apt_distribution_with_ros1_gets_the_debian_names_and_a_note():
    plan = make_plan('ID=someos\nPRETTY_NAME="Some OS 1"\n', noetic=False, python=(3, 11))
    assert plan.ros == "distro" and "python3-rospy" in plan.apt
    assert "Some OS 1" in plan.notes[0]


def test_no_wheel_off_x86_64():
    plan = make_plan(UBUNTU_2004, noetic=True, python=(3, 8), machine="aarch64")
    assert plan.pybullet_from == "source" and "aarch64" in plan.notes[0]
    assert plan.pip_first == ("numpy>=1.23,<1.25", "setuptools", "wheel")


def test_the_venv_stamp_changes_with_the_plan():
    stamps = {make_plan(DEBIAN_12, False, (3, 11)).stamp,
              make_plan(DEBIAN_13, False, (3, 13)).stamp,
              make_plan(UBUNTU_2004, True, (3, 8)).stamp}
    assert len(stamps) == 3


def test_parse_os_release_quotes_and_comments():
    fields = setup_plan.parse_os_release('# comment\nA="x y"\nB=\'z\'\nC=plain\n\nbroken line\n')
    assert fields == {"A": "x y", "B": "z", "C": "plain"}


# --- the Python 3.8 venv of make test -------------------------------------------------------------

def test_py38_is_found_on_path_then_in_pyenv_newest_first(tmp_path):
    for version in ("3.8.9", "3.8.18", "3.10.13"):
        (tmp_path / "pyenv" / "versions" / version / "bin").mkdir(parents=True)
    found = setup_plan.py38_candidates(
        os.pathsep.join(["/usr/local/bin", str(tmp_path / "pyenv" / "shims")]),
        str(tmp_path / "pyenv"))
    assert found[0] == "/usr/local/bin/python3.8"
    assert not [p for p in found if "shims" in p]  # a shim runs only the selected version
    # the glob finds files only: make them
    for version in ("3.8.9", "3.8.18"):
        (tmp_path / "pyenv" / "versions" / version / "bin" / "python3.8").write_text("")
    found = setup_plan.py38_candidates("", str(tmp_path / "pyenv"))
    assert [p.split(os.sep)[-3] for p in found] == ["3.8.18", "3.8.9"]


def test_py38_plan_skips_with_a_reason():
    assert setup_plan.plan_py38((3, 11), ["/a/python3.8", "/b/python3.8"],
                                lambda exe: exe.startswith("/b")) == ("/b/python3.8", "")
    exe, reason = setup_plan.plan_py38((3, 11), ["/a/python3.8"], lambda exe: False)
    assert exe == "" and "no Python 3.8" in reason
    exe, reason = setup_plan.plan_py38((3, 8), ["/a/python3.8"], lambda exe: True)
    assert exe == "" and "3.8 already" in reason


# --- the command line and setup.sh ----------------------------------------------------------------

def run_plan(tmp_path, os_release, *args):
    path = tmp_path / "os-release"
    path.write_text(os_release)
    return subprocess.run([sys.executable, SCRIPT, "--os-release", str(path), "--apt", "yes",
                           "--ros1-apt", "yes", "--machine", "x86_64"] + list(args),
                          stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                          universal_newlines=True, timeout=60)


def test_shell_output_evaluates_in_bash(tmp_path):
    run = run_plan(tmp_path, UBUNTU_2004, "--shell", "--noetic", "yes", "--python", "3.8")
    assert run.returncode == 0, run.stderr
    shown = subprocess.run(
        ["bash", "-c", 'set -eu; eval "$1"; printf "%s\\n" "$PLAN_ROS_SETUP" "$PLAN_PIP" '
         '"$PLAN_GAZEBO_MSGS" "$PLAN_PLATFORM"', "bash", run.stdout],
        stdout=subprocess.PIPE, universal_newlines=True, timeout=60).stdout.splitlines()
    assert shown == ["/opt/ros/noetic/setup.bash",
                     "pybullet==3.2.7 numpy>=1.23,<1.25 trimesh>=4,<5 pycollada>=0.8,<0.9 "
                     "charset-normalizer>=3,<4 xacro==1.13.3 catkin-lint==1.6.25 "
                     "gymnasium>=1.0,<2 pycodestyle==2.12.1 pyflakes==3.2.0 pytest>=6.2 "
                     "Pillow>=7.1",
                     "system", "Ubuntu 20.04 LTS with ROS Noetic (/opt/ros/noetic)"]
    # a name with a quote survives the round trip
    run = run_plan(tmp_path, 'ID=debian\nVERSION_ID=12\nPRETTY_NAME="Bob\'s Debian 12"\n',
                   "--shell", "--noetic", "no", "--python", "3.11")
    shown = subprocess.run(["bash", "-c", 'eval "$1"; printf "%s" "$PLAN_PLATFORM"', "bash",
                            run.stdout], stdout=subprocess.PIPE, universal_newlines=True,
                           timeout=60).stdout
    assert shown.startswith("Bob's Debian 12 with")


def test_words_output_names_the_packages(tmp_path):
    run = run_plan(tmp_path, DEBIAN_13, "--noetic", "no", "--python", "3.13")
    assert run.returncode == 0 and run.stderr == ""
    assert "apt packages: ros-core" in run.stdout and "5 minutes" in run.stdout


def test_command_line_refusal_is_one_line_and_status_1(tmp_path):
    run = run_plan(tmp_path, UBUNTU_2004, "--shell", "--noetic", "no", "--python", "3.8")
    assert run.returncode == 1 and run.stdout == ""
    assert len(run.stderr.splitlines()) == 1 and "Noetic" in run.stderr


def test_bad_option_values_are_one_readable_error(tmp_path):
    run = run_plan(tmp_path, DEBIAN_12, "--python", "three")
    assert run.returncode == 2 and "expected a version like 3.8" in run.stderr
    assert "Traceback" not in run.stderr


def test_setup_sh_refuses_before_installing_anything(tmp_path):
    """The real setup.sh, pretending to be Ubuntu 20.04 without Noetic: the plan's one line,
    status 1, and no apt-get (a fake apt-get and sudo first on PATH would leave a trace)."""
    path = tmp_path / "os-release"
    path.write_text(UBUNTU_2004)
    trace = tmp_path / "trace"
    fake_bin = tmp_path / "bin"
    fake_bin.mkdir()
    for tool in ("apt-get", "sudo", "dpkg-query", "catkin_make"):
        exe = fake_bin / tool
        exe.write_text("#!/bin/sh\necho %s >> %s\nexit 1\n" % (tool, trace))
        exe.chmod(0o755)
    env = dict(os.environ, PATH="%s:%s" % (fake_bin, os.environ.get("PATH", "")),
               TUTORIAL_TURTLEBOT_PLAN_ARGS="--os-release %s --noetic no --python 3.8" % path)
    run = subprocess.run(["bash", SETUP_SH], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                         universal_newlines=True, env=env, timeout=120)
    assert run.returncode == 1
    assert len(run.stderr.splitlines()) == 1 and "needs ROS Noetic first" in run.stderr
    assert not trace.exists(), trace.read_text()


# --- what Debian 13 needs that Debian 12 pulled in by itself --------------------------------------

def test_debian_12_and_13_install_ros_environment_and_xauth():
    # ros-environment's catkin hook sets ROS_PACKAGE_PATH (rospack, roslaunch find nothing
    # without it); xvfb-run needs xauth. Debian 12 pulled both in through other packages.
    for release, python in ((DEBIAN_12, (3, 11)), (DEBIAN_13, (3, 13))):
        apt = make_plan(release, noetic=False, python=python).apt
        assert "ros-environment" in apt and "xauth" in apt


def test_a_source_build_gets_gcc_14s_flag_and_a_kept_wheel():
    source = make_plan(DEBIAN_13, noetic=False, python=(3, 13))
    assert source.build_cflags == "-Wno-error=incompatible-pointer-types"
    assert source.wheel_cache == "pybullet-3.2.7-py3.13-numpy2"
    shell = source.shell()
    assert "PLAN_BUILD_CFLAGS=-Wno-error=incompatible-pointer-types" in shell
    assert "PLAN_WHEEL_CACHE=pybullet-3.2.7-py3.13-numpy2" in shell
    wheel = make_plan(DEBIAN_12, noetic=False, python=(3, 11))
    assert wheel.build_cflags == "" and wheel.wheel_cache == ""
