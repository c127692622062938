"""The house rules of src/tutorial_turtlebot (doc/development.md), read from the imports of every
module: pybullet only in sim/engine/, no ROS in sim/, each sub-wing of sim/ importing only the
ones below it, the lab's nodes apart from the simulator."""
import ast
import os

import pytest

import unit_paths

PACKAGE = os.path.join(unit_paths.ROOT, "src", "tutorial_turtlebot")
# what each part of the package may import of the package (besides itself and the top level:
# errors, robot_models, package_data, ros_names, node_params, node_output)
MAY_IMPORT = {
    "sim.kinematics": set(),
    "sim.files": {"sim.kinematics"},
    "sim.engine": {"sim.kinematics", "sim.files"},
    "sim.devices": {"sim.kinematics", "sim.files"},
    "sim.world": {"sim.kinematics", "sim.files", "sim.engine", "sim.devices"},
    "gazebo": {"sim"},
    "lab": set(),
    "learning": {"sim"},
}
ROS = ("rospy", "rosgraph", "roslaunch", "genpy", "rosbag", "tf2_ros", "actionlib")


def modules():
    """{dotted name below tutorial_turtlebot: file path} of every module of the package."""
    out = {}
    for folder, _, files in os.walk(PACKAGE):
        for name in files:
            if name.endswith(".py"):
                rel = os.path.relpath(os.path.join(folder, name), PACKAGE)[:-3]
                out[rel.replace(os.sep, ".")] = os.path.join(folder, name)
    return out


def imports(module, path):
    """Every module ``path`` imports, as absolute dotted names (the package's own beginning
    with ``tutorial_turtlebot.``), including imports inside functions."""
    package = ("tutorial_turtlebot." + module).split(".")
    if not path.endswith("__init__.py"):
        package = package[:-1]
    with open(path, encoding="utf-8") as f:
        tree = ast.parse(f.read(), path)
    out = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            out.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            base = package[:len(package) - node.level + 1] if node.level else []
            target = ".".join(base + ([node.module] if node.module else []))
            out.add(target)
            out.update(target + "." + alias.name for alias in node.names)   # modules too
    return out


def part_of(name):
    """The MAY_IMPORT key a dotted name below tutorial_turtlebot belongs to, or None."""
    for key in sorted(MAY_IMPORT, key=len, reverse=True):
        if name == key or name.startswith(key + "."):
            return key
    return None


MODULES = modules()


@pytest.mark.parametrize("module", sorted(MODULES))
def test_pybullet_is_imported_by_the_engine_alone(module):
    found = {name for name in imports(module, MODULES[module])
             if name.split(".")[0] in ("pybullet", "pybullet_data", "eglRenderer")
             or name.endswith("engine.bullet.pybullet")}
    if module.startswith("sim.engine."):
        return
    assert not found, "%s imports %s: only sim/engine/ talks to pybullet" % (module, found)


@pytest.mark.parametrize("module", sorted(m for m in MODULES if m.startswith("sim.")))
def test_the_simulator_knows_nothing_of_ros(module):
    found = {name for name in imports(module, MODULES[module])
             if name.split(".")[0] in ROS or name.split(".")[0].endswith("_msgs")
             or name.startswith(("tutorial_turtlebot.gazebo", "tutorial_turtlebot.lab"))}
    assert not found, "%s imports %s" % (module, found)


@pytest.mark.parametrize("module", sorted(m for m in MODULES if part_of(m)))
def test_each_part_imports_only_what_lies_below_it(module):
    own = part_of(module)
    allowed = MAY_IMPORT[own] | {own}
    wrong = set()
    for name in imports(module, MODULES[module]):
        if not name.startswith("tutorial_turtlebot."):
            continue
        inner = name[len("tutorial_turtlebot."):]
        target = part_of(inner)
        if target is None:
            continue   # the top level
        if target not in allowed and not any(target.startswith(a + ".") for a in allowed):
            wrong.add(inner)
    assert not wrong, "%s (%s) imports %s" % (module, own, sorted(wrong))


def test_the_rules_see_every_wing():
    """The checks above would pass on an empty package: they must have modules to check."""
    parts = {part_of(m) for m in MODULES}
    assert {"sim.files", "sim.engine", "sim.devices", "sim.world", "gazebo", "lab"} <= parts
    assert any(m.startswith("sim.engine.") and "pybullet" in " ".join(imports(m, MODULES[m]))
               for m in MODULES)


def test_setup_py_installs_every_package():
    """catkin_make install installs the packages setup.py names: a folder of src/ missing there
    would be missing from every install space."""
    folders = {os.path.relpath(folder, os.path.dirname(PACKAGE)).replace(os.sep, ".")
               for folder, _, files in os.walk(PACKAGE) if "__init__.py" in files}
    with open(os.path.join(unit_paths.ROOT, "setup.py"), encoding="utf-8") as f:
        tree = ast.parse(f.read())
    listed = {node.value for node in ast.walk(tree)
              if isinstance(node, ast.Constant) and isinstance(node.value, str)
              and node.value.startswith("tutorial_turtlebot")}
    assert folders <= listed, sorted(folders - listed)


@pytest.mark.parametrize("module", sorted(m for m in MODULES
                                          if m.startswith(("sim.", "lab.", "gazebo."))))
def test_no_wing_but_learning_needs_the_learning_libraries(module):
    found = {name for name in imports(module, MODULES[module])
             if name.split(".")[0] in ("gymnasium", "ray", "stable_baselines3", "torch")}
    assert not found, "%s imports %s: only learning/ may" % (module, found)
