"""make peer's own logic, without the peer's tree, a build or a ROS master: gzserver's command
line as the sim's (tools/peer/gzserver_args.py), upstream's test targets read from CMake text
and the scratch packages' build files (tools/peer/peer_plan.py, on fixture strings of our own),
the scratch workspace's layout (tools/peer/run_peer.py's plan, on a small fake tree), one run's
result and the table, the PyYAML shim, and fetch_peer.py's check."""
import os
import subprocess
import sys
import types

import pytest

import unit_paths

sys.path.insert(0, os.path.join(unit_paths.ROOT, "tools", "peer"))
import fetch_peer  # noqa: E402
import gzserver_args  # noqa: E402
import peer_plan  # noqa: E402
import run_peer  # noqa: E402
import yaml_shim  # noqa: E402

SIM = ["rosrun", "tutorial_turtlebot", "sim"]

# --- gzserver's command line ---------------------------------------------------------------------


def test_a_test_files_gzserver_runs_the_sim_on_that_world_without_a_robot(tmp_path):
    world = tmp_path / "camera.world"
    world.write_text("<sdf/>")
    # <node pkg="gazebo_ros" type="gzserver" args="--verbose WORLD"> as roslaunch runs it
    command, warnings = gzserver_args.translate(
        ["--verbose", str(world), "__name:=gazebo", "__log:=/tmp/gazebo-1.log"])
    assert command == SIM + ["_world:=%s" % world, "_spawn_robot:=false", "__name:=gazebo",
                             "__log:=/tmp/gazebo-1.log"]
    assert warnings == []


def test_empty_world_launch_options_become_params_and_its_world_the_projects_own():
    # empty_world.launch paused:=true: "-u  --verbose -e ode  worlds/empty.world" (no such
    # file here, no GAZEBO_RESOURCE_PATH): Gazebo's empty.world is the sim's worlds/empty.world
    command, _ = gzserver_args.translate(
        ["-u", "", "--verbose", "-e", "ode", "", "worlds/empty.world", "__name:=gazebo"],
        environ={}, cwd="/nonexistent")
    assert command[3] == "_world:=%s" % os.path.join(unit_paths.ROOT, "worlds", "empty.world")
    assert "_paused:=true" in command and "_spawn_robot:=false" in command
    assert "ode" not in " ".join(command)          # -e's value is not taken for a world
    assert command[-1] == "__name:=gazebo"         # remaps last


def test_no_world_is_gazebos_default_empty_world():
    command, _ = gzserver_args.translate([], environ={}, cwd="/nonexistent")
    assert command[3] == "_world:=%s" % os.path.join(unit_paths.ROOT, "worlds", "empty.world")


def test_a_relative_world_is_looked_for_in_cwd_then_gazebo_resource_path(tmp_path):
    (tmp_path / "share" / "worlds").mkdir(parents=True)
    (tmp_path / "share" / "worlds" / "range.world").write_text("<sdf/>")
    env = {"GAZEBO_RESOURCE_PATH": "/nowhere:%s" % (tmp_path / "share")}
    command, _ = gzserver_args.translate(["worlds/range.world"], environ=env, cwd=str(tmp_path))
    assert command[3] == "_world:=%s" % (tmp_path / "share" / "worlds" / "range.world")
    (tmp_path / "worlds").mkdir()
    (tmp_path / "worlds" / "range.world").write_text("<sdf/>")
    command, _ = gzserver_args.translate(["worlds/range.world"], environ=env, cwd=str(tmp_path))
    assert command[3] == "_world:=%s" % (tmp_path / "worlds" / "range.world")
    # found nowhere: passed on as it is, for the sim to refuse in one line
    command, _ = gzserver_args.translate(["lost.world"], environ={}, cwd=str(tmp_path))
    assert command[3] == "_world:=lost.world"


def test_plugins_seed_and_unsupported_options():
    command, warnings = gzserver_args.translate(
        ["-s", "libgazebo_ros_api_plugin.so", "--server-plugin=libx.so", "--seed", "7",
         "--iters", "100", "/w.world"])
    assert command[3:] == ["_world:=/w.world", "_spawn_robot:=false", "_seed:=7"]
    assert len(warnings) == 1 and "--iters" in warnings[0]


def test_the_gazebo_entry_asks_for_the_window():
    command, _ = gzserver_args.translate(["/w.world"], entry="gazebo")
    assert "_gui:=true" in command
    assert "_gui:=true" not in gzserver_args.translate(["/w.world"])[0]


@pytest.mark.parametrize("argv", [["--bogus"], ["-e"], ["/a.world", "/b.world"]])
def test_command_lines_gzserver_refuses(argv):
    with pytest.raises(gzserver_args.GzArgsError):
        gzserver_args.translate(argv)


# --- upstream's CMakeLists ----------------------------------------------------------------------

PLUGINS_CMAKE = """
cmake_minimum_required(VERSION 3.0.2)
project(fixture)
add_library(not_a_test src/x.cpp)  # add_rostest(test/in_a_comment.test)
if (CATKIN_ENABLE_TESTING)
  find_package(rostest REQUIRED)
  add_rostest_gtest(alpha-test
                    test/alpha/alpha.test
                    test/alpha/alpha.cpp test/alpha/helper.cpp)
  target_link_libraries(alpha-test ${catkin_LIBRARIES})
  add_rostest(test/beta.test)
  # add_rostest_gtest(gamma-test test/gamma.test test/gamma.cpp)
  if (ENABLE_DISPLAY_TESTS)
    add_rostest_gtest(delta_test test/delta.test test/delta.cpp)
    target_link_libraries(delta_test ${catkin_LIBRARIES} ${OpenCV_LIBRARIES})
  endif()
  add_rostest_gtest(set_model_state-test test/sms/set_model_state_test.test test/sms/s.cpp)
endif()
"""

ROS_TEST_CMAKE = """
set (rostests_python
  net/one.test
  net/two.test
)
if(CATKIN_ENABLE_TESTING)
  foreach (rostest ${rostests_python})
    add_rostest(${rostest} rostest ${CMAKE_CURRENT_SOURCE_DIR}/${rostest})
    add_test(check_${rostest} rosrun rosunit check_test_ran.py --rostest x ${rostest})
  endforeach()
endif()
"""

ROSBUILD_CMAKE = """
rosbuild_add_executable(spawn_box test/spawn_model/spawn_box.cpp)
rosbuild_add_gtest_build_flags(spawn_box)
rosbuild_add_rostest_labeled(gazebo test/spawn_model/spawn_box.launch)
"""


def test_catkin_tests_reads_each_gtest_target_and_rostest_with_its_origin():
    exes, tests = peer_plan.catkin_tests(PLUGINS_CMAKE, "gazebo_plugins")
    assert [(e.name, e.sources, e.libs, e.origin) for e in exes] == [
        ("alpha-test", ["test/alpha/alpha.cpp", "test/alpha/helper.cpp"],
         ["${catkin_LIBRARIES}"], "active"),
        ("delta_test", ["test/delta.cpp"], ["${catkin_LIBRARIES}", "${OpenCV_LIBRARIES}"],
         "display"),
        ("set_model_state-test", ["test/sms/s.cpp"], [], "active")]
    assert [(t.name, t.path, t.runs, t.origin) for t in tests] == [
        ("alpha", "test/alpha/alpha.test", 1, "active"),
        ("beta", "test/beta.test", 1, "active"),
        ("delta", "test/delta.test", 1, "display"),
        ("set_model_state_test", "test/sms/set_model_state_test.test", 10, "active")]


def test_catkin_tests_unrolls_gazebo_ros_foreach_over_a_set():
    exes, tests = peer_plan.catkin_tests(ROS_TEST_CMAKE, "gazebo_ros", "test/")
    assert exes == []
    assert [(t.name, t.package, t.path) for t in tests] == [
        ("one", "gazebo_ros", "test/net/one.test"), ("two", "gazebo_ros", "test/net/two.test")]


def test_rosbuild_tests_reads_test2s_executables_and_launch_files():
    exes, tests = peer_plan.rosbuild_tests(ROSBUILD_CMAKE, "gazebo_tests")
    assert [(e.name, e.sources, e.origin) for e in exes] == [
        ("spawn_box", ["test/spawn_model/spawn_box.cpp"], "test2")]
    assert [(t.name, t.path, t.origin) for t in tests] == [
        ("spawn_box", "test/spawn_model/spawn_box.launch", "test2")]


def test_generated_cmakelists_builds_each_target_under_upstreams_name_with_the_debian_flags():
    exes, _ = peer_plan.catkin_tests(PLUGINS_CMAKE, "gazebo_plugins")
    text = peer_plan.cmakelists("gazebo_plugins", exes)
    assert "project(gazebo_plugins)" in text
    assert ("add_executable(gazebo_plugins__alpha-test test/alpha/alpha.cpp "
            "test/alpha/helper.cpp)") in text
    assert "set_target_properties(gazebo_plugins__alpha-test PROPERTIES OUTPUT_NAME alpha-test)" \
        in text
    assert ("target_link_libraries(gazebo_plugins__delta_test ${catkin_LIBRARIES} "
            "${OpenCV_LIBRARIES} ${GTEST_LIBRARIES} Threads::Threads)") in text
    assert "add_compile_options(-DBOOST_BIND_GLOBAL_PLACEHOLDERS -include boost/bind.hpp)" in text
    for component in ("roscpp", "image_transport", "tf", "cv_bridge", "gazebo_msgs"):
        assert component in text.split("find_package(catkin REQUIRED COMPONENTS")[1].split(")")[0]
    assert peer_plan.COMPAT_DIR not in text
    assert peer_plan.COMPAT_DIR in peer_plan.cmakelists("gazebo_tests", [], compat=True)


def test_compat_headers_name_gazebo_msgs_services():
    text = '#include "gazebo/SpawnModel.h"\n#include <gazebo/x.hh>\n#include "gazebo/DeleteModel.h"'
    assert peer_plan.compat_services(text) == ["DeleteModel", "SpawnModel"]
    header = peer_plan.compat_header("SpawnModel")
    assert "#include <gazebo_msgs/SpawnModel.h>" in header
    assert "using gazebo_msgs::SpawnModelRequest;" in header


def test_launch_test_nodes_and_order():
    launch = ('<launch><node pkg="gazebo_ros" type="gzserver"/>'
              '<test test-name="t" pkg="gazebo_plugins" type="camera-test"/></launch>')
    assert peer_plan.launch_test_nodes(launch) == [("gazebo_plugins", "camera-test")]
    assert peer_plan.launch_test_nodes("not xml") == []
    tests = [peer_plan.PeerTest(n, "p", n, 1, o) for n, o in
             [("zeta", "test2"), ("camera", "display"), ("other", "active"),
              ("set_model_state_test", "active")]]
    assert [t.name for t in peer_plan.ordered(tests)] == ["set_model_state_test", "camera",
                                                          "other", "zeta"]


# --- the scratch workspace ----------------------------------------------------------------------

def _fake_peer(root):
    files = {
        "gazebo_plugins/package.xml": "<package><version>2.9.2</version></package>",
        "gazebo_plugins/CMakeLists.txt": PLUGINS_CMAKE,
        "gazebo_plugins/test/alpha/alpha.test": "<launch/>",
        "gazebo_plugins/scripts/test_range.py": "#!/usr/bin/env python\n",
        "gazebo_plugins/test2/CMakeLists_tests_pkg.txt": ROSBUILD_CMAKE + (
            "rosbuild_add_executable(check_model test/spawn_model/check_model.cpp)\n"
            "rosbuild_add_rostest_labeled(gazebo test/spawn_model/spawn_box_file.launch)\n"),
        "gazebo_plugins/test2/spawn_model/spawn_box.launch":
            '<launch><test pkg="gazebo_tests" type="spawn_box"/></launch>',
        "gazebo_plugins/test2/spawn_model/spawn_box_file.launch":
            '<launch><test pkg="gazebo_plugins" type="check_model"/></launch>',
        "gazebo_plugins/test2/spawn_model/spawn_box.cpp": '#include "gazebo/SpawnModel.h"\n',
        "gazebo_plugins/test2/spawn_model/check_model.cpp":
            '#include "gazebo/GetWorldProperties.h"\n',
        "gazebo_ros/launch/empty_world.launch": "<launch/>",
        "gazebo_ros/test/CMakeLists.txt": ROS_TEST_CMAKE,
        "gazebo_ros/test/net/one.test": "<launch/>",
    }
    for rel, text in files.items():
        os.makedirs(os.path.dirname(os.path.join(root, rel)), exist_ok=True)
        with open(os.path.join(root, rel), "w") as handle:
            handle.write(text)
    os.chmod(os.path.join(root, "gazebo_plugins/scripts/test_range.py"), 0o755)


def test_plan_lays_out_three_packages_from_upstreams_files(tmp_path):
    _fake_peer(str(tmp_path))
    files, tests, built = run_peer.plan(str(tmp_path))
    # upstream's files, as upstream has them, and test2 as gazebo_tests' test/
    assert files["gazebo_plugins/test/alpha/alpha.test"] == (b"<launch/>", 0o644)
    assert files["gazebo_plugins/scripts/test_range.py"][1] == 0o755
    assert "gazebo_ros/launch/empty_world.launch" in files
    assert "gazebo_tests/test/spawn_model/spawn_box.launch" in files
    # the stand-in's entry points, executable; gzserver runs gzserver_args
    for entry in ("gzserver", "gazebo", "debug", "gzclient", "spawn_model"):
        assert files["gazebo_ros/scripts/" + entry][1] == 0o755, entry
    gzserver = files["gazebo_ros/scripts/gzserver"][0].decode()
    assert "from gzserver_args import main" in gzserver and "entry='gzserver'" in gzserver
    # each test2 executable where its launch file's <test pkg=...> looks for it
    assert sorted(built) == [("gazebo_plugins", "alpha-test"), ("gazebo_plugins", "check_model"),
                             ("gazebo_plugins", "delta_test"),
                             ("gazebo_plugins", "set_model_state-test"),
                             ("gazebo_tests", "spawn_box")]
    assert built[("gazebo_plugins", "check_model")].sources == [
        "test2/spawn_model/check_model.cpp"]
    assert "gazebo_plugins/%s/gazebo/GetWorldProperties.h" % peer_plan.COMPAT_DIR in files
    assert "gazebo_tests/%s/gazebo/SpawnModel.h" % peer_plan.COMPAT_DIR in files
    assert b"<version>2.9.2</version>" in files["gazebo_tests/package.xml"][0]
    assert [t.name for t in tests] == ["set_model_state_test", "alpha", "beta", "delta", "one",
                                       "two", "spawn_box", "spawn_box_file"]


# --- one run, and the table ---------------------------------------------------------------------

SUCCESS = ("[ROSTEST]----\nSUMMARY\n\x1b[32m * RESULT: SUCCESS\x1b[0m\n * TESTS: 1\n"
           " * ERRORS: 0\n * FAILURES: 0\n")
FAIL = "SUMMARY\n\x1b[1m * RESULT: FAIL\x1b[0m\n * TESTS: 1\n * ERRORS: 0\n * FAILURES: 1\n"
GTEST_XML = """<?xml version="1.0"?><testsuites><testsuite name="t" tests="1" failures="1">
<testcase name="cameraSubscribeTest" classname="CameraTest"><failure message="/ws/src/test/\
camera.cpp:66&#x0A;Expected: (images_received_) &gt; (20), actual: 0 vs 20" type=""/>\
</testcase></testsuite>
</testsuites>"""


def test_run_result_passes_only_on_status_0_and_rostests_success():
    assert peer_plan.run_result(0, SUCCESS, [], 12.0) == peer_plan.RunResult(True, 12.0, "")
    assert not peer_plan.run_result(1, SUCCESS, [], 1.0).passed
    assert not peer_plan.run_result(0, FAIL, [], 1.0).passed


def test_run_result_names_the_first_failure():
    failure = peer_plan.run_result(1, FAIL, ["<bad", GTEST_XML], 3.0).failure
    assert failure == ("cameraSubscribeTest: camera.cpp:66 Expected: (images_received_) > (20), "
                       "actual: 0 vs 20")
    # a Python test's message: up to its traceback; ROS names are not file paths
    xml = ('<testsuite><testcase name="test_extra_topics"><failure message="Items in the first '
           'set but not the second:&#x0A;\'/gazebo/performance_metrics\'&#x0A;  File '
           '&quot;/usr/lib/python3.11/unittest/case.py&quot;, line 57"/></testcase></testsuite>')
    assert peer_plan.run_result(1, FAIL, [xml], 3.0).failure == (
        "test_extra_topics: Items in the first set but not the second: "
        "'/gazebo/performance_metrics'")
    # a node's [FATAL] line (the sim refusing its world) before the time-out it causes
    output = FAIL + ("\x1b[31m[FATAL] [1796620040.752904, 0.000000]: gazebo: world file not "
                     "found: gazebo_plugins/test/worlds/empty.world\x1b[0m\n")
    assert peer_plan.run_result(1, output, [GTEST_XML], 3.0).failure == (
        "FATAL: gazebo: world file not found: gazebo_plugins/test/worlds/empty.world")
    # no XML: the output's first error line, never the summary's "* ERRORS: 0"
    output = FAIL + "ERROR: cannot launch node of type [gazebo/gazebo]\n"
    assert peer_plan.run_result(1, output, [], 3.0).failure == (
        "ERROR: cannot launch node of type [gazebo/gazebo]")
    assert peer_plan.run_result(2, "", [], 3.0).failure == "rostest exit status 2"


def test_format_table_one_row_per_test_and_the_peer_line():
    sms = peer_plan.PeerTest("set_model_state_test", "gazebo_plugins", "x.test", 10, "active")
    cam = peer_plan.PeerTest("camera", "gazebo_plugins", "c.test", 1, "display")
    good = peer_plan.RunResult(True, 17.0, "")
    bad = peer_plan.RunResult(False, 31.0, "cameraSubscribeTest: a | b")
    text = peer_plan.format_table([(sms, [good] * 10), (cam, [bad])], "make peer, today")
    lines = text.splitlines()
    assert lines[0] == "make peer, today"
    assert "| set_model_state_test | active | 10 | 10 | 170 |  |" in lines
    assert "| camera | display | 1 | 0 | 31 | cameraSubscribeTest: a / b |" in lines
    assert lines[-1] == "peer: 1 passed, 0 fail as on Gazebo, 1 failed"
    # one failed run of ten fails the test
    text = peer_plan.format_table([(sms, [good] * 9 + [bad])], "h")
    assert "| set_model_state_test | active | 10 | 9 | 184 | cameraSubscribeTest: a / b |" in text
    assert text.endswith("peer: 0 passed, 0 fail as on Gazebo, 1 failed")


EXTRA_TOPIC = ("test_extra_topics: Items in the first set but not the second: "
               "'/gazebo/performance_metrics'")


def test_a_test_that_fails_as_on_gazebo_counts_apart_only_with_that_failure_alone():
    net = peer_plan.PeerTest("ros_network_default", "gazebo_ros", "n.test", 1, "active")
    known = peer_plan.RunResult(False, 30.0, EXTRA_TOPIC, (EXTRA_TOPIC,))
    text = peer_plan.format_table([(net, [known])], "h")
    assert ("| ros_network_default | active | 1 | 0 | 30 | as upstream (Gazebo 11.2 and later"
            in text)
    assert text.endswith("peer: 0 passed, 1 fail as on Gazebo, 0 failed")
    # a second failure beside it, another extra topic, or another test: a failure
    for results in ([peer_plan.RunResult(False, 30.0, EXTRA_TOPIC,
                                         (EXTRA_TOPIC, "test_services: a service missing"))],
                    [peer_plan.RunResult(False, 30.0, EXTRA_TOPIC + ", '/x'")]):
        assert peer_plan.format_table([(net, results)], "h").endswith(
            "0 fail as on Gazebo, 1 failed")
    cam = peer_plan.PeerTest("camera", "gazebo_plugins", "c.test", 1, "display")
    assert peer_plan.as_upstream("camera", [known]) is None
    assert peer_plan.format_table([(cam, [known])], "h").endswith("1 failed")


def test_run_result_keeps_every_xml_failure_or_the_fatal_line_alone():
    xml = ('<testsuite><testcase name="a"><failure message="one"/></testcase>'
           '<testcase name="b"><error message="two"/></testcase></testsuite>')
    assert peer_plan.run_result(1, FAIL, [xml], 1.0).failures == ("a: one", "b: two")
    fatal = "[FATAL] [1.0]: gazebo: world file not found: w.world\n" + FAIL
    result = peer_plan.run_result(1, fatal, [xml], 1.0)
    assert result.failures == (result.failure,) == ("FATAL: gazebo: world file not found: "
                                                    "w.world",)


# --- the PyYAML shim and the tree check -------------------------------------------------------

def test_yaml_shim_gives_load_its_old_default_loader():
    calls = []
    fake = types.SimpleNamespace(FullLoader="full", load=lambda s, Loader: calls.append(Loader))
    yaml_shim.install(fake)
    yaml_shim.install(fake)   # once only
    fake.load("a: 1")
    fake.load("a: 1", Loader="safe")
    assert calls == ["full", "safe"]


def test_yaml_shim_as_sitecustomize_mends_a_bare_yaml_load(tmp_path):
    pytest.importorskip("yaml")
    (tmp_path / "sitecustomize.py").write_text(
        open(os.path.join(unit_paths.ROOT, "tools", "peer", "yaml_shim.py")).read())
    env = dict(os.environ, PYTHONPATH=str(tmp_path))
    out = subprocess.run([sys.executable, "-c", "import io, yaml; "
                          "print(yaml.load(io.StringIO('a: 1')))"],
                         env=env, capture_output=True, text=True)
    assert out.stdout.strip() == "{'a': 1}", out.stderr


def test_fetch_peer_check_names_what_is_wrong(tmp_path, monkeypatch):
    assert fetch_peer.check(str(tmp_path / "none")) == ["%s does not exist" % (tmp_path / "none")]
    faults = fetch_peer.check(str(tmp_path))
    assert any(fetch_peer.STAMP in f for f in faults)
    assert any("gazebo_plugins/CMakeLists.txt missing" in f for f in faults)
    (tmp_path / "hello").write_text("hello\n")
    assert fetch_peer.blob_id(str(tmp_path / "hello")) == \
        "ce013625030ba8dba906f756967f9e9ca394464a"   # git hash-object
    (tmp_path / fetch_peer.STAMP).write_text("0" * 40 + "\n")
    assert any("is at commit 0000000000" in f for f in fetch_peer.check(str(tmp_path)))
    (tmp_path / fetch_peer.STAMP).write_text(fetch_peer.PEER_COMMIT + "\n")
    assert not any("commit" in f for f in fetch_peer.check(str(tmp_path)))
    monkeypatch.setenv("PEER_SRC", str(tmp_path))
    assert fetch_peer.peer_src() == str(tmp_path)
    monkeypatch.delenv("PEER_SRC")
    assert fetch_peer.peer_src() == fetch_peer.DEFAULT_PEER_SRC
