#!/usr/bin/env python3
"""What tools/setup.sh installs on this machine, decided before anything is installed.

Plain Python 3 (3.8 or newer), standard library only: it runs under the system's python3
before any venv exists. The decision (``make_plan``) is a pure function of

- the text of /etc/os-release (which distribution and release),
- whether /opt/ros/noetic/setup.bash exists (ROS Noetic from packages.ros.org),
- the system Python's version and the machine (pybullet 3.2.7 has wheels for CPython 3.8 to
  3.11 on x86_64 only; elsewhere it is built from source),
- whether apt-get exists, and whether the apt sources offer ROS 1 (python3-rospy),

and answers with the apt packages, the pip requirements, the ROS environment to source, where
gazebo_msgs comes from, or a refusal: one line saying what the machine needs.

    python3 tools/setup_plan.py             # the plan for this machine, in words
    python3 tools/setup_plan.py --shell     # the same as shell assignments PLAN_*=... (setup.sh)
    python3 tools/setup_plan.py --py38 --shell
                                            # the Python 3.8 venv that `make test` adds, PY38_*=...

The probes can be overridden to see the plan for another machine, e.g.
``--os-release /path/to/os-release --noetic yes --python 3.8``. A refusal prints one line on
stderr and exits with status 1.
"""
import argparse
import glob
import os
import platform
import shlex
import shutil
import subprocess
import sys

PYBULLET = "pybullet==3.2.7"
NOETIC_SETUP = "/opt/ros/noetic/setup.bash"
NUMPY_PY38 = "numpy>=1.23,<1.25"  # pybullet's cp38 wheel needs numpy's C API 0x10 (1.23, 1.24)
NUMPY_PY39_UP = "numpy>=2"
PYTEST_NOETIC = "pytest>=6.2"  # focal's python3-pytest 4.6.9 fails pytest.approx on tuples
PILLOW_NOETIC = "Pillow>=7.1"  # focal's 7.0 has no ImageGrab.grab(xdisplay=): the screenshot tests
# Gazebo's assets: meshes (Collada through pycollada, STL, OBJ) and ROS 1's xacro (PyPI's 1.13.x;
# its 2.x releases are ROS 2's). On Python 3.8: trimesh 4.x, and pycollada 0.8 (0.9 needs 3.9;
# 0.8 is a source package, pure Python). trimesh reads an ASCII STL that is not UTF-8 only with
# charset-normalizer (3.x still supports 3.8).
MESH_PIP = ("trimesh>=4,<6", "pycollada>=0.8", "charset-normalizer>=3,<4")
MESH_PIP_PY38 = ("trimesh>=4,<5", "pycollada>=0.8,<0.9", "charset-normalizer>=3,<4")
XACRO = "xacro==1.13.3"
# learning/'s environments (gymnasium.make("TurtleBot3Stage1-v0")): Gymnasium 1.x, pure Python
# (numpy, cloudpickle, typing-extensions, farama-notifications); 1.1.1 is the last for 3.8.
GYMNASIUM = "gymnasium>=1.0,<2"
CATKIN_LINT = "catkin-lint==1.6.25"  # make test checks the packages' CMakeLists.txt and package.xml
# make test's lint (test/unit/package/test_lint.py): pycodestyle at 100 columns and pyflakes,
# pinned so that every platform reads the code alike (both take Python 3.8 to 3.13)
LINT = ("pycodestyle==2.12.1", "pyflakes==3.2.0")
WHEEL_MACHINES = ("x86_64", "amd64")
WHEEL_PYTHONS = ((3, 8), (3, 11))  # pybullet 3.2.7 wheels: cp38, cp39, cp310, cp311
# pybullet 3.2.7's C passes numpy arrays as PyObject*: GCC 14 (Debian 13, Ubuntu 24.10) made
# that an error. The flag is known to every GCC since 5 and to clang.
PYBULLET_BUILD_CFLAGS = "-Wno-error=incompatible-pointer-types"
DEBIAN_DIST_PACKAGES = "/usr/lib/python3/dist-packages"

# Both kinds of ROS 1: the lab's tools that are not ROS packages.
COMMON_APT = (
    "python3-venv", "python3-pip", "build-essential", "cmake",
    "python3-pil",                          # JPEG for .../compressed
    "libegl1", "libgl1-mesa-dri",           # the cameras render through Mesa's EGL
    "python3-tk", "python3-pil.imagetk",    # the camera viewer
    "xvfb", "xauth", "x11-utils",           # a display for the viewer's test (xvfb-run needs
                                            # xauth); xdpyinfo
    "graphviz", "xdot",                     # the graph command (rqt_graph's picture)
    "shellcheck",                           # make test checks every shell script
)

# Debian 12+ and Ubuntu 22.04+: Debian's ROS 1 packages in /usr. The message packages come as
# three parts each: python3-X (the Python module), ros-X (the .msg definitions that rosmsg
# show reads) and libX-dev (the CMake config that catkin_make of gazebo_msgs needs).
DISTRO_ROS_APT = (
    "ros-core", "ros-environment",          # ros-environment: ROS_PACKAGE_PATH in devel/setup.bash
    "python3-rospy", "python3-roslaunch", "python3-rostest", "librostest-dev",
    "rosbash", "catkin", "python3-catkin-pkg", "python3-rosbag", "python3-pytest",
    "python3-std-msgs", "python3-geometry-msgs", "python3-sensor-msgs", "python3-nav-msgs",
    "python3-std-srvs", "python3-rosgraph-msgs", "python3-tf2-msgs", "python3-trajectory-msgs",
    "ros-std-msgs", "ros-geometry-msgs", "ros-sensor-msgs", "ros-nav-msgs", "ros-std-srvs",
    "ros-rosgraph-msgs", "ros-tf2-msgs", "ros-trajectory-msgs",
    "libstd-msgs-dev", "libgeometry-msgs-dev", "libsensor-msgs-dev", "libnav-msgs-dev",
    "libstd-srvs-dev", "libtrajectory-msgs-dev",
    "ros-message-generation", "ros-message-runtime", "python3-genmsg", "python3-genpy",
    "python3-tf2-ros", "ros-robot-state-publisher", "ros-image-view", "rviz",
    "python3-dynamic-reconfigure",
    "ignition-tools", "libsdformat-dev",    # Gazebo's SDF checker `ign sdf` (a unit test)
)

# Ubuntu 20.04 with ROS Noetic from packages.ros.org: Noetic's own packages for everything.
NOETIC_ROS_APT = (
    "ros-noetic-ros-base", "ros-noetic-rostest", "ros-noetic-rosbag",
    "ros-noetic-std-msgs", "ros-noetic-geometry-msgs", "ros-noetic-sensor-msgs",
    "ros-noetic-nav-msgs", "ros-noetic-std-srvs", "ros-noetic-rosgraph-msgs",
    "ros-noetic-tf2-msgs", "ros-noetic-trajectory-msgs", "ros-noetic-gazebo-msgs",
    "ros-noetic-message-generation", "ros-noetic-message-runtime", "ros-noetic-genmsg",
    "ros-noetic-genpy", "ros-noetic-tf2-ros", "ros-noetic-robot-state-publisher",
    "ros-noetic-image-view", "ros-noetic-rviz", "ros-noetic-dynamic-reconfigure",
    "ros-noetic-rqt-graph", "ros-noetic-xacro",
)

# Installed where the distribution has them, skipped with a line where it does not.
OPTIONAL_APT = ("ignition-tools", "libsdformat-dev", "xdot", "ros-noetic-rqt-graph")

# The Python 3.8 venv of `make test` (unit tests only): compiled modules from PyPI, since
# Debian's are built for its own Python; Debian's pure-Python ROS modules through a .pth.
PY38_PIP = ((PYBULLET, NUMPY_PY38, "pytest", "Pillow", "PyYAML", "netifaces") + MESH_PIP_PY38
            + (GYMNASIUM,))

UBUNTU_CODENAMES = {"bionic": (18, 4), "focal": (20, 4), "jammy": (22, 4), "noble": (24, 4)}
DEBIAN_CODENAMES = {"buster": 10, "bullseye": 11, "bookworm": 12, "trixie": 13, "forky": 14}
SUPPORTED = ("Debian 12 or newer, Ubuntu 22.04 or newer, or Ubuntu 20.04 with ROS Noetic in "
             "/opt/ros/noetic")


class Refusal(Exception):
    """This machine cannot be set up: the message says what it needs, in one line."""


class Plan:
    """The set-up's answer for one machine (the attributes are what setup.sh reads)."""

    def __init__(self, platform_name, ros, ros_setup, apt, numpy, pytest, pybullet_from,
                 gazebo_msgs, python, apt_update_first=False, notes=()):
        self.platform = platform_name       # words for the user
        self.ros = ros                      # "noetic" or "distro"
        self.ros_setup = ros_setup          # file to source before anything, or ""
        self.apt = tuple(apt)
        self.apt_optional = tuple(p for p in self.apt if p in OPTIONAL_APT)
        self.numpy = numpy
        self.pytest = pytest                # "" where the system's python3-pytest serves
        self.pybullet_from = pybullet_from  # "wheel" or "source"
        self.gazebo_msgs = gazebo_msgs      # "system" (installed) or "repo" (msgs/gazebo_msgs)
        self.python = python                # (major, minor) of the venv's base Python
        self.apt_update_first = apt_update_first
        self.notes = tuple(notes)

    @property
    def pip_first(self):
        """Installed before pybullet: what its build from source imports."""
        if self.pybullet_from == "source":
            return (self.numpy, "setuptools", "wheel")
        return ()

    @property
    def pip(self):
        meshes = MESH_PIP_PY38 if tuple(self.python) == (3, 8) else MESH_PIP
        return ((PYBULLET, self.numpy) + meshes + (XACRO, CATKIN_LINT, GYMNASIUM) + LINT
                + ((self.pytest,) if self.pytest else ())
                + ((PILLOW_NOETIC,) if self.ros == "noetic" else ()))

    @property
    def pip_flags(self):
        # pip's build isolation would hide numpy from pybullet's setup.py: no numpy support.
        return ("--no-build-isolation",) if self.pybullet_from == "source" else ()

    @property
    def build_cflags(self):
        """CFLAGS for building pybullet from source ("" where the wheel is used)."""
        return PYBULLET_BUILD_CFLAGS if self.pybullet_from == "source" else ""

    @property
    def wheel_cache(self):
        """The folder, under the user's cache, that keeps the pybullet wheel built here, so
        that a second venv (a `make clean`, another clone) does not build it again; "" where
        PyPI's wheel is used."""
        if self.pybullet_from != "source":
            return ""
        numpy_major = "".join(c for c in self.numpy.split(",")[0] if c.isdigit() or c == ".")
        return "pybullet-3.2.7-py%d.%d-numpy%s" % (self.python + (numpy_major.split(".")[0],))

    @property
    def stamp(self):
        """What the venv was made for: a venv stamped otherwise is made again."""
        steps = [" ".join(self.pip_first), " ".join(self.pip_flags + self.pip)]
        return "python %d.%d: pip install %s" % (self.python + (" | ".join(s for s in steps if s),))

    def shell(self):
        values = [
            ("PLAN_PLATFORM", self.platform), ("PLAN_ROS", self.ros),
            ("PLAN_ROS_SETUP", self.ros_setup), ("PLAN_APT", " ".join(self.apt)),
            ("PLAN_APT_OPTIONAL", " ".join(self.apt_optional)),
            ("PLAN_APT_UPDATE_FIRST", "1" if self.apt_update_first else "0"),
            ("PLAN_PIP_FIRST", " ".join(self.pip_first)), ("PLAN_PIP", " ".join(self.pip)),
            ("PLAN_PIP_FLAGS", " ".join(self.pip_flags)),
            ("PLAN_BUILD_CFLAGS", self.build_cflags), ("PLAN_WHEEL_CACHE", self.wheel_cache),
            ("PLAN_PYBULLET", self.pybullet_from), ("PLAN_GAZEBO_MSGS", self.gazebo_msgs),
            ("PLAN_PYTHON", "%d.%d" % self.python), ("PLAN_STAMP", self.stamp),
            ("PLAN_NOTES", "\n".join(self.notes)),
        ]
        return "".join("%s=%s\n" % (k, shlex.quote(v)) for k, v in values)

    def describe(self):
        lines = ["platform: %s" % self.platform]
        if self.ros_setup:
            lines.append("ROS environment: source %s first" % self.ros_setup)
        lines.append("apt packages: %s" % " ".join(self.apt))
        if self.apt_optional:
            lines.append("  (skipped where the distribution lacks them: %s)"
                         % " ".join(self.apt_optional))
        if self.pip_first:
            lines.append("venv, first: pip install %s" % " ".join(self.pip_first))
        lines.append("venv (Python %d.%d, system site packages): pip install %s%s" % (
            self.python + (" ".join(self.pip_flags) + " " if self.pip_flags else "",
                           " ".join(self.pip))))
        lines.append("gazebo_msgs: %s" % (
            "the system's package" if self.gazebo_msgs == "system"
            else "built from this repository's msgs/gazebo_msgs"))
        lines.extend(self.notes)
        return "\n".join(lines)


def parse_os_release(text):
    """The KEY=value pairs of an os-release file, quotes removed."""
    fields = {}
    for line in text.splitlines():
        line = line.strip()
        if not line or line.startswith("#") or "=" not in line:
            continue
        key, _, value = line.partition("=")
        try:
            words = shlex.split(value)
        except ValueError:
            words = [value.strip("\"'")]
        fields[key.strip()] = " ".join(words)
    return fields


def _version_tuple(text):
    parts = []
    for piece in text.split("."):
        digits = "".join(c for c in piece if c.isdigit())
        if not digits:
            break
        parts.append(int(digits))
    return tuple(parts)


def identify(fields):
    """("ubuntu", (22, 4)), ("debian", 12), or ("other", None)."""
    ids = [fields.get("ID", "").lower()] + fields.get("ID_LIKE", "").lower().split()
    if ids[0] == "ubuntu" and _version_tuple(fields.get("VERSION_ID", ""))[:2]:
        version = _version_tuple(fields["VERSION_ID"])
        return "ubuntu", (version + (0,))[:2]
    if "ubuntu" in ids and fields.get("UBUNTU_CODENAME", "").lower() in UBUNTU_CODENAMES:
        return "ubuntu", UBUNTU_CODENAMES[fields["UBUNTU_CODENAME"].lower()]
    if ids[0] == "debian" and _version_tuple(fields.get("VERSION_ID", "")):
        return "debian", _version_tuple(fields["VERSION_ID"])[0]
    if "debian" in ids:
        codename = fields.get("VERSION_CODENAME", "").lower()
        if codename in DEBIAN_CODENAMES:
            return "debian", DEBIAN_CODENAMES[codename]
        if ids[0] == "debian":  # testing or unstable: no VERSION_ID, newer than any release
            return "debian", 99
    return "other", None


def make_plan(os_release, noetic, python, machine="x86_64", apt=True, ros1_apt=True):
    """The plan for a machine, or Refusal.

    os_release: the text of /etc/os-release; noetic: /opt/ros/noetic/setup.bash exists;
    python: (major, minor) of the system python3; machine: platform.machine();
    apt: apt-get exists; ros1_apt: the apt sources offer python3-rospy (True, False, or None
    when apt has no package lists yet: then apt-get update comes first and the plan is asked
    again).
    """
    fields = parse_os_release(os_release)
    name = fields.get("PRETTY_NAME") or fields.get("NAME") or "this system"
    python = tuple(python)[:2]
    if not apt:
        raise Refusal(
            "%s has no apt-get: tools/setup.sh installs with apt (%s); elsewhere install ROS 1 "
            "(rospy, roslaunch, rostest, the message packages) and `pip install %s numpy` "
            "yourself, then build as README's 'In your own catkin workspace' says"
            % (name, SUPPORTED, PYBULLET))
    if python < (3, 8):
        raise Refusal("%s's python3 is %d.%d: tutorial_turtlebot needs Python 3.8 or newer (%s)"
                      % (name, python[0], python[1], SUPPORTED))
    family, version = identify(fields)
    notes = []
    if noetic:
        ros, ros_setup, apt_packages = "noetic", NOETIC_SETUP, NOETIC_ROS_APT
        platform_name = "%s with ROS Noetic (%s)" % (name, os.path.dirname(NOETIC_SETUP))
        pytest = PYTEST_NOETIC
    else:
        if family == "ubuntu" and version < (20, 4):
            raise Refusal("%s is too old: tools/setup.sh needs %s" % (name, SUPPORTED))
        if family == "ubuntu" and version < (22, 4):
            raise Refusal(
                "%s needs ROS Noetic first: install ros-noetic-ros-base from packages.ros.org "
                "(wiki.ros.org/noetic/Installation/Ubuntu) so that %s exists, then run this again "
                "(Ubuntu 20.04's own ROS 1 packages are not supported and must not be mixed "
                "with Noetic's)" % (name, NOETIC_SETUP))
        if family == "debian" and version < 12:
            raise Refusal("%s is too old: tools/setup.sh needs %s" % (name, SUPPORTED))
        if ros1_apt is False:
            where = ("enable Ubuntu's universe component (sudo add-apt-repository universe; "
                     "sudo apt-get update)" if family == "ubuntu" else
                     "use %s" % SUPPORTED)
            raise Refusal("%s's apt sources have no ROS 1 packages (python3-rospy): %s"
                          % (name, where))
        ros, ros_setup, apt_packages = "distro", "", DISTRO_ROS_APT
        platform_name = "%s with the distribution's ROS 1 packages (in /usr)" % name
        pytest = ""
        if family == "other":
            notes.append("%s is not a platform this set-up was tried on; using the Debian "
                         "package names" % name)
    numpy = NUMPY_PY38 if python == (3, 8) else NUMPY_PY39_UP
    wheel = (machine in WHEEL_MACHINES and WHEEL_PYTHONS[0] <= python <= WHEEL_PYTHONS[1])
    apt_list = list(apt_packages) + [p for p in COMMON_APT if p not in apt_packages]
    if not wheel:
        apt_list.append("python3-dev")
        why = ("Python %d.%d" % python if machine in WHEEL_MACHINES
               else "%s (Python %d.%d)" % (machine, python[0], python[1]))
        notes.append("pybullet has no wheel for %s: it is built from source, which takes about "
                     "5 minutes on 2 cores (more on a small ARM board), once" % why)
    return Plan(platform_name, ros, ros_setup, apt_list, numpy, pytest,
                "wheel" if wheel else "source", "system" if ros == "noetic" else "repo",
                python, apt_update_first=(ros == "distro" and ros1_apt is None), notes=notes)


# --- the Python 3.8 venv of `make test` ----------------------------------------------------------

def py38_candidates(path_env, pyenv_root):
    """Where a CPython 3.8 may be: python3.8 on PATH (pyenv's shims excepted: they run only
    when 3.8 is the selected version), then pyenv's versions/3.8.*, newest first."""
    found = []
    for folder in path_env.split(os.pathsep):
        if not folder or os.path.basename(os.path.normpath(folder)) == "shims":
            continue
        found.append(os.path.join(folder, "python3.8"))
    if pyenv_root:
        versions = glob.glob(os.path.join(pyenv_root, "versions", "3.8.*", "bin", "python3.8"))
        versions.sort(key=lambda p: _version_tuple(p.split(os.sep)[-3]), reverse=True)
        found.extend(versions)
    return found


def plan_py38(system_python, candidates, is_python38):
    """(python, "") for the Python 3.8 venv, or ("", reason to skip it)."""
    if tuple(system_python)[:2] == (3, 8):
        return "", "the main venv runs Python 3.8 already"
    for exe in candidates:
        if is_python38(exe):
            return exe, ""
    return "", "no Python 3.8 on this machine (python3.8 on PATH or pyenv's 3.8.x)"


def _is_python38(exe):
    if not (os.path.isfile(exe) and os.access(exe, os.X_OK)):
        return False
    try:
        run = subprocess.run([exe, "-c", "import sys; print(sys.version_info[:2] == (3, 8))"],
                             stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
                             universal_newlines=True, timeout=30)
    except (OSError, subprocess.SubprocessError):
        return False
    return run.returncode == 0 and run.stdout.strip() == "True"


def _pyenv_root():
    root = os.environ.get("PYENV_ROOT")
    if root:
        return root
    if shutil.which("pyenv"):
        try:
            return subprocess.run(["pyenv", "root"], stdout=subprocess.PIPE,
                                  stderr=subprocess.DEVNULL, universal_newlines=True,
                                  timeout=30).stdout.strip()
        except (OSError, subprocess.SubprocessError):
            pass
    return os.path.expanduser("~/.pyenv")


# --- probing this machine -----------------------------------------------------------------------

def read_os_release(path=None):
    for candidate in ([path] if path else ["/etc/os-release", "/usr/lib/os-release"]):
        try:
            with open(candidate) as f:
                return f.read()
        except OSError:
            if path:
                raise Refusal("cannot read %s" % path)
    return ""


def ros1_in_apt(package="python3-rospy"):
    """True or False: apt offers the package; None: apt has no package lists to ask yet."""
    try:
        run = subprocess.run(["apt-cache", "policy", package], stdout=subprocess.PIPE,
                             stderr=subprocess.DEVNULL, universal_newlines=True, timeout=60)
    except (OSError, subprocess.SubprocessError):
        return None
    for line in run.stdout.splitlines():
        key, _, value = line.strip().partition(":")
        if key == "Candidate":
            return value.strip() not in ("", "(none)")
    if glob.glob("/var/lib/apt/lists/*_Packages*"):
        return False
    return None


def _yes_no(text):
    if text not in ("yes", "no"):
        raise argparse.ArgumentTypeError("expected yes or no, got %r" % text)
    return text == "yes"


def _python_version(text):
    version = _version_tuple(text)
    if len(version) < 2:
        raise argparse.ArgumentTypeError("expected a version like 3.8, got %r" % text)
    return version[:2]


def main(argv=None):
    parser = argparse.ArgumentParser(
        prog="setup_plan.py", description="What tools/setup.sh installs on this machine.")
    parser.add_argument("--shell", action="store_true",
                        help="print shell assignments (PLAN_* or PY38_*) instead of words")
    parser.add_argument("--py38", action="store_true",
                        help="the Python 3.8 venv of make test instead of the main plan")
    parser.add_argument("--os-release", metavar="FILE", help="instead of /etc/os-release")
    parser.add_argument("--noetic", type=_yes_no, metavar="yes|no",
                        help="instead of looking for %s" % NOETIC_SETUP)
    parser.add_argument("--python", type=_python_version, metavar="X.Y",
                        help="instead of this python3's version")
    parser.add_argument("--machine", help="instead of platform.machine()")
    parser.add_argument("--apt", type=_yes_no, metavar="yes|no",
                        help="instead of looking for apt-get")
    parser.add_argument("--ros1-apt", choices=("yes", "no", "unknown"),
                        help="instead of asking apt-cache about python3-rospy")
    args = parser.parse_args(argv)
    python = args.python or tuple(sys.version_info[:2])

    if args.py38:
        exe, reason = plan_py38(python, py38_candidates(os.environ.get("PATH", ""),
                                                        _pyenv_root()), _is_python38)
        if args.shell:
            print("PY38_PYTHON=%s\nPY38_SKIP=%s\nPY38_PIP=%s\nPY38_PTH=%s" % (
                shlex.quote(exe), shlex.quote(reason), shlex.quote(" ".join(PY38_PIP)),
                shlex.quote(DEBIAN_DIST_PACKAGES)))
        else:
            print("Python 3.8 for the unit tests: %s" % (exe or "none: " + reason))
        return 0

    try:
        apt = shutil.which("apt-get") is not None if args.apt is None else args.apt
        if args.ros1_apt is None:
            ros1 = ros1_in_apt() if apt else False
        else:
            ros1 = {"yes": True, "no": False, "unknown": None}[args.ros1_apt]
        plan = make_plan(read_os_release(args.os_release),
                         os.path.isfile(NOETIC_SETUP) if args.noetic is None else args.noetic,
                         python, args.machine or platform.machine(), apt, ros1)
    except Refusal as refusal:
        print("[setup] cannot set up here: %s" % refusal, file=sys.stderr)
        return 1
    print(plan.shell() if args.shell else plan.describe(), end="\n" if not args.shell else "")
    return 0


if __name__ == "__main__":
    sys.exit(main())
