"""The one plugin table (files/plugins/table.py): its modules are found by name (every
gazebo_ros_* and hector_* module of the folder that declares a plugin), every library the doc's
plugin table marks simulated or approximated has one module, no library has two, and each
plugin runs on the hosts it names (a model plugin's drives and IMU on robots alone). The
discovery itself is tried on a package of our own making in a temporary folder. No ROS, no
pybullet."""
import os
import re
import sys
from pathlib import Path

import pytest

from tutorial_turtlebot.sim.files.plugins import table

import unit_paths

FOLDER = Path(table.__file__).parent
DOC = Path(unit_paths.ROOT) / "doc" / "gazebo_node.md"
# hector_gazebo_plugins names its imu and gps libraries with a hector_ prefix, not its
# force-based move (the doc's rows name the source files).
HECTOR_LIBRARIES = {"gazebo_ros_imu": "libhector_gazebo_ros_imu.so",
                    "gazebo_ros_gps": "libhector_gazebo_ros_gps.so",
                    "gazebo_ros_force_based_move": "libgazebo_ros_force_based_move.so"}


def short(module) -> str:
    return module.__name__.rsplit(".", 1)[1]


def doc_libraries():
    """The libraries of the rows of doc/gazebo_node.md's "Gazebo plugins" table marked
    simulated or approximated."""
    text = DOC.read_text(encoding="utf-8")
    section = text.split("\n## Gazebo plugins\n", 1)[1].split("\n## ", 1)[0]
    found = set()
    for line in section.splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) < 3 or not cells[1].startswith(("simulated", "approximated")):
            continue
        for name in re.findall(r"`([^`]+)`", cells[0]):
            if not re.fullmatch(r"\w+", name):
                continue               # camera lens `<distortion>`: a feature, not a plugin
            if cells[0].startswith("hector"):
                assert name in HECTOR_LIBRARIES, "a new hector row %r: name its library" % name
                found.add(HECTOR_LIBRARIES[name])
            else:
                found.add("lib%s.so" % name)
    return found


def test_every_plugin_module_of_the_folder_is_in_the_table_in_name_order():
    files = sorted(name[:-3] for name in os.listdir(FOLDER)
                   if name.endswith(".py") and name.startswith(table.PREFIXES))
    assert [short(m) for m in table.MODULES] == files
    assert "gazebo_ros_imu" in files and "gazebo_ros_skid_steer_drive" in files


def test_every_library_the_doc_marks_simulated_maps_to_a_module_and_no_other():
    documented = doc_libraries()
    assert len(documented) >= 21
    assert set(table.PLUGINS) == documented
    assert short(table.PLUGINS["libgazebo_ros_imu.so"]) == "gazebo_ros_imu"
    assert short(table.PLUGINS["libgazebo_ros_gpu_laser.so"]) == "gazebo_ros_laser"


def test_no_library_is_claimed_by_two_modules():
    claimed = [f for m in table.MODULES for f in table.libraries(m)]
    assert len(claimed) == len(set(claimed)) == len(table.PLUGINS)
    assert all(table.PLUGINS[f] is m for m in table.MODULES for f in table.libraries(m))
    laser = table.PLUGINS["libgazebo_ros_laser.so"]
    with pytest.raises(ValueError, match="^libgazebo_ros_laser.so is claimed by both .*"
                                         "gazebo_ros_laser and .*gazebo_ros_laser$"):
        table.by_library([laser, laser])


def test_each_module_declares_the_table_attributes():
    for module in table.MODULES:
        assert table.is_sensor_module(module) != hasattr(module, "MODEL_FILES"), module
        assert callable(module.read) and module.PARAMS and module.HOSTS
        assert set(module.HOSTS) <= {"robot", "world"}
        if not table.is_sensor_module(module):
            assert module.DRIVE in (True, False)


def test_model_plugins_run_on_their_hosts_and_the_drives_are_marked():
    libs = set(table.PLUGINS)
    on_world = {f for f in libs if table.is_model_plugin(f, "world")}
    on_robot = {f for f in libs if table.is_model_plugin(f, "robot")}
    drives = {"libgazebo_ros_diff_drive.so", "libgazebo_ros_skid_steer_drive.so",
              "libgazebo_ros_planar_move.so", "libgazebo_ros_tricycle_drive.so",
              "libgazebo_ros_force_based_move.so"}     # on an SDF model (a robot's: its drive)
    assert on_world == {"libgazebo_ros_p3d.so", "libgazebo_ros_joint_state_publisher.so",
                        "libhector_gazebo_ros_imu.so", "libhector_gazebo_ros_gps.so"} | drives
    assert on_robot == on_world | {"libgazebo_ros_imu.so"}
    assert {f for f in on_robot if table.PLUGINS[f].DRIVE} == drives
    assert not table.is_model_plugin("libgazebo_ros_laser.so", "robot")    # a sensor plugin
    assert table.sensor_type("libgazebo_ros_p3d.so") is None
    assert not table.runs_on("libgazebo_ros_p3d.so", "world")
    assert table.model_plugin("libgazebo_ros_nothing.so", "robot") is None


# --- discovery on a package of our own ---------------------------------------------------------

TINY = '''MODEL_FILES = ("libgazebo_ros_tiny.so",)
HOSTS = ("world",)
PARAMS = frozenset({"robotNamespace"})
DRIVE = False


def read(reader, plugin, model, links, joints):
    return None
'''
TINY_SENSOR = '''SENSORS = {"libhector_tiny_sonar.so": "sonar"}
HOSTS = ("robot", "world")
PARAMS = frozenset({"topicName"})


def read(reader, sensor, plugin, link):
    return None
'''


@pytest.fixture
def package(tmp_path, monkeypatch):
    """make(name, {module: text}): a package ``name`` in a temporary folder, importable; its
    modules are dropped from sys.modules afterwards."""
    made = []

    def make(name, modules):
        folder = tmp_path / name
        folder.mkdir()
        (folder / "__init__.py").write_text("")
        for module, text in modules.items():
            (folder / (module + ".py")).write_text(text)
        made.append(name)
        return name

    monkeypatch.syspath_prepend(str(tmp_path))
    yield make
    for key in [k for k in sys.modules if k.split(".")[0] in made]:
        del sys.modules[key]


def test_discovery_finds_a_plugin_module_by_its_name_alone(package):
    name = package("tiny_plugins", {
        "gazebo_ros_tiny": TINY, "hector_tiny_sonar": TINY_SENSOR,
        "gazebo_ros_utils": "SHARED = 1\n",             # no plugin declared: not a plugin
        "tiny_helpers": TINY.replace("tiny.so", "helper.so")})     # not a plugin's name
    found = table.discover(name)
    assert [short(m) for m in found] == ["gazebo_ros_tiny", "hector_tiny_sonar"]
    plugins = table.by_library(found)
    assert sorted(plugins) == ["libgazebo_ros_tiny.so", "libhector_tiny_sonar.so"]
    assert plugins["libhector_tiny_sonar.so"].SENSORS["libhector_tiny_sonar.so"] == "sonar"


def test_discovery_refuses_a_half_declared_or_doubly_claimed_plugin(package):
    half = package("half_plugins", {"gazebo_ros_half": TINY.replace("DRIVE = False\n", "")})
    with pytest.raises(TypeError, match="^plugin module half_plugins.gazebo_ros_half declares "
                                        "MODEL_FILES but not DRIVE$"):
        table.discover(half)
    both = package("both_plugins", {"gazebo_ros_both": TINY + TINY_SENSOR})
    with pytest.raises(TypeError, match="declares both SENSORS and MODEL_FILES"):
        table.discover(both)
    twice = package("twice_plugins", {"gazebo_ros_one": TINY, "gazebo_ros_two": TINY})
    with pytest.raises(ValueError, match="^libgazebo_ros_tiny.so is claimed by both "
                                         "twice_plugins.gazebo_ros_one and "
                                         "twice_plugins.gazebo_ros_two$"):
        table.by_library(table.discover(twice))
