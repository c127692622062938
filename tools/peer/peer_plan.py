"""make peer's logic, without ROS: which of gazebo_ros_pkgs' tests there are (read from its own
CMakeLists.txt files), the scratch workspace that builds and runs them (file lists, generated
CMakeLists.txt and package.xml), one rostest run's result, and the table.

The scratch workspace (tools/peer/run_peer.py writes it into catkin_ws/peer/) holds packages
named as upstream's, each made of upstream's files copied from the snapshot (PEER_SRC) at run
time and the build files written here:

  gazebo_plugins   test/ and test2/ as upstream has them, scripts/test_*.py (the Python test
                   nodes), and the C++ test executables of upstream's add_rostest_gtest() calls
                   (the ENABLE_DISPLAY_TESTS ones too), built against the system's roscpp
  gazebo_ros       launch/ and test/ as upstream has them; scripts/ the stand-in's own entry
                   points: gzserver, gazebo, debug (the sim: tools/peer/gzserver_args.py),
                   gzclient (waits; the sim has no separate client), spawn_model (the sim's)
  gazebo_tests     upstream's test2/ as its test/: test2 is the rosbuild-era gazebo_tests
                   package (test2/CMakeLists_tests_pkg.txt), whose launch files name
                   $(find gazebo_tests); its executables built as that file lists them, with
                   compat headers for the pre-gazebo_msgs ``gazebo/X.h`` services
"""
import os
import re
import xml.etree.ElementTree as ET
from collections import namedtuple

# --- reading CMake -------------------------------------------------------------------------------

Command = namedtuple("Command", "name args conditions")

_COMMAND = re.compile(r"([A-Za-z_][A-Za-z0-9_]*)\s*\(")
_VAR = re.compile(r"\$\{([A-Za-z0-9_]+)\}")


def _strip_comments(text):
    """CMake text without its line comments (# outside a quoted string)."""
    lines = []
    for line in text.splitlines():
        quoted = False
        for i, char in enumerate(line):
            if char == '"':
                quoted = not quoted
            elif char == "#" and not quoted:
                line = line[:i]
                break
        lines.append(line)
    return "\n".join(lines)


def _split_args(text):
    return [w.strip('"') for w in re.findall(r'"[^"]*"|[^\s"]+', text)]


def raw_commands(text):
    """[(lower-case name, [args])] of CMake ``text``, comments left out, in order."""
    text = _strip_comments(text)
    found, pos = [], 0
    while True:
        match = _COMMAND.search(text, pos)
        if not match:
            return found
        depth, i = 1, match.end()
        while i < len(text) and depth:
            depth += {"(": 1, ")": -1}.get(text[i], 0)
            i += 1
        found.append((match.group(1).lower(), _split_args(text[match.end():i - 1])))
        pos = i


def cmake_commands(text, variables=None):
    """[Command(name, args, conditions)] of CMake ``text``: set() variables expanded, foreach()
    loops unrolled, each command with the if() conditions it sits under (an else() branch's as
    "NOT (...)"); the if/else/foreach/set commands themselves are left out."""
    variables = dict(variables or {})
    commands = []
    raw = raw_commands(text)

    def expand(word):
        return _VAR.sub(lambda m: variables.get(m.group(1), m.group(0)), word)

    def run(items, conditions):
        i = 0
        while i < len(items):
            name, args = items[i]
            i += 1
            if name == "set" and args:
                variables[args[0]] = " ".join(expand(a) for a in args[1:])
            elif name == "if":
                conditions = conditions + (" ".join(args),)
            elif name == "else" and conditions:
                conditions = conditions[:-1] + ("NOT (%s)" % conditions[-1],)
            elif name == "endif" and conditions:
                conditions = conditions[:-1]
            elif name == "foreach" and args:
                depth, j = 1, i
                while j < len(items) and depth:
                    depth += {"foreach": 1, "endforeach": -1}.get(items[j][0], 0)
                    j += 1
                body = items[i:j - 1]
                values = " ".join(expand(a) for a in args[1:]).split()
                for value in values:
                    variables[args[0]] = value
                    run(body, conditions)
                i = j
            else:
                args = [w for a in args for w in (expand(a).split() if "${" in a else [a])]
                commands.append(Command(name, args, conditions))

    run(raw, ())
    return commands


# --- upstream's tests ----------------------------------------------------------------------------

# An executable to build: its name, its sources (paths in its scratch package), what upstream
# links it with, and where it comes from.
Executable = namedtuple("Executable", "name sources libs origin")
# One test: the table's name, the scratch package and the launch file's path in it, how many
# runs, its origin: "active" (upstream's CI runs it), "display" (upstream builds it only with
# ENABLE_DISPLAY_TESTS), "test2" (rosbuild-era, built nowhere upstream).
PeerTest = namedtuple("PeerTest", "name package path runs origin")

DISPLAY_OPTION = "ENABLE_DISPLAY_TESTS"
REPEATS = {"set_model_state_test": 10}   # the issue asks 10 passes out of 10
ORDER = ["set_model_state_test", "ros_network_default", "ros_network_disabled", "range_plugin",
         "block_laser_clipping", "camera", "camera16bit", "depth_camera", "multicamera",
         "triggered_camera", "distortion_barrel", "distortion_pincushion"]


def _origin(conditions):
    return "display" if any(DISPLAY_OPTION in c for c in conditions) else "active"


def test_name(path):
    """The table's name of a launch or .test file: its file name without the suffix."""
    return os.path.splitext(os.path.basename(path))[0]


def catkin_tests(text, package, prefix=""):
    """([Executable], [PeerTest]) of a catkin CMakeLists.txt's add_rostest_gtest() and
    add_rostest() calls (what a commented-out call or an if() that is never true upstream,
    such as NOT CATKIN_ENABLE_TESTING, hides is left out; ENABLE_DISPLAY_TESTS is kept, as
    "display"). ``prefix``: the CMakeLists' folder in the package ("test/" for
    gazebo_ros/test/CMakeLists.txt)."""
    commands = cmake_commands(text, {"CMAKE_CURRENT_SOURCE_DIR": "", "ROS_PACKAGE_NAME": package})
    libs = {}
    for cmd in commands:
        if cmd.name == "target_link_libraries" and cmd.args:
            libs.setdefault(cmd.args[0], []).extend(cmd.args[1:])
    executables, tests = [], []
    for cmd in commands:
        if any("CATKIN_ENABLE_TESTING" in c and c.startswith("NOT") for c in cmd.conditions):
            continue
        if cmd.name == "add_rostest_gtest" and len(cmd.args) >= 3:
            target, launch, sources = cmd.args[0], cmd.args[1], cmd.args[2:]
            executables.append(Executable(target, [prefix + s for s in sources],
                                          libs.get(target, []), _origin(cmd.conditions)))
            tests.append(PeerTest(test_name(launch), package, prefix + launch,
                                  REPEATS.get(test_name(launch), 1), _origin(cmd.conditions)))
        elif cmd.name == "add_rostest" and cmd.args:
            launch = cmd.args[0].lstrip("/")
            tests.append(PeerTest(test_name(launch), package, prefix + launch,
                                  REPEATS.get(test_name(launch), 1), _origin(cmd.conditions)))
    return executables, tests


def rosbuild_tests(text, package):
    """([Executable], [PeerTest]) of a rosbuild CMakeLists (test2/CMakeLists_tests_pkg.txt):
    rosbuild_add_executable() and rosbuild_add_rostest[_labeled]() (the label first)."""
    executables, tests = [], []
    for cmd in cmake_commands(text):
        if cmd.name == "rosbuild_add_executable" and len(cmd.args) >= 2:
            executables.append(Executable(cmd.args[0], cmd.args[1:],
                                          ["${catkin_LIBRARIES}", "tinyxml"], "test2"))
        elif cmd.name in ("rosbuild_add_rostest", "rosbuild_add_rostest_labeled") and cmd.args:
            launch = cmd.args[-1]
            tests.append(PeerTest(test_name(launch), package, launch, 1, "test2"))
    return executables, tests


def launch_test_nodes(text):
    """[(pkg, type)] of a launch file's <test> elements."""
    try:
        root = ET.fromstring(text)
    except ET.ParseError:
        return []
    return [(t.get("pkg", ""), t.get("type", "")) for t in root.iter("test")]


def ordered(tests):
    """``tests`` in the table's order: ORDER's first, then the rest as found."""
    rank = {name: i for i, name in enumerate(ORDER)}
    return sorted(tests, key=lambda t: (rank.get(t.name, len(ORDER)),
                                        t.origin == "test2"))


# --- the scratch workspace ---------------------------------------------------------------------

CATKIN_COMPONENTS = ["roscpp", "image_transport", "message_filters", "tf", "cv_bridge",
                     "sensor_msgs", "std_msgs", "std_srvs", "geometry_msgs", "gazebo_msgs"]
COMPILE_FLAGS = ["-DBOOST_BIND_GLOBAL_PLACEHOLDERS", "-include", "boost/bind.hpp"]
# What the build needs from Debian (the C++ tests against Debian's ROS 1 packages).
APT_PACKAGES = ["libroscpp-dev", "libimage-transport-dev", "libmessage-filters-dev",
                "libtf-dev", "libgtest-dev", "libtinyxml-dev", "libcv-bridge-dev",
                "libopencv-dev"]
COMPAT_DIR = "compat_include"   # in a scratch package: the gazebo/X.h headers of test2


def target_name(package, name):
    """The CMake target of executable ``name`` in ``package`` (one workspace has one target of
    a name: gazebo_plugins and gazebo_tests both build check_model)."""
    return "%s__%s" % (package, name)


def cmakelists(package, executables, compat=False):
    """The scratch package's CMakeLists.txt: each executable built from upstream's sources
    (under the name upstream gives it, in devel/lib/PACKAGE/) and linked with what upstream
    names (plus gtest, which add_rostest_gtest adds)."""
    lines = [
        "# Written by tools/peer/run_peer.py (make peer): upstream's test executables of %s,"
        % package,
        "# built against the system's ROS 1 packages. Regenerated on every run; do not edit.",
        "cmake_minimum_required(VERSION 3.0.2)",
        "project(%s)" % package,
        "find_package(catkin REQUIRED COMPONENTS %s)" % " ".join(CATKIN_COMPONENTS),
        "find_package(OpenCV REQUIRED)",
        "find_package(GTest REQUIRED)",
        "find_package(Threads REQUIRED)",
        "catkin_package()",
        "add_compile_options(%s)" % " ".join(COMPILE_FLAGS),
        "include_directories(%s${catkin_INCLUDE_DIRS} ${OpenCV_INCLUDE_DIRS} ${GTEST_INCLUDE_DIRS})"
        % (COMPAT_DIR + " " if compat else ""),
    ]
    for exe in executables:
        target = target_name(package, exe.name)
        lines.append("add_executable(%s %s)" % (target, " ".join(exe.sources)))
        lines.append("set_target_properties(%s PROPERTIES OUTPUT_NAME %s)" % (target, exe.name))
        lines.append("target_link_libraries(%s %s ${GTEST_LIBRARIES} Threads::Threads)"
                     % (target, " ".join(exe.libs) or "${catkin_LIBRARIES}"))
    return "\n".join(lines) + "\n"


def package_xml(package, version, description):
    """A format-2 package.xml for a scratch package."""
    deps = "\n".join("  <depend>%s</depend>" % d for d in CATKIN_COMPONENTS)
    return """<?xml version="1.0"?>
<!-- Written by tools/peer/run_peer.py (make peer); regenerated on every run. -->
<package format="2">
  <name>%s</name>
  <version>%s</version>
  <description>%s</description>
  <maintainer email="nobody@example.com">make peer</maintainer>
  <license>BSD</license>
  <buildtool_depend>catkin</buildtool_depend>
%s
  <exec_depend>rostest</exec_depend>
</package>
""" % (package, version, description, deps)


def compat_header(service):
    """A compat header gazebo/SERVICE.h: the rosbuild-era gazebo package's service as
    gazebo_msgs' (the same .srv, since renamed)."""
    return ("// Written by tools/peer/run_peer.py (make peer): the rosbuild-era gazebo package's\n"
            "// %s service, which is gazebo_msgs' %s now.\n"
            "#pragma once\n#include <gazebo_msgs/%s.h>\n"
            "namespace gazebo {\nusing gazebo_msgs::%s;\nusing gazebo_msgs::%sRequest;\n"
            "using gazebo_msgs::%sResponse;\n}\n") % ((service,) * 6)


def compat_services(sources_text):
    """The services a source text includes as "gazebo/NAME.h", sorted."""
    return sorted(set(re.findall(r'#include\s+"gazebo/(\w+)\.h"', sources_text)))


# --- results and the table ---------------------------------------------------------------------

RunResult = namedtuple("RunResult", "passed seconds failure failures", defaults=((),))
RunResult.__doc__ = ("One rostest run: passed, wall seconds, its first failure in one line and "
                     "every failure it gave (failures: the XML's, else the first one)")

# The tests that fail on Gazebo itself, with the one failure each gives there; a run that fails
# with that failure and no other is counted "as upstream", any other failure is a failure.
KNOWN_UPSTREAM = {
    "ros_network_default": (
        r"test_extra_topics: Items in the first set but not the second: "
        r"'/gazebo/performance_metrics'",
        "Gazebo 11.2 and later publish /gazebo/performance_metrics, which the test's strict "
        "list lacks; reported upstream"),
    "spawn_box": (
        r"FATAL: gazebo: world file not found: gazebo_plugins/test/worlds/empty\.world",
        "its launch file names a world gazebo_ros_pkgs does not have; gzserver exits"),
    "contact_tolerance": (
        r"testgazebo_tests: False is not true : "
        r"Test Fixture Nodes \[.gazebo.\] failed to launch",
        "its launch file starts package gazebo, the rosbuild package since renamed"),
}
KNOWN_UPSTREAM["spawn_box_file"] = KNOWN_UPSTREAM["spawn_box_param"] = KNOWN_UPSTREAM["spawn_box"]


def as_upstream(name, results):
    """The reason test ``name`` fails on Gazebo too, when each failed run of ``results``
    failed with the failure it gives there and with no other; None otherwise."""
    known = KNOWN_UPSTREAM.get(name)
    failed = [r for r in results if not r.passed]
    if known is None or not failed:
        return None
    pattern = re.compile(known[0] + r"$")
    if all(all(pattern.match(f) for f in (r.failures or (r.failure,))) for r in failed):
        return known[1]
    return None


# An absolute path to a file (its name has a suffix; a ROS name such as /gazebo/x has none).
_PATH = re.compile(r"(?<![\w.])/(?:[\w.+-]+/)+([\w+-]+\.[\w.+-]+)")
_TRACEBACK = re.compile(r'\n\s*File "|\nTraceback')


def first_line(text, width=110):
    for line in (text or "").splitlines():
        line = " ".join(line.split())
        if line:
            return line if len(line) <= width else line[:width - 3] + "..."
    return ""


def one_line(text, width=110):
    """``text`` up to a Python traceback in one line, absolute file paths as their file names,
    at most ``width`` long."""
    text = _TRACEBACK.split(text)[0]
    line = " ".join(_PATH.sub(lambda m: m.group(1), text).split())
    return line if len(line) <= width else line[:width - 3] + "..."


def xml_failure(texts):
    """The first failure or error message in JUnit XML texts (rostest's, gtest's, rosunit's),
    in one line (gtest's "file:line" and "Expected ..." lines together); "" when none."""
    return next(iter(xml_failures(texts)), "")


def xml_failures(texts):
    """Every failure or error message in JUnit XML texts, each as xml_failure gives it."""
    found = []
    for text in texts:
        try:
            root = ET.fromstring(text)
        except ET.ParseError:
            continue
        for case in root.iter("testcase"):
            for kind in ("failure", "error"):
                for element in case.iter(kind):
                    line = one_line(element.get("message") or element.text or "")
                    if line:
                        found.append("%s: %s" % (case.get("name", "?"), line))
    return found


_LOG_STAMP = re.compile(r"^\[FATAL\]\s*(\[[0-9., ]+\]:\s*)?")
_ANSI = re.compile(r"\x1b\[[0-9;]*m")
_ERROR = re.compile(r"\[(ERROR|FATAL)\]|\b(error|ERROR):|Traceback|did not generate"
                    r"|[Cc]annot locate")
_SUMMARY = re.compile(r"^\s*\*\s*(RESULT|TESTS|ERRORS|FAILURES):\s*(\S+)", re.M)


def run_result(status, output, xml_texts, seconds):
    """One rostest run's RunResult from its exit status, its output and its XML results:
    passed only with exit status 0 and rostest's SUCCESS. The failure is the first [FATAL] log
    line (a node that refused to start: the sim's one line, which the tests' own time-outs only
    follow), else the XML's first message, else the output's first error line, else the exit
    status."""
    output = _ANSI.sub("", output)
    summary = dict(_SUMMARY.findall(output))
    passed = status == 0 and summary.get("RESULT") == "SUCCESS"
    if passed:
        return RunResult(True, seconds, "")
    fatal = next((line for line in output.splitlines() if "[FATAL]" in line), "")
    failure = (one_line(_LOG_STAMP.sub("FATAL: ", fatal[fatal.index("[FATAL]"):])) if fatal
               else xml_failure(xml_texts))
    if not failure:
        for line in output.splitlines():
            if _ERROR.search(line) and not _SUMMARY.match(line):
                failure = first_line(line)
                break
    failure = failure or "rostest exit status %d" % status
    failures = () if fatal else tuple(xml_failures(xml_texts))   # a fatal line is the cause
    return RunResult(False, seconds, failure, failures or (failure,))


def format_table(rows, header):
    """The markdown table: one row per (PeerTest, [RunResult]), and the ``peer:`` line (a test
    passes when every run passed; it fails as upstream when each failed run gave only the
    failure it gives on Gazebo, KNOWN_UPSTREAM, which the row names)."""
    lines = [header, "",
             "| test | upstream | runs | passed | s | first failure |",
             "|---|---|---|---|---|---|"]
    passed = upstream = failed = 0
    for test, results in rows:
        good = sum(1 for r in results if r.passed)
        ok = bool(results) and good == len(results)
        reason = None if ok else as_upstream(test.name, results)
        passed, upstream = passed + ok, upstream + (reason is not None)
        failed += not ok and reason is None
        first = next((r.failure for r in results if not r.passed), "")
        if reason is not None:
            first = "as upstream (%s): %s" % (reason, first)
        lines.append("| %s | %s | %d | %d | %.0f | %s |" % (
            test.name, test.origin, len(results), good, sum(r.seconds for r in results),
            first.replace("|", "/")))
    lines += ["", "peer: %d passed, %d fail as on Gazebo, %d failed" % (passed, upstream, failed)]
    return "\n".join(lines)
